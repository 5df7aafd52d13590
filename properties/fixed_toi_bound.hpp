// How far from contact the analytic method's fixed-mode answer may be: a
// bound on |true gap at the reported time| (and on the gap a reported miss
// may have missed), derived from the Q63.64 format and the method's own
// arithmetic, per query. It replaces the acceptance rule's old fixed
// tolerance of 1e-7 of the scale (the worst error ever observed was 1.6e-12
// of the scale): the time-of-impact properties, the regression replay and
// the stored answers are judged with it (tol = bound / scale in
// judge_toi_answer, lab/oracle.hpp).
//
// The format (numeric/fixed.hpp): a Fixed is raw · u, u = 2^-64, below 2^63;
// + and − are exact, ×, ÷ and √ round to nearest (≤ u/2 absolute), half()
// by ≤ u/2. A double converts exactly when it is a multiple of u (every
// double of magnitude ≥ 2^-12), else to the nearest (≤ u/2). So every error
// below is absolute, a few u times the sizes of the numbers involved.
//
// Inputs. Each component of the query (positions, velocities,
// accelerations, radii, wall ends) converts within u/2; the gap at any time
// t ≤ H is 1-Lipschitz in the positions and radii, and moves by t |δv| and
// t²/2 |δa|: E_in = 2 (u/2) (√2 (1 + H + H²/2) + 1) for the two objects.
//
// Scaling. The method multiplies every length by 2^k (exact shifts, k ≥ 0)
// so that the largest length of the motion over the horizon, max(|Δp|, R,
// 2 |Δv| H, 4 |Δa| H²) in its exponents, reaches [1, 2), within caps that
// keep its products in range (point_contact.hpp, unit_scale_exponent; for
// a wall the wall's extent counts as a length, analytic.hpp). The errors
// below are absolute in the scaled units, so in the query's units they are
// 2^-k of what they are at k = 0. The bound takes k one less than that rule
// gives, capped the same way; a smaller k only loosens it.
//
// Each path of the method, in scaled units (q = Δp, v = Δv, a = Δa, R the
// contact distance; a wall's face with d = b − a, L = |d|, S0 = d × (p − a),
// Sv = d × v, Sa = d × a):
//
//  - A quadratic root in closed form, w(t) = A t² + 2 b t + C (ball–ball or
//    a wall's end without relative acceleration: A = |v|², b = q·v, C = |q|²
//    − R², D = A R² − (q × v)² by Lagrange's identity, w = |q|² − R²; a
//    wall's face: A = ½ε Sa, b = ½ε Sv, C = ε S0 − R L, w = L (gap), after
//    an exact shift of all three). The method forms b̂, Ĉ, D̂ within δb,
//    δC, δD and returns t̂ = Ĉ / (√D̂ − b̂) (b < 0), or −(b̂ + √D̂)/Â (b ≥ 0,
//    A < 0), or Ĉ / (−2 b̂) (A = 0), each rounded once more. The quadratic
//    (Ã, b̂, Ĉ) with Ã = (b̂² − s²)/Ĉ, s = fl(√D̂), has exactly t0 = Ĉ /
//    (s − b̂) as its root, so the true w at t0 is
//        w(t0) = (A − Ã) t0² + 2 (b − b̂) t0 + (C − Ĉ),
//    (A − Ã) t0² = (s² − (b̂² − A Ĉ)) t0 / (s − b̂),
//    and s² − (b̂² − A Ĉ) is D̂'s error against the discriminant of (A, b̂,
//    Ĉ) plus the square root's rounding: ≤ δD + 2 |b| δb + |A| δC + √D u.
//    t0 / (s − b̂) ≤ H / max(|b|, √D), and ≤ 1 / A when A > 0 (a downward
//    root comes before the vertex, t0 ≤ |b| / A). The last rounding moves
//    t0 by u/2 where |w'| = 2 √D: √D u. So
//        |w(t̂)| ≤ (δD + 2|b| δb + |A| δC + √D u) · min(H / max(|b|, √D), 1/A)
//                 + 2 δb H + δC + √D u,
//    the b ≥ 0 branch the same with the roles of A and C swapped:
//        |w(t̂)| ≤ δA H² + 2 δb H + 2 δC + (u + √D u) / |A| + √D u,
//    and the linear one |w| ≤ δA H² + 2 δb H + δC + |b| u.
//    The coefficients (products rounded ≤ u/2 each, sums exact):
//      balls, ends:  δb ≤ u, δC ≤ 1.5 u, δA ≤ u,
//                    δD ≤ (R² + A/2 + 1 + 2 |q × v|) u   (A R², (q × v)²)
//      face:         δb ≤ u, δA ≤ u, δC ≤ (1.5 + R/2 + R/(2L)) u   (S0, R L,
//                    L = √|d|²), δD ≤ |C| δA + u (the products of D̂).
//    The gap is w / (|q| + R) ≤ w / R for balls and ends, w / L for a face.
//  - A root polished by safeguarded Newton (relative acceleration: the
//    derivative cascade, point_contact.hpp): g(t) = |q(t)|² − R², q(t)
//    formed as p + t (v + t/2 a) within δq ≤ u (1 + H + H |a|) per
//    component, g within δg ≤ 2 √2 |q| δq + 1.5 u with |q| ≈ R at contact;
//    the bracket ends one unit apart, where g changes its computed sign,
//    so |g(t̂)| ≤ δg + |g'| u, |g'| ≤ 2 R (|v| + |a| H):
//        gap ≤ (δg + |g'| u) / R.
//    Every decision of the cascade (a graze's minimum above or below zero,
//    touching at the start) is a sign of g computed within δg.
// The answer comes from one of the paths the query can take (balls: one;
// a wall: its face and either end); the bound is the largest of them, over
// 2^k, plus E_in, E_out and E_judge (below). Second-order terms (products of two errors) are left out:
// each is below u² · (the sizes)² ≪ u.
// Output. The time a query line answers (collide2d toi, answer_toi_query)
// is the Fixed time converted to a double: rounded to 53 bits, by ≤ 2^-53 t
// ≤ 2^-53 H, in which the pair closes by at most (|Δv| + |Δa| H) 2^-53 H:
// E_out, a relative rounding like strict mode's (about 1e-16 of the
// scale), which outweighs every fixed-point term for sizes near 1. A
// caller reading the Fixed time itself (a ToiResult) leaves it out.
// The judge. The oracle (lab/oracle.hpp) expands its polynomials in 60
// digits, but forms a ball–ball query's relative velocity and acceleration
// in doubles first (q.ball.velocity − q.other.velocity): each rounds by
// ≤ 2^-53 of itself, which moves its gap at t ≤ H by ≤ 2^-53 (|Δv| H +
// ½ |Δa| H²): E_judge, added for ball–ball queries. (Found by this bound:
// a fixed answer exact to 1e-22 was 1.4e-16 off the oracle's contact. Left
// as it is: forming them in 60 digits would change the oracle's answers
// stored in datasets/hard, which must stay as they are.)
#pragma once

