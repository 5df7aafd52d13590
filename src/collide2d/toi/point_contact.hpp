// First time a moving point comes within distance R of the origin:
// the core of ball–ball and ball–wall-end time of impact.
//
// The relative position is q(t) = Δp + Δv t + ½ Δa t² and contact is
//
//     g(t) = |q(t)|² − R² = 0,   g(0) > 0,   g decreasing.
//
// Δa = 0 (no gravity, or equal accelerations): g is the quadratic
//     |Δv|² t² + 2 (Δp·Δv) t + |Δp|² − R²
// whose discriminant is, by Lagrange's identity,
//     (Δp·Δv)² − |Δv|² (|Δp|² − R²) = |Δv|² R² − (Δp × Δv)²,
// free of the cancellation that makes b² − ac vanish for a small ball far away.
//
// Δa ≠ 0: g is a quartic. Instead of a general quartic solver we isolate its
// first root on [0, H] with the derivative cascade (as in Yuksel, HPG 2022):
//   ½ g'''(t) = 3 q'(t)·Δa          linear: one root t₃
//   ½ g''(t)  = |q'(t)|² + q(t)·Δa  quadratic in t: its roots split [0, H]
//                                   into pieces on which g' is monotone
//   ½ g'(t)   = q(t)·q'(t)          one root at most per piece: the critical
//                                   points of the distance
// and g is monotone between critical points, so the first piece on which g
// falls from positive to non-positive holds the contact, which a safeguarded
// Newton iteration polishes. Every function is evaluated from the motion
// itself (q, q'), never from expanded coefficients: near contact |q| ≈ R and
// the expanded quartic would cancel terms of size |Δp|² (1e14 for a ball of
// radius 1e-6 at distance 1e7), while q(t) only carries errors of size
// ε |Δp|, below 1e-12 of the query's length scale whenever contact is possible.
#pragma once

#include <array>

#include "collide2d/geometry/vec2.hpp"
#include "collide2d/toi/quadratic.hpp"
#include "collide2d/toi/root_polish.hpp"

