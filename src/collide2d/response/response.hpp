// What a contact does to the velocities.
#pragma once

#include "collide2d/geometry/vec2.hpp"

namespace collide2d {

// A contact's restitution is the product of the two objects' values.
template <class Num>
inline Num contact_restitution(const Num& e1, const Num& e2) { return e1 * e2; }

// Reflection about the unit normal n of an immovable object (wall, fixed
// ball), with restitution e: the normal component of v is reversed and scaled
// by e, the tangential one kept:
//     v' = v − (1 + e) (v·n) n.
// Only an approaching ball (v·n < 0) is reflected; a receding one is returned
// unchanged, so a contact is never turned into an attraction.
template <class Num>
Vec2<Num> reflect_velocity(const Vec2<Num>& v, const Vec2<Num>& n, const Num& e) {
  const Num vn = dot(v, n);
  if (!(vn < Num{})) return v;
  const Num k = (num<Num>(1.0) + e) * vn;
  return {v.x - k * n.x, v.y - k * n.y};
}

template <class Num>
struct TwoBallVelocities {
  Vec2<Num> v1;
  Vec2<Num> v2;
  Num impulse;  // magnitude of the normal impulse J on ball 1 (mass × speed)
};

// Two free balls, masses m1 and m2, unit normal n from ball 2 to ball 1,
// restitution e. With the normal closing speed u = (v1 − v2)·n < 0 the
// impulse along n is
//     J = −(1 + e) u · m1 m2 / (m1 + m2),
//     v1' = v1 + (J / m1) n,   v2' = v2 − (J / m2) n,
// so m1 v1' + m2 v2' = m1 v1 + m2 v2 for any masses, the tangential parts are
// untouched and the normal closing speed becomes −e u. Receding balls are
// returned unchanged with J = 0.
template <class Num>
TwoBallVelocities<Num> two_ball_impulse_response(const Vec2<Num>& v1, const Vec2<Num>& v2, const Num& m1,
                                                 const Num& m2, const Vec2<Num>& n, const Num& e) {
  const Num u = dot(v1 - v2, n);
  if (!(u < Num{})) return {v1, v2, Num{}};
  const Num reduced_mass = m1 * m2 / (m1 + m2);
  const Num J = -(num<Num>(1.0) + e) * u * reduced_mass;
  // Equal masses (a gas of one kind of disc): J / m2 is J / m1, the same
  // bits, and one division fewer (a long one in fixed point).
  const Num dv1 = J / m1, dv2 = m2 == m1 ? dv1 : J / m2;
  return {{v1.x + dv1 * n.x, v1.y + dv1 * n.y}, {v2.x - dv2 * n.x, v2.y - dv2 * n.y}, J};
}

// Resting contact between balls pressed together (see event_engine.hpp):
// after the collision's own impulse, a further impulse along n raises the
// normal separating speed s = (v1 − v2)·n to at least `least`:
//     J = (least − s) m1 m2 / (m1 + m2)   (ball 2 fixed: J = (least − s) m1),
// equal and opposite on the two balls, so momentum is kept. Returns J, 0 if
// they already separate fast enough.
template <class Num>
Num separate_at_least(Vec2<Num>& v1, Vec2<Num>& v2, const Num& m1, const Num& m2, bool second_fixed,
                      const Vec2<Num>& n, const Num& least) {
  const Num s = dot(v1 - v2, n);
  if (!(s < least)) return Num{};
  const Num J = (least - s) * (second_fixed ? m1 : m1 * m2 / (m1 + m2));
  const Num dv1 = J / m1;
  v1 = {v1.x + dv1 * n.x, v1.y + dv1 * n.y};
  if (!second_fixed) {
    const Num dv2 = J / m2;
    v2 = {v2.x - dv2 * n.x, v2.y - dv2 * n.y};
  }
  return J;
}

// The seed article's CalcPostCollisionVelB2B, kept under its own name for
// studies. Its first ball is right; its second uses (m − rc2 m2) where
// (m2 − rc m) belongs, so momentum is conserved only for equal masses and
// restitutions. Here n points from ball 2 to ball 1 as in the article; rc1,
// rc2 are the two balls' restitution coefficients.
template <class Num>
TwoBallVelocities<Num> article_two_ball_response(const Vec2<Num>& v1, const Vec2<Num>& v2, const Num& m,
                                                 const Num& m2, const Vec2<Num>& n, const Num& rc,
                                                 const Num& rc2) {
  const Num one = num<Num>(1.0);
  const Vec2<Num> t{-n.y, n.x};
  const Num vin = dot(v1, n), vit = dot(v1, t);
  const Num vin2 = dot(v2, n), vit2 = dot(v2, t);
  const Num vfnmag = ((rc2 + one) * m2 * vin2 + vin * (m - rc2 * m2)) / (m + m2);
  const Num vfnmag2 = ((rc + one) * m * vin + vin2 * (m - rc2 * m2)) / (m + m2);
  const Vec2<Num> out1{n.x * vfnmag + t.x * vit, n.y * vfnmag + t.y * vit};
  const Vec2<Num> out2{n.x * vfnmag2 + t.x * vit2, n.y * vfnmag2 + t.y * vit2};
  return {out1, out2, m * (vfnmag - vin)};
}

}  // namespace collide2d
