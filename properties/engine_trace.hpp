// Runs a scene through the event engine exactly as simulate() does (record
// times k·interval, prediction afresh at each) and keeps what the checks
// need: each ball's motion as pieces (a Body: position, velocity and
// acceleration at its clock, valid until the next piece) and every collision
// with the two balls' states just before (velocities as the engine recorded
// them) and just after it.
//
// The engine tells the trace of every change of a ball's motion (its
// observer, event_engine.hpp: a collision's response, contact forces solved
// again, a contact left or renewed, sleep, wake), each a new version of the
// ball; the trace also looks at every ball at each record time. So every
// piece of every path is seen, and the trace checks the engine's bookkeeping
// of it as it goes:
//  - each change told comes with exactly one new version (Body::version: an
//    event predicted from the old motion is stale only if it does);
//  - a ball's position is continuous: a change moves its velocity or its
//    acceleration, never the ball;
//  - between two changes told, a ball moves on its parabola: at each record
//    time its velocity is the last piece's carried there and its
//    acceleration, mobility and version are the same;
//  - every ball–ball collision happens at contact distance (|p_a − p_b| =
//    r_a + r_b), every ball–wall one at the radius from the wall, within
//    rounding: an event acted on after a ball changed course meets a ball
//    that is not there.
// What breaks one of these is counted (unseen_changes, misplaced_collisions)
// with the first of each described; every check that reads the trace fails
// on it (trace_failure), so no stretch of motion is ever skipped unseen.
//
// A run making more events than the scene's event cap (event_cap.hpp) is
// stopped: RunawayRun, which the checks report as their failure.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "collide2d/numeric/fixed_words.hpp"
#include "collide2d/sim/simulate.hpp"
#include "event_cap.hpp"

