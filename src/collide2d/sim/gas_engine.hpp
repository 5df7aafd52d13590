// The event engine of a gas: the same events as EventEngine, in the same
// order, to the same bits, with nothing of the rest rules in its loop.
//
// In a gas (no ball accelerates, none fixed, the analytic method) every
// strike is a plain one until two collisions of one ball fall at one
// instant: the textbook response (contact_rules.hpp), each ball its own
// island, nothing to hold, sleep or wake. EventEngine answers such strikes
// by its plain gas path already (event_engine_gas.hpp), but every event
// still passes through its general machinery: a queue that can hold many
// events a ball, versions on both sides of every event, the contact graph,
// the observer. This engine keeps what a gas needs and no more:
//   - each ball's pending events are two, its earliest contact (with the
//     partner's version it was predicted against: a change of the owner's
//     own motion replaces them) and its next cell crossing, and the
//     calendar (ball_calendar.hpp, Paul's queue) orders the balls by the
//     earlier of the two in (time, kind, a, b), ties by the ball;
//   - a contact is predicted from the later of the two clocks, a wall from
//     the ball's, exactly as EventEngine predicts them (the same functions
//     with the same arguments), and after a stale or idle contact the
//     owner's next contact is asked again from that contact's place in the
//     order on (Smallenburg's EDMD, one event a particle);
//   - a strike is EventEngine::collide_in_gas's arithmetic, call for call.
// So the events processed are the current predictions in (time, kind, a,
// b) order, which is what EventEngine processes: the bits are its bits.
// The property gas-engine (properties/determinism_checks.cpp) holds the two
// to the same frames, events and final hash on generated gases, with and
// without simultaneous strikes.
//
// The counts of what changes nothing may differ from EventEngine's: a
// ball whose prediction finds nothing drops its old events here, where
// EventEngine's queue keeps them until they come out stale; and a contact
// that changed nothing (creeping) at a jam's instant, ordered after the
// jam, is judged again by the EventEngine that takes over. The events that
// act, and so the bits, are the same.
//
// A ball struck twice at one instant (a jam: Newton's cradle, a symmetric
// break) is where the rest rules begin to act (contact_rules.hpp, rule 1).
// There the gas engine hands the run over, before that event, to an
// EventEngine made from its world (EventEngine::take_over_gas), which goes
// on to the end of the run; its predictions, made afresh from the balls'
// clocks, are the ones the gas had (the queue's order is total and its
// predictions depend on the clocks alone).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "collide2d/sim/ball_calendar.hpp"
#include "collide2d/sim/cell_grid.hpp"
#include "collide2d/sim/event_engine.hpp"
#include "collide2d/sim/gas_world.hpp"
#include "collide2d/sim/prefetch.hpp"

namespace collide2d {

template <class Num>
class GasEngine {
 public:
  // Whether a run of the gas's world `g` (every ball fits a one-line body,
  // none accelerates or is fixed: gas_world_of_scene) can be a gas: the
  // analytic method, no negative least press (which would press balls of
  // equal acceleration together: EventEngine::plain_gas_scene), and its keys
  // hold a ball's index in 30 bits and a partner ball's or a wall's in 31:
  // both are asked to be below 2^30.
  static bool applies(const GasWorld<Num>& g, ToiMethod method, const RestThresholds<Num>& th) {
    return method == ToiMethod::analytic && !(th.least_press < Num{}) && g.balls.size() < (std::size_t{1} << 30) &&
           g.walls.size() < (std::size_t{1} << 30);
  }

  // The world's bodies are let go as soon as the gas's are made, before the
  // grid and the queue take their room (a million balls' Bodies are 128 MB).
  GasEngine(World<Num> world, const RestThresholds<Num>& thresholds)
      : GasEngine(gas_world_releasing(world), thresholds) {}
  GasEngine(GasWorld<Num> world, const RestThresholds<Num>& thresholds)
      : world_(std::move(world)), thresholds_(thresholds),
        grid_(world_, false, NumberTraits<Num>::to_double(thresholds.band)) {
    pending_.resize(world_.balls.size());
    calendar_.reserve(world_.balls.size());
    collision_.has_piece_starts = true;
  }

