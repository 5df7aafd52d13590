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

// Ball against a two-sided wall segment with round ends. Candidates:
//  - a face: the signed distance to the wall's line, s(t) = s₀ + s_v t + ½ s_a t²,
//    reaches +r from above or −r from below (a quadratic each) while the
//    centre projects inside the segment;
//  - an end: contact of the centre with a point at distance r (point_contact).
// The first candidate in time is the contact; a face wins a tie with an end.
// s₀ = (d × (p − w_a)) / |d| with d = w_b − w_a, both differences kept as
// hi + lo, so a ball near the middle of a long oblique wall still gets its
// distance to the last bits.
template <class Num>
ToiResult<Num> time_of_impact_ball_wall(const BallState<Num>& ball, const Segment<Num>& wall, const Num& horizon) {
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
  const Vec2<Num> wall_lo{wall.a.x < wall.b.x ? wall.a.x : wall.b.x, wall.a.y < wall.b.y ? wall.a.y : wall.b.y};
  const Vec2<Num> wall_hi{wall.a.x < wall.b.x ? wall.b.x : wall.a.x, wall.a.y < wall.b.y ? wall.b.y : wall.a.y};
  if (out_of_reach(wall_lo, wall_hi)) return {};

  const auto d = accurate_difference(wall.b, wall.a);
  const auto rel = accurate_difference(ball.position, wall.a);
  const Num length_sq = length_squared(d.hi);
  // Divided, not multiplied by a reciprocal: exact whenever the quotient is
  // representable (an axis-aligned wall keeps its distances exact).
  const Num len = T::sqrt(length_sq);
  const Num s0 = (accurate_cross(d.hi, rel.hi) + (cross(d.hi, rel.lo) + cross(d.lo, rel.hi))) / len;
  const Num sv = cross(d.hi, ball.velocity) / len;
  const Num sa = cross(d.hi, ball.acceleration) / len;

  auto projects_inside = [&](const Num& t) {
    const Vec2<Num> q = position_at(rel.hi, ball.velocity, ball.acceleration, t);
    const Num along = dot(d.hi, q);
    return !(along < zero) && !(length_sq < along);
  };

  ToiResult<Num> best;
  Num best_t = horizon;
  int best_side = 0;  // +1: contact on the side d × (p − w_a) > 0
  // Already within r of the face and closing in: contact at t = 0.
  if (!(r < T::abs(s0)) && projects_inside(zero) && (s0 < zero ? zero < sv : sv < zero)) {
    best.state = ToiState::hit;
    best_t = zero;
    best.feature = ContactFeature::wall_face;
    best_side = s0 < zero ? -1 : 1;
  }
  // Faces: w(t) = ε s(t) − r for ε = ±1, A = ½ ε s_a, b = ½ ε s_v, C = ε s₀ − r.
  // Without acceleration across the wall (s_a = 0) the ball cannot come back
  // to the side it is not on: only its own side is searched.
  for (const int side : {1, -1}) {
    if (best.hit() && best_t == zero) break;
    if (sa == zero && (side > 0 ? s0 < zero : zero < s0)) continue;
    const Num eps = num<Num>(side);
    const Num A = T::half(eps * sa), b = T::half(eps * sv), C = eps * s0 - r;
    const RootSearch<Num> root = first_downward_root(A, b, C, [&] { return compensated_discriminant(A, b, C); }, best_t);
    if (root.found && projects_inside(root.t) && (!best.hit() || root.t < best_t)) {
      best.state = ToiState::hit;
      best_t = root.t;
      best.feature = ContactFeature::wall_face;
      best_side = side;
    }
  }
  // Ends: only the part of the horizon before the best face contact.
  const Vec2<Num>* ends[2] = {&wall.a, &wall.b};
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
    // perp(d) points to the side where d × (p − w_a) > 0.
    const Vec2<Num> unit_normal = normalized(perp(d.hi));
    best.normal = best_side < 0 ? -unit_normal : unit_normal;
    best.point = centre - r * best.normal;
  } else {
    const Vec2<Num>& end = best.feature == ContactFeature::wall_end_a ? wall.a : wall.b;
    best.normal = normalized(centre - end);
    best.point = end;
  }
  return best;
}

}  // namespace collide2d
