// The analytic method: time of impact from the exact motion model, with roots
// computed robustly (see point_contact.hpp and quadratic.hpp).
#pragma once

#include "toi/point_contact.hpp"
#include "toi/toi_result.hpp"

namespace collide2d {

// Ball a against ball b (b may be fixed: zero velocity and acceleration).
// The normal points from b's centre to a's.
template <class Num>
ToiResult<Num> time_of_impact_ball_ball(const BallState<Num>& a, const BallState<Num>& b, const Num& horizon) {
  const RelativeMotion<Num> m{accurate_difference(a.position, b.position), a.velocity - b.velocity,
                              a.acceleration - b.acceleration, a.radius + b.radius};
  const RootSearch<Num> root = first_contact(m, horizon);
  if (!root.found) return {};
  ToiResult<Num> r;
  r.state = ToiState::hit;
  r.time = root.t;
  r.feature = ContactFeature::ball;
  const Vec2<Num> pa = position_at(a, root.t);
  const Vec2<Num> pb = position_at(b, root.t);
  r.normal = normalized(pa - pb);
  r.point = pb + b.radius * r.normal;
  return r;
}

// What a wall query needs of the wall, computed once per wall (a simulator
// prepares its walls at load time).
template <class Num>
struct WallGeometry {
  Segment<Num> segment;
  TwoTerm<Vec2<Num>> direction;  // d = b − a, as hi + lo
  Num length_squared{};          // |d|² of d.hi
  Num length{};                  // |d|
  Vec2<Num> unit_normal;         // perp(d) / |d|: the side where d × (p − a) > 0
  Vec2<Num> box_lo, box_hi;      // bounding box
};

template <class Num>
WallGeometry<Num> prepare_wall(const Segment<Num>& wall) {
  WallGeometry<Num> g;
  g.segment = wall;
  g.direction = accurate_difference(wall.b, wall.a);
  g.length_squared = length_squared(g.direction.hi);
  g.length = NumberTraits<Num>::sqrt(g.length_squared);
  g.unit_normal = normalized(perp(g.direction.hi));
  g.box_lo = {wall.a.x < wall.b.x ? wall.a.x : wall.b.x, wall.a.y < wall.b.y ? wall.a.y : wall.b.y};
  g.box_hi = {wall.a.x < wall.b.x ? wall.b.x : wall.a.x, wall.a.y < wall.b.y ? wall.b.y : wall.a.y};
  return g;
}

// Ball against a two-sided wall segment with round ends. Candidates:
//  - a face: with d = w_b − w_a and S(t) = d × (p(t) − w_a) = |d| s(t), where
//    s is the signed distance to the wall's line,
//        S(t) = S₀ + S_v t + ½ S_a t²,
//    the clearance of side ε = ±1 is w(t) = ε S(t) − r |d| (a quadratic in t;
//    no division by |d| on the way), and a contact is its downward root with
//    the centre projecting inside the segment;
//  - an end: contact of the centre with a point at distance r (point_contact).
// The first candidate in time is the contact; a face wins a tie with an end.
// S₀ uses both differences as hi + lo and an exact-product cross product, so
// a ball near the middle of a long oblique wall gets its distance to the last
// bits.
template <class Num>
ToiResult<Num> time_of_impact_ball_wall(const BallState<Num>& ball, const WallGeometry<Num>& wall,
                                        const Num& horizon) {
  using T = NumberTraits<Num>;
  const Num zero{};
  const Num r = ball.radius;
  // Early out: the box around the centre's path over [0, H], grown by r,
  // misses the box around the wall (or an end, below).
  const Box<Num> path = trajectory_box(ball.position, ball.velocity, ball.acceleration, horizon);
  const Num reach = r + r * num<Num>(0x1p-40);
  auto out_of_reach = [&](const Vec2<Num>& lo, const Vec2<Num>& hi) {
    return hi.x < path.lo.x - reach || path.hi.x + reach < lo.x || hi.y < path.lo.y - reach || path.hi.y + reach < lo.y;
  };
  if (out_of_reach(wall.box_lo, wall.box_hi)) return {};

  const Vec2<Num>& d = wall.direction.hi;
  const auto rel = accurate_difference(ball.position, wall.segment.a);
  const Num S0 = accurate_cross(d, rel.hi) + (cross(d, rel.lo) + cross(wall.direction.lo, rel.hi));
  const Num Sv = cross(d, ball.velocity);
  const Num Sa = cross(d, ball.acceleration);
  const Num rL = r * wall.length;

  auto projects_inside = [&](const Num& t) {
    const Num along = dot(d, position_at(rel.hi, ball.velocity, ball.acceleration, t));
    return !(along < zero) && !(wall.length_squared < along);
  };

  ToiResult<Num> best;
  Num best_t = horizon;
  int best_side = 0;  // +1: contact on the side d × (p − w_a) > 0
  // Already within r of the face and closing in: contact at t = 0.
  if (!(rL < T::abs(S0)) && projects_inside(zero) && (S0 < zero ? zero < Sv : Sv < zero)) {
    best.state = ToiState::hit;
    best_t = zero;
    best.feature = ContactFeature::wall_face;
    best_side = S0 < zero ? -1 : 1;
  }
  // Faces: w(t) = ε S(t) − r |d|, so A = ½ ε S_a, b = ½ ε S_v, C = ε S₀ − r |d|.
  // Without acceleration across the wall (S_a = 0) the ball cannot come back
  // to the side it is not on: only its own side is searched.
  for (const int side : {1, -1}) {
    if (best.hit() && best_t == zero) break;
    if (Sa == zero && (side > 0 ? S0 < zero : zero < S0)) continue;
    const Num A = side > 0 ? T::half(Sa) : -T::half(Sa);
    const Num b = side > 0 ? T::half(Sv) : -T::half(Sv);
    const Num C = (side > 0 ? S0 : -S0) - rL;
    const RootSearch<Num> root = first_downward_root(A, b, C, [&] { return compensated_discriminant(A, b, C); }, best_t);
    if (root.found && projects_inside(root.t) && (!best.hit() || root.t < best_t)) {
      best.state = ToiState::hit;
      best_t = root.t;
      best.feature = ContactFeature::wall_face;
      best_side = side;
    }
  }
  // Ends: only the part of the horizon before the best face contact.
  const Vec2<Num>* ends[2] = {&wall.segment.a, &wall.segment.b};
  for (int e = 0; e < 2; ++e) {
    if (best.hit() && best_t == zero) break;
    if (out_of_reach(*ends[e], *ends[e])) continue;
    const RelativeMotion<Num> m{accurate_difference(ball.position, *ends[e]), ball.velocity, ball.acceleration, r};
    const RootSearch<Num> root = first_contact(m, best_t);
    if (root.found && (!best.hit() || root.t < best_t)) {
      best.state = ToiState::hit;
      best_t = root.t;
      best.feature = e == 0 ? ContactFeature::wall_end_a : ContactFeature::wall_end_b;
    }
  }
  if (!best.hit()) return best;

  best.time = best_t;
  const Vec2<Num> centre = position_at(ball, best_t);
  if (best.feature == ContactFeature::wall_face) {
    best.normal = best_side < 0 ? -wall.unit_normal : wall.unit_normal;
    best.point = centre - r * best.normal;
  } else {
    const Vec2<Num>& end = best.feature == ContactFeature::wall_end_a ? wall.segment.a : wall.segment.b;
    best.normal = normalized(centre - end);
    best.point = end;
  }
  return best;
}

template <class Num>
ToiResult<Num> time_of_impact_ball_wall(const BallState<Num>& ball, const Segment<Num>& wall, const Num& horizon) {
  return time_of_impact_ball_wall(ball, prepare_wall(wall), horizon);
}

}  // namespace collide2d