#include <algorithm>
#include <cmath>

#include "collide2d/toi/query.hpp"

namespace collide2d::properties {

namespace fixed_toi_detail {

using LD = long double;
inline constexpr LD u = 0x1p-64L;

inline LD len(LD x, LD y) { return std::hypot(x, y); }

// ⌊log2 |x|⌋, or a very small number for 0.
inline int exponent_of(LD x) { return x == 0 ? -10000 : std::ilogb(x); }

// The method's scaling, one short of its rule (see the top).
inline int scale_exponent(LD largest_length, LD v_max, LD a_max) {
  const int e_v = exponent_of(v_max), e_a = exponent_of(a_max);
  const int k = std::min({-exponent_of(largest_length) - 1, 28 - e_v, 28 - e_a, (24 - e_v - e_a) / 2, 60}) - 1;
  return std::max(0, k);
}

// A closed-form quadratic root (see the top): the bound on |w(t̂)|.
inline LD quadratic_w(LD A, LD b, LD C, LD D, LD dA, LD db, LD dC, LD dD, LD H) {
  const LD sqrt_d = std::sqrt(std::max(D, LD(0)));
  if (A == 0) return dA * H * H + 2 * db * H + dC + std::fabs(b) * u;
  if (b < 0) {
    LD ratio = H / std::max(std::fabs(b), sqrt_d);
    if (A > 0) ratio = std::min(ratio, 1 / A);
    return (dD + 2 * std::fabs(b) * db + std::fabs(A) * dC + sqrt_d * u) * ratio + 2 * db * H + dC + sqrt_d * u;
  }
  return dA * H * H + 2 * db * H + 2 * dC + (u + sqrt_d * u) / std::fabs(A) + sqrt_d * u;
}

// A point contact (ball–ball, or a ball and a wall's end): q, v, a relative,
// R the contact distance; gap bound in the same (scaled) units.
inline LD point_gap(LD qx, LD qy, LD vx, LD vy, LD ax, LD ay, LD R, LD H) {
  if (ax == 0 && ay == 0) {
    const LD A = vx * vx + vy * vy, b = qx * vx + qy * vy, C = qx * qx + qy * qy - R * R;
    const LD cross = std::fabs(qx * vy - qy * vx);
    const LD D = A * R * R - cross * cross;
    const LD dD = (R * R + A / 2 + 1 + 2 * cross) * u;
    return quadratic_w(A, b, C, D, u, u, LD(1.5) * u, dD, H) / R;
  }
  const LD a = len(ax, ay), v = len(vx, vy);
  const LD dq = u * (1 + H + H * a);
  const LD dg = 2 * std::sqrt(LD(2)) * R * dq + LD(1.5) * u;
  const LD slope = 2 * R * (v + a * H);
  return (dg + slope * u) / R;
}

}  // namespace fixed_toi_detail

// The bound, in the query's own units (see the top); `answer_as_double`:
// the time is read as a double (E_out).
inline double fixed_toi_gap_bound(const ToiQuery& q, bool answer_as_double = true) {
  using namespace fixed_toi_detail;
  const LD H = q.horizon;
  const bool ball = q.kind == QueryKind::ball_ball;
  const LD dv = len(LD(q.ball.velocity.x) - (ball ? q.other.velocity.x : 0), LD(q.ball.velocity.y) - (ball ? q.other.velocity.y : 0));
  const LD da = len(LD(q.ball.acceleration.x) - (ball ? q.other.acceleration.x : 0),
                    LD(q.ball.acceleration.y) - (ball ? q.other.acceleration.y : 0));
  const LD judge = ball ? std::ldexp(LD(1), -53) * (dv * H + da * H * H / 2) : LD(0);
  const LD input = 2 * (u / 2) * (std::sqrt(LD(2)) * (1 + H + H * H / 2) + 1) +
                   (answer_as_double ? (dv + da * H) * std::ldexp(LD(1), -53) * H : LD(0)) + judge;
  if (q.kind == QueryKind::ball_ball) {
    const LD qx = LD(q.ball.position.x) - q.other.position.x, qy = LD(q.ball.position.y) - q.other.position.y;
    const LD vx = LD(q.ball.velocity.x) - q.other.velocity.x, vy = LD(q.ball.velocity.y) - q.other.velocity.y;
    const LD ax = LD(q.ball.acceleration.x) - q.other.acceleration.x, ay = LD(q.ball.acceleration.y) - q.other.acceleration.y;
    const LD R = LD(q.ball.radius) + q.other.radius;
    const LD v = std::max(std::fabs(vx), std::fabs(vy)), a = std::max(std::fabs(ax), std::fabs(ay));
    const int k = scale_exponent(std::max({std::fabs(qx), std::fabs(qy), R, 2 * v * H, 4 * a * H * H}), v, a);
    const LD s = std::ldexp(LD(1), k);
    return static_cast<double>(input + point_gap(s * qx, s * qy, s * vx, s * vy, s * ax, s * ay, s * R, H) / s);
  }
  // A wall: the method scales relative to the wall's end a, with the wall's
  // extent as one of the lengths.
  const LD px = LD(q.ball.position.x) - q.wall.a.x, py = LD(q.ball.position.y) - q.wall.a.y;
  const LD dx = LD(q.wall.b.x) - q.wall.a.x, dy = LD(q.wall.b.y) - q.wall.a.y;
  const LD vx = q.ball.velocity.x, vy = q.ball.velocity.y, ax = q.ball.acceleration.x, ay = q.ball.acceleration.y;
  const LD r = q.ball.radius;
  const LD v = std::max(std::fabs(vx), std::fabs(vy)), a = std::max(std::fabs(ax), std::fabs(ay));
  const LD extent = std::max(std::fabs(dx), std::fabs(dy));
  const int k = scale_exponent(std::max({std::fabs(px), std::fabs(py), std::max(r, extent), 2 * v * H, 4 * a * H * H}), v, a);
  const LD s = std::ldexp(LD(1), k);
  // Face, both sides (the worse), in scaled units: w = L · gap.
  const LD L = s * len(dx, dy);
  const LD S0 = s * s * (dx * py - dy * px), Sv = s * s * (dx * vy - dy * vx), Sa = s * s * (dx * ay - dy * ax);
  const LD R = s * r;
  const LD dC = (LD(1.5) + R / 2 + R / (2 * L)) * u;
  LD face = 0;
  for (const int side : {1, -1}) {
    const LD A = side * Sa / 2, b = side * Sv / 2, C = side * S0 - R * L;
    const LD D = b * b - A * C;
    face = std::max(face, quadratic_w(A, b, C, D, u, u, dC, std::fabs(C) * u + u, H) / L);
  }
  // The ends: point contacts from each end.
  const LD end_a = point_gap(s * px, s * py, s * vx, s * vy, s * ax, s * ay, R, H);
  const LD end_b = point_gap(s * (px - dx), s * (py - dy), s * vx, s * vy, s * ax, s * ay, R, H);
  return static_cast<double>(input + std::max({face, end_a, end_b}) / s);
}

}  // namespace collide2d::properties
