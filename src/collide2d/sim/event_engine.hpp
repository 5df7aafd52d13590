// The event-driven engine: exact event order, deterministic ties.
//
// Time advances from event to event; nothing is stepped. Between record
// times T_k = k Δ every ball moves on its exact parabola, each pair's next
// contact is predicted by the analytic time of impact, and the earliest
// event is processed first, in (time, kind, a, b) order (event_queue.hpp).
// How record times meet the motion depends on the scene (simulate.hpp):
//  - Without accelerations (a gas), record times do not touch the motion:
//    run_to carries nothing and keeps every prediction (made once, to the
//    end of the run), a frame reads each ball's state at T_k from its own
//    clock, and a checkpoint holds the queue itself, so a resumed
//    run goes on with the very predictions the uninterrupted one had. The
//    record interval changes what is written, never the run.
//  - Under accelerations, advance_to carries every ball to T_k and the
//    prediction starts afresh for [T_k, T_k+1]: a horizon of one record
//    interval. A parabola's time of impact over a long horizon is costly in
//    fixed point, and a settling pile's predictions rarely live long
//    (README, "Frames that keep predictions"). The step engine's steps are
//    runs of their own the same way.
//
// Only neighbours are predicted against each other (cell_grid.hpp); a pair
// is always predicted from the later of the two balls' clocks, so the grid
// changes the cost of a run, never its bits.
//
// What a contact does, and the rules that bring balls to rest (persistent
// contacts, sleep) and wake them, are in contact_rules.hpp, contact_graph.hpp
// and rest.hpp. This file decides when: after each contact it solves the
// forces of the islands involved, lets their balls fall asleep if they can,
// wakes what a strike wakes, and predicts again for every ball whose motion
// changed. A sleeping ball is static, like a fixed one: it makes no events of
// its own and is predicted against as an obstacle.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "collide2d/sim/cell_grid.hpp"
#include "collide2d/sim/contact_graph.hpp"
#include "collide2d/sim/contact_rules.hpp"
#include "collide2d/sim/event_queue.hpp"
#include "collide2d/sim/prefetch.hpp"
#include "collide2d/sim/state_bytes.hpp"
#include "collide2d/sim/world.hpp"
#include "collide2d/toi/article_methods.hpp"

namespace collide2d {

struct EngineStall : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// What changed a ball's motion, as the engine tells its observer (below).
enum class MotionChange {
  response,  // the response to a collision (contact_rules.hpp): velocities of an island
  renewed,   // a contact renewed where it slid off a round partner (ContactRules::renew): velocities of an island
  forces,    // the ball's island's contact forces solved again (its acceleration; after a hold, its velocity)
  sleep,     // it fell asleep (rest.hpp, rule 2): velocity and acceleration zero
  wake,      // it woke (rule 3)
};

// The engine's observer: told of every change of a ball's motion, right
// after the change, with the ball carried to the engine's present time and
// its version (Body::version) one higher than before. Every change is told,
// wherever the engine makes it: in a collision's response and outside any
// collision callback (a contact left or renewed, forces solved again, sleep,
// wake), so that a trace of the motion (properties/engine_trace.hpp) sees
// every piece of every ball's path. The default observer does nothing and
// costs nothing: simulate() and the command line use it.
// An observer may also have ball_ball_asked(BallState a, BallState b, Num
// horizon) and ball_wall_asked(BallState a, int wall, Num horizon): then it
// is told of every time-of-impact query the engine asks (lab/engine_queries
// gathers the engine's own query mix with them).
struct NoMotionObserver {
  template <class Num>
  void motion_changed(const World<Num>&, int, MotionChange) {}
};

struct EngineCounters {
  std::uint64_t ball_ball = 0, ball_wall = 0, leave_wall = 0, leave_pair = 0, stale = 0;
  std::uint64_t cell_crossings = 0;
  std::uint64_t ignored = 0;  // contacts a method reported for objects moving apart
  RestCounters rest;          // what the rest rules did (rest.hpp)
  IslandSolveCounters islands;  // what their island solves cost (contact_graph.hpp)
};

template <class Num, class Observer = NoMotionObserver>
class EventEngine {
 public:
  // `method`: how contacts are predicted. analytic is exact; bisection and
  // seed (the article's, tolerance `eps`) are for the step engine, which is
  // this engine advanced one step at a time (see simulate.hpp).
  // `one_cell`: predict every pair (no grid); the results are the same bits.
  // `observer`: told of every change of a ball's motion (NoMotionObserver).
  EventEngine(World<Num> world, const RestThresholds<Num>& thresholds, ToiMethod method = ToiMethod::analytic,
              const Num& eps = Num{}, bool one_cell = false, Observer observer = {})
      : world_(std::move(world)), rules_(thresholds), method_(method), eps_(eps),
        grid_(world_, one_cell, NumberTraits<Num>::to_double(thresholds.band)), observer_(std::move(observer)) {
    graph_.reset(world_.balls.size());
    queue_.reserve(world_.balls.size());
    queue_.keep_earliest_contact_only(keeps_predictions_);
  }

  const World<Num>& world() const { return world_; }
  World<Num>& world() { return world_; }
  EngineCounters counters() const {
    EngineCounters c = counters_;
    c.rest = rules_.counters;
    c.islands = graph_.solve_counters;
    return c;
  }
  const Num& now() const { return now_; }
  // Whether a plain strike in a gas takes collide_in_gas (the default) or
  // the general collide() and settle(): the same bits either way.
  void use_plain_gas_path(bool on) { plain_gas_path_ = on && plain_gas_scene(); }
  // Whether a gas's queue keeps each ball's earliest contact only (the
  // default) or every prediction, as under accelerations (event_queue.hpp):
  // the same bits either way. Before the first event.
  void keep_earliest_contact_only(bool on) { queue_.keep_earliest_contact_only(on && keeps_predictions_); }
  const Num& energy_removed_by_rest() const { return rules_.energy_removed; }
  // No ball accelerates (a gas: straight paths, no rest rules): run_to keeps
  // the predictions across record times.
  bool keeps_predictions() const { return keeps_predictions_; }
  bool all_at_rest() const {
    return std::all_of(world_.balls.begin(), world_.balls.end(), [](const Body<Num>& b) { return b.is_static(); });
  }

