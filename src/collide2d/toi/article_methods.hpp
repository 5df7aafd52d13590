// The seed article's two time-of-impact methods, kept faithful, blind spots
// included, so that studies can measure them against the analytic method.
#pragma once

#include "collide2d/geometry/segment_distance.hpp"
#include "collide2d/toi/point_contact.hpp"
#include "collide2d/toi/toi_result.hpp"

namespace collide2d {

// Step and bisect (article, part III): move the whole step; only if the
// objects overlap at its end, bisect the step until the gap is within ±eps.
// A contact that begins and ends inside the step (a graze, or a fast ball
// passing a corner) leaves no overlap at the end and is missed: the method's
// blind spot, measured by the studies, not mended here.
template <class Num, class Gap>
RootSearch<Num> article_step_and_bisect(Gap gap, const Num& horizon, const Num& eps) {
  using T = NumberTraits<Num>;
  const Num zero{};
  if (!(gap(horizon) < zero)) return {};
  Num lo = zero, hi = horizon;
  for (int i = 0; i < T::max_root_iterations; ++i) {
    const Num mid = lo + T::half(hi - lo);
    const Num g = gap(mid);
    if (!(eps < T::abs(g))) return {true, mid};
    if (g < zero) hi = mid; else lo = mid;
    if (T::no_value_between(lo, hi)) break;
  }
  return {true, hi};
}

template <class Num>
ToiResult<Num> bisection_ball_ball(const BallState<Num>& a, const BallState<Num>& b, const Num& horizon,
                                   const Num& eps) {
  const Num contact_distance = a.radius + b.radius;
  auto gap = [&](const Num& t) { return length(position_at(a, t) - position_at(b, t)) - contact_distance; };
  const RootSearch<Num> root = article_step_and_bisect(gap, horizon, eps);
  if (!root.found) return {};
  ToiResult<Num> r;
  r.state = ToiState::hit;
  r.time = root.t;
  r.feature = ContactFeature::ball;
  const Vec2<Num> pb = position_at(b, root.t);
  r.normal = normalized(position_at(a, root.t) - pb);
  r.point = pb + b.radius * r.normal;
  return r;
}

template <class Num>
ToiResult<Num> bisection_ball_wall(const BallState<Num>& ball, const Segment<Num>& wall, const Num& horizon,
                                   const Num& eps) {
  const Num zero{};
  auto gap = [&](const Num& t) { return distance_to_segment(position_at(ball, t), wall) - ball.radius; };
  const RootSearch<Num> root = article_step_and_bisect(gap, horizon, eps);
  if (!root.found) return {};
  ToiResult<Num> r;
  r.state = ToiState::hit;
  r.time = root.t;
  const Vec2<Num> centre = position_at(ball, root.t);
  const Vec2<Num> d = wall.b - wall.a;
  const Num along = dot(d, centre - wall.a);
  if (!(zero < along) || !(along < length_squared(d))) {
    const bool end_a = !(zero < along);
    r.feature = end_a ? ContactFeature::wall_end_a : ContactFeature::wall_end_b;
    r.point = end_a ? wall.a : wall.b;
    r.normal = normalized(centre - r.point);
  } else {
    r.feature = ContactFeature::wall_face;
    const Vec2<Num> n = normalized(perp(d));
    r.normal = dot(n, centre - wall.a) < zero ? -n : n;
    r.point = centre - ball.radius * r.normal;
  }
  return r;
}

// The article's wall method (part II), generalised to oblique walls: move the
// wall towards the ball by its radius, intersect the straight chord from the
// centre's start to its end-of-step position with the moved wall, and if they
// cross, solve the quadratic for the centre reaching the moved wall's line
//     ½ (n·a) t² + (n·v) t + n·(p − w'_a) = 0
// with the textbook formula t = (−B ± √(B² − 4AC)) / 2A, taking the smaller
// root in [0, H] ("one of these t values will be outside of our time range").
// Blind spots kept: round ends are never hit; a parabola that bends across
// the wall but whose chord does not is missed; the textbook formula cancels.
// A = 0 (no acceleration along the normal), where the article would divide by
// zero, is solved as the linear equation it is.
template <class Num>
ToiResult<Num> seed_ball_wall(const BallState<Num>& ball, const Segment<Num>& wall, const Num& horizon) {
  using T = NumberTraits<Num>;
  const Num zero{};
  const Vec2<Num> wall_dir = wall.b - wall.a;
  const Vec2<Num> unit_perp = normalized(perp(wall_dir));
  const Vec2<Num> n = dot(unit_perp, ball.position - wall.a) < zero ? -unit_perp : unit_perp;
  const Vec2<Num> wa = wall.a + ball.radius * n;  // the moved wall, towards the ball
  const Vec2<Num> wb = wall.b + ball.radius * n;

  // Segment–segment intersection with the article's parametric formulas.
  const Vec2<Num> p0 = ball.position;
  const Vec2<Num> p1 = position_at(ball, horizon);
  const Vec2<Num> s1 = p1 - p0;
  const Vec2<Num> s2 = wb - wa;
  const Num denom = -s2.x * s1.y + s1.x * s2.y;
  if (denom == zero) return {};
  const Num s = (-s1.y * (p0.x - wa.x) + s1.x * (p0.y - wa.y)) / denom;
  const Num u = (s2.x * (p0.y - wa.y) - s2.y * (p0.x - wa.x)) / denom;
  const Num one = num<Num>(1.0);
  if (s < zero || one < s || u < zero || one < u) return {};

  const Num A = T::half(dot(n, ball.acceleration));
  const Num B = dot(n, ball.velocity);
  const Num C = dot(n, p0 - wa);
  Num t;
  if (A == zero) {
    if (B == zero) return {};
    t = -C / B;
  } else {
    const Num disc = B * B - num<Num>(4.0) * A * C;
    if (disc < zero) return {};
    const Num root_disc = T::sqrt(disc);
    const Num t_plus = (-B + root_disc) / (num<Num>(2.0) * A);
    const Num t_minus = (-B - root_disc) / (num<Num>(2.0) * A);
    const Num t_small = t_plus < t_minus ? t_plus : t_minus;
    const Num t_large = t_plus < t_minus ? t_minus : t_plus;
    t = !(t_small < zero) ? t_small : t_large;
  }
  if (t < zero || horizon < t) return {};
  ToiResult<Num> r;
  r.state = ToiState::hit;
  r.time = t;
  r.feature = ContactFeature::wall_face;
  r.normal = n;
  r.point = position_at(ball, t) - ball.radius * n;
  return r;
}

}  // namespace collide2d