namespace collide2d {

// Whether Num's conservative screens run in doubles (NumberTraits::screens_in_double).
template <class Num>
inline constexpr bool screens_in_double = [] {
  if constexpr (requires { NumberTraits<Num>::screens_in_double; }) return NumberTraits<Num>::screens_in_double;
  else return false;
}();

// x as a screen sees it: NumberTraits::screen_double for a number type that
// screens in doubles (its cheap conversion, within 3 · 2^-53 of x), to_double
// otherwise. Only screens use it; no answer is formed from it.
template <class Num>
inline double screen_value(const Num& x) {
  if constexpr (screens_in_double<Num>) return NumberTraits<Num>::screen_double(x);
  else return NumberTraits<Num>::to_double(x);
}

template <class Num>
struct RelativeMotion {
  TwoTerm<Vec2<Num>> offset;  // Δp = hi + lo: lo keeps what rounding hi dropped
  Vec2<Num> velocity;         // Δv
  Vec2<Num> acceleration;     // Δa
  Num radius;                 // R, the contact distance
};

template <class Num>
TwoTerm<Vec2<Num>> accurate_difference(const Vec2<Num>& p, const Vec2<Num>& q) {
  const auto x = NumberTraits<Num>::two_diff(p.x, q.x);
  const auto y = NumberTraits<Num>::two_diff(p.y, q.y);
  return {{x.hi, y.hi}, {x.lo, y.lo}};
}

template <class Num>
Vec2<Num> relative_position(const RelativeMotion<Num>& m, const Num& t) {
  const Vec2<Num> q = position_at(m.offset.hi, m.velocity, m.acceleration, t);
  return q + m.offset.lo;
}

// Axis-aligned box holding p + v t + ½ a t² for all t in [0, T]: per axis the
// values at 0 and T and, if inside, at the turning point t = −v/a.
template <class Num>
struct Box {
  Vec2<Num> lo;
  Vec2<Num> hi;
};

template <class Num>
Box<Num> trajectory_box(const Vec2<Num>& p, const Vec2<Num>& v, const Vec2<Num>& a, const Num& T) {
  using Tr = NumberTraits<Num>;
  const Num zero{};
  auto axis = [&](const Num& p0, const Num& v0, const Num& a0, Num& lo, Num& hi) {
    const Num end = p0 + T * (v0 + Tr::half(T) * a0);
    lo = p0 < end ? p0 : end;
    hi = p0 < end ? end : p0;
    // Turning point inside (0, T): v0 and a0 of opposite signs, |v0| < |a0| T.
    if ((v0 < zero && zero < a0) || (zero < v0 && a0 < zero)) {
      if (Tr::abs(v0) < Tr::abs(a0) * T) {
        const Num turn = p0 - Tr::half(v0 * v0 / a0);
        if (turn < lo) lo = turn;
        if (hi < turn) hi = turn;
      }
    }
    // Widen by a bound on the rounding of these few operations.
    const Num slack = (Tr::abs(p0) + T * (Tr::abs(v0) + T * Tr::abs(a0))) * num<Num>(0x1p-40);
    lo = lo - slack;
    hi = hi + slack;
  };
  Box<Num> box;
  axis(p.x, v.x, a.x, box.lo.x, box.hi.x);
  axis(p.y, v.y, a.y, box.lo.y, box.hi.y);
  return box;
}

// Squared distance from a point to a box (zero inside).
template <class Num>
Num squared_distance_to_box(const Vec2<Num>& c, const Box<Num>& box) {
  const Num zero{};
  auto gap = [&](const Num& x, const Num& lo, const Num& hi) { return x < lo ? lo - x : (hi < x ? x - hi : zero); };
  const Num dx = gap(c.x, box.lo.x, box.hi.x), dy = gap(c.y, box.lo.y, box.hi.y);
  return dx * dx + dy * dy;
}

// True when the segment from P to Q keeps a distance greater than `clearance`
// from the origin (compared squared, without a division).
template <class Num>
bool segment_clear_of_origin(const Vec2<Num>& P, const Vec2<Num>& Q, const Num& clearance) {
  const Num zero{};
  const Vec2<Num> d = Q - P;
  const Num c2 = clearance * clearance;
  if (!(dot(P, d) < zero)) return c2 < length_squared(P);  // nearest point: P
  if (!(zero < dot(Q, d))) return c2 < length_squared(Q);  // nearest point: Q
  const Num c = cross(P, d);
  return c2 * length_squared(d) < c * c;
}

// True when the point certainly stays farther than R from the origin within
// [0, T]. Two cheap tests, never a miss (both are widened for rounding):
//  - the trajectory box keeps that distance;
//  - over each quarter of [0, T] the parabola strays at most |Δa| (T/4)² / 8
//    from its chord, and every chord keeps R plus that distance.
//
// A number type whose products are dear (NumberTraits::screens_in_double:
// fixed point) runs the test in doubles on its data rounded to doubles.
// The conversion (screen_value) moves each datum by at most 3 · 2^-53 of
// itself, and so the endpoints and chords by at most 2^-50 of |Δp| + T |Δv|
// + T² |Δa| and R by 2^-51 of itself, far inside the 2^-40 the test widens
// by: a pair it clears stays farther than R for the data
// themselves. It only spares the exact search of pairs that cannot meet; the
// search itself, and so every event, stays in the scene's own numbers.
template <class Num>
bool certainly_out_of_reach(const RelativeMotion<Num>& m, const Num& horizon) {
  using T = NumberTraits<Num>;
  if constexpr (screens_in_double<Num>) {
    auto d = [](const Num& x) { return screen_value(x); };
    auto d2 = [&](const Vec2<Num>& v) { return Vec2<double>{d(v.x), d(v.y)}; };
    const RelativeMotion<double> md{{d2(m.offset.hi), {}}, d2(m.velocity), d2(m.acceleration), d(m.radius)};
    return certainly_out_of_reach(md, d(horizon));
  }
  const Num zero{};
  const Box<Num> box = trajectory_box(m.offset.hi, m.velocity, m.acceleration, horizon);
  const Num R = m.radius + m.radius * num<Num>(0x1p-40);
  if (R * R < squared_distance_to_box(Vec2<Num>{}, box)) return true;
  if (m.acceleration.x == zero && m.acceleration.y == zero) return false;
  const Num quarter = T::half(T::half(horizon));
  const Num accel = T::abs(m.acceleration.x) + T::abs(m.acceleration.y);  // ≥ |Δa|
  const Num sag = accel * quarter * quarter * num<Num>(0.125);
  const Num clearance = R + sag + (box.hi.x - box.lo.x + box.hi.y - box.lo.y) * num<Num>(0x1p-40);
  Vec2<Num> from = m.offset.hi;
  for (int k = 1; k <= 4; ++k) {
    const Vec2<Num> to = position_at(m.offset.hi, m.velocity, m.acceleration, k == 4 ? horizon : quarter * num<Num>(k));
    if (!segment_clear_of_origin(from, to, clearance)) return false;
    from = to;
  }
  return true;
}

// Linear relative motion (Δa = 0).
template <class Num>
RootSearch<Num> first_contact_linear(const RelativeMotion<Num>& m, const Num& horizon) {
  const Num zero{};
  const Vec2<Num>& dp = m.offset.hi;
  const Vec2<Num>& dv = m.velocity;
  const Num A = length_squared(dv);
  if (A == zero) return {};  // no relative motion: they never meet
  // Plain products suffice here: each of b, C and q × v carries an absolute
  // error of a few ulp of |Δp| |Δv| or |Δp|², which moves the contact by
  // about ε |Δp|, and a contact is only possible when |Δp| is within a few
  // length scales of the query. (The cancellation that matters, b² − AC for
  // a small ball far away, is avoided by Lagrange's identity.)
  const Num b = dot(dp, dv) + dot(m.offset.lo, dv);
  // A receding pair (b ≥ 0; A > 0) never meets: touching or not at t = 0
  // (C, below), the answer is none. Fixed point, whose products are dear,
  // says so before forming C and the discriminant; doubles go on, for their
  // range checks of C name a scene whose squares overflow (and asking for
  // the discriminant only when closing cost them 1.04x the CPU of a gas).
  if constexpr (NumberTraits<Num>::rounds_absolutely)
    if (!(b < zero)) return {};
  const Num C = length_squared(dp) + num<Num>(2.0) * dot(dp, m.offset.lo) - m.radius * m.radius;
  // Strict mode: squares beyond the double range. Objects that far apart are
  // told apart by the trajectory box, which needs no squares of the distance
  // that cannot be formed (two balls 1e300 apart); anything else is refused.
  if (!is_in_range(A) || !is_in_range(b) || !is_in_range(C)) {
    if (certainly_out_of_reach(m, horizon)) return {};
    check_in_range(A, "a contact quadratic");
    check_in_range(b, "a contact quadratic");
    check_in_range(C, "a contact quadratic");
  }
  if (!(zero < C)) {
    // Touching or overlapping at t = 0: a contact only if still approaching.
    if (b < zero) return {true, zero};
    return {};
  }
  const Num q_cross_v = cross(dp, dv) + cross(m.offset.lo, dv);
  const Num D = A * (m.radius * m.radius) - q_cross_v * q_cross_v;  // Lagrange
  check_in_range(D, "a contact discriminant");
  return first_downward_root(A, b, C, [&] { return D; }, horizon);
}

// Accelerated relative motion (Δa ≠ 0): the derivative cascade.
template <class Num>
RootSearch<Num> first_contact_accelerated(const RelativeMotion<Num>& m, const Num& horizon) {
  using T = NumberTraits<Num>;
  const Num zero{};
  const Num R2 = m.radius * m.radius;
  const Vec2<Num>& dv = m.velocity;
  const Vec2<Num>& da = m.acceleration;
  auto g = [&](const Num& t) { return length_squared(relative_position(m, t)) - R2; };
  auto half_g1 = [&](const Num& t) { return dot(relative_position(m, t), velocity_at(dv, da, t)); };
  auto half_g2 = [&](const Num& t) {
    return length_squared(velocity_at(dv, da, t)) + dot(relative_position(m, t), da);
  };

  // Touching or overlapping at the start: a contact only if approaching.
  const Num g0 = g(zero);
  check_in_range(g0, "a contact quartic");
  check_in_range(half_g1(zero), "a contact quartic");
  if (!(zero < g0) && half_g1(zero) < zero) return {true, zero};

  // Roots of ½g'' = (3/2)|Δa|² t² + 3(Δv·Δa) t + (|Δv|² + Δp·Δa) in (0, H),
  // in increasing order: the pieces on which g' is monotone.
  std::array<Num, 4> cuts{};
  int n_cuts = 0;
  cuts[n_cuts++] = zero;
  // p / q, unless it lies beyond the horizon: fixed point would overflow
  // forming a root of a nearly degenerate ½g'' that no cut needs.
  auto root = [&](const Num& p, const Num& q, Num& r) {
    if (T::rounds_absolutely && !(T::abs(p) < horizon * T::abs(q))) return false;
    r = p / q;
    return true;
  };
  {
    const Num A = num<Num>(1.5) * length_squared(da);
    const Num b = num<Num>(1.5) * dot(dv, da);
    const Num C = half_g2(zero);
    for (const Num* x : {&A, &b, &C}) check_in_range(*x, "a contact quartic");
    const Num D = T::rounds_absolutely && A == zero ? zero : compensated_discriminant(A, b, C);
    check_in_range(D, "a contact quartic");
    if (T::rounds_absolutely && A == zero && !(b == zero)) {
      // |Δa|² below the resolution (fixed point): ½g'' is linear, one root.
      Num r{};
      if (root(C, -(b + b), r) && zero < r && r < horizon) cuts[n_cuts++] = r;
    } else if (zero < D) {
      const Num s = T::sqrt(D);
      // The two roots, the smaller first (A > 0), each in its stable form.
      const Num qq = b < zero ? s - b : -(b + s);
      Num r1 = horizon, r2 = horizon;  // a root beyond the horizon is no cut
      root(qq, A, r1);
      root(C, qq, r2);
      if (r2 < r1) std::swap(r1, r2);
      if (zero < r1 && r1 < horizon) cuts[n_cuts++] = r1;
      if (zero < r2 && r2 < horizon) cuts[n_cuts++] = r2;
    }
  }
  cuts[n_cuts++] = horizon;

  // Walk the pieces in time order; g'' keeps one sign on each. Return the
  // first downward crossing of g.
  auto g_and_slope = [&](const Num& t) {
    const Vec2<Num> q = relative_position(m, t);
    return std::pair<Num, Num>{length_squared(q) - R2, num<Num>(2.0) * dot(q, velocity_at(dv, da, t))};
  };
  auto crossing = [&](const Num& x0, const Num& x1, bool convex) {
    // Newton from the end where g g'' > 0 approaches without overshooting.
    return RootSearch<Num>{true, polish_root_monotone<Num>(g_and_slope, x0, x1, true, !convex)};
  };
  Num g_left = g0;
  for (int i = 0; i + 1 < n_cuts; ++i) {
    const Num& x0 = cuts[i];
    const Num& x1 = cuts[i + 1];
    const bool convex = zero < half_g2(T::half(x0 + x1));
    const Num g_right = g(x1);
    check_in_range(g_right, "a contact quartic");
    const Num g_x0 = g_left;
    g_left = g_right;
    // g' = 2 h is monotone here, so g is monotone or has one extremum: a
    // sign change of g between the ends is then the one crossing inside.
    if (zero < g_x0 && !(zero < g_right)) return crossing(x0, x1, convex);
    const Num h0 = half_g1(x0), h1 = half_g1(x1);
    auto h_and_slope = [&](const Num& t) {
      const Vec2<Num> q = relative_position(m, t);
      const Vec2<Num> v = velocity_at(dv, da, t);
      return std::pair<Num, Num>{dot(q, v), length_squared(v) + dot(q, da)};
    };
    if (zero < g_x0 && h0 < zero && zero < h1) {
      // g falls, then rises, and is positive at both ends: does its minimum
      // reach zero? g is convex here, so the tangents at both ends bound it
      // from below; if their crossing stays above zero (with a margin for
      // rounding), so does g and the minimum need not be found.
      const Num s0 = num<Num>(2.0) * h0, s1 = num<Num>(2.0) * h1;
      const Num t_star = (g_right - g_x0 + s0 * x0 - s1 * x1) / (s0 - s1);
      const Num bound = g_x0 + s0 * (t_star - x0);
      const Num margin = (T::abs(g_x0) + T::abs(g_right) + R2) * num<Num>(0x1p-30);
      if (margin < bound) continue;
      const Num minimum = polish_root_monotone<Num>(h_and_slope, x0, x1, false);
      if (!(zero < g(minimum))) return crossing(x0, minimum, convex);
    } else if (!(zero < g_x0) && !(zero < g_right) && zero < h0 && h1 < zero) {
      // In contact at x0 (just after a bounce), g rises, then falls back: if
      // it got above zero, coming back down is a contact.
      const Num maximum = polish_root_monotone<Num>(h_and_slope, x0, x1, true);
      if (zero < g(maximum)) return crossing(maximum, x1, convex);
    }
  }
  return {};
}

template <class Num>
RootSearch<Num> first_contact_unscaled(const RelativeMotion<Num>& m, const Num& horizon) {
  const Num zero{};
  // The model the motion needs: a quartic only when the relative acceleration is not zero.
  if (m.acceleration.x == zero && m.acceleration.y == zero) return first_contact_linear(m, horizon);
  // (A type that screens in doubles was screened in first_contact, unscaled.)
  if constexpr (!screens_in_double<Num>)
    if (certainly_out_of_reach(m, horizon)) return {};
  return first_contact_accelerated(m, horizon);
}

// Fixed point rounds to an absolute 2^-64: for a contact of size 2^-20,
// |Δp|² − R² and the discriminant would keep a few significant bits. Time
// does not change when Δp, Δv, Δa and R are all multiplied by 2^k, and that
// multiplication is an exact shift; so a small motion is scaled up until its
// largest length over the horizon (|Δp|, R, |Δv| H, |Δa| H²) reaches 2^0,
// keeping Δv, Δa and their product small enough that the solver's squares
// fit (below) and k ≤ 60. Floating point
// rounds relatively and needs none of this (k = 0).
template <class Num>
int unit_scale_exponent(const RelativeMotion<Num>& m, const Num& horizon) {
  using T = NumberTraits<Num>;
  if constexpr (!T::rounds_absolutely) {
    return 0;
  } else {
    // A length of at least 1 (|Δp| or R: a ball–ball query of radii 1/2 or
    // more, the common case) leaves nothing to scale: k = 0 whatever the
    // motion, before its exponents are formed.
    const int e_p = std::max({T::exponent(m.offset.hi.x), T::exponent(m.offset.hi.y), T::exponent(m.radius)});
    if (e_p >= 0) return 0;
    const Vec2<Num>& v = m.velocity;
    const Vec2<Num>& a = m.acceleration;
    const int e_v = std::max(T::exponent(v.x), T::exponent(v.y));
    const int e_a = std::max(T::exponent(a.x), T::exponent(a.y));
    const int e_h = T::exponent(horizon);
    const int largest = std::max({e_p, e_v + e_h + 1, e_a + 2 * e_h + 2});
    // The products the solvers form must fit too. With e the exponent of the
    // largest component, |Δv| < 2^(e_v + 1.5) and |Δv·Δa| < 2^(e_v + e_a + 3):
    // b = 1.5 Δv·Δa, A C ~ |Δa|² |Δv|² and b² + |A C| stay below 2^62 when
    // e_v + e_a + 2k ≤ 24, and (q × Δv)², |Δv|⁴-sized terms when e_v + k ≤ 28.
    return std::max(0, std::min({-largest, 28 - e_v, 28 - e_a, (24 - e_v - e_a) / 2, 60}));
  }
}

template <class Num>
RelativeMotion<Num> scaled_lengths(const RelativeMotion<Num>& m, int k) {
  using T = NumberTraits<Num>;
  auto scale = [&](const Vec2<Num>& x) { return Vec2<Num>{T::times_power_of_two(x.x, k), T::times_power_of_two(x.y, k)}; };
  return {{scale(m.offset.hi), scale(m.offset.lo)}, scale(m.velocity), scale(m.acceleration),
          T::times_power_of_two(m.radius, k)};
}

template <class Num>
RootSearch<Num> first_contact(const RelativeMotion<Num>& m, const Num& horizon) {
  // The screen is scale-free, and in doubles it needs no scaling: done first,
  // it spares a pair it clears the scaling too.
  if constexpr (screens_in_double<Num>) {
    const Num zero{};
    if (!(m.acceleration.x == zero && m.acceleration.y == zero) && certainly_out_of_reach(m, horizon)) return {};
  }
  if constexpr (NumberTraits<Num>::rounds_absolutely) {
    const int k = unit_scale_exponent(m, horizon);
    if (k > 0) return first_contact_unscaled(scaled_lengths(m, k), horizon);
  }
  return first_contact_unscaled(m, horizon);
}

}  // namespace collide2d
