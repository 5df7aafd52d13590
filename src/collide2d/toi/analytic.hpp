// The analytic method: time of impact from the exact motion model, with roots
// computed robustly (see point_contact.hpp and quadratic.hpp).
#pragma once

#include "collide2d/toi/point_contact.hpp"
#include "collide2d/toi/toi_result.hpp"

namespace collide2d {

// When ball a first meets ball b within the horizon, and nothing else: what
// an event engine asks of every neighbour (the normal waits for the event).
template <class Num>
RootSearch<Num> time_of_contact_ball_ball(const BallState<Num>& a, const BallState<Num>& b, const Num& horizon) {
  const RelativeMotion<Num> m{accurate_difference(a.position, b.position), a.velocity - b.velocity,
                              a.acceleration - b.acceleration, a.radius + b.radius};
  return first_contact(m, horizon);
}

// Ball a against ball b (b may be fixed: zero velocity and acceleration).
// The normal points from b's centre to a's.
template <class Num>
ToiResult<Num> time_of_impact_ball_ball(const BallState<Num>& a, const BallState<Num>& b, const Num& horizon) {
  const RootSearch<Num> root = time_of_contact_ball_ball(a, b, horizon);
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

// Ball against a two-sided wall segment with round ends.
//
// With d = w_b − w_a, S(t) = d × (p(t) − w_a) = |d| s(t) is |d| times the
// signed distance to the wall's line: S(t) = S₀ + S_v t + ½ S_a t². The
// clearance of side ε = ±1 is w(t) = ε S(t) − r |d|, a quadratic in t (no
// division by |d| on the way); its downward root is the ball reaching the
// line's band of half-width r from that side.
//
// For a ball that starts outside the band, the first time it reaches the
// band is the first time it can touch the wall at all (the distance to the
// segment is never less than the distance to its line). So if the centre
// then projects inside the segment,
// that face contact is the answer and the ends need not be looked at. If it
// projects outside, the ball is beside an end: the contact, if any, is at a
// round end (point_contact), or at a face it reaches later (a ball thrown
// past an end, falling back onto the top); the earliest of those wins, a face
// winning a tie. A ball outside the band, moving away from the line and not
// accelerated towards it, never touches.
//
// S₀ uses both differences as hi + lo and an exact-product cross product, so
// a ball near the middle of a long oblique wall gets its distance to the last
// bits.
template <class Num>
ToiResult<Num> time_of_impact_ball_wall_unscaled(const BallState<Num>& ball, const WallGeometry<Num>& wall,
                                                 const Num& horizon) {
  using T = NumberTraits<Num>;
  const Num zero{};
  const Num r = ball.radius;
  const Vec2<Num>& d = wall.direction.hi;
  const auto rel = accurate_difference(ball.position, wall.segment.a);
  const Num S0 = accurate_cross(d, rel.hi) + (cross(d, rel.lo) + cross(wall.direction.lo, rel.hi));
  const Num Sv = cross(d, ball.velocity);
  const Num Sa = cross(d, ball.acceleration);
  const Num rL = r * wall.length;
  const bool outside_band = rL < T::abs(S0);
  if (outside_band && Sa == zero && !(S0 < zero ? zero < Sv : Sv < zero)) return {};

  auto projects_inside = [&](const Num& t) {
    const Num along = dot(d, position_at(rel.hi, ball.velocity, ball.acceleration, t));
    return !(along < zero) && !(wall.length_squared < along);
  };
  auto face_hit = [&](const Num& t, int side) {
    ToiResult<Num> hit;
    hit.state = ToiState::hit;
    hit.time = t;
    hit.feature = ContactFeature::wall_face;
    hit.normal = side < 0 ? -wall.unit_normal : wall.unit_normal;  // unit_normal: the side S > 0
    hit.point = position_at(ball, t) - r * hit.normal;
    return hit;
  };

  // Already in the band, over the segment and closing in: contact at t = 0.
  if (!outside_band && projects_inside(zero) && (S0 < zero ? zero < Sv : Sv < zero))
    return face_hit(zero, S0 < zero ? -1 : 1);

  // Both sides' band entries: A = ½ ε S_a, b = ½ ε S_v, C = ε S₀ − r |d|.
  RootSearch<Num> entry[2];
  for (int i = 0; i < 2; ++i) {
    const bool plus = i == 0;
    Num A = plus ? T::half(Sa) : -T::half(Sa);
    Num b = plus ? T::half(Sv) : -T::half(Sv);
    Num C = (plus ? S0 : -S0) - rL;
    normalise_quadratic(A, b, C);
    entry[i] = first_downward_root(A, b, C, [&] { return compensated_discriminant(A, b, C); }, horizon);
  }
  const int first = !entry[0].found || (entry[1].found && entry[1].t < entry[0].t) ? 1 : 0;
  if (outside_band) {
    if (!entry[first].found) return {};  // never reaches the band
    if (projects_inside(entry[first].t)) return face_hit(entry[first].t, first == 0 ? 1 : -1);
  }
  // Beside an end (or starting in the band beside it, where the ends may
  // come before any face). The earliest face entry over the segment bounds
  // the search at the ends.
  ToiResult<Num> best;
  Num best_t = horizon;
  for (const int i : {first, 1 - first}) {
    if (entry[i].found && projects_inside(entry[i].t)) {
      best = face_hit(entry[i].t, i == 0 ? 1 : -1);
      best_t = best.time;
      break;
    }
  }
  const Box<Num> path = trajectory_box(ball.position, ball.velocity, ball.acceleration, best_t);
  const Num reach = r + r * num<Num>(0x1p-40);
  const Vec2<Num>* ends[2] = {&wall.segment.a, &wall.segment.b};
  for (int e = 0; e < 2; ++e) {
    const Vec2<Num>& end = *ends[e];
    if (end.x < path.lo.x - reach || path.hi.x + reach < end.x || end.y < path.lo.y - reach ||
        path.hi.y + reach < end.y)
      continue;
    const RelativeMotion<Num> m{accurate_difference(ball.position, end), ball.velocity, ball.acceleration, r};
    const RootSearch<Num> root = first_contact(m, best_t);
    if (root.found && (!best.hit() || root.t < best_t)) {
      best.state = ToiState::hit;
      best.time = best_t = root.t;
      best.feature = e == 0 ? ContactFeature::wall_end_a : ContactFeature::wall_end_b;
      best.point = end;
      best.normal = normalized(position_at(ball, root.t) - end);
    }
  }
  return best;
}

// Fixed point: a small ball and wall (lengths near 2^-20) would leave the
// face's quadratic with few significant bits. As in first_contact
// (point_contact.hpp), lengths are scaled up by an exact power of two, here
// relative to the wall's end a (so a far offset costs nothing either); the
// time is unchanged, the contact point and normal are mapped back.
template <class Num>
ToiResult<Num> time_of_impact_ball_wall(const BallState<Num>& ball, const WallGeometry<Num>& wall,
                                        const Num& horizon) {
  using T = NumberTraits<Num>;
  if constexpr (T::rounds_absolutely) {
    const Vec2<Num> rel = ball.position - wall.segment.a;
    const Vec2<Num>& d = wall.direction.hi;
    const Num extent = T::abs(d.x) < T::abs(d.y) ? T::abs(d.y) : T::abs(d.x);
    const RelativeMotion<Num> m{{rel, {}}, ball.velocity, ball.acceleration, ball.radius < extent ? extent : ball.radius};
    const int k = unit_scale_exponent(m, horizon);
    if (k > 0) {
      auto up = [&](const Vec2<Num>& x) { return Vec2<Num>{T::times_power_of_two(x.x, k), T::times_power_of_two(x.y, k)}; };
      const BallState<Num> scaled{up(rel), up(ball.velocity), up(ball.acceleration), T::times_power_of_two(ball.radius, k)};
      ToiResult<Num> r = time_of_impact_ball_wall_unscaled(scaled, prepare_wall(Segment<Num>{{}, up(d)}), horizon);
      if (r.hit()) {
        const Num down = T::times_power_of_two(Num::resolution(), Num::fraction_bits - k);  // 2^-k, exact
        r.point = wall.segment.a + down * r.point;
      }
      return r;
    }
  }
  return time_of_impact_ball_wall_unscaled(ball, wall, horizon);
}

template <class Num>
ToiResult<Num> time_of_impact_ball_wall(const BallState<Num>& ball, const Segment<Num>& wall, const Num& horizon) {
  return time_of_impact_ball_wall(ball, prepare_wall(wall), horizon);
}

}  // namespace collide2d
