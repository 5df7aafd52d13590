#include "collide2d/sim/simulate.hpp"

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

double deepest_overlap(const FrameRecord& f, const std::vector<double>& radius,
                       const std::vector<std::array<double, 4>>& walls) {
  double r_max = 0;
  for (const double r : radius) r_max = std::max(r_max, r);
  return deepest_overlap_of(f, [&](std::size_t i) { return radius[i]; }, radius.size(), r_max, walls);
}

}  // namespace collide2d