  // Processes every event up to `until` (inclusive) and carries all balls
  // there, predicting afresh within [now, until] (record times under
  // accelerations; each step of the step engine). `on_collision(const
  // Collision<Num>&)` sees each collision in order.
  template <class OnCollision>
  void advance_to(const Num& until, OnCollision on_collision) {
    predict_all(until);
    process_until(until, until, on_collision);
    for (Body<Num>& b : world_.balls) advance_to_time(b, until);
    now_ = until;
    primed_ = false;
  }

  // The event engine from one record time to the next: every event up to
  // `until` (inclusive). A gas (keeps_predictions) predicts to `end`, the
  // run's end, the same at every call, and leaves every ball on its own
  // clock: the predictions stay good and are kept; the first call predicts
  // every ball. Under accelerations this is advance_to(until).
  template <class OnCollision>
  void run_to(const Num& until, const Num& end, OnCollision on_collision) {
    if (!keeps_predictions_) return advance_to(until, on_collision);
    if (!primed_ || !(end == end_)) predict_all(end);
    primed_ = true;
    end_ = end;
    process_until(until, end, on_collision);
    now_ = until;
  }

 private:
  void predict_all(const Num& end) {
    queue_.clear();
    grid_.assign(world_, now_);
    for (int i = 0; i < static_cast<int>(world_.balls.size()); ++i)
      predict(i, end, [&](int j) { return j < i && !world_.balls[j].is_static(); });
  }

  // Events up to `until`, each predicted again within `end`.
  template <class OnCollision>
  void process_until(const Num& until, const Num& end, OnCollision& on_collision) {
    while (!queue_.empty() && !(until < queue_.top().time)) {
      const PoppedEvent<Num> popped = queue_.pop();
      const Event<Num>& e = popped.event;
      queue_.prefetch_next([&](int k) __attribute__((always_inline)) {
        prefetch_object(&world_.balls[static_cast<std::size_t>(k)]);
        grid_.prefetch_cell_of(k);
      });
      // The look-ahead of the event before asked for these balls' cell
      // numbers; now the cells around them, which predict() reads.
      grid_.prefetch_neighbourhood(e.a);
      if (between_two_balls(e.kind)) grid_.prefetch_neighbourhood(e.b);
      // The owner's earliest contact, out of the queue with its owner's
      // motion as predicted: its next contact is asked for again after it.
      auto owner_as_predicted = [&] {
        return popped.contact && world_.balls[static_cast<std::size_t>(popped.owner)].version == popped.owner_version;
      };
      if (!current(e)) {
        ++counters_.stale;
        if (owner_as_predicted()) predict_contacts_after(popped.owner, e, end, true);
        continue;
      }
      // A run of events that never lets time advance is a stall (a contact the
      // model cannot resolve): report it rather than loop forever.
      same_time_events_ = e.time == now_ ? same_time_events_ + 1 : 0;
      if (same_time_events_ > max_events_at_one_time)
        throw EngineStall("engine stalled: more than " + std::to_string(max_events_at_one_time) +
                          " events at one time, last between ball " + std::to_string(e.a) + " and " +
                          (e.kind == EventKind::ball_ball ? "ball " : "wall ") + std::to_string(e.b));
      now_ = e.time;
      const bool as_predicted = owner_as_predicted();
      process(e, end, on_collision);
      if (as_predicted && owner_as_predicted()) predict_contacts_after(popped.owner, e, end, false);
    }
  }

 public:
  // The whole mutable state at a record time (checkpoints): the clock, the
  // counters, the rest rules' energy tallies, every body on its own clock,
  // the contact graph, and (from run_to) the pending events and each ball's
  // cell. Walls never change and are not stored. The layout's version leads,
  // so that a checkpoint of another layout is refused by name instead of
  // misread (4: wall contacts in the contact graph, no faces; 6: the island
  // solves' counters; 7: the queue and the cells, from run_to; 8: a ball's
  // earliest contact, crossing and contact ends in the queue, not a list).
  static constexpr std::uint32_t checkpoint_layout = 8;

  void save(ByteWriter& out) const {
    out.put(checkpoint_layout);
    out.put(now_);
    for (const std::uint64_t* c : counter_fields(const_cast<EngineCounters&>(counters_), const_cast<RestCounters&>(rules_.counters),
                                                 const_cast<IslandSolveCounters&>(graph_.solve_counters)))
      out.put(*c);
    out.put(rules_.energy_removed);
    out.put(static_cast<std::uint64_t>(world_.balls.size()));
    for (const Body<Num>& b : world_.balls) {
      for (const Vec2<Num>* v : {&b.position, &b.velocity, &b.acceleration, &b.free_acceleration}) out.put(*v);
      for (const Num* x : {&b.time, &b.radius, &b.mass, &b.restitution, &b.struck_at}) out.put(*x);
      out.put(static_cast<std::uint8_t>(b.fixed));
      out.put(static_cast<std::uint8_t>(b.asleep));
      out.put(b.version);
    }
    graph_.save(out);
    out.put(static_cast<std::uint8_t>(primed_));
    if (!primed_) return;
    out.put(end_);
    queue_.save(out);
    grid_.save(out);
  }
  void load(ByteReader& in) {
    std::uint32_t layout = 0;
    in.get(layout);
    if (layout != checkpoint_layout)
      throw std::runtime_error("checkpoint of layout " + std::to_string(layout) + ", this build reads layout " +
                               std::to_string(checkpoint_layout) + ": resume it with the collide2d that wrote it");
    in.get(now_);
    for (std::uint64_t* c : counter_fields(counters_, rules_.counters, graph_.solve_counters)) in.get(*c);
    in.get(rules_.energy_removed);
    std::uint64_t n = 0;
    in.get(n);
    if (n != world_.balls.size()) throw std::runtime_error("checkpoint holds a different number of balls");
    for (Body<Num>& b : world_.balls) {
      for (Vec2<Num>* v : {&b.position, &b.velocity, &b.acceleration, &b.free_acceleration}) in.get(*v);
      for (Num* x : {&b.time, &b.radius, &b.mass, &b.restitution, &b.struck_at}) in.get(*x);
      std::uint8_t fixed = 0, asleep = 0;
      in.get(fixed);
      in.get(asleep);
      in.get(b.version);
      b.fixed = fixed != 0;
      b.asleep = asleep != 0;
    }
    graph_.load(in);
    std::uint8_t primed = 0;
    in.get(primed);
    primed_ = primed != 0;
    if (!primed_) return;
    in.get(end_);
    queue_.load(in);
    grid_.load(in);
  }

