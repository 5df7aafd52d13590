// The event-driven engine: exact event order, deterministic ties.
//
// Time advances from event to event; nothing is stepped. Between record
// times T_k = k Δ every ball moves on its exact parabola, each pair's next
// contact is predicted by the analytic time of impact, and the earliest
// event is processed first, in (time, kind, a, b) order (event_queue.hpp).
// At every record time all balls are carried to T_k and the prediction
// starts afresh for [T_k, T_k+1], so a frame, a checkpoint and a resumed run
// all start from the same exact state.
//
// Only neighbours are predicted against each other (cell_grid.hpp); a pair
// is always predicted from the later of the two balls' clocks, so the grid
// changes the cost of a run, never its bits.
//
// What a contact does, and the rules that bring balls to rest (on a face,
// asleep) and wake them, are in contact_rules.hpp and rest.hpp. This file
// decides when: after each contact it lets the balls involved fall asleep if
// they can, wakes what a strike or a lost support wakes, and predicts again
// for every ball whose motion changed. A sleeping ball is static, like a
// fixed one: it makes no events of its own and is predicted against as an
// obstacle.
#pragma once

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/cell_grid.hpp"
#include "sim/contact_graph.hpp"
#include "sim/contact_rules.hpp"
#include "sim/event_queue.hpp"
#include "sim/state_bytes.hpp"
#include "sim/world.hpp"
#include "toi/article_methods.hpp"

namespace collide2d {

struct EngineStall : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct EngineCounters {
  std::uint64_t ball_ball = 0, ball_wall = 0, leave_wall = 0, leave_pair = 0, stale = 0;
  std::uint64_t cell_crossings = 0;
  std::uint64_t ignored = 0;  // contacts a method reported for objects moving apart
  RestCounters rest;          // what the rest rules did (rest.hpp)
};

template <class Num>
class EventEngine {
 public:
  // `method`: how contacts are predicted. analytic is exact; bisection and
  // seed (the article's, tolerance `eps`) are for the step engine, which is
  // this engine advanced one step at a time (see simulate.hpp).
  // `one_cell`: predict every pair (no grid); the results are the same bits.
  EventEngine(World<Num> world, const RestThresholds<Num>& thresholds, ToiMethod method = ToiMethod::analytic,
              const Num& eps = Num{}, bool one_cell = false)
      : world_(std::move(world)), rules_(thresholds), method_(method), eps_(eps),
        grid_(world_, one_cell, NumberTraits<Num>::to_double(thresholds.band)) {
    graph_.reset(world_.balls.size());
  }

  const World<Num>& world() const { return world_; }
  World<Num>& world() { return world_; }
  EngineCounters counters() const {
    EngineCounters c = counters_;
    c.rest = rules_.counters;
    return c;
  }
  const Num& now() const { return now_; }
  const Num& energy_removed_by_rest() const { return rules_.energy_removed; }
  bool all_at_rest() const {
    return std::all_of(world_.balls.begin(), world_.balls.end(), [](const Body<Num>& b) { return b.is_static(); });
  }

