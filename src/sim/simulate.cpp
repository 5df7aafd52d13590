#include "sim/simulate.hpp"

#include "toi/article_methods.hpp"

#include <algorithm>
#include <limits>

namespace collide2d {

CollapseThresholds collapse_thresholds(const Scene& scene) {
  double r_min = std::numeric_limits<double>::infinity();
  double g_max = std::hypot(scene.gravity[0], scene.gravity[1]);
  for (const BallSpec& b : scene.balls) {
    r_min = std::min(r_min, b.radius);
    if (b.acceleration) g_max = std::max(g_max, std::hypot((*b.acceleration)[0], (*b.acceleration)[1]));
  }
  if (!std::isfinite(r_min)) r_min = 1;
  const double tc = g_max > 0 ? 1e-3 * std::sqrt(r_min / g_max) : 1e-9 * scene.duration;
  return {tc, 1e-6 * r_min};
}

double deepest_overlap(const FrameRecord& f, const std::vector<double>& radius,
                       const std::vector<std::array<double, 4>>& walls) {
  double deepest = 0;
  const std::size_t n = radius.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2<double> pi{f.position[2 * i], f.position[2 * i + 1]};
    for (std::size_t j = i + 1; j < n; ++j) {
      const Vec2<double> pj{f.position[2 * j], f.position[2 * j + 1]};
      deepest = std::max(deepest, radius[i] + radius[j] - length(pi - pj));
    }
    for (const auto& w : walls)
      deepest = std::max(deepest, radius[i] - distance_to_segment(pi, Segment<double>{{w[0], w[1]}, {w[2], w[3]}}));
  }
  return deepest;
}

}  // namespace collide2d
