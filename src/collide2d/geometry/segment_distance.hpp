// The distance from a point to a segment: the overlap checks of scenes and
// runs, and the seed article's wall method, all measure with it.
#pragma once

#include "collide2d/geometry/vec2.hpp"

namespace collide2d {

// Distance from point p to the segment [a, b].
template <class Num>
Num distance_to_segment(const Vec2<Num>& p, const Segment<Num>& s) {
  const Num zero{};
  const Vec2<Num> d = s.b - s.a;
  const Vec2<Num> rel = p - s.a;
  const Num along = dot(d, rel);
  if (!(zero < along)) return length(rel);
  const Num len_sq = length_squared(d);
  if (!(along < len_sq)) return length(p - s.b);
  return NumberTraits<Num>::abs(cross(d, rel)) / NumberTraits<Num>::sqrt(len_sq);
}

}  // namespace collide2d