namespace collide2d::properties {

// Exact enough conversions for the checks: a Fixed keeps 64 of its 127 bits
// (a long double's mantissa), a double all of its own.
inline long double to_long_double(double x) { return x; }
inline long double to_long_double(const Fixed& x) {
  const FixedWords w = to_words(x);
  return static_cast<long double>(w.hi) + static_cast<long double>(static_cast<std::uint64_t>(w.lo)) * 0x1p-64L;
}

template <class Num>
struct MotionPiece {
  Body<Num> body;  // the motion from body.time on
};

template <class Num>
struct TracedCollision {
  Collision<Num> collision;
  Body<Num> before_a, before_b;  // just before the response (the engine's record of the velocities)
  Body<Num> after_a, after_b;
  std::vector<Body<Num>> island_before, island_after;  // every moving ball the response could move
  // A rest rule acted (src/collide2d/sim/rest.hpp): rest on a face, a plastic pair, a
  // held face, a ball put to sleep or woken.
  bool came_to_rest = false, plastic = false, held = false, slept = false, woken = false;
  bool rule_acted() const { return came_to_rest || plastic || held || slept || woken; }
};

// One change of a ball's motion as the engine told it, with the ball just
// before (its last piece carried to the change) and just after.
template <class Num>
struct TracedChange {
  int ball = 0;
  MotionChange why = MotionChange::response;
  Body<Num> before, after;
  std::size_t collisions_before = 0;  // how many collisions the trace had seen when it was told
};

template <class Num>
struct EngineTrace {
  std::vector<std::vector<MotionPiece<Num>>> pieces;  // per ball, in time order
  std::vector<TracedCollision<Num>> collisions;
  std::vector<TracedChange<Num>> changes;  // every change told, in order
  Num end{};
  EngineCounters counters;
  std::array<std::int64_t, 5> changes_by_kind{};  // by MotionChange
  std::int64_t unseen_changes = 0;        // changes of motion the engine did not tell (or told without a new version)
  std::string first_unseen;
  std::int64_t misplaced_collisions = 0;  // collisions not at contact distance
  std::string first_misplaced;
  // Every change told outside a collision's response (a contact renewed,
  // forces solved again, sleep, wake): what a collision callback alone
  // would not have shown.
  std::int64_t changes_outside_collisions() const {
    return changes_by_kind[static_cast<int>(MotionChange::renewed)] + changes_by_kind[static_cast<int>(MotionChange::forces)] +
           changes_by_kind[static_cast<int>(MotionChange::sleep)] + changes_by_kind[static_cast<int>(MotionChange::wake)];
  }
};

// The failure every check that reads a trace reports first: motion the
// trace did not see, or a collision away from contact. nullopt if none.
template <class Num>
std::optional<std::string> trace_failure(const EngineTrace<Num>& trace) {
  if (trace.unseen_changes > 0)
    return "the engine changed a ball's motion without telling its observer (or without a new version) " +
           std::to_string(trace.unseen_changes) + " times; the first: " + trace.first_unseen;
  if (trace.misplaced_collisions > 0)
    return std::to_string(trace.misplaced_collisions) + " collisions away from contact distance; the first: " +
           trace.first_misplaced;
  return std::nullopt;
}

namespace trace_detail {

using LD = long double;

template <class Num>
LD ld(const Num& x) { return to_long_double(x); }

inline std::string text(LD x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17Lg", x);
  return buf;
}

// The rounding unit of one operation of the mode: strict relative eps,
// fixed 2^-64 absolute.
template <class Num>
constexpr LD unit() {
  return std::is_same_v<Num, double> ? LD(0x1p-52) : LD(0x1p-64);
}

// How far the engine's own carrying of a ball from piece to piece may stray
// from the piece's parabola evaluated here in long double: each carry
// (advance_to: p + τ(v + τ/2 a), v + τ a) rounds 4 times, each by half a
// unit of the largest term, strict relative to (|p| + |v| τ + |a| τ²),
// fixed absolute; a ball is carried at most once per event it takes part in
// between two changes (a creep, a contact that ended already) and once per
// record time: 2^8 carries between two looks is far more than a run makes.
// 2^10 units of the sizes involved (plus one, for fixed point's absolute
// unit), far below any real jump (a ball moved or turned by a bug).
template <class Num>
LD carry_tolerance(LD size) {
  return LD(1024) * unit<Num>() * (1 + size);
}

// The piece `from` carried to time t, in long double.
template <class Num>
struct Carried {
  LD px, py, vx, vy;
};
template <class Num>
Carried<Num> carried(const Body<Num>& from, const Num& t) {
  const LD tau = ld(Num(t - from.time));
  if (from.is_static()) return {ld(from.position.x), ld(from.position.y), 0, 0};
  const LD ax = ld(from.acceleration.x), ay = ld(from.acceleration.y);
  const LD vx = ld(from.velocity.x), vy = ld(from.velocity.y);
  return {ld(from.position.x) + tau * (vx + tau / 2 * ax), ld(from.position.y) + tau * (vy + tau / 2 * ay), vx + tau * ax,
          vy + tau * ay};
}

// The sizes a carry from `from` to t rounds on: |p| + |v| τ + |a| τ², and
// |v| + |a| τ for the velocity.
template <class Num>
LD position_size(const Body<Num>& from, const Num& t) {
  const LD tau = std::fabs(ld(Num(t - from.time)));
  return std::max(std::fabs(ld(from.position.x)), std::fabs(ld(from.position.y))) +
         std::hypot(ld(from.velocity.x), ld(from.velocity.y)) * tau +
         std::hypot(ld(from.acceleration.x), ld(from.acceleration.y)) * tau * tau;
}
template <class Num>
LD velocity_size(const Body<Num>& from, const Num& t) {
  const LD tau = std::fabs(ld(Num(t - from.time)));
  return std::hypot(ld(from.velocity.x), ld(from.velocity.y)) + std::hypot(ld(from.acceleration.x), ld(from.acceleration.y)) * tau;
}

inline const char* change_name(MotionChange why) {
  switch (why) {
    case MotionChange::response: return "a response";
    case MotionChange::renewed: return "a contact renewed";
    case MotionChange::forces: return "contact forces";
    case MotionChange::sleep: return "sleep";
    case MotionChange::wake: return "wake";
  }
  return "?";
}

// What the engine's observer does for a trace: see each change, check the
// bookkeeping, keep the pieces. Held by pointer: the engine keeps its own
// copy of the observer.
template <class Num>
struct TraceState {
  EngineTrace<Num>* trace = nullptr;
  std::vector<std::uint64_t> seen;  // each ball's version as last seen
  EventCount* events = nullptr;      // the scene's event cap (event_cap.hpp)

