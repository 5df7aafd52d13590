// The "general-purpose polynomial solver" baseline for time of impact: what a
// user reaches for first. Expand the contact condition into a polynomial in t
// and hand it to a generic root finder, here Eigen's PolynomialSolver (the
// eigenvalues of the balanced companion matrix, by Hessenberg QR). Studies
// measure it against the analytic method (analytic.hpp) for speed and error,
// so it is an ordinary, honest implementation in double, and it deliberately
// borrows none of that method's safeguards: no compensated differences or
// products, no Lagrange discriminant, no root polishing, no scaling. Its
// accuracy is what the companion matrix and plain expanded coefficients give.
//
// Which eigenvalues count as real roots: |imag| ≤ 1e-9 max(1, |real|).
// Eigen's realRoots() takes only an absolute threshold, so roots() is
// filtered here with this relative one. A double root (a graze) splits under
// rounding into two roots about √ε apart, possibly a complex pair beyond the
// threshold: a graze touching by less than about ε relative may be missed.
// That is part of what is measured, not mended.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <vector>

#include <unsupported/Eigen/Polynomials>

#include "collide2d/geometry/vec2.hpp"
#include "collide2d/toi/toi_result.hpp"

namespace collide2d {

namespace polynomial_baseline_detail {

// p(t) = c[0] + c[1] t + ... + c[n] t^n: increasing degree, as Eigen wants.
using Coefficients = std::vector<double>;

// p'(t) by Horner's rule on k c[k].
inline double evaluate_derivative(const Coefficients& c, double t) {
  double s = 0;
  for (std::size_t k = c.size(); k-- > 1;) s = s * t + static_cast<double>(k) * c[k];
  return s;
}

// The real roots of p in [0, horizon] at which p is not increasing (p' ≤ 0):
// the times a gap p closes, not the times it opens again. Increasing order.
// Exact-zero leading coefficients are dropped (Eigen needs a non-zero one);
// a constant has no root.
inline std::vector<double> closing_roots(Coefficients c, double horizon) {
  while (!c.empty() && c.back() == 0.0) c.pop_back();
  std::vector<double> closing;
  if (c.size() < 2) return closing;
  Eigen::VectorXd poly(static_cast<Eigen::Index>(c.size()));
  for (std::size_t k = 0; k < c.size(); ++k) poly[static_cast<Eigen::Index>(k)] = c[k];
  const Eigen::PolynomialSolver<double, Eigen::Dynamic> solver(poly);
  for (const std::complex<double>& z : solver.roots()) {
    const double t = z.real();
    if (std::abs(z.imag()) > 1e-9 * std::max(1.0, std::abs(t))) continue;  // complex
    if (t < 0.0 || horizon < t) continue;
    if (evaluate_derivative(c, t) <= 0.0) closing.push_back(t);
  }
  std::sort(closing.begin(), closing.end());
  return closing;
}

// A point moving as Δp + Δv t + ½Δa t² (relative to a fixed origin) first
// comes within R of it. Expanding |q(t)|² − R²:
//
//   g(t) = ¼|Δa|² t⁴ + (Δv·Δa) t³ + (|Δv|² + Δp·Δa) t² + 2(Δp·Δv) t + |Δp|² − R²
//
// degree 4, or 2 when Δa = 0 (the t³, t⁴ coefficients are then exact zeros).
// Contact: g(0) ≤ 0 with g'(0) = 2 Δp·Δv < 0 (touching and approaching), or
// else the first root in [0, H] where g decreases.
inline std::optional<double> first_point_contact(const Vec2<double>& dp, const Vec2<double>& dv,
                                                 const Vec2<double>& da, double R, double horizon) {
  const Coefficients g{dot(dp, dp) - R * R, 2.0 * dot(dp, dv), dot(dv, dv) + dot(dp, da), dot(dv, da),
                       0.25 * dot(da, da)};
  if (g[0] <= 0.0 && g[1] < 0.0) return 0.0;
  const std::vector<double> roots = closing_roots(g, horizon);
  if (roots.empty()) return std::nullopt;
  return roots.front();
}

}  // namespace polynomial_baseline_detail

// Ball a against ball b (b may be fixed): the point contact above with
// Δp = p_a − p_b, Δv = v_a − v_b, Δa = a_a − a_b, R = r_a + r_b. The result
// is filled as time_of_impact_ball_ball fills it: the normal points from b's
// centre to a's, the point is on b's surface.
inline ToiResult<double> polynomial_solver_ball_ball(const BallState<double>& a, const BallState<double>& b,
                                                     double horizon) {
  const std::optional<double> t = polynomial_baseline_detail::first_point_contact(
      a.position - b.position, a.velocity - b.velocity, a.acceleration - b.acceleration, a.radius + b.radius,
      horizon);
  if (!t) return {};
  ToiResult<double> r;
  r.state = ToiState::hit;
  r.time = *t;
  r.feature = ContactFeature::ball;
  const Vec2<double> pb = position_at(b, *t);
  r.normal = normalized(position_at(a, *t) - pb);
  r.point = pb + b.radius * r.normal;
  return r;
}

// Ball against a two-sided wall segment [A, B] with round ends.
//
// Faces: with u = (B − A)/|B − A| along the wall and n = perp(u) its unit
// normal, the centre's signed distance to the wall's line is
//
//   s(t) = n·(p(t) − A) = ½(n·a) t² + (n·v) t + n·(p − A),
//
// and the ball touches the face on side ε = ±1 where w_ε(t) = ε s(t) − r = 0
// with w_ε decreasing (coming towards the line), provided the centre then
// projects inside the segment: 0 ≤ u·(p(t) − A) ≤ |B − A|. Each w_ε is a
// quadratic (linear when n·a = 0), solved by the same Eigen solver as the
// quartics, for an even-handed comparison.
//
// Ends: the point contact above against each end (Δp = p − A or p − B,
// Δv = v, Δa = a, R = r), a quartic.
//
// The earliest valid contact wins, a face winning a tie.
inline ToiResult<double> polynomial_solver_ball_wall(const BallState<double>& ball, const Segment<double>& wall,
                                                     double horizon) {
  namespace detail = polynomial_baseline_detail;
  const Vec2<double> d = wall.b - wall.a;
  const double wall_length = length(d);
  const Vec2<double> along_unit = (1.0 / wall_length) * d;
  const Vec2<double> n = perp(along_unit);  // the side where d × (p − A) > 0
  const Vec2<double> rel = ball.position - wall.a;
  const double r = ball.radius;
  const double s0 = dot(n, rel), sv = dot(n, ball.velocity), sa = dot(n, ball.acceleration);
  auto projects_inside = [&](double t) {
    const double along = dot(along_unit, position_at(rel, ball.velocity, ball.acceleration, t));
    return 0.0 <= along && along <= wall_length;
  };

  ToiResult<double> best;
  for (const double side : {1.0, -1.0}) {
    const detail::Coefficients w{side * s0 - r, side * sv, 0.5 * side * sa};
    std::optional<double> t;
    // Touching this side at t = 0 (on it, within r) and approaching.
    if (0.0 <= side * s0 && w[0] <= 0.0 && w[1] < 0.0 && projects_inside(0.0)) t = 0.0;
    if (!t) {
      for (const double root : detail::closing_roots(w, horizon)) {
        if (projects_inside(root)) {
          t = root;
          break;
        }
      }
    }
    if (t && (!best.hit() || *t < best.time)) {
      best.state = ToiState::hit;
      best.time = *t;
      best.feature = ContactFeature::wall_face;
      best.normal = side * n;
      best.point = position_at(ball, *t) - r * best.normal;
    }
  }

  const Vec2<double>* ends[2] = {&wall.a, &wall.b};
  for (int e = 0; e < 2; ++e) {
    const Vec2<double>& end = *ends[e];
    const std::optional<double> t =
        detail::first_point_contact(ball.position - end, ball.velocity, ball.acceleration, r, horizon);
    if (t && (!best.hit() || *t < best.time)) {
      best.state = ToiState::hit;
      best.time = *t;
      best.feature = e == 0 ? ContactFeature::wall_end_a : ContactFeature::wall_end_b;
      best.point = end;
      best.normal = normalized(position_at(ball, *t) - end);
    }
  }
  return best;
}

}  // namespace collide2d
