// A collision of a ball held on its face: one ball of the pair rests on a
// face (rest.hpp: a wall's face or the tangent to a static obstacle) and the
// contact pushes it into that face. Both contacts act at once: the held ball
// can only move along the face (unit tangent t), and the face's owner, which
// cannot move, takes the part of the impulse that would push it in.
//
// With n the contact normal towards the held ball X, c = n·t its share along
// the face and u = t·v_X the held ball's speed along it, the pair closes at
// v_n = c u − n·v_Y. An impulse J along n changes u by (J/m_X) c and the
// partner's velocity by −(J/m_Y) n, so v_n changes by J k with the inverse
// effective mass k = c²/m_X + 1/m_Y. Restitution e asks for v_n' = −e v_n:
//     J = −(1 + e) v_n / k.
// Against a static partner (1/m_Y = 0) this is u' = −e u, formed directly (no
// division by c²): a gap narrower than the ball, between a wall and a fixed
// ball, is a wedge the ball bounces back from along the wall.
//
// Resolved one contact at a time instead, the held ball would be pushed into
// the face, bounce off it at the same instant, strike the partner again at
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

// n_x · (the normal of ball x's face): < 0 when a contact with normal n_x
// (towards x) pushes x into its face.
template <class Num>
Num share_off_its_face(const Body<Num>& x, const Vec2<Num>& n_x) {
  return dot(n_x, x.face.normal);
}

// Ball x rests on a face that a contact with normal n_x (towards x) pushes
// it into.
template <class Num>
bool pushed_into_its_face(const Body<Num>& x, const Vec2<Num>& n_x) {
  if (x.is_static() || !x.on_face) return false;
  return share_off_its_face(x, n_x) < Num{};
}

// Ball x rests on a face and a contact would lift it off only at less than
// `least` (the hop speed against the face: a rise below h_rest), where
// `lift_per_impulse` is the speed away from the face its impulse alone would
// give: it stays held, as a bounce that low comes to rest (two balls resting
// on one wall, meeting along it with a tilt of a few ulps, would otherwise
// free the higher one a hair inside its wall's contact band).
template <class Num>
bool lifted_less_than(const Body<Num>& x, const Vec2<Num>& n_x, const Num& lift_per_impulse, const Num& least) {
  if (x.is_static() || !x.on_face) return false;
  return lift_per_impulse * share_off_its_face(x, n_x) < least;
}

// How one ball of the pair answers an impulse J along n_x, the contact normal
// towards it: freely (Δv = (J/m) n_x: inverse mass 1/m along n), held on its
// face (Δv = (J c/m) t with c = n_x·t: c²/m), or not at all (static: 0).
template <class Num>
struct Mobility {
  Body<Num>& body;
  Vec2<Num> n;  // the contact normal towards this ball
  bool held = false;
  Vec2<Num> t{};  // its face's unit tangent, if held
  Num c{};        // n·t

  Mobility(Body<Num>& b, const Vec2<Num>& normal, bool is_held) : body(b), n(normal), held(is_held) {
    if (held) {
      t = b.face.tangent;
      c = dot(n, t);
    }
  }
  Num inverse_mass() const {
    if (body.is_static()) return Num{};
    return held ? c * c / body.mass : num<Num>(1.0) / body.mass;
  }
  // Its velocity along n (only the part along the face counts when held).
  Num speed_along_n() const { return held ? c * dot(t, body.velocity) : dot(n, body.velocity); }
  void apply(const Num& J) {
    if (body.is_static()) return;
    body.velocity = held ? body.velocity + (J * c / body.mass) * t : body.velocity + (J / body.mass) * n;
  }
};

// A held ball (unit tangent t of its face) against something that cannot
// move (a static ball, or a wall), c = n·t with n the contact normal towards
// the ball: u' = −e u when closing (c u < 0). Returns its momentum change
// along the face. (A slow rebound here is a ball in a wedge of two supports:
// the sleep rule, not this one, ends that series; rest.hpp.)
template <class Num>
Num bounce_along_face(Body<Num>& x, const Num& c, const Num& e) {
  const Num zero{};
  const Vec2<Num>& t = x.face.tangent;
  const Num u = dot(t, x.velocity);
  const Num u_after = c * u < zero ? -e * u : u;
  const Num du = u_after - u;
  x.velocity = x.velocity + du * t;
  return x.mass * (du < zero ? -du : du);
}

// The held collision (see the top of this file) of balls a and b, n pointing
// from b to a; `a_held`, `b_held`: which of them rests on a face that the
// contact pushes it into (at least one). Held balls keep resting. Returns
// the impulse on a: J along n, or, against a static partner, the held ball's
// momentum change along its face (J itself grows as 1/c there). A slow
// rebound of two moving balls is then made plastic by the rest rules
// (rest.hpp, rule 4).
template <class Num>
Num collide_held(Body<Num>& a, Body<Num>& b, bool a_held, bool b_held, const Vec2<Num>& n, const Num& e) {
  const Num zero{};
  Mobility<Num> ma(a, n, a_held), mb(b, -n, b_held);
  if (a.is_static() || b.is_static()) {
    Mobility<Num>& x = a.is_static() ? mb : ma;
    return bounce_along_face(x.body, x.c, e);
  }
  const Num k = ma.inverse_mass() + mb.inverse_mass();
  if (k == zero) return zero;  // neither can move along n
  const Num closing = ma.speed_along_n() + mb.speed_along_n();
  const Num J = closing < zero ? -(num<Num>(1.0) + e) * closing / k : zero;
  ma.apply(J);
  mb.apply(J);
  return J;
}

}  // namespace collide2d