  void unseen(const std::string& what) {
    if (trace->unseen_changes++ == 0) trace->first_unseen = what;
  }

  // Ball i as the engine has it now, against its last piece: continuity of
  // position always; of velocity, acceleration and mobility unless `told`.
  void compare(int i, const Body<Num>& now, bool told, const char* when) {
    const Body<Num>& last = trace->pieces[i].back().body;
    const Carried<Num> c = carried(last, now.time);
    const LD dp = std::hypot(ld(now.position.x) - c.px, ld(now.position.y) - c.py);
    const LD p_tol = carry_tolerance<Num>(position_size(last, now.time));
    const std::string where = "ball " + std::to_string(i) + " at t = " + text(ld(now.time)) + " (" + when + ")";
    if (!(dp <= p_tol)) {
      unseen(where + ": its position jumped by " + text(dp) + " from its path (tolerance " + text(p_tol) + ")");
      return;
    }
    if (told) return;
    if (now.version != seen[i]) {
      unseen(where + ": its version went from " + std::to_string(seen[i]) + " to " + std::to_string(now.version) +
             " with no change told");
      return;
    }
    const LD dv = std::hypot(ld(now.velocity.x) - c.vx, ld(now.velocity.y) - c.vy);
    const LD v_tol = carry_tolerance<Num>(velocity_size(last, now.time));
    if (!(dv <= v_tol) || !(now.acceleration == last.acceleration) || now.is_static() != last.is_static())
      unseen(where + ": its motion changed (velocity by " + text(dv) + ", tolerance " + text(v_tol) + (now.acceleration == last.acceleration ? "" : "; acceleration") +
             (now.is_static() != last.is_static() ? "; mobility" : "") + ") with no change told and no new version");
  }

  void keep(int i, const Body<Num>& now) {
    auto& list = trace->pieces[i];
    if (now.time == list.back().body.time) list.back().body = now;  // several changes at one instant: the last
    else list.push_back({now});
    seen[i] = now.version;
  }

  void motion_changed(const World<Num>& world, int i, MotionChange why) {
    const Body<Num>& now = world.balls[i];
    const Body<Num>& last = trace->pieces[i].back().body;
    if (now.version != seen[i] + 1)
      unseen("ball " + std::to_string(i) + " at t = " + text(ld(now.time)) + ": " + change_name(why) +
             " told with its version going from " + std::to_string(seen[i]) + " to " + std::to_string(now.version));
    compare(i, now, true, change_name(why));
    // The state just before: the last piece carried to now in Num by the
    // engine's own motion (the same parabola).
    TracedChange<Num> change{i, why, last, now, trace->collisions.size()};
    if (last.is_static()) change.before.time = now.time;
    else collide2d::advance_to(change.before, now.time);
    trace->changes.push_back(change);
    ++trace->changes_by_kind[static_cast<int>(why)];
    keep(i, now);
    if (events) events->motion_change(ld(now.time));
  }