  // f(the world): the gas's (GasWorld) or, after a jam, the general
  // engine's (World). Both have balls with a Body's names for what the
  // frames and the watch read.
  template <class F>
  void with_world(F f) const {
    if (general_) f(general_->world());
    else f(world_);
  }
  const Num& now() const { return general_ ? general_->now() : now_; }
  EngineCounters counters() const { return general_ ? general_->counters() : counters_; }
  Num energy_removed_by_rest() const { return general_ ? general_->energy_removed_by_rest() : Num{}; }
  bool keeps_predictions() const { return true; }
  bool all_at_rest() const { return general_ ? general_->all_at_rest() : world_.balls.empty(); }
  // Whether the run was handed over to the general engine (a jam), and when.
  bool handed_over() const { return general_ != nullptr; }
  // Called with the world as the general engine takes it, before it acts
  // (the tunnelling watch starts keeping its pieces there).
  void on_hand_over(std::function<void(const World<Num>&)> f) { on_hand_over_ = std::move(f); }
  const Num& handed_over_at() const { return handed_over_at_; }

  // Every event up to `until` (inclusive), predicted within `end`, the
  // run's end; balls stay on their own clocks (EventEngine::run_to).
  template <class OnCollision>
  void run_to(const Num& until, const Num& end, OnCollision on_collision) {
    if (general_) return general_->run_to(until, end, on_collision);
    if (!primed_ || !(end == end_)) {
      end_ = end;
      predict_all();
    }
    primed_ = true;
    process_until(until, on_collision);
    if (general_) return general_->run_to(until, end, on_collision);
    now_ = until;
  }
  template <class OnCollision>
  void advance_to(const Num&, OnCollision) {
    throw std::logic_error("the gas engine has no steps: the step engine is EventEngine's");
  }

  // Checkpoints: which engine runs, then its state. The gas's is the
  // clock, counters, bodies, each ball's two pending events and the grid's
  // cells in their order: a loaded run pops exactly what the saved one would.
  static constexpr std::uint32_t checkpoint_layout = 1;
  void save(ByteWriter& out) const;
  void load(ByteReader& in);

 private:
  // The order of the queue: EventEngine's (time, kind, a, b), then the
  // ball whose event it is (two balls may hold one contact). All but the
  // time are packed in one word, most significant first, so that comparing
  // the words is comparing them in that order: kind (2 bits: a ball, a wall,
  // a crossing), a (30), b (31), and whether the ball is b (1; a < b where
  // either ball may be the owner, so this orders the owners as their
  // indices do). A key is 16 bytes in doubles and a calendar entry 24.
  struct Key {
    Num time{};
    std::uint64_t order = 0;
    int kind() const { return static_cast<int>(order >> 62); }
    int a() const { return static_cast<int>((order >> 32) & ((std::uint64_t{1} << 30) - 1)); }
    int b() const { return static_cast<int>((order >> 1) & ((std::uint64_t{1} << 31) - 1)); }
    int ball() const { return (order & 1) != 0 ? b() : a(); }  // whose event it is
  };
  static Key make_key(const Num& time, int kind, int a, int b, int ball) {
    return {time, std::uint64_t(kind) << 62 | std::uint64_t(a) << 32 | std::uint64_t(b) << 1 | std::uint64_t(ball != a)};
  }
  struct KeyEarlier {
    bool operator()(const Key& x, const Key& y) const {
      if (x.time != y.time) return x.time < y.time;
      return x.order < y.order;
    }
  };
  // A ball's pending events: its earliest contact (a ball or a wall) and its
  // next cell crossing.
  struct Pending {
    Num contact_time{}, crossing_time{};
    std::uint64_t partner_version = 0;  // a ball partner's, when predicted
    int partner = 0;                    // ball or wall
    EventKind kind = EventKind::ball_ball;
    ContactFeature feature = ContactFeature::none;
    bool has_contact : 1 = false, has_crossing : 1 = false;  // (bits: 32 bytes in doubles, not 40)
    std::uint8_t step = 0;  // CellStep
  };
  static_assert(sizeof(Num) != 8 || (sizeof(Pending) == 32 && sizeof(Key) == 16));