 private:
  World<Num> world_;
  ContactRules<Num> rules_;
  ToiMethod method_;
  Num eps_;
  CellGrid<Num> grid_;
  ContactGraph<Num> graph_;
  Num now_{};
  EngineCounters counters_;
  int same_time_events_ = 0;
  static constexpr int max_events_at_one_time = 100000;
  EventQueue<Num> queue_;
  bool keeps_predictions_ = no_ball_accelerates(world_);  // fixed by the scene
  bool primed_ = false;  // run_to: the queue holds every prediction to end_
  Num end_{};
  // Scratch lists of an event, kept so that their storage is reused.
  std::vector<int> changed_, island_, neighbours_;
  std::vector<std::uint64_t> judged_;  // settle(): the judgement in which a ball's island was found unable to sleep
  std::uint64_t judgement_ = 0;
  Collision<Num> gas_collision_;  // collide_in_gas's answer, its vectors reused
  const Event<Num>* contacts_after_ = nullptr;  // predict_contacts_after: only contacts from this one on are pushed
  bool contacts_from_stale_ = false;            // ... this one's key included (it was stale)
  bool plain_gas_path_ = plain_gas_scene();  // fixed by the scene and the method (plain_gas_strike)
  [[no_unique_address]] Observer observer_;

  // Ball x's motion has just changed (it is carried to now): a new version,
  // so that every prediction made from its old motion is stale, and the
  // observer is told. Every change of motion goes through here.
  void motion_changed(int x, MotionChange why) {
    ++world_.balls[x].version;
    observer_.motion_changed(world_, x, why);
  }

  static std::vector<std::uint64_t*> counter_fields(EngineCounters& c, RestCounters& r, IslandSolveCounters& s) {
    return {&c.ball_ball,     &c.ball_wall,     &c.leave_wall,    &c.leave_pair,    &c.stale,         &c.cell_crossings,
            &c.ignored,       &r.came_to_rest,  &r.fell_asleep,   &r.woken,         &r.plastic_pairs,
            &r.creeping,      &r.held,          &r.renewed,       &s.impact_solves, &s.force_solves,
            &s.rows,          &s.rounds,        &s.largest};
  }

  static void advance_to_time(Body<Num>& b, const Num& t) {
    if (!b.is_static()) collide2d::advance_to(b, t);
    b.time = t;
  }

  bool current(const Event<Num>& e) const {
    if (world_.balls[e.a].version != e.version_a) return false;
    return !between_two_balls(e.kind) || world_.balls[e.b].version == e.version_b;
  }

  // `owner`: the moving ball whose prediction this is (its place in the queue).
  void push(Event<Num> e, int owner) {
    if (contacts_after_ && is_contact(e.kind)) {
      const bool earlier = after_in_order(*contacts_after_, e);
      const bool same_place = !earlier && !after_in_order(e, *contacts_after_);
      if (earlier || (same_place && !contacts_from_stale_)) return;
    }
    const std::uint64_t owner_version = world_.balls[owner].version;
    if (!queue_.would_keep(e, owner, owner_version)) return;
    e.version_a = world_.balls[e.a].version;
    if (between_two_balls(e.kind)) e.version_b = world_.balls[e.b].version;
    queue_.push(e, owner, owner_version);
  }

  // Every future event of moving ball i within [now, until]: against its
  // neighbours but those `skip(j)` names (pairs predicted elsewhere) and
  // those it is in contact with, the walls near its cell, the end of each of
  // its contacts, and leaving its cell.
  template <class Skip>
  void predict(int i, const Num& until, Skip skip) {
    const Body<Num>& bi = world_.balls[i];
    if (bi.is_static()) return;
    for (int j : neighbours_of(i, skip)) predict_pair(i, j, until);
    const Num horizon = until - now_;
    const BallState<Num> si = state_at(bi, now_);
    for (int w : grid_.walls_near(i)) predict_wall(i, w, until);
    graph_.for_each_contact_of(i, [&](const PersistentContact<Num>& c) {
      const int partner = c.partner_of(i);
      if (i == c.i || partner < 0 || world_.balls[partner].is_static()) predict_contact_ending(c, horizon, i);
    });
    predict_crossing(i, si, horizon);
  }

