#include <algorithm>
#include <cmath>
#include <limits>

#include "collide2d/geometry/segment_distance.hpp"
#include "peers/peer_run.hpp"

namespace collide2d {

double scene_energy(const Scene& scene, const PeerSample& s) {
  double e = 0;
  for (std::size_t i = 0; i < scene.balls.size(); ++i) {
    const BallSpec& b = scene.balls[i];
    if (b.fixed) continue;
    const Point a = effective_acceleration(scene, b);
    e += 0.5 * b.mass * length_squared(s.velocity[i]) - b.mass * (a[0] * s.position[i].x + a[1] * s.position[i].y);
  }
  return e;
}

// Pairs by a sweep along x: only balls whose x-extents overlap are compared.
double deepest_relative_overlap(const Scene& scene, const PeerSample& s) {
  const std::size_t n = scene.balls.size();
  std::vector<std::size_t> order;  // balls at finite places (an engine that blew up leaves NaN)
  for (std::size_t i = 0; i < n; ++i)
    if (std::isfinite(s.position[i].x) && std::isfinite(s.position[i].y)) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return s.position[a].x - scene.balls[a].radius < s.position[b].x - scene.balls[b].radius;
  });
  double deepest = 0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t i = order[k];
    const double ri = scene.balls[i].radius, right = s.position[i].x + ri;
    for (std::size_t m = k + 1; m < order.size(); ++m) {
      const std::size_t j = order[m];
      const double rj = scene.balls[j].radius;
      if (s.position[j].x - rj > right) break;
      const double depth = ri + rj - length(s.position[i] - s.position[j]);
      deepest = std::max(deepest, depth / std::min(ri, rj));
    }
    for (const WallSpec& w : scene.walls) {
      const double d = distance_to_segment(s.position[i], Segment<double>{{w.a[0], w.a[1]}, {w.b[0], w.b[1]}});
      deepest = std::max(deepest, (ri - d) / ri);
    }
  }
  return deepest;
}

int balls_outside(const Scene& scene, const PeerSample& s) {
  if (scene.walls.empty()) return 0;
  double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
  for (const WallSpec& w : scene.walls)
    for (const Point& p : {w.a, w.b}) {
      lo_x = std::min(lo_x, p[0]), hi_x = std::max(hi_x, p[0]);
      lo_y = std::min(lo_y, p[1]), hi_y = std::max(hi_y, p[1]);
    }
  int outside = 0;
  for (const Vec2<double>& p : s.position)
    if (!(p.x >= lo_x && p.x <= hi_x && p.y >= lo_y && p.y <= hi_y)) ++outside;
  return outside;
}

}  // namespace collide2d