  GasWorld<Num> world_;
  RestThresholds<Num> thresholds_;
  CellGrid<Num> grid_;
  std::vector<Pending> pending_;
  BallCalendar<Num, Key, KeyEarlier> calendar_;
  Num now_{}, end_{};
  bool primed_ = false;
  int same_time_events_ = 0;
  EngineCounters counters_;
  Collision<Num> collision_;  // what on_collision sees (no island: each ball is its own)
  std::unique_ptr<EventEngine<Num>> general_;  // after a jam
  std::function<void(const World<Num>&)> on_hand_over_;
  Num handed_over_at_{};
  // predict_contacts_after: only contacts from this one on are kept
  // (`from_stale`: this one's own place as well).
  const Event<Num>* contacts_after_ = nullptr;
  bool from_stale_ = false;

  static Key contact_key(const Pending& p, int ball) {
    if (p.kind == EventKind::ball_ball)
      return make_key(p.contact_time, 0, std::min(ball, p.partner), std::max(ball, p.partner), ball);
    return make_key(p.contact_time, static_cast<int>(p.kind), ball, p.partner, ball);
  }
  static Key crossing_key(const Pending& p, int ball) {
    return make_key(p.crossing_time, static_cast<int>(EventKind::cell_crossing), ball, p.step, ball);
  }
  Event<Num> contact_event(const Pending& p, int ball) const {
    const int a = p.kind == EventKind::ball_ball ? std::min(ball, p.partner) : ball;
    const int b = p.kind == EventKind::ball_ball ? std::max(ball, p.partner) : p.partner;
    return Event<Num>{p.contact_time, p.kind, a, b, p.feature};
  }
  // The calendar holds ball i by its earlier pending event, or not at all.
  void place(int i) {
    const Pending& p = pending_[i];
    if (p.has_contact && p.has_crossing) {
      const Key c = contact_key(p, i), x = crossing_key(p, i);
      calendar_.set(i, KeyEarlier{}(c, x) ? c : x);
    } else if (p.has_contact) {
      calendar_.set(i, contact_key(p, i));
    } else if (p.has_crossing) {
      calendar_.set(i, crossing_key(p, i));
    } else {
      calendar_.remove(i);
    }
  }

  // A contact found for ball `owner` at `time`: kept if it is the owner's
  // earliest (and, re-asking after a contact, not before that one).
  void keep_contact(int owner, const Num& time, EventKind kind, int partner, ContactFeature feature) {
    Pending& p = pending_[owner];
    if (contacts_after_) {
      const int a = kind == EventKind::ball_ball ? std::min(owner, partner) : owner;
      const int b = kind == EventKind::ball_ball ? std::max(owner, partner) : partner;
      const Event<Num> e{time, kind, a, b, feature};
      const bool earlier = after_in_order(*contacts_after_, e);
      if (earlier || (!from_stale_ && !after_in_order(e, *contacts_after_))) return;
    }
    if (p.has_contact && !(time < p.contact_time)) {  // by the time first, the whole key at a tie
      if (p.contact_time < time) return;
      Pending q = p;
      q.kind = kind, q.partner = partner;
      if (!KeyEarlier{}(contact_key(q, owner), contact_key(p, owner))) return;
    }
    p.contact_time = time, p.kind = kind, p.partner = partner, p.feature = feature, p.has_contact = true;
    p.partner_version = kind == EventKind::ball_ball ? world_.balls[partner].version : 0;
  }