  // The next contact of moving ball i with wall w, predicted from the ball's
  // clock (the last change of its motion), so that a wall first met at a
  // cell crossing gives the same answer as at that change. In contact with a
  // wall's face, the ball cannot meet its ends; on the tangent at an end its
  // centre stays outside that end's circle, and cannot reach the face: a
  // contact with the feature it touches, or with the face from an end, is a
  // rounding echo. At a crossing (`now_` past the clock) an answer before now
  // is one the ball had from an earlier cell near the wall too, and handled.
  void predict_wall(int i, int w, const Num& until) {
    const Body<Num>& bi = world_.balls[i];
    const PersistentContact<Num>* touching = graph_.with_wall(i, w);
    if (touching && touching->feature == ContactFeature::wall_face) return;
    const ContactFeature resting_on = touching ? touching->feature : ContactFeature::none;
    const BallState<Num> si = state_at(bi, bi.time);
    const Num horizon = until - bi.time;
    if constexpr (requires(Observer& o) { o.ball_wall_asked(si, w, horizon); }) observer_.ball_wall_asked(si, w, horizon);
    const ToiResult<Num> r = wall_contact(si, w, horizon);
    if (r.hit() && !(touching && (r.feature == resting_on || r.feature == ContactFeature::wall_face)) &&
        !(bi.time + r.time < now_))
      push({bi.time + r.time, EventKind::ball_wall, i, w, r.feature}, i);
    // A ball a hair inside the wall by rounding and pressed into it meets it
    // now, whatever later event the time of impact may also find with this
    // wall (an end beside the ball): the earlier event is taken, and the
    // other is stale once the ball's motion changes.
    if (method_ == ToiMethod::analytic && !(r.hit() && r.time == Num{}))
      predict_pressed_on_wall(i, si, w, horizon, resting_on);
  }
  void predict(int i, const Num& until) {
    predict(i, until, [](int) { return false; });
  }

  // Ball i's neighbours but those `skip(j)` names. They are gathered first
  // and their bodies asked for from memory all at once: in a large gas each
  // is a cache miss, and the misses then overlap instead of coming one
  // after another.
  template <class Skip>
  const std::vector<int>& neighbours_of(int i, Skip skip) {
    std::vector<int>& near = neighbours_;
    near.clear();
    grid_.for_each_neighbour(i, [&](int j) {
      if (j == i || skip(j)) return;
      near.push_back(j);
      prefetch_object(&world_.balls[j]);
    });
    return near;
  }

  // Moving ball i's kept contact `e` came out of the queue and left i's
  // motion as it was (event_queue.hpp): its next contact from e on, against
  // every neighbour and wall near. The contacts it had predicted come out
  // the same, to the bit, for they depend on the clocks alone; a contact
  // with a partner that has changed since is also that partner's
  // prediction, and held there. After e itself (processed, and changing
  // nothing: asked again, it would come back), or, if e was `stale`, from
  // e's place in the order on: the queue kept e over a copy equal in (time,
  // kind, a, b) but predicted from the partner's new motion, pushed later.
  void predict_contacts_after(int i, const Event<Num>& e, const Num& until, bool stale) {
    if (world_.balls[i].is_static()) return;
    contacts_after_ = &e;
    contacts_from_stale_ = stale;
    for (int j : neighbours_of(i, [](int) { return false; })) predict_pair(i, j, until);
    for (int w : grid_.walls_near(i)) predict_wall(i, w, until);
    contacts_after_ = nullptr;
  }

  // The next contact of balls i (moving) and j, predicted from the later of
  // their clocks (the last change of either's motion): the answer depends
  // only on the two motions, never on when, or whether, the grid asks for it.
  // None for two balls in contact (the end of their contact is the event).
  void predict_pair(int i, int j, const Num& until) {
    const Body<Num>& bi = world_.balls[i];
    const Body<Num>& bj = world_.balls[j];
    if (bi.is_static() && bj.is_static()) return;
    if (graph_.touching(i, j)) return;
    // The clock first: the neighbour's flags are on its second cache line.
    const Num t0 = bj.time < bi.time || bj.fixed ? bi.time : bj.time;
    const BallState<Num> si = state_at(bi, t0), sj = state_at(bj, t0);
    const Num horizon = until - t0;
    if constexpr (requires(Observer& o) { o.ball_ball_asked(si, sj, horizon); }) observer_.ball_ball_asked(si, sj, horizon);
    const RootSearch<Num> r = method_ == ToiMethod::analytic ? time_of_contact_ball_ball(si, sj, horizon)
                                                             : bisection_contact(si, sj, horizon);
    if (r.found) {
      push({t0 + r.t, EventKind::ball_ball, std::min(i, j), std::max(i, j), ContactFeature::ball}, i);
      return;
    }
    // Nothing presses two balls of the same acceleration together (Δp·Δa =
    // 0, never below −least_press ≤ 0): no pressed contact, and a gas skips
    // forming its arguments.
    if (si.acceleration == sj.acceleration) return;
    const Vec2<Num> dp = si.position - sj.position, dv = si.velocity - sj.velocity, da = si.acceleration - sj.acceleration;
    const Num R = si.radius + sj.radius;
    const RootSearch<Num> pressed =
        pressed_contact_due(dp, dv, da, R, largest_magnitude(si.position) + largest_magnitude(sj.position) + R, horizon,
                            [&](const Num& t) { return within_reach(position_at(dp, dv, da, t), R); });
    if (pressed.found)
      push({t0 + pressed.t, EventKind::ball_ball, std::min(i, j), std::max(i, j), ContactFeature::ball}, i);
  }

  // An offset of at most R + h_rest between centres (or from a wall's nearest point).
  bool within_reach(const Vec2<Num>& offset, const Num& R) const {
    const Num reach = R + rules_.thresholds().height;
    return !(reach * reach < length_squared(offset));
  }

