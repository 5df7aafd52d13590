// An independent, high-precision time-of-impact oracle for tests and studies.
//
// It shares nothing with the analytic method but the query type: it expands
// the exact contact polynomials from the double inputs in Reference (about
// 200 bits, so the coefficients are exact or nearly so), isolates their real
// roots on [0, H] by the monotone-piece recursion (the roots of p' cut [0, H]
// into pieces on which p is monotone; a piece whose end values differ in sign
// holds exactly one root) and bisects each root to about 1e-42 relative.
// Every sign it needs comes from evaluating a polynomial or the true distance
// in Reference; there is no tolerance and no Newton step to go astray.
//
// Slow (milliseconds per query): for tests, never for the simulation.
#pragma once

#include <algorithm>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "collide2d/toi/query.hpp"
#include "lab/reference.hpp"

namespace collide2d {

struct OracleAnswer {
  bool hit = false;
  double t = 0;        // first contact, valid if hit
  double min_gap = 0;  // min over [0, H] of (distance − contact distance)
  double scale = 0;    // max(contact radius, |Δv| H, ½ |Δa| H²)
};

namespace oracle_detail {

using R = Reference;

// p(t) = c[0] + c[1] t + ... + c[n] t^n.
struct Poly {
  std::vector<R> c;
};

// Degree of p with exact-zero leading coefficients dropped; −1 for p ≡ 0.
inline int degree(const Poly& p) {
  int n = static_cast<int>(p.c.size()) - 1;
  while (n >= 0 && p.c[n] == 0) --n;
  return n;
}

// p(t) by Horner's rule: (((c_n t + c_{n−1}) t + ...) t + c_0.
inline R evaluate(const Poly& p, const R& t) {
  R s = 0;
  for (auto it = p.c.rbegin(); it != p.c.rend(); ++it) s = s * t + *it;
  return s;
}

// p'(t) = Σ k c_k t^(k−1).
inline Poly derivative(const Poly& p) {
  Poly d;
  for (std::size_t k = 1; k < p.c.size(); ++k) d.c.push_back(R(static_cast<int>(k)) * p.c[k]);
  return d;
}

// (p + q)(t) and (p q)(t), coefficientwise.
inline Poly operator+(const Poly& p, const Poly& q) {
  Poly s;
  s.c.assign(std::max(p.c.size(), q.c.size()), R(0));
  for (std::size_t k = 0; k < p.c.size(); ++k) s.c[k] += p.c[k];
  for (std::size_t k = 0; k < q.c.size(); ++k) s.c[k] += q.c[k];
  return s;
}
inline Poly operator*(const Poly& p, const Poly& q) {
  Poly s;
  if (p.c.empty() || q.c.empty()) return s;
  s.c.assign(p.c.size() + q.c.size() - 1, R(0));
  for (std::size_t i = 0; i < p.c.size(); ++i)
    for (std::size_t j = 0; j < q.c.size(); ++j) s.c[i + j] += p.c[i] * q.c[j];
  return s;
}
inline Poly operator*(const R& k, const Poly& p) {
  Poly s = p;
  for (auto& c : s.c) c *= k;
  return s;
}
inline Poly constant(const R& k) { return Poly{{k}}; }

// The single root of p in [a, b], where p is monotone and p(a), p(b) are
// non-zero with opposite signs: bisection until the bracket is ~1e-42 of |t|.
inline R bisect_monotone(const Poly& p, R a, R b, bool p_a_negative) {
  static const R relative_width("1e-42");
  static const R absolute_width("1e-300");
  for (int i = 0; i < 2000; ++i) {
    const R mid = a + (b - a) / 2;
    if (!(a < mid && mid < b)) break;
    if (b - a <= relative_width * std::max(abs(a), abs(b)) + absolute_width) break;
    const R f = evaluate(p, mid);
    if (f == 0) return mid;
    if ((f < 0) == p_a_negative) a = mid; else b = mid;
  }
  return a + (b - a) / 2;
}

// The distinct real roots of p in [lo, hi], ascending. The roots of p' (found
// the same way, recursively) split [lo, hi] into pieces where p is monotone;
// each piece holds a root exactly when p vanishes at an end or changes sign.
// If `critical` is given, the roots of p' in [lo, hi] are appended to it.
// p ≡ 0 has no isolated roots: callers never need its (constant) sign change.
inline std::vector<R> real_roots(const Poly& p, const R& lo, const R& hi, std::vector<R>* critical = nullptr) {
  std::vector<R> roots;
  const int n = degree(p);
  if (n <= 0 || hi < lo) return roots;
  std::vector<R> cuts{lo};
  if (n >= 2) {
    const std::vector<R> crit = real_roots(derivative(p), lo, hi);
    if (critical) critical->insert(critical->end(), crit.begin(), crit.end());
    for (const R& t : crit)
      if (lo < t && t < hi) cuts.push_back(t);
  }
  cuts.push_back(hi);
  R f_left = evaluate(p, cuts[0]);
  if (f_left == 0) roots.push_back(cuts[0]);
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const R f_right = evaluate(p, cuts[i + 1]);
    if (f_left != 0 && f_right != 0 && ((f_left < 0) != (f_right < 0)))
      roots.push_back(bisect_monotone(p, cuts[i], cuts[i + 1], f_left < 0));
    if (f_right == 0) roots.push_back(cuts[i + 1]);
    f_left = f_right;
  }
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  return roots;
}

// A point moving as e(t) = e0 + e1 t + ½ e2 t², one polynomial per axis.
struct MotionPoly {
  Poly x, y;
};
inline MotionPoly motion(const R& px, const R& py, const Vec2<double>& v, const Vec2<double>& a) {
  return {Poly{{px, R(v.x), R(a.x) / 2}}, Poly{{py, R(v.y), R(a.y) / 2}}};
}
// e·f and (constant d) × e = d.x e.y − d.y e.x as polynomials in t.
inline Poly dot(const MotionPoly& e, const MotionPoly& f) { return e.x * f.x + e.y * f.y; }
inline Poly cross(const R& dx, const R& dy, const MotionPoly& e) { return dx * e.y + (-dy) * e.x; }

// Everything the contact search needs about one query, for a given contact
// distance (the nominal one, or one moved by ±tol for the acceptance rule).
struct ContactModel {
  bool possible = true;            // false if the contact distance is negative
  std::vector<Poly> sign_changes;  // the contact condition is constant between their roots
  std::vector<Poly> start;         // "approaching at 0" if any of these decreases at 0
  std::function<R(const R&)> gap;  // true distance − contact distance at t
  R horizon;
};

// Ball–ball. q(t) = Δp + Δv t + ½ Δa t² (exact differences of the inputs),
//   gap(t) = |q(t)| − R,   contact ⇔ g(t) = |q(t)|² − R² ≤ 0   (degree ≤ 4).
inline ContactModel ball_ball_model(const ToiQuery& q, const R& extra) {
  ContactModel m;
  m.horizon = R(q.horizon);
  const R radius = R(q.ball.radius) + R(q.other.radius) + extra;
  m.possible = !(radius < 0);
  const R px = R(q.ball.position.x) - R(q.other.position.x);
  const R py = R(q.ball.position.y) - R(q.other.position.y);
  const MotionPoly e = motion(px, py, q.ball.velocity - q.other.velocity, q.ball.acceleration - q.other.acceleration);
  const Poly g = dot(e, e) + constant(-radius * radius);
  m.sign_changes = {g};
  m.start = {g};
  m.gap = [e, radius](const R& t) { return sqrt(evaluate(e.x, t) * evaluate(e.x, t) + evaluate(e.y, t) * evaluate(e.y, t)) - radius; };
  return m;
}

// Ball–wall, wall [A, B], d = B − A, L² = |d|², centre c(t), e(t) = c(t) − A:
//   along u(t) = d·e(t)  (the centre projects inside the segment iff 0 ≤ u ≤ L²)
//   face   s̃(t) = d × e(t) = L · s(t)  (s: signed distance to the wall line),
//          contact with a face ⇔ F(t) = s̃(t)² − r² L² ≤ 0 while inside  (degree 4)
//   ends   P_A(t) = |c − A|² − r²,  P_B(t) = |c − B|² − r²   (degree ≤ 4)
//   gap(t) = distance from c(t) to the segment − r.
// Contact ⇔ P_A ≤ 0 or P_B ≤ 0 or (F ≤ 0 and inside): constant between the
// roots of P_A, P_B, F, u and u − L².
inline ContactModel ball_wall_model(const ToiQuery& q, const R& extra) {
  ContactModel m;
  m.horizon = R(q.horizon);
  const R r = R(q.ball.radius) + extra;
  m.possible = !(r < 0);
  const R ax = R(q.wall.a.x), ay = R(q.wall.a.y), bx = R(q.wall.b.x), by = R(q.wall.b.y);
  const R dx = bx - ax, dy = by - ay, L2 = dx * dx + dy * dy;
  const R px = R(q.ball.position.x), py = R(q.ball.position.y);
  const MotionPoly e_a = motion(px - ax, py - ay, q.ball.velocity, q.ball.acceleration);
  const MotionPoly e_b = motion(px - bx, py - by, q.ball.velocity, q.ball.acceleration);
  const Poly u = dx * e_a.x + dy * e_a.y;
  const Poly s = cross(dx, dy, e_a);
  const Poly P_A = dot(e_a, e_a) + constant(-r * r);
  const Poly P_B = dot(e_b, e_b) + constant(-r * r);
  const Poly F = s * s + constant(-r * r * L2);
  m.sign_changes = {P_A, P_B, F, u, u + constant(-L2)};
  const R u0 = evaluate(u, R(0));
  if (!(0 < u0)) m.start.push_back(P_A);
  if (!(u0 < L2)) m.start.push_back(P_B);
  if (!(u0 < 0) && !(L2 < u0)) m.start.push_back(F);
  m.gap = [e_a, e_b, u, s, L2, r](const R& t) {
    const R along = evaluate(u, t);
    if (!(0 < along)) return sqrt(evaluate(dot(e_a, e_a), t)) - r;
    if (!(along < L2)) return sqrt(evaluate(dot(e_b, e_b), t)) - r;
    return abs(evaluate(s, t)) / sqrt(L2) - r;
  };
  return m;
}

// The model of either kind; `extra` moves the contact distance out (> 0) or in.
inline ContactModel model(const ToiQuery& q, const R& extra) {
  return q.kind == QueryKind::ball_ball ? ball_ball_model(q, extra) : ball_wall_model(q, extra);
}

// p(t) < p(0) for all small t > 0: the first non-zero of c_1, c_2, ... is negative.
inline bool decreasing_at_zero(const Poly& p) {
  for (std::size_t k = 1; k < p.c.size(); ++k)
    if (p.c[k] != 0) return p.c[k] < 0;
  return false;
}

// The sorted times where the contact condition may change: 0, H, and every
// root in [0, H] of the sign-change polynomials. Roots of their derivatives
// (the critical points of each piece) go to *critical if asked.
inline std::vector<R> breakpoints(const ContactModel& m, std::vector<R>* critical) {
  std::vector<R> times{R(0), m.horizon};
  for (const Poly& p : m.sign_changes) {
    const std::vector<R> roots = real_roots(p, R(0), m.horizon, critical);
    times.insert(times.end(), roots.begin(), roots.end());
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

// First contact: t = 0 if gap(0) ≤ 0 and the objects approach; otherwise the
// first breakpoint t_i > 0 where gap > 0 just before it and gap ≤ 0 at t_i or
// just after it (the contact condition only changes at breakpoints, so its
// value on an open piece is its value at the piece's midpoint).
inline std::optional<R> first_contact(const ContactModel& m, const std::vector<R>& times) {
  if (!m.possible) return std::nullopt;
  auto touching = [&](const R& t) { return !(0 < m.gap(t)); };
  if (touching(R(0)) && std::any_of(m.start.begin(), m.start.end(), decreasing_at_zero)) return R(0);
  for (std::size_t i = 1; i < times.size(); ++i) {
    if (touching((times[i - 1] + times[i]) / 2)) continue;
    const bool after = i + 1 < times.size() && touching((times[i] + times[i + 1]) / 2);
    if (touching(times[i]) || after) return times[i];
  }
  return std::nullopt;
}

// scale = max(R, |Δv| H, ½ |Δa| H²): R = r (wall) or r_a + r_b (ball), Δ relative
// to the wall (fixed) or to the other ball.
inline double scale_of(const ToiQuery& q) {
  const bool ball = q.kind == QueryKind::ball_ball;
  const double radius = ball ? q.ball.radius + q.other.radius : q.ball.radius;
  const Vec2<double> dv = ball ? q.ball.velocity - q.other.velocity : q.ball.velocity;
  const Vec2<double> da = ball ? q.ball.acceleration - q.other.acceleration : q.ball.acceleration;
  // sqrt, not hypot: correctly rounded everywhere, so a stored scale is the
  // same bits on every machine.
  return std::max({radius, std::sqrt(dot(dv, dv)) * q.horizon, 0.5 * std::sqrt(dot(da, da)) * q.horizon * q.horizon});
}

}  // namespace oracle_detail

// The true gap (distance − contact distance) at time t, in Reference.
inline Reference oracle_gap_at(const ToiQuery& q, const Reference& t) {
  return oracle_detail::model(q, Reference(0)).gap(t);
}

// The first time in [0, H] at which the gap enters ≤ `level` (0: contact):
// the contact time for the contact distance moved out by `level`.
inline std::optional<Reference> oracle_first_time_gap_at_most(const ToiQuery& q, const Reference& level) {
  const auto m = oracle_detail::model(q, level);
  return oracle_detail::first_contact(m, oracle_detail::breakpoints(m, nullptr));
}

// The oracle: first contact, minimum gap over [0, H] (from the gap at the
// breakpoints and at every critical point of the pieces), and the scale.
inline OracleAnswer oracle_time_of_impact(const ToiQuery& q) {
  using oracle_detail::R;
  const auto m = oracle_detail::model(q, R(0));
  std::vector<R> critical;
  const std::vector<R> times = oracle_detail::breakpoints(m, &critical);
  OracleAnswer out;
  const auto first = oracle_detail::first_contact(m, times);
  out.hit = first.has_value();
  out.t = first ? first->convert_to<double>() : 0.0;
  R min_gap = m.gap(R(0));
  critical.insert(critical.end(), times.begin(), times.end());
  for (const R& t : critical)
    if (!(t < 0) && !(m.horizon < t)) min_gap = std::min(min_gap, m.gap(t));
  out.min_gap = min_gap.convert_to<double>();
  out.scale = oracle_detail::scale_of(q);
  return out;
}

// The query as C++-readable text, every double to 17 digits.
inline std::string describe(const ToiQuery& q) {
  char buf[768];
  auto ball = [](const BallState<double>& b) {
    char s[256];
    std::snprintf(s, sizeof s, "p=(%.17g, %.17g) v=(%.17g, %.17g) a=(%.17g, %.17g) r=%.17g", b.position.x,
                  b.position.y, b.velocity.x, b.velocity.y, b.acceleration.x, b.acceleration.y, b.radius);
    return std::string(s);
  };
  if (q.kind == QueryKind::ball_wall)
    std::snprintf(buf, sizeof buf, "ball_wall ball{%s} wall{(%.17g, %.17g)-(%.17g, %.17g)} H=%.17g",
                  ball(q.ball).c_str(), q.wall.a.x, q.wall.a.y, q.wall.b.x, q.wall.b.y, q.horizon);
  else
    std::snprintf(buf, sizeof buf, "ball_ball ball{%s} other{%s} H=%.17g", ball(q.ball).c_str(),
                  ball(q.other).c_str(), q.horizon);
  return buf;
}

// The acceptance rule, with tol = rel_tol · scale, for a valid query (gap(0) ≥ −tol):
//  - oracle min_gap < −tol: the method must report a hit;
//  - oracle min_gap > +tol: it must report no hit;
//  - a hit at t: 0 ≤ t ≤ H, the true gap at t within ±tol, t no later than the
//    first time the true gap reaches −tol, and no earlier than the first time
//    it comes within +tol while approaching (a contact, never a separation).
struct Verdict {
  bool ok = true;
  std::string why;  // the query, the oracle's view and what went wrong
};

inline Verdict judge_toi_answer(const ToiQuery& q, bool hit, double t, double rel_tol) {
  using oracle_detail::R;
  const OracleAnswer o = oracle_time_of_impact(q);
  const double tol = rel_tol * o.scale;
  char head[512];
  std::snprintf(head, sizeof head, "%s\n  oracle: hit=%d t=%.17g min_gap=%.6g scale=%.6g tol=%.3g; method: hit=%d t=%.17g\n  ",
                describe(q).c_str(), o.hit, o.t, o.min_gap, o.scale, tol, hit, t);
  Verdict v;
  auto fail = [&](const std::string& why) {
    v.ok = false;
    v.why = head + why;
    return v;
  };
  const R gap0 = oracle_gap_at(q, R(0));
  if (gap0 < R(-tol)) return fail("invalid test query: it starts overlapping by more than tol");
  if (o.min_gap < -tol && !hit) return fail("missed a contact (min gap < -tol)");
  if (o.min_gap > tol && hit) return fail("reported a hit, but the gap never comes within tol");
  if (!hit) return v;
  if (!(t >= 0 && t <= q.horizon)) return fail("hit time outside [0, H]");
  const R gap = oracle_gap_at(q, R(t));
  if (abs(gap) > R(tol)) return fail("true gap at t is " + gap.str(6) + ", not within tol");
  const auto latest = oracle_first_time_gap_at_most(q, R(-tol));
  if (latest && R(t) > *latest) return fail("t is later than the first time the gap reaches -tol, " + latest->str(17));
  const auto earliest = oracle_first_time_gap_at_most(q, R(tol));
  if (!earliest || R(t) < *earliest)
    return fail("t is before the objects first come within tol while approaching (" +
                (earliest ? earliest->str(17) : std::string("never")) + ")");
  return v;
}

}  // namespace collide2d
