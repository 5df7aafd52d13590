// A collision of a ball held on a wall: one ball of the pair rests on a wall
// face and the contact pushes it into that wall. Both contacts act at once:
// the held ball can only move along the wall (unit tangent t), and the wall
// takes the part of the impulse that would push it in.
//
// With n the contact normal towards the held ball X, c = n·t its share along
// the wall and u = t·v_X the held ball's speed along it, the pair closes at
// v_n = c u − n·v_Y. An impulse J along n changes u by (J/m_X) c and the
// partner's velocity by −(J/m_Y) n, so v_n changes by J k with the inverse
// effective mass k = c²/m_X + 1/m_Y. Restitution e asks for v_n' = −e v_n:
//     J = −(1 + e) v_n / k.
// Against a fixed partner (1/m_Y = 0) this is u' = −e u, formed directly (no
// division by c²): a gap narrower than the ball, between a wall and a fixed
// ball, is a wedge the ball bounces back from along the wall.
//
// Resolved one contact at a time instead, the held ball would be pushed into
// the wall, bounce off it at the same instant, strike the partner again at
// the same instant, and so on without end (the engine stalls).
#pragma once

#include "geometry/vec2.hpp"
#include "numeric/number_traits.hpp"
#include "sim/world.hpp"

namespace collide2d {

// The unit normal of wall face w on the side of point p.
template <class Num>
Vec2<Num> face_normal_towards(const WallGeometry<Num>& w, const Vec2<Num>& p) {
  const Num side = cross(w.direction.hi, p - w.segment.a);
  return side < Num{} ? -w.unit_normal : w.unit_normal;
}

// Ball x rests on a wall face that a contact with normal n_x (towards x)
// pushes it into.
template <class Num>
bool pushed_into_its_wall(const Body<Num>& x, const World<Num>& world, const Vec2<Num>& n_x) {
  if (x.fixed || x.resting_wall < 0) return false;
  return dot(n_x, face_normal_towards(world.walls[x.resting_wall], x.position)) < Num{};
}

struct HeldOutcome {
  bool hopped = false;  // the separating speed was raised to the hop speed
};

// The held collision (see the top of this file). `held` rests on its wall and
// keeps resting; `partner` is struck (and may be fixed). `n` points towards
// `held`. A pair pressed together leaves at no less than the hop speed
// `hop_speed(g)` for the pressing acceleration g: along n, from n·Δa, or,
// against a fixed partner, along the wall from the held ball's tangential
// acceleration (the speed that rises h_rest along the wall). Returns the
// impulse J along n.
template <class Num, class HopSpeed>
Num collide_held(Body<Num>& held, Body<Num>& partner, const World<Num>& world, const Vec2<Num>& n, const Num& e,
                 HopSpeed hop_speed, HeldOutcome& outcome) {
  const Num zero{};
  const Num one = num<Num>(1.0);
  const Vec2<Num> wall_normal = world.walls[held.resting_wall].unit_normal;
  const Vec2<Num> t{wall_normal.y, -wall_normal.x};
  const Num c = dot(n, t);
  const Num u = dot(t, held.velocity);
  if (partner.fixed) {
    // u' = −e u when closing (c u < 0); then, if the tangential acceleration
    // a_t carries it into the contact (c a_t < 0), away at the hop speed at least.
    Num u_after = c * u < zero ? -e * u : u;
    const Num a_t = dot(t, held.acceleration);
    const Num away = c < zero ? -u_after : u_after;
    const Num hop = c * a_t < zero ? hop_speed(a_t < zero ? -a_t : a_t) : zero;
    if (zero < hop && away < hop) {
      u_after = c < zero ? -hop : hop;
      outcome.hopped = true;
    }
    const Num du = u_after - u;
    held.velocity = held.velocity + du * t;
    return held.mass * du * c;  // J = m Δu / c, as m Δu c / c² (no division)
  }
  const Num pressing = dot(n, held.acceleration - partner.acceleration);
  const Num hop = pressing < zero ? hop_speed(-pressing) : zero;
  const Num k = c * c / held.mass + one / partner.mass;
  const Num closing = c * u - dot(n, partner.velocity);
  Num J = closing < zero ? -(one + e) * closing / k : zero;
  const Num after = closing + J * k;
  if (zero < hop && after < hop) {
    J = J + (hop - after) / k;
    outcome.hopped = true;
  }
  held.velocity = held.velocity + (J * c / held.mass) * t;
  partner.velocity = partner.velocity - (J / partner.mass) * n;
  return J;
}

}  // namespace collide2d