  // Pressed together while touching. Rounding can leave a pair (Δp the
  // offset between centres, or from a wall's nearest point; R the contact
  // distance) a hair inside contact, where the gap never crosses zero again
  // and no time of impact exists; the contact is then due when their normal
  // separating speed has fallen to zero: t = (Δp·Δv) / −(Δp·Δa) for
  // Δp·Δv ≥ 0, at once otherwise. Only while the rise before that,
  // s_n² / 2|a_n| = (Δp·Δv)² / (2 |Δp·Δa| |Δp|), stays within h_rest
  // (|Δp| ≈ R): a larger rise would take them apart, and the time of impact
  // would have seen them come back. Motion along the tangent of a round
  // partner (another ball, a wall's end) carries them apart as well, which
  // the normal speed does not see: the contact is due only if at that time
  // the caller's `still_touching(t)` holds, the pair within h_rest of
  // touching (a ball hopping straight up from a wall's end it was pressed
  // against sideways is not on it at the top of its hop).
  //
  // Rounding is measured against `scale`, the largest coordinate the offset
  // was formed from: a double rounds positions to 2^-53 of their magnitude,
  // so far from the origin (2^26, with balls of radius 2^-10) a ball left on
  // a wall after a bounce can be inside it by 1e-8, more than its next hop
  // rises (a hop of 3e-9 never brings the gap back above zero, and the time
  // of impact finds no root). Touching therefore counts to within ρ = 2^-50
  // of the scale (the offset's few roundings, 2^-53 of it each), and the
  // rise that keeps the contact is h_rest plus the depth it starts at: a
  // rise that cannot clear the contact is no flight. (A margin of ρ on the
  // rise as well made hops of a quarter radius contacts in a scene at 2^29
  // with balls of radius 2^-18, and stalled it.)
  template <class StillTouching>
  RootSearch<Num> pressed_contact_due(const Vec2<Num>& dp, const Vec2<Num>& dv, const Vec2<Num>& da, const Num& R,
                                      const Num& scale, const Num& horizon, StillTouching still_touching) const {
    const Num zero{};
    const Num pressing = dot(dp, da);
    // Touching to rounding counts: the time of impact finds no root for a
    // gap of a few ulps of R either (its band test and this one round apart).
    const Num rounding = num<Num>(0x1p-50) * scale;
    const Num R2 = R * R, reach_relative = R2 + R2 * num<Num>(0x1p-40), reach_absolute = (R + rounding) * (R + rounding);
    const Num reach_squared = reach_relative < reach_absolute ? reach_absolute : reach_relative;
    const Num offset_squared = length_squared(dp);
    if (!(pressing < -rules_.thresholds().least_press) || reach_squared < offset_squared) return {};
    const Num separating = dot(dp, dv);
    // rise = s² / (2 |p| R) with s = Δp·Δv, p = Δp·Δa; depth ≈ (R² − |Δp|²) / 2R.
    // The depth is not bounded by the rounding: a ball that cannot rise out
    // of an overlap of any depth has no time of impact either, and would
    // sink on without this contact.
    const Num depth_term = offset_squared < R2 ? -pressing * (R2 - offset_squared) : zero;
    const Num keeps_contact = num<Num>(2.0) * -pressing * R * rules_.thresholds().height + depth_term;
    if (keeps_contact < separating * separating) return {};
    if (horizon * -pressing < separating) return {};  // not within the horizon (and no division that could overflow)
    const Num due = separating < zero ? zero : separating / -pressing;
    if (zero < due && !still_touching(due)) return {};
    return {true, due};
  }

  // The wall's counterpart of a pair left a hair inside contact (see
  // pressed_contact_due): the ball touches the wall's nearest point q, is
  // pressed towards it (Δp·a < 0 with Δp = p − q) and no time of impact
  // exists. The contact is due when it stops moving away from q.
  // `resting_on`: the end of this wall the ball is in contact with (its
  // centre stays outside that end's circle: an echo, not a contact).
  void predict_pressed_on_wall(int i, const BallState<Num>& s, int w, const Num& horizon, ContactFeature resting_on) {
    if (s.acceleration == Vec2<Num>{}) return;  // nothing presses it on the wall (as for a pair, above)
    ContactFeature feature = ContactFeature::none;
    const Vec2<Num> q = nearest_point(world_.walls[w], s.position, &feature);
    if (feature == resting_on) return;
    // Still touching: within h_rest of the wall (its face or either end,
    // whichever is nearest then), wherever along it the ball has moved.
    auto still_touching = [&](const Num& t) {
      if (feature == ContactFeature::wall_face) return true;
      const Vec2<Num> p = position_at(s, t);
      return within_reach(p - nearest_point(world_.walls[w], p), s.radius);
    };
    const RootSearch<Num> pressed =
        pressed_contact_due(s.position - q, s.velocity, s.acceleration, s.radius,
                            largest_magnitude(s.position) + largest_magnitude(q) + s.radius, horizon, still_touching);
    const Num due = world_.balls[i].time + pressed.t;
    if (pressed.found && !(due < now_)) push({due, EventKind::ball_wall, i, w, feature}, i);
  }

  void predict_crossing(int i, const BallState<Num>& s, const Num& horizon) {
    const typename CellGrid<Num>::Crossing c = grid_.next_crossing(i, s, horizon, now_);
    if (c.found) push({now_ + c.time, EventKind::cell_crossing, i, static_cast<int>(c.step), ContactFeature::none}, i);
  }

  RootSearch<Num> bisection_contact(const BallState<Num>& si, const BallState<Num>& sj, const Num& horizon) const {
    const ToiResult<Num> r = bisection_ball_ball(si, sj, horizon, eps_);
    return {r.hit(), r.time};
  }

  ToiResult<Num> wall_contact(const BallState<Num>& s, int w, const Num& horizon) const {
    switch (method_) {
      case ToiMethod::analytic: return time_of_impact_ball_wall(s, world_.walls[w], horizon);
      case ToiMethod::bisection: return bisection_ball_wall(s, world_.walls[w].segment, horizon, eps_);
      case ToiMethod::seed: return seed_ball_wall(s, world_.walls[w].segment, horizon);
    }
    return {};
  }

