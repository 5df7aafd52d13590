// The magnitudes a tolerance is made of, measured on the run itself: every
// bound in the checks is (rounding unit of the mode) × (a count of rounding
// steps) × (the size of the numbers rounded), so the sizes are taken from
// what the engine actually held, not guessed from the scene.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine_trace.hpp"

namespace collide2d::properties {

// A unit normal d / |d| = d · (1/|d|): in fixed mode 1/|d| rounds by 2^-65
// absolute, which d's length turns into a relative error |d| 2^-65 (and |d|
// itself, formed from squares, is off by ~2^-65 / |d|): so a fixed normal is
// off by ≤ 2^-64 (1/|d| + |d|), the longer the wall the worse.
// The rounding unit of one operation: strict, relative (eps = 2^-52, half an
// ulp is eps/2); fixed, absolute (2^-64 resolution, half of it per rounding).
inline constexpr double strict_eps = std::numeric_limits<double>::epsilon();
inline constexpr double fixed_resolution = 0x1p-64;

struct RunScales {
  double position = 0;      // largest |coordinate| of a centre or a wall end
  double speed = 0;         // largest |v|
  double acceleration = 0;  // largest |a|
  double mass_max = 0;
  double r_min = std::numeric_limits<double>::infinity();
  double wall_min = std::numeric_limits<double>::infinity();  // shortest wall
  double normal_length = 0;  // longest vector a unit normal is formed from: a wall, or 2 r_max
};

template <class Num>
RunScales scales_of(const Scene& scene, const EngineTrace<Num>& trace) {
  using T = NumberTraits<Num>;
  RunScales s;
  for (const WallSpec& w : scene.walls) {
    s.position = std::max({s.position, std::fabs(w.a[0]), std::fabs(w.a[1]), std::fabs(w.b[0]), std::fabs(w.b[1])});
    s.wall_min = std::min(s.wall_min, std::hypot(w.b[0] - w.a[0], w.b[1] - w.a[1]));
    s.normal_length = std::max(s.normal_length, std::hypot(w.b[0] - w.a[0], w.b[1] - w.a[1]));
  }
  for (const auto& pieces : trace.pieces)
    for (const MotionPiece<Num>& p : pieces) {
      const Body<Num>& b = p.body;
      s.position = std::max({s.position, std::fabs(T::to_double(b.position.x)), std::fabs(T::to_double(b.position.y))});
      s.speed = std::max(s.speed, std::hypot(T::to_double(b.velocity.x), T::to_double(b.velocity.y)));
      s.acceleration = std::max(s.acceleration, std::hypot(T::to_double(b.free_acceleration.x), T::to_double(b.free_acceleration.y)));
      s.mass_max = std::max(s.mass_max, T::to_double(b.mass));
      s.r_min = std::min(s.r_min, T::to_double(b.radius));
      s.normal_length = std::max(s.normal_length, 2 * T::to_double(b.radius));
    }
  return s;
}

}  // namespace collide2d::properties