  // EventEngine::predict_pair for a gas: from the later clock; no pressed
  // contacts (nothing presses balls of one acceleration together).
  void predict_pair(int i, int j) {
    const GasBody<Num>& bi = world_.balls[i];
    const GasBody<Num>& bj = world_.balls[j];
    const Num t0 = bj.time < bi.time ? bi.time : bj.time;
    const RootSearch<Num> r = time_of_contact_ball_ball(state_at(bi, t0), state_at(bj, t0), end_ - t0);
    if (r.found) keep_contact(i, t0 + r.t, EventKind::ball_ball, j, ContactFeature::ball);
  }
  // EventEngine::predict_wall for a gas: from the ball's clock; an answer
  // before now (at a crossing) is one an earlier cell near the wall had.
  void predict_wall(int i, int w) {
    const GasBody<Num>& bi = world_.balls[i];
    const ToiResult<Num> r = time_of_impact_ball_wall(state_at(bi, bi.time), world_.walls[w], end_ - bi.time);
    if (r.hit() && !(bi.time + r.time < now_)) keep_contact(i, bi.time + r.time, EventKind::ball_wall, w, r.feature);
  }
  void predict_crossing(int i) {
    const BallState<Num> s = state_at(world_.balls[i], now_);
    const typename CellGrid<Num>::Crossing c = grid_.next_crossing_linear(i, s.position, s.velocity, end_ - now_);
    Pending& p = pending_[i];
    p.has_crossing = c.found;
    if (c.found) p.crossing_time = now_ + c.time, p.step = static_cast<std::uint8_t>(c.step);
  }
  // Ball i's motion changed (or the run starts): all its events afresh,
  // but the pairs `skip(j)` names (predicted by j).
  template <class Skip>
  void predict(int i, Skip skip) {
    pending_[i].has_contact = false;
    for (int j : neighbours_of(i))
      if (!skip(j)) predict_pair(i, j);
    for (int w : grid_.walls_near(i)) predict_wall(i, w);
    predict_crossing(i);
    place(i);
  }
  // Ball i's contact e came out stale or changed nothing: its next contact
  // from e's place on (EventEngine::predict_contacts_after).
  void predict_contacts_after(int i, const Event<Num>& e, bool stale) {
    contacts_after_ = &e;
    from_stale_ = stale;
    for (int j : neighbours_of(i)) predict_pair(i, j);
    for (int w : grid_.walls_near(i)) predict_wall(i, w);
    contacts_after_ = nullptr;
    place(i);
  }
  void predict_all() {
    calendar_.clear();
    for (Pending& p : pending_) p = Pending{};
    grid_.assign(world_, now_);
    for (int i = 0; i < static_cast<int>(world_.balls.size()); ++i) predict(i, [&](int j) { return j < i; });
  }