  // When a point moving as p + v t + ½ a t² along the unit tangent t first
  // leaves lo < t·(p − origin) < hi: along(t) = C + 2 b t + A t² falls
  // through lo, or rises through hi.
  RootSearch<Num> first_exit(const Vec2<Num>& tangent, const Vec2<Num>& p, const Vec2<Num>& v, const Vec2<Num>& a,
                             const Vec2<Num>& origin, const Num& lo, const Num& hi, const Num& horizon) const {
    using T = NumberTraits<Num>;
    auto first_root = [&](Num A, Num b, Num C) {
      normalise_quadratic(A, b, C);
      return first_downward_root(A, b, C, [&] { return compensated_discriminant(A, b, C); }, horizon);
    };
    const Num A = T::half(dot(tangent, a)), b = T::half(dot(tangent, v));
    const Num C = dot(tangent, p - origin);
    const RootSearch<Num> past_lo = first_root(A, b, C - lo);
    const RootSearch<Num> past_hi = first_root(-A, -b, hi - C);
    RootSearch<Num> first = past_lo;
    if (past_hi.found && (!first.found || past_hi.t < first.t)) first = past_hi;
    return first;
  }

  // A persistent contact (contact_graph.hpp) ends when its offset (p_i − p_j,
  // or p_i against a wall) has slid out of (lo, hi) along its tangent.
  void predict_contact_ending(const PersistentContact<Num>& c, const Num& horizon, int owner) {
    const BallState<Num> si = state_at(world_.balls[c.i], now_);
    Vec2<Num> p = si.position, v = si.velocity, a = si.acceleration;
    if (!c.with_wall()) {
      const BallState<Num> sj = state_at(world_.balls[c.j], now_);
      p = p - sj.position, v = v - sj.velocity, a = a - sj.acceleration;
    }
    // Past an end of its range already (two contacts made at one instant,
    // with one range, reach its end at one instant too: the first to be
    // processed re-predicts the other from there, a rounding past it), it
    // ends now; first_exit looks only ahead.
    const Vec2<Num> tangent = tangent_of(c.normal);
    const Num along = dot(tangent, p - c.origin);
    RootSearch<Num> r;
    if (along < c.lo || c.hi < along) r.found = true, r.t = Num{};
    else r = first_exit(tangent, p, v, a, c.origin, c.lo, c.hi, horizon);
    if (!r.found) return;
    if (c.with_wall()) push({now_ + r.t, EventKind::leave_wall, c.i, c.wall, c.feature}, owner);
    else push({now_ + r.t, EventKind::leave_pair, c.i, c.j, ContactFeature::ball}, owner);
  }

  // The contact forces of the islands holding `seeds` are found again where
  // a contact came or went or a ball's mobility changed (ContactGraph::forces
  // keeps them otherwise): every ball of them is carried to now and takes its
  // acceleration.
  void solve_islands(const std::vector<int>& seeds, std::vector<int>& changed) {
    std::vector<int>& balls = island_;
    graph_.island(world_, seeds, balls);
    if (balls.empty()) return;
    for (int x : balls) advance_to_time(world_.balls[x], now_);
    graph_.forces(world_, balls);
    for (int x : balls) {
      motion_changed(x, MotionChange::forces);
      changed.push_back(x);
    }
  }

  // The moving balls in contact with ball i.
  std::vector<int> moving_partners(int i) const {
    std::vector<int> out;
    graph_.for_each_contact_of(i, [&](const PersistentContact<Num>& c) {
      const int p = c.partner_of(i);
      if (p >= 0 && !world_.balls[p].is_static()) out.push_back(p);
    });
    return out;
  }

  // Ball e.a meets its partner (n towards e.a): the balls of the islands
  // involved are carried to now, the collision is resolved (contact_rules.hpp)
  // and their forces are solved again, with those of every ball in `changed`
  // (balls woken by the strike).
  template <class OnCollision>
  void collide(const Event<Num>& e, const Vec2<Num>& n, std::vector<int>& changed, OnCollision& on_collision) {
    const int seeds[2] = {e.a, e.b};
    graph_.island(world_, std::span<const int>(seeds, e.kind == EventKind::ball_ball ? 2 : 1), island_);
    for (int x : island_) advance_to_time(world_.balls[x], now_);
    const Collision<Num>& c = rules_.collide(world_, graph_, grid_, e, rules_.contact_for(world_, e, n), island_, changed);
    for (int x : rules_.moved_balls()) motion_changed(x, MotionChange::response);
    on_collision(c);
    solve_islands(changed, changed);  // the collision's islands, and any woken ball's
  }

