// The world of a gas in the gas engine (gas_engine.hpp): a ball's state in
// one 64-byte cache line (strict mode), where a Body (world.hpp) takes two.
//
// In a gas no ball accelerates, none is fixed or asleep, and a body changes
// only at its own strikes, so of a Body's fields a gas needs the motion, its
// clock, radius, mass and version: 64 bytes in doubles. What it leaves out
// follows from those:
//   - the accelerations are zero (GasEngine::applies asks for +0 to the bit,
//     so that the arithmetic on the zero below is the Body's arithmetic);
//   - struck_at, the time of the ball's last collision, is its clock once it
//     has been struck (a strike carries both balls to its instant and bumps
//     their versions), −1 before (version 0);
//   - the restitution is kept beside the bodies, once for all when every
//     ball has the same.
// A million balls take 64 MB instead of 128, and a prediction reads one line
// of each neighbour instead of two.
#pragma once

#include <cstdint>
#include <cstring>
#include <optional>
#include <type_traits>
#include <vector>

#include "collide2d/numeric/fixed.hpp"
#include "collide2d/sim/world.hpp"

namespace collide2d {

template <class Num>
struct alignas(64) GasBody {
  Vec2<Num> position;
  Vec2<Num> velocity;
  Num time{};
  Num radius{};
  Num mass{};
  std::uint64_t version = 0;  // bumped at every change of motion (Body::version)

  // What the frames, the watch and the time of impact read of a body, under
  // Body's names: a gas's ball moves on a straight line, by itself.
  static inline const Vec2<Num> acceleration{};
  static inline const Vec2<Num> free_acceleration{};
  static constexpr bool fixed = false;
  bool is_static() const { return false; }
  // Body::struck_at: its clock once struck, −1 before.
  Num struck_at() const { return version == 0 ? NumberTraits<Num>::from_double(-1.0) : time; }
  // struck_at() == t for a time t ≥ 0, without forming the −1 (in fixed
  // point a conversion from double, at every event).
  bool struck_at_time(const Num& t) const { return version != 0 && time == t; }
};

static_assert(sizeof(GasBody<double>) == 64);

// A gas's ball carried to time t ≥ its clock: state_at's arithmetic
// (world.hpp) on its zero acceleration. In fixed point, which has no −0, a
// product with zero is zero and x + 0 is x exactly, so the products of the
// zero are left out: p + t v and v, the same bits for four products less a
// carry (a gas's predictions carry both balls of every pair they try), and
// none where t is its clock (a pair is tried from the later of its two
// clocks; a strike carries its balls to the present twice). In floating
// point the zero's terms stay: +0 added turns a −0 into +0.
template <class Num>
BallState<Num> state_at(const GasBody<Num>& b, const Num& t) {
  const Num dt = t - b.time;
  if constexpr (std::is_same_v<Num, Fixed>) {
    if (dt == Num{}) return {b.position, b.velocity, b.acceleration, b.radius};
    return {{b.position.x + dt * b.velocity.x, b.position.y + dt * b.velocity.y}, b.velocity, b.acceleration, b.radius};
  }
  return {position_at(b.position, b.velocity, b.acceleration, dt), velocity_at(b.velocity, b.acceleration, dt),
          b.acceleration, b.radius};
}

template <class Num>
struct GasWorld {
  std::vector<GasBody<Num>> balls;
  std::vector<WallGeometry<Num>> walls;
  std::vector<Num> wall_restitution;
  // Each ball's restitution, or none where all have `common_restitution`.
  std::vector<Num> restitution;
  Num common_restitution{};

  const Num& restitution_of(int ball) const {
    return restitution.empty() ? common_restitution : restitution[static_cast<std::size_t>(ball)];
  }
};

// Whether x is +0 to the bit (−0 would make other bits in the arithmetic on it).
template <class Num>
bool is_plus_zero(const Num& x) {
  const Num zero{};
  return std::memcmp(&x, &zero, sizeof x) == 0;
}

// Whether a Body is what a GasBody can hold exactly.
template <class Num>
bool fits_a_gas_body(const Body<Num>& b) {
  const Num minus_one = NumberTraits<Num>::from_double(-1.0);
  const bool struck_at_its_clock = b.version == 0 ? b.struck_at == minus_one : b.struck_at == b.time;
  return !b.fixed && !b.asleep && struck_at_its_clock &&
         is_plus_zero(b.acceleration.x) && is_plus_zero(b.acceleration.y) &&
         is_plus_zero(b.free_acceleration.x) && is_plus_zero(b.free_acceleration.y);
}

// The gas's world of bodies 0 .. n − 1, body_at(i) each, and the walls of
// `w`; none if a body does not fit_a_gas_body. Each ball's restitution is
// kept only once they differ (a million equal ones are 8 MB).
template <class Num, class Walls, class BodyAt>
std::optional<GasWorld<Num>> gas_world_of_bodies(std::size_t n, BodyAt body_at, const Walls& w) {
  GasWorld<Num> g;
  g.walls = w.walls;
  g.wall_restitution = w.wall_restitution;
  g.balls.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Body<Num> b = body_at(i);
    if (!fits_a_gas_body(b)) return std::nullopt;
    g.balls.push_back({b.position, b.velocity, b.time, b.radius, b.mass, b.version});
    if (i == 0) g.common_restitution = b.restitution;
    if (!g.restitution.empty()) {
      g.restitution.push_back(b.restitution);
    } else if (std::memcmp(&b.restitution, &g.common_restitution, sizeof(Num)) != 0) {
      g.restitution.assign(i, g.common_restitution);  // the balls before, all the first's
      g.restitution.push_back(b.restitution);
    }
  }
  return g;
}

// The gas's world from a World whose every ball fits_a_gas_body.
template <class Num>
GasWorld<Num> gas_world_of(const World<Num>& w) {
  return gas_world_of_bodies<Num>(w.balls.size(), [&](std::size_t i) { return w.balls[i]; }, w).value();
}

// The gas's world of a scene straight from its balls, without the World
// between (a million balls' Bodies are 128 MB, held with the scene's 88),
// or none if a ball does not fit a gas (it accelerates, or is fixed).
template <class Num>
std::optional<GasWorld<Num>> gas_world_of_scene(const Scene& scene) {
  return gas_world_of_bodies<Num>(
      scene.balls.size(), [&](std::size_t i) { return body_of<Num>(scene, scene.balls[i]); }, world_of_walls<Num>(scene));
}

// The same, letting w's bodies go once the gas's are made.
template <class Num>
GasWorld<Num> gas_world_releasing(World<Num>& w) {
  GasWorld<Num> g = gas_world_of(w);
  std::vector<Body<Num>>().swap(w.balls);
  return g;
}

// And back, bit for bit (the general engine takes a gas over at a jam).
template <class Num>
World<Num> world_of(const GasWorld<Num>& g) {
  World<Num> w;
  w.walls = g.walls;
  w.wall_restitution = g.wall_restitution;
  w.balls.reserve(g.balls.size());
  for (std::size_t i = 0; i < g.balls.size(); ++i) {
    const GasBody<Num>& gb = g.balls[i];
    Body<Num> b;
    b.position = gb.position;
    b.velocity = gb.velocity;
    b.time = gb.time;
    b.radius = gb.radius;
    b.mass = gb.mass;
    b.restitution = g.restitution_of(static_cast<int>(i));
    b.version = gb.version;
    b.struck_at = gb.struck_at();
    w.balls.push_back(b);
  }
  return w;
}

}  // namespace collide2d
