// Runs a scene through the event engine exactly as simulate() does (record
// times k·interval, prediction afresh at each) and keeps what the checks
// need: each ball's motion as pieces (a Body: position, velocity and
// acceleration at its clock, valid until the next piece) and every collision
// with the two balls' states just before (velocities as the engine recorded
// them) and just after it.
//
// The engine is observed at each collision callback and at each record time.
// A ball's motion changes only at a collision (its version goes up by one,
// seen in the callback) or when it leaves a wall it rests on (version up by
// one, no callback). A change the trace did not see is detected by the
// version: the piece before it is then marked unknown past its start (its end
// is not known), the interval is skipped by the motion checks and counted.
#pragma once

#include <cstdint>
#include <vector>

#include "collide2d/numeric/fixed_words.hpp"
#include "collide2d/sim/simulate.hpp"

namespace collide2d::properties {

template <class Num>
struct MotionPiece {
  Body<Num> body;      // the motion from body.time on
  bool known = true;   // false: an unseen change happened before the next piece
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

template <class Num>
struct EngineTrace {
  std::vector<std::vector<MotionPiece<Num>>> pieces;  // per ball, in time order
  std::vector<TracedCollision<Num>> collisions;
  Num end{};
  EngineCounters counters;
  std::int64_t unknown_pieces = 0;
};

template <class Num>
EngineTrace<Num> trace_engine(const Scene& scene, double until) {
  EventEngine<Num> engine(make_world<Num>(scene), rest_scales(scene).in<Num>());
  EngineTrace<Num> trace;
  const auto& balls = engine.world().balls;
  std::vector<std::uint64_t> seen(balls.size());
  trace.pieces.resize(balls.size());
  for (std::size_t i = 0; i < balls.size(); ++i) {
    trace.pieces[i].push_back({balls[i], true});
    seen[i] = balls[i].version;
  }
  // Records ball i's current motion; `changes`: how many changes of its
  // version this observation accounts for.
  auto observe = [&](int i, std::uint64_t changes) {
    const Body<Num>& b = balls[i];
    auto& list = trace.pieces[i];
    if (b.version != seen[i] + changes) {
      list.back().known = false;
      ++trace.unknown_pieces;
    }
    if (b.version != seen[i] || !(b.time == list.back().body.time)) list.push_back({b, true});
    seen[i] = b.version;
  };
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
    // ball does not change in a collision. (The motion pieces could not
    // tell: an island's forces change a ball's motion with no callback.)
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
    observe(c.a, balls[c.a].fixed ? 0 : 1);
    if (two_balls) observe(c.b, balls[c.b].fixed ? 0 : 1);
    trace.collisions.push_back(t);
  };
  const Num interval = num<Num>(scene.record_interval);
  const Num end = num<Num>(until);
  for (std::int64_t k = 1;; ++k) {
    Num t = interval * num<Num>(static_cast<double>(k));
    const bool is_last = !(t < end);
    if (is_last) t = end;
    engine.advance_to(t, on_collision);
    for (int i = 0; i < static_cast<int>(balls.size()); ++i) observe(i, 0);
    if (is_last) break;
  }
  trace.end = end;
  trace.counters = engine.counters();
  return trace;
}

// Exact enough conversions for the checks: a Fixed keeps 64 of its 127 bits
// (a long double's mantissa), a double all of its own.
inline long double to_long_double(double x) { return x; }
inline long double to_long_double(const Fixed& x) {
  const FixedWords w = to_words(x);
  return static_cast<long double>(w.hi) + static_cast<long double>(static_cast<std::uint64_t>(w.lo)) * 0x1p-64L;
}

}  // namespace collide2d::properties
