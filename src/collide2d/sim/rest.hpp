// Rest: how a ball stops bouncing and how it starts again.
//
// Under gravity with restitution e < 1 a ball bounces infinitely often in
// finite time (inelastic collapse). Each of these rules ends such a series
// without adding energy (docs/REST.md has the reasoning and the sources):
//
//  1. Contact. A ball that has just rebounded off a partner (a wall's face
//     or end, another ball, moving or not) while pressed against it
//     (n·Δa < 0) and would rise less than h_rest off it does not part: the
//     impact is made plastic (an impulse takes the relative normal speed to
//     zero) and the pair becomes a persistent contact (contact_graph.hpp).
//     On a flat face the rest of the bounce series would not change the
//     tangential motion, so from the series' end on this is exact; the
//     normal kinetic energy it removes, at most m g_n h_rest, is what the
//     series would dissipate anyway. A contact holds the relative normal
//     motion at zero by a constant force λ ≥ 0, solved with every contact
//     that shares a moving ball (an island) as a complementarity problem;
//     the force does no work. It ends where the offset has slid past the
//     wall's end, or L = sqrt(2 R h_rest + h_rest²) along the tangent of a
//     round partner (R the contact distance: there they have parted by
//     h_rest and fly free; a ball perched on another slides off this way, as
//     it should without friction), or when its force would have to pull.
//     Where it slid L off a round partner while the two are still pressed
//     together and part slower than sqrt(2 |a_n| h_rest), the hop is
//     collapsed like any other and the contact renewed along the tangent
//     from there to the circle (ContactRules::renew).
//     A strike on a ball in contact is answered by its whole island at once:
//     the struck contact with its restitution, the held ones without
//     parting unless the strike parts them. A struck pair one of whose
//     balls is held (in contact) and that the island's answer leaves
//     parting slower than v_rest (without gravity, the creep speed of rule
//     5) does not part either, pressed or not: a ball rattling in its cage
//     of neighbours at such speeds has less kinetic energy than a ball may
//     keep and still sleep (rule 2), and each of its strikes on the island
//     costs the solve of the whole island (pile_80_e075: a third of its
//     strikes closed slower than 2 v_rest, 90 % were pairs struck again
//     within 10 ms). So does a ball jammed between two partners it is not
//     held by (struck again at the very instant of its last strike):
//     otherwise it would ring between them at one instant, losing a factor
//     e per round for ever. Every pair of a struck ball with a ball of its
//     island that touches it (within δ) joins as a contact, and the island
//     takes one plastic impact: the limit of that series, at once. A lone
//     ball struck again itself between two immovable partners on opposite
//     sides whose gap is at least its diameter, to rounding (a pinch,
//     pinch.hpp), is answered along the pinch's axis, plastically, at any
//     speed: there rounding tilts the two normals so that its tangential
//     motion feeds the ringing for ever.
//  2. Sleep. A ball slower than the rest speed v_rest = sqrt(2 g h_rest)
//     whose supports carry its load stops: velocity zero, no acceleration,
//     no events. Supports are walls, fixed balls and sleeping balls within
//     the contact band δ = h_rest; they carry it when −load lies in the cone
//     of their contact normals (λ_k ≥ 0 with Σ λ_k n_k = −load: frictionless
//     statics, McNamara & Herrmann 2004), the load being its weight plus
//     the pushes of the moving balls it touches. A ball on a slope, or
//     perched on one ball, is not carried and keeps moving. The kinetic
//     energy a sleeping ball had (below ½ m v_rest²) is removed and counted.
//     Its contacts stay: a moving ball on a sleeper is held as on a wall.
//  3. Wake. A sleeping ball struck at a closing speed of at least v_rest wakes
//     and takes part in the collision as a moving ball, its contacts held
//     (the momentum of the pair is kept where no support takes a share); a
//     slower strike finds it immovable, like the ground under it. A ball
//     that wakes wakes every sleeper it helped to carry (the cone test is
//     made again without it), and a sleeper one of whose contacts with a
//     moving ball ends is asked again (its load has lost that push): it
//     wakes if its supports no longer carry it.
//  4. Plastic pairs: rule 1 between two moving balls, counted apart.
//  5. Creep. An unpressed contact closing slower than h_rest / duration is
//     not processed: the two creep together by less than h_rest over the run.
//
// Every threshold follows from the scene (r_min the smallest radius, g the
// largest acceleration, T the duration) and can be set in its "rest" object.
#pragma once

#include <cstdint>
#include <vector>

#include "collide2d/geometry/vec2.hpp"
#include "collide2d/numeric/number_traits.hpp"
#include "collide2d/toi/toi_result.hpp"

namespace collide2d {

// The scales of the rules above, in the run's number type.
template <class Num>
struct RestThresholds {
  Num height;       // h_rest: rebounds rising less come to rest on a face
  Num speed;        // v_rest = sqrt(2 g_max h_rest): slower balls may sleep; faster strikes wake
  Num band;         // δ: a support this close counts as touching
  Num creep_speed;  // unpressed contacts closing slower than this are let creep
  Num least_press;  // a relative normal acceleration smaller than this presses nothing together
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
  std::uint64_t came_to_rest = 0;  // rule 1: a contact with a wall or a static ball
  std::uint64_t fell_asleep = 0;   // rule 2
  std::uint64_t woken = 0;         // rule 3 (struck, or a support gone)
  std::uint64_t plastic_pairs = 0; // rule 4
  std::uint64_t creeping = 0;      // rule 5
  std::uint64_t held = 0;          // strikes answered by an island with its contacts held (rule 1)
  std::uint64_t renewed = 0;       // contacts with a round partner renewed where they slid off (rule 1)
  // The collisions whose restitution the rules set aside: made plastic, each
  // the end of a bounce series (rules 1 and 4).
  std::uint64_t made_plastic() const { return came_to_rest + plastic_pairs; }
};

}  // namespace collide2d