  template <class OnCollision>
  void process(const Event<Num>& e, const Num& until, OnCollision& on_collision) {
    if (e.kind == EventKind::cell_crossing) {
      // The motion goes on unchanged (no new clock, no new version): only
      // the balls it may meet change.
      ++counters_.cell_crossings;
      const std::span<const int> walls_before = grid_.walls_near(e.a);
      grid_.cross(e.a, static_cast<CellStep>(e.b), [&](int j) {
        if (j != e.a) predict_pair(e.a, j, until);
      });
      for (int w : grid_.walls_near(e.a))
        if (!std::binary_search(walls_before.begin(), walls_before.end(), w)) predict_wall(e.a, w, until);
      predict_crossing(e.a, state_at(world_.balls[e.a], now_), until - now_);
      return;
    }
    // An event that changes nothing (a contact that ended already, a
    // creeping one, one the article's methods report for objects moving
    // apart) leaves its balls on their clocks: it is judged on copies
    // carried to its time, and only an event that acts carries the balls
    // themselves. A ball's clock moves with its motion or not at all, so
    // that a pair asked for again later is predicted from the same clocks,
    // to the same bits (predict_pair), whenever it is asked.
    Body<Num>& a = world_.balls[e.a];
    std::vector<int>& changed = changed_;
    changed.assign(1, e.a);
    if (e.kind == EventKind::leave_wall || e.kind == EventKind::leave_pair) {
      // A contact slid out of its range: it ends, and its island is solved
      // again without it. Past the end of a wall's face the ball goes on
      // along the tangent at that end (the same line), until it has risen
      // off it.
      const PersistentContact<Num>* c =
          e.kind == EventKind::leave_wall ? graph_.with_wall(e.a, e.b) : graph_.find_pair(e.a, e.b);
      if (!c) return;  // it ended already
      advance_to_time(a, e.time);
      if (e.kind == EventKind::leave_pair) {
        advance_to_time(world_.balls[e.b], e.time);
        changed.push_back(e.b);
        ++counters_.leave_pair;
      } else {
        ++counters_.leave_wall;
      }
      const PersistentContact<Num> gone = *c;
      graph_.remove(gone);
      if (gone.feature == ContactFeature::wall_face) graph_.add(rules_.onto_the_end(world_, gone));
      solve_islands(changed, changed);
      if (method_ == ToiMethod::analytic && rules_.renew(world_, graph_, gone, changed)) {
        for (int x : rules_.moved_balls()) motion_changed(x, MotionChange::renewed);
        solve_islands(changed, changed);
      }
      settle(changed, until);
      return;
    }
    Body<Num> a_then = a;
    advance_to_time(a_then, e.time);
    if (e.kind == EventKind::ball_wall) {
      const Vec2<Num> n = wall_normal(a_then, e);
      // The article's methods can report a contact with a ball that is
      // leaving the wall (the seed method's textbook root, bisection's
      // overlap test); acting on it would ring forever at one instant. The
      // step engine drops it and counts it; the next step predicts afresh.
      if (method_ != ToiMethod::analytic && !approaching(a_then, n)) {
        ++counters_.ignored;
        return;
      }
      if (rules_.creeping(n, a_then.velocity, a_then.acceleration)) return;
      a = a_then;
      ++counters_.ball_wall;
      if (plain_gas_strike(e)) return collide_in_gas(e, n, on_collision, until);
      collide(e, n, changed, on_collision);
      settle(changed, until);
      return;
    }
    Body<Num>& b = world_.balls[e.b];
    Body<Num> b_then = b;
    advance_to_time(b_then, e.time);
    const Vec2<Num> n = normalized(a_then.position - b_then.position);  // from b to a
    if (method_ != ToiMethod::analytic && !(dot(n, a_then.velocity - b_then.velocity) < Num{})) {
      ++counters_.ignored;  // likewise for two balls moving apart
      return;
    }
    if (rules_.creeping(n, a_then.velocity - b_then.velocity, a_then.acceleration - b_then.acceleration)) return;
    a = a_then, b = b_then;
    // A strike fast enough wakes a sleeping ball (rest.hpp, rule 3).
    changed.push_back(e.b);
    if (rules_.wakes(-dot(n, a.velocity - b.velocity)))
      for (int x : {e.a, e.b})
        if (world_.balls[x].asleep) wake(x, changed);
    ++counters_.ball_ball;
    if (plain_gas_strike(e)) return collide_in_gas(e, n, on_collision, until);
    collide(e, n, changed, on_collision);
    settle(changed, until);
  }

  // A strike in a gas (no ball accelerates, the analytic method) on balls
  // that are moving, in contact with nothing and not struck at this instant
  // already: every rest rule is idle there (rest.hpp: no weight to carry, no
  // press, no jam), so the response is the textbook one, the islands are the
  // struck balls alone, nothing can fall asleep, and collide() and settle()
  // would do exactly what collide_in_gas does, with more bookkeeping. The
  // same calls in the same order: the same bits (a gas's stored hashes and
  // the property gas-fast-path, properties/determinism_checks.cpp,
  // holds it to that).
  bool plain_gas_strike(const Event<Num>& e) const {
    if (!plain_gas_path_) return false;
    const Body<Num>& a = world_.balls[e.a];
    if (a.is_static() || graph_.in_contact(e.a) || a.struck_at == e.time) return false;
    if (e.kind != EventKind::ball_ball) return true;
    const Body<Num>& b = world_.balls[e.b];
    return !b.is_static() && !graph_.in_contact(e.b) && !(b.struck_at == e.time);
  }

  // What plain_gas_strike needs of the run as a whole: a gas, the analytic
  // method, and no negative least press (which would make pressed_low true).
  bool plain_gas_scene() const {
    return keeps_predictions_ && method_ == ToiMethod::analytic && !(rules_.thresholds().least_press < Num{});
  }

  // collide() and settle() for a plain_gas_strike: ball e.a meets its
  // partner (n from the partner towards e.a), both carried to now already.
  template <class OnCollision>
  void collide_in_gas(const Event<Num>& e, const Vec2<Num>& n, OnCollision& on_collision, const Num& until) {
    const bool pair = e.kind == EventKind::ball_ball;
    Body<Num>& a = world_.balls[e.a];
    Body<Num>* b = pair ? &world_.balls[e.b] : nullptr;
    Collision<Num>& c = gas_collision_;
    c.island.assign(1, e.a);
    if (pair) c.island.push_back(e.b);
    for (int x : c.island) advance_to_time(world_.balls[x], now_);  // as collide() carries its island (a no-op but for −0)
    c.island_velocity_before.assign(1, a.velocity);
    if (pair) c.island_velocity_before.push_back(b->velocity);
    const Num restitution = contact_restitution(a.restitution, pair ? b->restitution : world_.wall_restitution[e.b]);
    c.impulse = ContactRules<Num>::textbook_response(a, b, true, pair, n, restitution);
    a.struck_at = e.time;
    if (pair) b->struck_at = e.time;
    c.time = e.time, c.kind = e.kind, c.a = e.a, c.b = e.b;
    for (int x : c.island) motion_changed(x, MotionChange::response);
    on_collision(c);
    // solve_islands: each struck ball is an island of its own, its forces
    // (none, or its own acceleration again after a contact it has left).
    for (int x : c.island) advance_to_time(world_.balls[x], now_);
    graph_.forces(world_, c.island);
    for (int x : c.island) motion_changed(x, MotionChange::forces);
    // settle: the lower index predicts the pair, the other skips it.
    predict(e.a, until);
    if (pair) predict(e.b, until, [&](int j) { return j == e.a; });
  }