  // At a record time: every ball, nothing told since its last change.
  void look_at_all(const World<Num>& world) {
    for (int i = 0; i < static_cast<int>(world.balls.size()); ++i) {
      const Body<Num>& now = world.balls[i];
      compare(i, now, false, "a record time");
      if (!(now.time == trace->pieces[i].back().body.time) || now.version != seen[i]) keep(i, now);
    }
  }
};

// The engine's observer: a pointer to the trace's state.
template <class Num>
struct TraceObserver {
  TraceState<Num>* state = nullptr;
  void motion_changed(const World<Num>& world, int i, MotionChange why) { state->motion_changed(world, i, why); }
};

// The distance a collision's two objects are apart at its time, minus the
// contact distance (0 at contact), in long double: ball–ball from the
// centres, ball–wall from the centre to the segment.
template <class Num>
LD contact_gap(const Scene& scene, const TracedCollision<Num>& c) {
  // Differences formed in Num (exact in fixed point) before converting.
  if (c.collision.kind == EventKind::ball_ball) {
    const Vec2<Num> d = c.after_a.position - c.after_b.position;
    return std::hypot(ld(d.x), ld(d.y)) - ld(c.after_a.radius) - ld(c.after_b.radius);
  }
  const WallSpec& w = scene.walls[c.collision.b];
  // Relative to the wall's end a, formed in Num (exact in fixed point).
  const Vec2<Num> rel = c.after_a.position - vec2_from_double<Num>(w.a[0], w.a[1]);
  const LD rx = ld(rel.x), ry = ld(rel.y);
  const LD dx = LD(w.b[0]) - w.a[0], dy = LD(w.b[1]) - w.a[1];
  const LD s = std::clamp((rx * dx + ry * dy) / (dx * dx + dy * dy), LD(0), LD(1));
  return std::hypot(rx - s * dx, ry - s * dy) - ld(c.after_a.radius);
}

}  // namespace trace_detail

// Every collision happens at contact distance, within rounding. The gap at
// a collision's time is formed from the positions the engine carried there
// and compared in long double. It may differ from zero by:
//  - a contact left a hair inside or outside on purpose: a pair pressed
//    together is due when it stops separating, within the rest height h of
//    contact (event_engine.hpp, pressed_contact_due); h is the scene's own
//    rest.height or the documented default 1e-6 r_min (the README, "Rest";
//    the overlap the checks allow everywhere, motion_checks.cpp);
//  - the time, a root the analytic method rounds within its stated bound,
//    1e-12 of the query's scale max(R, V Δ, A Δ²) (docs/PROPERTIES.md; the
//    fixed-mode bound is far tighter): R the contact distance, V the
//    closing speed, A the relative acceleration, Δ the horizon: the record
//    interval where prediction starts afresh at every record time (under
//    accelerations), the whole run for a gas;
//  - the positions, carried from the balls' clocks (at most Δ before: the
//    record interval, or the run for a gas, which keeps its predictions) by
//    p + τ(v + τ/2 a): 4 roundings each of half a unit of the largest term,
//    strict relative to P + V Δ + A Δ² (P the larger coordinate), fixed
//    absolute; 64 units of 1 + P + R + V Δ + A Δ² (as no-overlap's rounding).
// A ball acted on where its partner is not (an event predicted before one
// of its balls changed course: stale) misses by the partner's change of
// course, far more than this.
template <class Num>
void check_contact_distance(const Scene& scene, double rest_height, double clock_lag, EngineTrace<Num>& trace,
                            const TracedCollision<Num>& c,
                            std::size_t index) {
  using namespace trace_detail;
  const LD gap = contact_gap(scene, c);
  const bool two = c.collision.kind == EventKind::ball_ball;
  auto coordinate = [](const Body<Num>& b) { return std::max(std::fabs(ld(b.position.x)), std::fabs(ld(b.position.y))); };
  const LD P = two ? std::max(coordinate(c.after_a), coordinate(c.after_b)) : coordinate(c.after_a);
  const LD R = ld(c.after_a.radius) + (two ? ld(c.after_b.radius) : LD(0));
  auto vec = [](const Vec2<Num>& v) { return std::hypot(ld(v.x), ld(v.y)); };
  const LD V = vec(c.before_a.velocity) + (two ? vec(c.before_b.velocity) : LD(0));
  const LD A = vec(c.before_a.acceleration) + (two ? vec(c.before_b.acceleration) : LD(0));
  const LD D = clock_lag;
  const LD reach = V * D + A * D * D;
  const LD tolerance = LD(rest_height) + LD(1e-12) * (R + reach) + 64 * unit<Num>() * (1 + P + R + reach);
  if (std::fabs(gap) <= tolerance) return;
  if (trace.misplaced_collisions++ > 0) return;
  trace.first_misplaced = "collision " + std::to_string(index) + " at t = " + text(ld(c.collision.time)) +
                          (two ? " between balls " : " of ball ") + std::to_string(c.collision.a) +
                          (two ? " and " : " with wall ") + std::to_string(c.collision.b) + ": " +
                          (gap > 0 ? "apart by " : "overlapping by ") + text(std::fabs(gap)) + " (tolerance " +
                          text(tolerance) + ")";
}

template <class Num>
EngineTrace<Num> trace_engine(const Scene& scene, double until) {
  EngineTrace<Num> trace;
  const std::size_t n = scene.balls.size();
  trace_detail::TraceState<Num> state;
  state.trace = &trace;
  EventCount events(event_cap(scene, until));
  state.events = &events;
  double r_min = 0;
  for (std::size_t i = 0; i < n; ++i) r_min = i == 0 ? scene.balls[i].radius : std::min(r_min, scene.balls[i].radius);
  const double rest_height = scene.rest.height.value_or(1e-6 * r_min);  // the scene's, or the README's default
  EventEngine<Num, trace_detail::TraceObserver<Num>> engine(make_world<Num>(scene), rest_scales(scene).in<Num>(),
                                                             ToiMethod::analytic, Num{}, false,
                                                             trace_detail::TraceObserver<Num>{&state});
  const auto& balls = engine.world().balls;
  // A gas keeps its predictions across record times, as simulate() does: a
  // ball's clock may then lag the present by the whole run, not one record
  // interval (the bound of check_contact_distance).
  const double clock_lag = engine.keeps_predictions() ? until : scene.record_interval;
  trace.pieces.resize(n);
  state.seen.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    trace.pieces[i].push_back({balls[i]});
    state.seen[i] = balls[i].version;
  }
  EngineCounters last = engine.counters();
  auto on_collision = [&](const Collision<Num>& c) {
    TracedCollision<Num> t;
    t.collision = c;
    const EngineCounters now = engine.counters();
    t.plastic = now.rest.plastic_pairs != last.rest.plastic_pairs;
    t.came_to_rest = now.rest.came_to_rest != last.rest.came_to_rest;
    t.held = now.rest.held != last.rest.held;
    t.slept = now.rest.fell_asleep != last.rest.fell_asleep;
    t.woken = now.rest.woken != last.rest.woken;
    last = now;
    const bool two_balls = c.kind == EventKind::ball_ball;
    // The engine records the velocities just before its response; the
    // position is the collision's (motion is continuous), the rest of the
    // ball does not change in a collision.
    for (std::size_t k = 0; k < c.island.size(); ++k) {
      t.island_after.push_back(balls[c.island[k]]);
      t.island_before.push_back(balls[c.island[k]]);
      t.island_before.back().velocity = c.island_velocity_before[k];
    }
    auto before = [&](int x) {  // a static ball (not in the island) does not move
      for (std::size_t k = 0; k < c.island.size(); ++k)
        if (c.island[k] == x) return t.island_before[k];
      return balls[x];
    };
    t.after_a = balls[c.a];
    t.before_a = before(c.a);
    if (two_balls) {
      t.after_b = balls[c.b];
      t.before_b = before(c.b);
    }
    check_contact_distance(scene, rest_height, clock_lag, trace, t, trace.collisions.size());
    trace.collisions.push_back(t);
    events.collision(trace_detail::ld(c.time));
  };
  const Num interval = num<Num>(scene.record_interval);
  const Num end = num<Num>(until);
  for (std::int64_t k = 1;; ++k) {
    Num t = interval * num<Num>(static_cast<double>(k));
    const bool is_last = !(t < end);
    if (is_last) t = end;
    engine.run_to(t, end, on_collision);  // as simulate() does
    state.look_at_all(engine.world());
    if (is_last) break;
  }
  trace.end = end;
  trace.counters = engine.counters();
  return trace;
}

}  // namespace collide2d::properties
