// Rest: how a ball stops bouncing and how it starts again.
//
// Under gravity with restitution e < 1 a ball bounces infinitely often in
// finite time (inelastic collapse). Each of these rules ends such a series
// without adding energy (docs/REST.md has the reasoning and the sources):
//
//  1. Rest on a face. A ball pressed (g_n = −n·a > 0) against something that
//     cannot move (a wall, a fixed ball, a sleeping ball) whose rebound would
//     rise less than h_rest loses its normal speed and slides along a face:
//     the wall's face, or the tangent line to the obstacle at the contact
//     (a round wall end, a ball). On a flat face the rest of the bounce
//     series does not change the tangential motion, so from the series' end
//     on this is exact; the normal kinetic energy it removes, at most
//     m g_n h_rest, is what the series would dissipate anyway. A tangent face
//     ends where the centre has moved L = sqrt(2 R h_rest) along it (R the
//     contact distance): there the ball has risen h_rest off the curved
//     obstacle, flies free and lands on it again (a ball perched on another
//     slides off this way, as it should without friction).
//  2. Sleep. A ball slower than the rest speed v_rest = sqrt(2 g h_rest)
//     whose supports carry its weight stops: velocity zero, no acceleration,
//     no events. Supports are walls, fixed balls and sleeping balls within
//     the contact band δ = h_rest; they carry it when −a lies in the cone of
//     their contact normals (λ_k ≥ 0 with Σ λ_k n_k = −a: frictionless
//     statics, McNamara & Herrmann 2004). A ball on a slope, or perched on one
//     ball, is not carried and keeps moving. The kinetic energy a sleeping
//     ball had (below ½ m v_rest²) is removed and counted.
//  3. Wake. A sleeping ball struck at a closing speed of at least v_rest wakes
//     and takes part in the collision as a free ball (the pair's momentum is
//     kept); a slower strike finds it immovable, like the ground under it.
//     A ball that wakes wakes every sleeper it helped to carry (the cone test
//     is made again without it), and frees every ball sliding on its tangent.
//  4. Plastic pairs. Two moving balls pressed together (n·Δa < 0) whose
//     rebound would rise less than h_rest lose their relative normal speed,
//     as in rule 1, and their relative motion keeps to the tangent at the
//     contact: a constant contact force λ n with λ = −(n·Δa) / k (k the sum
//     of the two balls' inverse masses along n: 1/m free, c²/m held on a
//     face with c = n·t) makes n·Δa zero, so each ball moves on a parabola
//     and the force does no net work (n·Δv = 0). It ends when they have slid
//     L = sqrt(2 R h_rest) apart (R the sum of the radii: they have parted by
//     h_rest and fly free) or when either ball's motion changes. A ball sliding
//     over a moving ball, or two balls on two faces pushing each other, move
//     this way instead of in a storm of ever smaller bounces. Contacts that
//     share balls are solved together (contact_graph.hpp).
//  5. Creep. An unpressed contact closing slower than h_rest / duration is
//     not processed: the two creep together by less than h_rest over the run.
//
// Every threshold follows from the scene (r_min the smallest radius, g the
// largest acceleration, T the duration) and can be set in its "rest" object.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/vec2.hpp"
#include "numeric/number_traits.hpp"
#include "toi/toi_result.hpp"

namespace collide2d {

// The scales of the rules above, in the run's number type.
template <class Num>
struct RestThresholds {
  Num height;       // h_rest: rebounds rising less come to rest on a face
  Num speed;        // v_rest = sqrt(2 g_max h_rest): slower balls may sleep; faster strikes wake
  Num band;         // δ: a support this close counts as touching
  Num creep_speed;  // unpressed contacts closing slower than this are let creep
};

// A line a resting ball's centre slides along: the wall's face (shifted by
// the radius) or the tangent to a round obstacle at the contact. The ball
// stays on it while lo < tangent·(p − origin) < hi.
template <class Num>
struct Face {
  Vec2<Num> normal;   // unit, towards the ball
  Vec2<Num> tangent;  // unit, (n_y, −n_x)
  Vec2<Num> origin;   // the centre when it came to rest
  Num lo{}, hi{};
  int wall = -1;  // the wall whose face or end it is, or −1
  int ball = -1;  // the ball whose tangent it is, or −1
  ContactFeature feature = ContactFeature::none;  // wall_face, wall_end_a/b or ball
};

template <class Num>
Vec2<Num> tangent_of(const Vec2<Num>& unit_normal) {
  return {unit_normal.y, -unit_normal.x};
}

// How far a centre may slide along the tangent to a circle of radius R (the
// contact distance) before it is h off it: sqrt(R² + L²) − R = h gives
// L = sqrt(2 R h + h²). Tangent faces and persistent contacts end there.
template <class Num>
Num slide_length(const Num& R, const Num& h) {
  return NumberTraits<Num>::sqrt(h * (num<Num>(2.0) * R + h));
}

// The tangent face at a round obstacle (contact distance R, unit normal n
// towards the ball whose centre is at p), |s| < slide_length(R, h).
template <class Num>
Face<Num> tangent_face(const Vec2<Num>& p, const Vec2<Num>& n, const Num& R, const Num& h, int wall, int ball,
                       ContactFeature feature) {
  const Num L = slide_length(R, h);
  return {n, tangent_of(n), p, -L, L, wall, ball, feature};
}

// True when −a lies in the cone of the unit normals (each pointing from a
// support towards the ball): some λ_k ≥ 0 give Σ λ_k n_k = −a. In the plane
// two normals suffice (Carathéodory): −a along one normal, or strictly
// between two that are less than π apart. Signs of cross products only, so
// a flat floor under gravity along its normal carries exactly.
template <class Num>
bool carried_by(const Vec2<Num>& acceleration, const std::vector<Vec2<Num>>& normals) {
  const Num zero{};
  const Vec2<Num> up = -acceleration;
  if (up.x == zero && up.y == zero) return !normals.empty();
  for (const Vec2<Num>& n : normals)
    if (cross(n, up) == zero && zero < dot(n, up)) return true;
  for (const Vec2<Num>& ni : normals)
    for (const Vec2<Num>& nj : normals)
      if (zero < cross(ni, up) && zero < cross(up, nj) && zero < cross(ni, nj)) return true;
  return false;
}

// What the rest rules did, for the run summary.
struct RestCounters {
  std::uint64_t came_to_rest = 0;  // rule 1: onto a face
  std::uint64_t fell_asleep = 0;   // rule 2
  std::uint64_t woken = 0;         // rule 3 (struck, or a support gone)
  std::uint64_t plastic_pairs = 0; // rule 4
  std::uint64_t creeping = 0;      // rule 5
  std::uint64_t held = 0;          // collisions resolved with a face held (held_contact.hpp)
};

}  // namespace collide2d
