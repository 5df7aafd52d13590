// A pinch: a ball passing between two immovable partners (walls' faces or
// ends, fixed or sleeping balls) whose gap is exactly its diameter.
//
// Without gravity nothing presses the ball onto either partner, so rule 1
// of rest.hpp never holds it. Its clearance between the two shrinks to zero
// at the narrowest point while its normal speed w stays finite, so it
// bounces between them ever faster (a factor e per bounce) and the bounces
// meet at one instant: an inelastic collapse against the geometry. In
// exact arithmetic the two normals there are opposite (n' = −n, both along
// the pinch's axis) and the series at that instant has a limit: w → 0, the
// tangential motion unchanged, the ball touching both. In floating or fixed
// point the ball sits a few units of rounding inside the gap, so the two
// normals differ from opposite by an angle α ~ sqrt(2 ε / R): each bounce
// feeds the tangential speed u into the normal one (by ~ (1 + e) u α), and
// the series rings at a speed ~ u α / (1 − e) for ever instead of decaying
// (three stalls of the property suite: datasets/regressions/).
//
// So a strike on a ball struck again at the same instant, between two
// immovable partners on opposite sides, is answered along the pinch's axis
// (the line across the gap where it is narrowest) when the gap is at least
// its diameter, to within the rounding of the gap's own computation: the
// limit of the series, a plastic impact along the axis that leaves the
// tangential motion as it is (ContactRules::collide).
//
// A gap narrower than the ball is a wedge: the two normals are a true angle
// α off opposite. Only the normal speed falls by e a strike; the series at
// one instant either turns the ball back or collapses, and which depends on
// its two-strike map: with complex eigenvalues, where (1 + e)² sin² α >
// (1 − e)², it always turns the ball back (after ever more strikes as α
// falls to that bound); with real ones it collapses, the speed falling
// geometrically to zero without leaving the cone of velocities that close
// on a side, unless the ball's velocity turns it out in the first few
// strikes. A collapse has no end an engine could reach one strike at a time
// (a review's wedges, δ/2 and 2δ narrower than the ball: 10^5 events at one
// instant). ring_collapses runs the series itself, at one instant, as the
// engine would, for a bounded number of strikes; its limit, a collapse, is
// the plastic impact on both sides at once
// (ContactRules::collide). Here is only the geometry and the series.
#pragma once

#include <optional>

#include "collide2d/geometry/vec2.hpp"
#include "collide2d/numeric/number_traits.hpp"

namespace collide2d {

// One side of a pinch, as the ball meets it.
template <class Num>
struct PinchSide {
  bool face = false;  // a wall's face (a line) rather than a round partner
  Vec2<Num> point;    // on the face's line, or the round partner's centre
  Vec2<Num> normal;   // the face's unit normal (either sign); unused for a round partner
  Num radius{};       // the round partner's radius (0 for a wall's end)
};

// The unit axis of the pinch between sides p and q (its sign arbitrary),
// if the gap between them is at least the diameter where it is narrowest,
// to within 2^-48 of the scale of the numbers it is formed from (its few
// roundings, 2^-53 of that scale each in double, 2^-64 absolute in Q63.64,
// come to at most 2^-51 of it: eight times that, and still below the
// resolution of positions 2^5 times smaller than the coordinates):
// across a face and a round partner, along the face's normal;
// across two round partners, along the line of their centres; across two
// faces, only when they are exactly parallel (two faces at any other angle
// make a wedge, not a pinch).
template <class Num>
std::optional<Vec2<Num>> pinch_axis(const PinchSide<Num>& p, const PinchSide<Num>& q, const Num& diameter) {
  const Num zero{};
  auto magnitude = [&](const Num& x) { return x < zero ? -x : x; };
  const Num scale = largest_magnitude(p.point) + largest_magnitude(q.point) + p.radius + q.radius + diameter;
  const Num rounding = num<Num>(0x1p-48) * scale;
  Num gap{};
  Vec2<Num> axis;
  if (p.face && q.face) {
    if (cross(p.normal, q.normal) != zero) return std::nullopt;
    axis = p.normal;
    gap = magnitude(dot(q.point - p.point, axis));
  } else if (p.face || q.face) {
    const PinchSide<Num>& face = p.face ? p : q;
    const PinchSide<Num>& round = p.face ? q : p;
    axis = face.normal;
    gap = magnitude(dot(round.point - face.point, axis)) - round.radius;
  } else {
    const Vec2<Num> d = q.point - p.point;
    const Num length = NumberTraits<Num>::sqrt(length_squared(d));
    if (!(zero < length)) return std::nullopt;
    axis = {d.x / length, d.y / length};
    gap = length - p.radius - q.radius;
  }
  if (gap < diameter - rounding) return std::nullopt;
  return axis;
}

// The series of strikes at one instant of a ball of velocity v between two
// immovable sides with unit normals n1 (struck now) and n2 (towards the
// ball), restitution e: each strike reflects the normal speed of the side
// the ball closes on fastest, v ← v − (1 + e)(v·n) n. True if the series
// has not ended (the ball still closing on a side) after `strikes` of them,
// or has brought the ball to rest: a collapse, whose limit is rest against
// both sides.
template <class Num>
bool ring_collapses(Vec2<Num> v, const Vec2<Num>& n1, const Vec2<Num>& n2, const Num& e, int strikes) {
  const Num zero{};
  for (int k = 0; k < strikes; ++k) {
    if (v.x == zero && v.y == zero) return true;
    const Num d1 = dot(v, n1), d2 = dot(v, n2);
    const bool first = d1 < d2;
    const Num d = first ? d1 : d2;
    if (!(d < zero)) return false;  // opening both: the ring ended, the ball turned back
    const Vec2<Num>& n = first ? n1 : n2;
    const Num k_n = (num<Num>(1.0) + e) * d;
    v = {v.x - k_n * n.x, v.y - k_n * n.y};
  }
  return true;
}

}  // namespace collide2d