  // Processes every event up to `until` (inclusive) and carries all balls
  // there. `on_collision(const Collision<Num>&)` sees each collision in order.
  template <class OnCollision>
  void advance_to(const Num& until, OnCollision on_collision) {
    queue_.clear();
    grid_.assign(world_);
    for (int i = 0; i < static_cast<int>(world_.balls.size()); ++i)
      predict(i, until, [&](int j) { return j < i && !world_.balls[j].is_static(); });
    while (!queue_.empty() && !(until < queue_.top().time)) {
      const Event<Num> e = queue_.pop();
      if (!current(e)) {
        ++counters_.stale;
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
      process(e, until, on_collision);
    }
    for (Body<Num>& b : world_.balls) advance_to_time(b, until);
    now_ = until;
  }

  // The whole mutable state at a record time (checkpoints): the clock, the
  // counters, the rest rules' energy tallies and every body. Walls never
  // change and are not stored. The layout's version leads, so that a
  // checkpoint of another layout is refused by name instead of misread
  // (3: faces, sleep and the rest counters).
  static constexpr std::uint32_t checkpoint_layout = 3;

  void save(ByteWriter& out) const {
    out.put(checkpoint_layout);
    out.put(now_);
    for (const std::uint64_t* c : counter_fields(const_cast<EngineCounters&>(counters_), const_cast<RestCounters&>(rules_.counters)))
      out.put(*c);
    out.put(rules_.energy_removed);
    out.put(static_cast<std::uint64_t>(world_.balls.size()));
    for (const Body<Num>& b : world_.balls) {
      for (const Vec2<Num>* v : {&b.position, &b.velocity, &b.acceleration, &b.free_acceleration}) out.put(*v);
      for (const Num* x : {&b.time, &b.radius, &b.mass, &b.restitution}) out.put(*x);
      out.put(static_cast<std::uint8_t>(b.fixed));
      out.put(static_cast<std::uint8_t>(b.asleep));
      out.put(static_cast<std::uint8_t>(b.on_face));
      for (const Vec2<Num>* v : {&b.face.normal, &b.face.tangent, &b.face.origin}) out.put(*v);
      out.put(b.face.lo);
      out.put(b.face.hi);
      out.put(static_cast<std::int32_t>(b.face.wall));
      out.put(static_cast<std::int32_t>(b.face.ball));
      out.put(static_cast<std::int32_t>(b.face.feature));
      out.put(b.version);
    }
    graph_.save(out);
  }
  void load(ByteReader& in) {
    std::uint32_t layout = 0;
    in.get(layout);
    if (layout != checkpoint_layout)
      throw std::runtime_error("checkpoint of layout " + std::to_string(layout) + ", this build reads layout " +
                               std::to_string(checkpoint_layout) + ": resume it with the collide2d that wrote it");
    in.get(now_);
    for (std::uint64_t* c : counter_fields(counters_, rules_.counters)) in.get(*c);
    in.get(rules_.energy_removed);
    std::uint64_t n = 0;
    in.get(n);
    if (n != world_.balls.size()) throw std::runtime_error("checkpoint holds a different number of balls");
    for (Body<Num>& b : world_.balls) {
      for (Vec2<Num>* v : {&b.position, &b.velocity, &b.acceleration, &b.free_acceleration}) in.get(*v);
      for (Num* x : {&b.time, &b.radius, &b.mass, &b.restitution}) in.get(*x);
      std::uint8_t fixed = 0, asleep = 0, on_face = 0;
      in.get(fixed);
      in.get(asleep);
      in.get(on_face);
      for (Vec2<Num>* v : {&b.face.normal, &b.face.tangent, &b.face.origin}) in.get(*v);
      in.get(b.face.lo);
      in.get(b.face.hi);
      std::int32_t wall = -1, ball = -1, feature = 0;
      in.get(wall);
      in.get(ball);
      in.get(feature);
      in.get(b.version);
      b.fixed = fixed != 0;
      b.asleep = asleep != 0;
      b.on_face = on_face != 0;
      b.face.wall = wall;
      b.face.ball = ball;
      b.face.feature = static_cast<ContactFeature>(feature);
    }
    graph_.load(in);
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

  static std::vector<std::uint64_t*> counter_fields(EngineCounters& c, RestCounters& r) {
    return {&c.ball_ball,     &c.ball_wall,     &c.leave_wall,    &c.leave_pair,    &c.stale,         &c.cell_crossings,
            &c.ignored,       &r.came_to_rest,  &r.fell_asleep,   &r.woken,         &r.plastic_pairs,
            &r.creeping,      &r.held};
  }

  static void advance_to_time(Body<Num>& b, const Num& t) {
    if (!b.is_static()) collide2d::advance_to(b, t);
    b.time = t;
  }

  bool current(const Event<Num>& e) const {
    if (world_.balls[e.a].version != e.version_a) return false;
    return !between_two_balls(e.kind) || world_.balls[e.b].version == e.version_b;
  }

  void push(Event<Num> e) {
    e.version_a = world_.balls[e.a].version;
    if (between_two_balls(e.kind)) e.version_b = world_.balls[e.b].version;
    queue_.push(e);
  }

  // Every future event of moving ball i within [now, until]: against its
  // neighbours but those `skip(j)` names (pairs predicted elsewhere), the
  // ball whose tangent it slides on and its plastic partner, every wall,
  // leaving its face, the end of its plastic contact, and leaving its cell.
  template <class Skip>
  void predict(int i, const Num& until, Skip skip) {
    const Body<Num>& bi = world_.balls[i];
    if (bi.is_static()) return;
    grid_.for_each_neighbour(i, [&](int j) {
      if (j == i || skip(j)) return;
      predict_pair(i, j, until);
    });
    const Num horizon = until - now_;
    const BallState<Num> si = state_at(bi, now_);
    for (int w = 0; w < static_cast<int>(world_.walls.size()); ++w) {
      if (bi.on_face && w == bi.face.wall && bi.face.feature == ContactFeature::wall_face) continue;
      const ToiResult<Num> r = wall_contact(si, w, horizon);
      // On the tangent at a wall's end the centre stays outside that end's
      // circle: a contact with the same end is a rounding echo.
      if (r.hit() && !(bi.on_face && w == bi.face.wall && r.feature == bi.face.feature))
        push({now_ + r.time, EventKind::ball_wall, i, w, 0, 0, r.feature});
      else if (!r.hit() && method_ == ToiMethod::analytic)
        predict_pressed_on_wall(i, si, w, horizon, bi.on_face && w == bi.face.wall ? bi.face.feature : ContactFeature::none);
    }
    if (bi.on_face) predict_leaving(i, si, horizon);
    graph_.for_each_contact_of(i, [&](const PersistentContact<Num>& c) {
      if (c.i == i) predict_contact_ending(c, si, horizon);
    });
    predict_crossing(i, si, horizon);
  }
  void predict(int i, const Num& until) {
    predict(i, until, [](int) { return false; });
  }

  // The next contact of balls i (moving) and j, predicted from the later of
  // their clocks (the last change of either's motion): the answer depends
  // only on the two motions, never on when, or whether, the grid asks for it.
  // None for two balls in contact: one sliding on the other's tangent, or a
  // persistent pair (their contact's end is the event).
  void predict_pair(int i, int j, const Num& until) {
    const Body<Num>& bi = world_.balls[i];
    const Body<Num>& bj = world_.balls[j];
    if (bi.is_static() && bj.is_static()) return;
    if ((bi.on_face && bi.face.ball == j) || (bj.on_face && bj.face.ball == i) || graph_.touching(i, j)) return;
    const Num t0 = bj.fixed || bj.time < bi.time ? bi.time : bj.time;
    const BallState<Num> si = state_at(bi, t0), sj = state_at(bj, t0);
    const Num horizon = until - t0;
    const ToiResult<Num> r = method_ == ToiMethod::analytic ? time_of_impact_ball_ball(si, sj, horizon)
                                                            : bisection_ball_ball(si, sj, horizon, eps_);
    if (r.hit()) {
      push({t0 + r.time, EventKind::ball_ball, std::min(i, j), std::max(i, j), 0, 0, r.feature});
      return;
    }
    const RootSearch<Num> pressed = pressed_contact_due(si.position - sj.position, si.velocity - sj.velocity,
                                                        si.acceleration - sj.acceleration, si.radius + sj.radius, horizon);
    if (pressed.found)
      push({t0 + pressed.t, EventKind::ball_ball, std::min(i, j), std::max(i, j), 0, 0, ContactFeature::ball});
  }

  // Pressed together while touching. Rounding can leave a pair (Δp the
  // offset between centres, or from a wall's nearest point; R the contact
  // distance) a hair inside contact, where the gap never crosses zero again
  // and no time of impact exists; the contact is then due when their normal
  // separating speed has fallen to zero: t = (Δp·Δv) / −(Δp·Δa) for
  // Δp·Δv ≥ 0, at once otherwise. Only while the rise before that,
  // s_n² / 2|a_n| = (Δp·Δv)² / (2 |Δp·Δa| |Δp|), stays within h_rest
  // (|Δp| ≈ R): a larger rise would take them apart, and the time of impact
  // would have seen them come back.
  RootSearch<Num> pressed_contact_due(const Vec2<Num>& dp, const Vec2<Num>& dv, const Vec2<Num>& da, const Num& R,
                                      const Num& horizon) const {
    const Num zero{};
    const Num pressing = dot(dp, da);
    if (!(pressing < zero) || R * R < length_squared(dp)) return {};
    const Num separating = dot(dp, dv);
    if (num<Num>(2.0) * -pressing * R * rules_.thresholds().height < separating * separating) return {};
    if (horizon * -pressing < separating) return {};  // not within the horizon (and no division that could overflow)
    return {true, separating < zero ? zero : separating / -pressing};
  }

  // The wall's counterpart of a pair left a hair inside contact (see
  // pressed_contact_due): the ball touches the wall's nearest point q, is
  // pressed towards it (Δp·a < 0 with Δp = p − q) and no time of impact
  // exists. The contact is due when it stops moving away from q.
  // `resting_on`: the feature of this wall whose tangent the ball slides on
  // (its centre stays outside that feature's circle: an echo, not a contact).
  void predict_pressed_on_wall(int i, const BallState<Num>& s, int w, const Num& horizon, ContactFeature resting_on) {
    ContactFeature feature = ContactFeature::none;
    const Vec2<Num> q = nearest_point(world_.walls[w], s.position, &feature);
    if (feature == resting_on) return;
    const RootSearch<Num> pressed = pressed_contact_due(s.position - q, s.velocity, s.acceleration, s.radius, horizon);
    if (pressed.found) push({now_ + pressed.t, EventKind::ball_wall, i, w, 0, 0, feature});
  }

  void predict_crossing(int i, const BallState<Num>& s, const Num& horizon) {
    const typename CellGrid<Num>::Crossing c = grid_.next_crossing(i, s, horizon);
    if (c.found) push({now_ + c.time, EventKind::cell_crossing, i, static_cast<int>(c.step), 0, 0, ContactFeature::none});
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

  // A ball on a face leaves it when its centre passes an end of the face.
  void predict_leaving(int i, const BallState<Num>& s, const Num& horizon) {
    const Face<Num>& f = world_.balls[i].face;
    const RootSearch<Num> r = first_exit(f.tangent, s.position, s.velocity, s.acceleration, f.origin, f.lo, f.hi, horizon);
    if (r.found) push({now_ + r.t, EventKind::leave_wall, i, f.wall, 0, 0, ContactFeature::none});
  }

  // A persistent contact (contact_graph.hpp) ends when the two have slid L
  // apart along its tangent: the offset between the centres moves along it.
  void predict_contact_ending(const PersistentContact<Num>& c, const BallState<Num>& si, const Num& horizon) {
    const BallState<Num> sj = state_at(world_.balls[c.j], now_);
    const RootSearch<Num> r = first_exit(tangent_of(c.normal), si.position - sj.position, si.velocity - sj.velocity,
                                         si.acceleration - sj.acceleration, c.origin, -c.L, c.L, horizon);
    if (r.found) push({now_ + r.t, EventKind::leave_pair, c.i, c.j, 0, 0, ContactFeature::none});
  }

  // The contact forces of the islands holding `seeds` are found again (a
  // contact came or went, or a ball's mobility changed): every ball of them
  // is carried to now and takes its new acceleration.
  void solve_islands(const std::vector<int>& seeds, std::vector<int>& changed, bool impact = false) {
    const std::vector<int> balls = graph_.island(seeds);
    for (int x : balls) advance_to_time(world_.balls[x], now_);
    const Num before = kinetic_energy(balls);
    graph_.solve(world_, balls, impact, rules_.thresholds().speed);
    rules_.energy_removed = rules_.energy_removed + (before - kinetic_energy(balls));
    for (int x : balls) {
      ++world_.balls[x].version;
      changed.push_back(x);
    }
  }

  Num kinetic_energy(const std::vector<int>& balls) const {
    Num e{};
    for (int x : balls) e = e + collide2d::kinetic_energy(world_.balls[x]);
    return e;
  }

  // The velocities of `balls` have just changed in an impact: their islands
  // take it as a whole (contact_graph.hpp), or, out of contact, nothing more.
  void after_impact(const std::vector<int>& balls, std::vector<int>& changed) {
    std::vector<int> seeds;
    for (int x : balls)
      if (graph_.in_contact(x)) seeds.push_back(x);
    if (!seeds.empty()) solve_islands(seeds, changed, true);
  }

  // Ball i is about to fall asleep: its persistent contacts end (it becomes
  // a static support), and its former partners' islands are solved again.
  void leave_contacts(int i, std::vector<int>& changed) {
    const std::vector<int> partners = graph_.remove_all_of(i);
    if (partners.empty()) return;
    world_.balls[i].acceleration = own_acceleration(world_.balls[i]);
    solve_islands(partners, changed);
  }

  template <class OnCollision>
  void process(const Event<Num>& e, const Num& until, OnCollision& on_collision) {
    if (e.kind == EventKind::cell_crossing) {
      // The motion goes on unchanged (no new clock, no new version): only
      // the balls it may meet change.
      ++counters_.cell_crossings;
      grid_.cross(e.a, static_cast<CellStep>(e.b), [&](int j) {
        if (j != e.a) predict_pair(e.a, j, until);
      });
      predict_crossing(e.a, state_at(world_.balls[e.a], now_), until - now_);
      return;
    }
    Body<Num>& a = world_.balls[e.a];
    advance_to_time(a, e.time);
    std::vector<int> changed = {e.a};
    if (e.kind == EventKind::leave_wall) {
      ContactRules<Num>::free(a);
      ++a.version;
      ++counters_.leave_wall;
      if (graph_.in_contact(e.a)) solve_islands({e.a}, changed);  // it moves freely now
      settle(changed, until);
      return;
    }
    if (e.kind == EventKind::leave_pair) {
      advance_to_time(world_.balls[e.b], e.time);
      graph_.remove(e.a, e.b);
      ++counters_.leave_pair;
      solve_islands({e.a, e.b}, changed);
      settle(changed, until);
      return;
    }
    if (e.kind == EventKind::ball_wall) {
      const Vec2<Num> n = wall_normal(a, e);
      // The article's methods can report a contact with a ball that is
      // leaving the wall (the seed method's textbook root, bisection's
      // overlap test); acting on it would ring forever at one instant. The
      // step engine drops it and counts it; the next step predicts afresh.
      if (method_ != ToiMethod::analytic && !approaching(a, n)) {
        ++counters_.ignored;
        return;
      }
      if (rules_.creeping(n, a.velocity, a.acceleration)) return;
      ++counters_.ball_wall;
      on_collision(rules_.collide_with_wall(world_, e, n));
      after_impact({e.a}, changed);
      settle(changed, until);
      return;
    }
    Body<Num>& b = world_.balls[e.b];
    advance_to_time(b, e.time);
    const Vec2<Num> n = normalized(a.position - b.position);  // from b to a
    if (method_ != ToiMethod::analytic && !(dot(n, a.velocity - b.velocity) < Num{})) {
      ++counters_.ignored;  // likewise for two balls moving apart
      return;
    }
    if (rules_.creeping(n, a.velocity - b.velocity, a.acceleration - b.acceleration)) return;
    // A strike fast enough wakes a sleeping ball, or the sleeping ball whose
    // tangent the struck one slides on (rest.hpp, rule 3).
    changed.push_back(e.b);
    if (rules_.wakes(-dot(n, a.velocity - b.velocity))) {
      for (int x : {e.a, e.b}) {
        const Body<Num>& body = world_.balls[x];
        if (body.asleep) wake(x, changed);
        else if (body.on_face && body.face.ball >= 0 && world_.balls[body.face.ball].asleep) wake(body.face.ball, changed);
      }
    }
    ++counters_.ball_ball;
    on_collision(rules_.collide_balls(world_, e));
    if (rules_.plastic) {
      // Rule 4: the pair stays in contact; the island it joins takes the
      // impact as a whole and holds it with its contact forces.
      graph_.add({e.a, e.b, n, a.position - b.position, slide_length(a.radius + b.radius, rules_.thresholds().height)});
      solve_islands({e.a, e.b}, changed, true);
    } else {
      after_impact({e.a, e.b}, changed);
    }
    settle(changed, until);
  }

  // After a contact: balls that can sleep do (in index order, again while
  // one more falls asleep: a ball may be carried by one that just slept),
  // then every ball whose motion changed is predicted again, and every moving
  // neighbour of a ball that fell asleep is predicted against it.
  void settle(std::vector<int> changed, const Num& until) {
    std::sort(changed.begin(), changed.end());
    changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
    std::vector<int> slept, more_changed;
    for (bool more = true; more;) {
      more = false;
      for (int i : changed)
        if (rules_.can_sleep(world_, grid_, i)) {
          leave_contacts(i, more_changed);
          rules_.put_to_sleep(world_.balls[i]);
          ++world_.balls[i].version;
          slept.push_back(i);
          more = true;
        }
    }
    if (!more_changed.empty()) {
      changed.insert(changed.end(), more_changed.begin(), more_changed.end());
      std::sort(changed.begin(), changed.end());
      changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
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

  // Rule 3: ball i wakes; so does every sleeper it helped to carry (the cone
  // test again, now without it), and every ball sliding on the tangent of a
  // ball that woke is freed. Each ball woken or freed joins `changed`. The
  // set that wakes does not depend on the order of the search: waking only
  // ever removes supports.
  void wake(int first, std::vector<int>& changed) {
    std::vector<int> pending = {first};
    while (!pending.empty()) {
      const int i = pending.back();
      pending.pop_back();
      Body<Num>& b = world_.balls[i];
      if (!b.asleep) continue;
      advance_to_time(b, now_);
      ContactRules<Num>::wake(b);
      ++b.version;
      ++rules_.counters.woken;
      changed.push_back(i);
      grid_.for_each_neighbour(i, [&](int j) {
        Body<Num>& n = world_.balls[j];
        if (j == i) return;
        if (n.asleep && !rules_.carried(world_, grid_, j)) pending.push_back(j);
        if (!n.is_static() && n.on_face && n.face.ball == i) {
          advance_to_time(n, now_);
          ContactRules<Num>::free(n);
          if (graph_.in_contact(j)) solve_islands({j}, changed);  // it moves freely now
          ++n.version;
          changed.push_back(j);
        }
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
