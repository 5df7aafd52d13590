// How far a vector lies from the cone of some unit normals: what
// frictionless supports can push (each along its normal, never pulling).
// Shared by the wake check (rest_checks.cpp) and the impulse check
// (impulse_checks.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "collide2d/geometry/vec2.hpp"

namespace collide2d::properties {

// How far v lies from the cone {Σ λ_k n_k, λ_k ≥ 0} of unit normals: 0
// inside; otherwise the nearest of the apex and the rays (in the plane a
// point of the cone lies on a ray or strictly between two normals less than
// π apart: Carathéodory).
inline long double distance_to_cone(const Vec2<long double>& v, const std::vector<Vec2<long double>>& normals) {
  using LD = long double;
  auto cross = [](const Vec2<LD>& a, const Vec2<LD>& b) { return a.x * b.y - a.y * b.x; };
  LD best = std::hypot(v.x, v.y);
  for (const Vec2<LD>& n : normals) {
    const LD along = n.x * v.x + n.y * v.y;
    if (along > 0) best = std::min(best, std::fabs(cross(n, v)));
  }
  for (const Vec2<LD>& a : normals)
    for (const Vec2<LD>& b : normals)
      if (cross(a, b) > 0 && cross(a, v) >= 0 && cross(v, b) >= 0) return 0;
  return best;
}

}  // namespace collide2d::properties