  template <class OnCollision>
  void process_until(const Num& until, OnCollision& on_collision);
  // Asks the memory for what the events after this one will read (in a
  // large gas each is a cache miss; prefetch.hpp): the balls, events and
  // cells of the two that come next unless this one's own new events come
  // first, and the cells around this event's balls. A hint only.
  [[gnu::always_inline]] void look_ahead(const Key& now) const {
    for (int ball : calendar_.runners_up()) {
      if (ball < 0) continue;
      const Key& next = calendar_.key(ball);
      prefetch_element(pending_, ball);
      prefetch_object(&world_.balls[static_cast<std::size_t>(next.a())]);
      grid_.prefetch_cell_of(next.a());
      if (next.kind() != static_cast<int>(EventKind::ball_ball)) continue;
      prefetch_object(&world_.balls[static_cast<std::size_t>(next.b())]);
      grid_.prefetch_cell_of(next.b());
      calendar_.prefetch(next.a() == ball ? next.b() : next.a());
    }
    grid_.prefetch_neighbourhood(now.a());
    if (now.kind() == static_cast<int>(EventKind::ball_ball)) grid_.prefetch_neighbourhood(now.b());
  }
  // Ball i's neighbours, gathered and their bodies asked for at once (the
  // misses overlap instead of coming one after another), but i itself.
  const std::vector<int>& neighbours_of(int i) {
    near_.clear();
    grid_.for_each_neighbour(i, [&](int j) {
      if (j == i) return;
      near_.push_back(j);
      prefetch_object(&world_.balls[static_cast<std::size_t>(j)]);
    });
    return near_;
  }
  std::vector<int> near_;
  void cross(int i, CellStep step);
  enum class Outcome { struck, idle, handed_over };
  template <class OnCollision>
  Outcome strike(const Event<Num>& e, OnCollision& on_collision, int same_time_before);
  // A ball of e struck already at e's instant: the rest rules' case (rule 1).
  bool jammed(const Event<Num>& e) const {
    return world_.balls[e.a].struck_at_time(e.time) ||
           (e.kind == EventKind::ball_ball && world_.balls[e.b].struck_at_time(e.time));
  }
  void hand_over(const Event<Num>& next, int same_time_events);
};

// The events up to `until`, in order. A stale contact (its partner's motion
// changed since) or one that changes nothing (creeping) is followed by the
// owner's next contact from there on.
template <class Num>
template <class OnCollision>
void GasEngine<Num>::process_until(const Num& until, OnCollision& on_collision) {
  while (!calendar_.empty()) {
    const int owner = calendar_.first();
    const Key key = calendar_.key(owner);
    if (until < key.time) return;
    look_ahead(key);
    Pending& p = pending_[owner];
    const bool crossing = key.kind() == static_cast<int>(EventKind::cell_crossing);
    const Event<Num> e = crossing ? Event<Num>{key.time, EventKind::cell_crossing, owner, p.step, ContactFeature::none}
                                  : contact_event(p, owner);
    if (crossing) {
      p.has_crossing = false;
    } else {
      p.has_contact = false;
      if (e.kind == EventKind::ball_ball && world_.balls[p.partner].version != p.partner_version) {
        ++counters_.stale;
        predict_contacts_after(owner, e, true);
        continue;
      }
    }
    const int same_time_before = same_time_events_;
    same_time_events_ = count_events_at_one_time(same_time_events_, e.time, now_, e.kind, e.a, e.b);
    now_ = e.time;
    if (crossing) {
      ++counters_.cell_crossings;
      cross(owner, static_cast<CellStep>(p.step));
      continue;
    }
    switch (strike(e, on_collision, same_time_before)) {
      case Outcome::struck: break;
      case Outcome::idle: predict_contacts_after(owner, e, false); break;
      case Outcome::handed_over: return;
    }
  }
}

// A crossing: the motion goes on; the balls and walls it may now meet are
// asked (EventEngine::process, cell_crossing).
template <class Num>
void GasEngine<Num>::cross(int i, CellStep step) {
  const std::span<const int> walls_before = grid_.walls_near(i);
  grid_.cross(i, step, [&](int j) {
    if (j != i) predict_pair(i, j);
  });
  for (int w : grid_.walls_near(i))
    if (!std::binary_search(walls_before.begin(), walls_before.end(), w)) predict_wall(i, w);
  predict_crossing(i);
  place(i);
}

// Contact e, current: EventEngine::process and collide_in_gas, call for
// call (the same arithmetic in the same order, the −0 of a carry to the
// present included): idle if it changed nothing (creeping); a jam is
// handed over unprocessed.
template <class Num>
template <class OnCollision>
typename GasEngine<Num>::Outcome GasEngine<Num>::strike(const Event<Num>& e, OnCollision& on_collision,
                                                        int same_time_before) {
  auto carry = [](GasBody<Num>& b, const Num& t) {
    collide2d::advance_to(b, t);
    b.time = t;
  };
  const bool pair = e.kind == EventKind::ball_ball;
  GasBody<Num>& a = world_.balls[e.a];
  GasBody<Num>* b = pair ? &world_.balls[e.b] : nullptr;
  Collision<Num>& c = collision_;
  // A body changes only at its own strikes here: as it is now, it is where
  // its present piece of path began.
  c.piece_start_a = {a.position, a.velocity, a.time};
  if (pair) c.piece_start_b = {b->position, b->velocity, b->time};
  GasBody<Num> a_then = a, b_then;
  carry(a_then, e.time);
  Vec2<Num> n, relative_velocity = a_then.velocity, relative_acceleration = a_then.acceleration;
  if (pair) {
    b_then = *b;
    carry(b_then, e.time);
    n = normalized(a_then.position - b_then.position);
    relative_velocity = a_then.velocity - b_then.velocity;
    relative_acceleration = a_then.acceleration - b_then.acceleration;
  } else {
    n = wall_contact_normal(world_.walls[e.b], e.feature, a_then.position);
  }
  if (is_creeping(n, relative_velocity, relative_acceleration, thresholds_)) {
    ++counters_.rest.creeping;
    return Outcome::idle;
  }
  if (jammed(e)) {
    hand_over(e, same_time_before);
    return Outcome::handed_over;
  }
  a = a_then;
  if (pair) *b = b_then, ++counters_.ball_ball;
  else ++counters_.ball_wall;
  carry(a, now_);  // as collide_in_gas carries its island (a no-op but for −0)
  if (pair) carry(*b, now_);
  const Num restitution =
      contact_restitution(world_.restitution_of(e.a), pair ? world_.restitution_of(e.b) : world_.wall_restitution[e.b]);
  c.impulse = ContactRules<Num>::textbook_response(a, b, true, pair, n, restitution);
  // (Its clock is e's instant from here on: struck_at() is e.time.)
  ++a.version;
  if (pair) ++b->version;
  c.time = e.time, c.kind = e.kind, c.a = e.a, c.b = e.b;
  on_collision(c);
  carry(a, now_);
  if (pair) carry(*b, now_);
  // (The forces of a lone ball in a gas are its own acceleration, which it
  // has.) Both balls take their new versions before either predicts, as in
  // collide_in_gas: a contact of the two found at once is current.
  ++a.version;
  if (pair) ++b->version;
  predict(e.a, [](int) { return false; });
  if (pair) predict(e.b, [&](int j) { return j == e.a; });
  return Outcome::struck;
}

// A jam at e: the general engine takes the world and goes on from e, which
// it predicts again with every other current contact.
template <class Num>
void GasEngine<Num>::hand_over(const Event<Num>& next, int same_time_events) {
  World<Num> world = world_of(world_);
  if (on_hand_over_) on_hand_over_(world);
  general_ = std::make_unique<EventEngine<Num>>(std::move(world), thresholds_);
  general_->take_over_gas(now_, end_, next, counters_, same_time_events, std::move(grid_));
  handed_over_at_ = now_;
  world_.balls.clear();
  world_.restitution.clear();
  pending_.clear();
  calendar_.clear();
}

template <class Num>
void GasEngine<Num>::save(ByteWriter& out) const {
  out.put(checkpoint_layout);
  out.put(static_cast<std::uint8_t>(general_ != nullptr));
  if (general_) {
    out.put(handed_over_at_);
    return general_->save(out);
  }
  out.put(now_);
  out.put(end_);
  out.put(static_cast<std::uint8_t>(primed_));
  out.put(static_cast<std::int32_t>(same_time_events_));
  for (std::uint64_t x : {counters_.ball_ball, counters_.ball_wall, counters_.stale, counters_.cell_crossings,
                          counters_.rest.creeping})
    out.put(x);
  out.put(static_cast<std::uint64_t>(world_.balls.size()));
  for (std::size_t i = 0; i < world_.balls.size(); ++i) {
    const GasBody<Num>& b = world_.balls[i];
    for (const Vec2<Num>* v : {&b.position, &b.velocity}) out.put(*v);
    out.put(b.time);
    out.put(b.struck_at());
    out.put(b.version);
    const Pending& p = pending_[i];
    out.put(static_cast<std::uint8_t>(p.has_contact | p.has_crossing << 1));
    if (p.has_contact) {
      out.put(p.contact_time);
      out.put(static_cast<std::uint8_t>(p.kind));
      out.put(static_cast<std::uint8_t>(p.feature));
      out.put(static_cast<std::int32_t>(p.partner));
      out.put(p.partner_version);
    }
    if (p.has_crossing) out.put(p.crossing_time), out.put(p.step);
  }
  if (primed_) grid_.save(out);
}

template <class Num>
void GasEngine<Num>::load(ByteReader& in) {
  std::uint32_t layout = 0;
  in.get(layout);
  if (layout != checkpoint_layout)
    throw std::runtime_error("checkpoint of gas layout " + std::to_string(layout) + ", this build reads layout " +
                             std::to_string(checkpoint_layout) + ": resume it with the collide2d that wrote it");
  std::uint8_t general = 0;
  in.get(general);
  if (general) {
    in.get(handed_over_at_);
    general_ = std::make_unique<EventEngine<Num>>(world_of(world_), thresholds_);
    general_->adopt_grid(std::move(grid_));
    general_->load(in);
    world_.balls.clear();
    pending_.clear();
    return;
  }
  in.get(now_);
  in.get(end_);
  std::uint8_t primed = 0;
  in.get(primed);
  primed_ = primed != 0;
  std::int32_t same_time = 0;
  in.get(same_time);
  if (same_time < 0 || same_time > max_events_at_one_time) throw std::runtime_error("checkpoint holds a count of events at one time out of range");
  same_time_events_ = same_time;
  for (std::uint64_t* x : {&counters_.ball_ball, &counters_.ball_wall, &counters_.stale, &counters_.cell_crossings,
                           &counters_.rest.creeping})
    in.get(*x);
  std::uint64_t n = 0;
  in.get(n);
  if (n != world_.balls.size()) throw std::runtime_error("checkpoint holds a different number of balls");
  const auto balls = static_cast<int>(n);
  calendar_.clear();
  for (int i = 0; i < balls; ++i) {
    GasBody<Num>& b = world_.balls[i];
    for (Vec2<Num>* v : {&b.position, &b.velocity}) in.get(*v);
    Num struck_at{};
    in.get(b.time);
    in.get(struck_at);
    in.get(b.version);
    if (!(struck_at == b.struck_at()))
      throw std::runtime_error("checkpoint holds a gas's ball struck at another time than its clock");
    Pending& p = pending_[i];
    p = Pending{};
    std::uint8_t has = 0;
    in.get(has);
    if (has > 3) throw std::runtime_error("checkpoint holds a ball's events in no known form");
    p.has_contact = has & 1, p.has_crossing = has & 2;
    if (p.has_contact) {
      std::uint8_t kind = 0, feature = 0;
      std::int32_t partner = 0;
      in.get(p.contact_time);
      in.get(kind);
      in.get(feature);
      in.get(partner);
      in.get(p.partner_version);
      p.kind = static_cast<EventKind>(kind), p.feature = static_cast<ContactFeature>(feature), p.partner = partner;
      const bool ok = (p.kind == EventKind::ball_ball && partner >= 0 && partner < balls && partner != i) ||
                      (p.kind == EventKind::ball_wall && partner >= 0 && partner < static_cast<int>(world_.walls.size()));
      if (!ok || feature > static_cast<std::uint8_t>(ContactFeature::wall_end_b))
        throw std::runtime_error("checkpoint holds an event of no ball or wall of the scene");
    }
    if (p.has_crossing) {
      in.get(p.crossing_time);
      in.get(p.step);
    }
  }
  if (primed_) {
    grid_.load(in);
    for (int i = 0; i < balls; ++i)
      if (pending_[i].has_crossing && !grid_.step_stays_inside(i, pending_[i].step))
        throw std::runtime_error("checkpoint holds a cell crossing off the grid");
  }
  for (int i = 0; i < balls; ++i) place(i);
}

}  // namespace collide2d
