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

// The unit tangent of wall w (its direction, from the normal).
template <class Num>
Vec2<Num> wall_tangent(const WallGeometry<Num>& w) {
  return {w.unit_normal.y, -w.unit_normal.x};
}

// n_x · (the normal of the wall face ball x rests on, towards x): < 0 when a
// contact with normal n_x (towards x) pushes x into its wall.
template <class Num>
Num share_off_its_wall(const Body<Num>& x, const World<Num>& world, const Vec2<Num>& n_x) {
  return dot(n_x, face_normal_towards(world.walls[x.resting_wall], x.position));
}

// Ball x rests on a wall face that a contact with normal n_x (towards x)
// pushes it into.
template <class Num>
bool pushed_into_its_wall(const Body<Num>& x, const World<Num>& world, const Vec2<Num>& n_x) {
  if (x.fixed || x.resting_wall < 0) return false;
  return share_off_its_wall(x, world, n_x) < Num{};
}

// Ball x rests on a wall face and a contact would lift it off only at less
// than `least` (the hop speed against the wall: a rise below h_rest), where
// `lift` is the speed away from the wall its impulse alone would give: it
// stays held, as a bounce that low comes to rest (two balls resting on one
// wall, meeting along it with a tilt of a few ulps, would otherwise free the
// higher one a hair inside its wall's contact band, where no time of impact
// brings it back).
template <class Num>
bool lifted_less_than(const Body<Num>& x, const World<Num>& world, const Vec2<Num>& n_x, const Num& lift_per_impulse,
                      const Num& least) {
  if (x.fixed || x.resting_wall < 0) return false;
  return lift_per_impulse * share_off_its_wall(x, world, n_x) < least;
}

struct HeldOutcome {
  bool hopped = false;  // the separating speed was raised to the hop speed
};

// How one ball of the pair answers an impulse J along n_x, the contact normal
// towards it: freely (Δv = (J/m) n_x: inverse mass 1/m along n), held on its
// wall (Δv = (J c/m) t with c = n_x·t: c²/m), or not at all (fixed: 0).
template <class Num>
struct Mobility {
  Body<Num>& body;
  Vec2<Num> n;        // the contact normal towards this ball
  bool held = false;
  Vec2<Num> t{};      // its wall's unit tangent, if held
  Num c{};            // n·t

  Mobility(Body<Num>& b, const World<Num>& world, const Vec2<Num>& normal, bool is_held) : body(b), n(normal), held(is_held) {
    if (held) {
      t = wall_tangent(world.walls[b.resting_wall]);
      c = dot(n, t);
    }
  }
  Num inverse_mass() const {
    if (body.fixed) return Num{};
    return held ? c * c / body.mass : num<Num>(1.0) / body.mass;
  }
  // Its velocity along n (only the part along the wall counts when held).
  Num speed_along_n() const { return held ? c * dot(t, body.velocity) : dot(n, body.velocity); }
  void apply(const Num& J) {
    if (body.fixed) return;
    body.velocity = held ? body.velocity + (J * c / body.mass) * t : body.velocity + (J / body.mass) * n;
  }
};

// A held ball (unit tangent t of its wall) against something that cannot
// move (a fixed ball, or another wall), c = n·t with n the contact normal
// towards the ball: u' = −e u when closing (c u < 0); then, if the
// tangential acceleration a_t carries it into the contact (c a_t < 0), away
// at the hop speed at least. Returns its momentum change along the wall.
template <class Num, class HopSpeed>
Num bounce_along_wall(Body<Num>& x, const Vec2<Num>& t, const Num& c, const Num& e, HopSpeed hop_speed,
                      HeldOutcome& outcome) {
  const Num zero{};
  const Num u = dot(t, x.velocity);
  Num u_after = c * u < zero ? -e * u : u;
  const Num a_t = dot(t, x.acceleration);
  const Num away = c < zero ? -u_after : u_after;
  const Num hop = c * a_t < zero ? hop_speed(a_t < zero ? -a_t : a_t) : zero;
  if (zero < hop && away < hop) {
    u_after = c < zero ? -hop : hop;
    outcome.hopped = true;
  }
  const Num du = u_after - u;
  x.velocity = x.velocity + du * t;
  return x.mass * (du < zero ? -du : du);
}

// The held collision (see the top of this file) of balls a and b, n pointing
// from b to a; `a_held`, `b_held`: which of them rests on a wall that the
// contact pushes it into (at least one). Held balls keep resting. A pair
// pressed together leaves at no less than the hop speed `hop_speed(g)` for
// the pressing acceleration g = |n·Δa|; against a fixed partner, along the
// wall from the held ball's tangential acceleration (the speed that rises
// h_rest along the wall). Two held balls pressed together get no hop: along
// two nearly parallel walls it would need an unbounded speed (a known limit:
// such a jam can stall the engine). Returns the impulse on a: J along n, or,
// against a fixed partner, the held ball's momentum change along its wall
// (J itself grows as 1/c there).
template <class Num, class HopSpeed>
Num collide_held(Body<Num>& a, Body<Num>& b, bool a_held, bool b_held, const World<Num>& world, const Vec2<Num>& n,
                 const Num& e, HopSpeed hop_speed, HeldOutcome& outcome) {
  const Num zero{};
  const Num one = num<Num>(1.0);
  Mobility<Num> ma(a, world, n, a_held), mb(b, world, -n, b_held);
  if (a.fixed || b.fixed) {
    Mobility<Num>& x = a.fixed ? mb : ma;
    return bounce_along_wall(x.body, x.t, x.c, e, hop_speed, outcome);
  }
  const Num k = ma.inverse_mass() + mb.inverse_mass();
  if (k == zero) return zero;  // neither can move along n
  const Num closing = ma.speed_along_n() + mb.speed_along_n();
  Num J = closing < zero ? -(one + e) * closing / k : zero;
  const Num pressing = dot(n, a.acceleration - b.acceleration);
  const Num hop = pressing < zero && !(a_held && b_held) ? hop_speed(-pressing) : zero;
  const Num after = closing + J * k;
  if (zero < hop && after < hop) {
    J = J + (hop - after) / k;
    outcome.hopped = true;
  }
  ma.apply(J);
  mb.apply(J);
  return J;
}

}  // namespace collide2d
