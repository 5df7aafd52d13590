// The simulated world: bodies with their own clocks, walls prepared once.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "collide2d/scene/scene.hpp"
#include "collide2d/sim/rest.hpp"
#include "collide2d/toi/analytic.hpp"

namespace collide2d {

// A ball's state at its own time `time`; it moves as p + v t + ½ a t² from there.
// What a prediction reads of a neighbour comes first: in strict mode the
// motion, clock and radius fill one 64-byte cache line, and a body starts
// on a line of its own.
template <class Num>
struct alignas(64) Body {
  Vec2<Num> position;
  Vec2<Num> velocity;
  Vec2<Num> acceleration;       // what it moves with now: its own plus its contact forces (zero asleep)
  Num time{};
  Num radius{};
  Vec2<Num> free_acceleration;  // its own or the scene's gravity; zero if fixed
  Num mass{};
  Num restitution{};
  bool fixed = false;
  bool asleep = false;         // at rest on its supports (rest.hpp, rule 2): static until woken
  std::uint64_t version = 0;   // bumped at every change of motion: older predictions are stale
  Num struck_at = NumberTraits<Num>::from_double(-1.0);  // the time of its last collision (rest.hpp, rule 1)

  // Nothing moves it until something changes: fixed, or asleep.
  bool is_static() const { return fixed || asleep; }
};

template <class Num>
struct World {
  std::vector<Body<Num>> balls;
  std::vector<WallGeometry<Num>> walls;
  std::vector<Num> wall_restitution;
};

// What ball b accelerates with by itself (its contact forces add to this).
template <class Num>
Vec2<Num> own_acceleration(const Body<Num>& b) {
  return b.is_static() ? Vec2<Num>{} : b.free_acceleration;
}

// ½ m |v|² of a moving ball (a static one has none).
template <class Num>
Num kinetic_energy(const Body<Num>& b) {
  return b.is_static() ? Num{} : b.mass * NumberTraits<Num>::half(length_squared(b.velocity));
}

// Ball b of the scene as the engines start it: at rest on its own clock 0,
// never struck.
template <class Num>
Body<Num> body_of(const Scene& scene, const BallSpec& b) {
  Body<Num> body;
  const Point acc = effective_acceleration(scene, b);
  body.position = vec2_from_double<Num>(b.position[0], b.position[1]);
  body.velocity = vec2_from_double<Num>(b.velocity[0], b.velocity[1]);
  body.free_acceleration = vec2_from_double<Num>(acc[0], acc[1]);
  body.acceleration = body.free_acceleration;
  body.radius = num<Num>(b.radius);
  body.mass = num<Num>(b.mass);
  body.restitution = num<Num>(b.restitution);
  body.fixed = b.fixed;
  return body;
}

// The scene's walls in a world of no balls yet.
template <class Num>
World<Num> world_of_walls(const Scene& scene) {
  World<Num> w;
  for (const WallSpec& s : scene.walls) {
    w.walls.push_back(prepare_wall(Segment<Num>{vec2_from_double<Num>(s.a[0], s.a[1]), vec2_from_double<Num>(s.b[0], s.b[1])}));
    w.wall_restitution.push_back(num<Num>(s.restitution));
  }
  return w;
}

template <class Num>
World<Num> make_world(const Scene& scene) {
  World<Num> w = world_of_walls<Num>(scene);
  w.balls.reserve(scene.balls.size());
  for (const BallSpec& b : scene.balls) w.balls.push_back(body_of<Num>(scene, b));
  return w;
}

// The body's state carried to time t (t ≥ body.time) along its motion (a
// Body, or a gas's one-line body, gas_world.hpp: the same arithmetic).
template <class B, class Num>
BallState<Num> state_at(const B& b, const Num& t) {
  const Num dt = t - b.time;
  return {position_at(b.position, b.velocity, b.acceleration, dt), velocity_at(b.velocity, b.acceleration, dt),
          b.acceleration, b.radius};
}

template <class B, class Num>
void advance_to(B& b, const Num& t) {
  const BallState<Num> s = state_at(b, t);
  b.position = s.position;
  b.velocity = s.velocity;
  b.time = t;
}

// No ball has an acceleration of its own (a gas): paths are straight, and
// the rest rules, which need weight, never act.
template <class Num>
bool no_ball_accelerates(const World<Num>& w) {
  return std::all_of(w.balls.begin(), w.balls.end(),
                     [](const Body<Num>& b) { return b.free_acceleration.x == Num{} && b.free_acceleration.y == Num{}; });
}

// A moving ball's energy at position p and velocity v: ½ m |v|² − m a·p (a:
// its free acceleration, so a resting ball keeps its potential energy). A
// frame's energy is the sum over the balls that are not fixed.
template <class B, class Num>
Num mechanical_energy(const B& b, const Vec2<Num>& p, const Vec2<Num>& v) {
  return b.mass * (NumberTraits<Num>::half(length_squared(v)) - dot(b.free_acceleration, p));
}

}  // namespace collide2d
