#include "collide2d/sim/simulate.hpp"

#include "collide2d/geometry/nearby_pairs.hpp"
#include "collide2d/geometry/segment_distance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace collide2d {

// |a| by + x and sqrt only, each correctly rounded by IEEE 754 on every
// architecture, rather than std::hypot: libm's hypot is not correctly rounded
// and differs between libms (glibc's i386 one works in x87 extended
// precision), so a diagonal gravity would give another rest speed, and another
// run, on i686. For an axis-aligned a (every shipped scene) sqrt(fl(y*y)) is
// |y| exactly, as hypot gives: stored results are unchanged. No overflow or
// underflow below |a| ~ 1e154 or above ~ 1e-154.
static double magnitude_of(const std::array<double, 2>& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1]); }

RestScales rest_scales(const Scene& scene) {
  double r_min = std::numeric_limits<double>::infinity();
  double g_max = magnitude_of(scene.gravity);
  for (const BallSpec& b : scene.balls) {
    r_min = std::min(r_min, b.radius);
    if (b.acceleration) g_max = std::max(g_max, magnitude_of(*b.acceleration));
  }
  if (!std::isfinite(r_min)) r_min = 1;
  RestScales s;
  s.height = scene.rest.height.value_or(1e-6 * r_min);
  s.speed = scene.rest.speed.value_or(std::sqrt(2 * g_max * s.height));
  s.band = scene.rest.band.value_or(s.height);
  // Creeping for a whole run at this speed sinks a contact by at most h_rest.
  s.creep_speed = scene.duration > 0 ? s.height / scene.duration : 0.0;
  // Balls in a balanced island press each other with what rounding leaves of
  // g (a few ulps): that is no press, and must not make contacts.
  s.least_press = 0x1p-30 * g_max;
  return s;
}

// Pairs are found through a grid (geometry/nearby_pairs.hpp): O(N log N) a
// frame, so that checking a frame of a million balls costs about a second.
double deepest_overlap(const FrameRecord& f, const std::vector<double>& radius,
                       const std::vector<std::array<double, 4>>& walls) {
  double deepest = 0;
  const std::size_t n = radius.size();
  auto centre = [&](std::size_t i) { return Vec2<double>{f.position[2 * i], f.position[2 * i + 1]}; };
  double r_max = 0;
  for (double r : radius) r_max = std::max(r_max, r);
  // A pair farther apart than the sum of its radii (by more than rounding:
  // squares compared with a margin of 2^-40) cannot deepen the overlap:
  // its square root, the cost of the check, is taken only for the rest.
  for_each_nearby_pair(n, r_max, centre, [&](std::size_t i, std::size_t j) {
    const double reach = radius[i] + radius[j];
    const double d2 = length_squared(centre(i) - centre(j));
    if (d2 > reach * reach * (1 + 0x1p-40)) return;
    deepest = std::max(deepest, reach - std::sqrt(d2));
  });
  // A ball whose centre lies farther than r_max from a wall's bounding box
  // along either axis is farther than its radius from the wall: it cannot
  // deepen the overlap (which starts at 0), and most balls of a large
  // scene are such for every wall. The reach is widened far beyond the
  // rounding of the test.
  const double wall_reach = r_max * (1 + 0x1p-40) + 0x1p-1000;
  for (const auto& w : walls) {
    const Segment<double> segment{{w[0], w[1]}, {w[2], w[3]}};
    const double lo_x = std::min(w[0], w[2]) - wall_reach, hi_x = std::max(w[0], w[2]) + wall_reach;
    const double lo_y = std::min(w[1], w[3]) - wall_reach, hi_y = std::max(w[1], w[3]) + wall_reach;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2<double> c = centre(i);
      if (c.x < lo_x || hi_x < c.x || c.y < lo_y || hi_y < c.y) continue;
      deepest = std::max(deepest, radius[i] - distance_to_segment(c, segment));
    }
  }
  return deepest;
}

}  // namespace collide2d