  // After a contact: balls that can sleep do (in index order, again while
  // one more falls asleep: a ball may be carried by one that just slept),
  // then every ball whose motion changed is predicted again, and every moving
  // neighbour of a ball that fell asleep is predicted against it.
  void settle(std::vector<int>& changed, const Num& until) {
    auto tidy = [](std::vector<int>& v) {
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
    };
    tidy(changed);
    std::vector<int> slept;
    // A ball of an island already found unable to sleep, since the last ball
    // fell asleep, has that island and that answer (the tests change
    // nothing): judged_[x] == judgement_ marks it, and a sleep starts a new
    // judgement. A strike on a pile changes every ball of its island; each
    // would otherwise search the whole island again.
    if (judged_.size() != world_.balls.size()) judged_.assign(world_.balls.size(), 0);
    for (bool more = true; more;) {
      more = false;
      ++judgement_;
      std::vector<int> more_changed;
      for (int i : changed) {
        if (world_.balls[i].is_static()) continue;
        if (rules_.can_sleep(world_, grid_, graph_, i)) {
          fall_asleep({i}, more_changed);
          slept.push_back(i);
          more = true;
          ++judgement_;
        } else if (graph_.in_contact(i) && judged_[i] != judgement_) {
          const std::vector<int> island = graph_.island(world_, {i});
          if (rules_.island_can_sleep(world_, island)) {
            fall_asleep(island, more_changed);
            slept.insert(slept.end(), island.begin(), island.end());
            more = true;
            ++judgement_;
          } else {
            for (int x : island) judged_[x] = judgement_;
          }
        }
      }
      changed.insert(changed.end(), more_changed.begin(), more_changed.end());
      tidy(changed);
    }
    auto in_changed = [&](int j) { return std::binary_search(changed.begin(), changed.end(), j); };
    for (int i : changed) {
      if (world_.balls[i].is_static()) continue;
      predict(i, until, [&](int j) { return j < i && in_changed(j) && !world_.balls[j].is_static(); });
    }
    for (int s : slept)
      grid_.for_each_neighbour(s, [&](int j) {
        if (!in_changed(j) && !world_.balls[j].is_static()) predict_pair(j, s, until);
      });
  }

  // Rule 2: `balls` fall asleep. Their contacts stay; their moving partners
  // now lean on static balls, and lose what normal speed they had relative
  // to them (an impact of their islands with every contact held: less than
  // v_rest each); those islands' forces are solved again.
  void fall_asleep(const std::vector<int>& balls, std::vector<int>& changed) {
    for (int i : balls) {
      advance_to_time(world_.balls[i], now_);
      rules_.put_to_sleep(world_.balls[i]);
      graph_.mobility_changed(i);
      motion_changed(i, MotionChange::sleep);
    }
    std::vector<int> partners;
    for (int i : balls)
      for (int p : moving_partners(i)) partners.push_back(p);
    if (partners.empty()) return;
    const std::vector<int> island = graph_.island(world_, partners);
    for (int x : island) advance_to_time(world_.balls[x], now_);
    rules_.hold(world_, graph_, island);
    solve_islands(partners, changed);
  }

  // Rule 3: ball i wakes; so does every sleeper it helped to carry: within
  // the contact band of it, and no longer carried (the cone test again, now
  // without it). Each ball woken joins `changed`, and so do the moving balls
  // in contact with it (their partner moves now). The set that wakes does
  // not depend on the order of the search (waking only ever removes
  // supports), nor on the grid (only balls within the band are asked).
  void wake(int first, std::vector<int>& changed) {
    std::vector<int> pending = {first};
    while (!pending.empty()) {
      const int i = pending.back();
      pending.pop_back();
      Body<Num>& b = world_.balls[i];
      if (!b.asleep) continue;
      advance_to_time(b, now_);
      ContactRules<Num>::wake(b);
      graph_.mobility_changed(i);
      motion_changed(i, MotionChange::wake);
      ++rules_.counters.woken;
      changed.push_back(i);
      for (int p : moving_partners(i)) changed.push_back(p);
      grid_.for_each_neighbour(i, [&](int j) {
        if (j != i && world_.balls[j].asleep && rules_.within_band(world_.balls[j], b) &&
            !rules_.carried(world_, grid_, graph_, j))
          pending.push_back(j);
      });
    }
  }

  // The ball's velocity has a component into the wall (or it is pressed on it).
  static bool approaching(const Body<Num>& a, const Vec2<Num>& n) {
    const Num zero{};
    const Num vn = dot(a.velocity, n);
    return vn < zero || (vn == zero && dot(a.free_acceleration, n) < zero);
  }

  // The wall's unit normal at the contact, towards the ball.
  Vec2<Num> wall_normal(const Body<Num>& a, const Event<Num>& e) const {
    const WallGeometry<Num>& w = world_.walls[e.b];
    if (e.feature == ContactFeature::wall_face) return face_normal_towards(w, a.position);
    return normalized(a.position - (e.feature == ContactFeature::wall_end_a ? w.segment.a : w.segment.b));
  }
};

}  // namespace collide2d
