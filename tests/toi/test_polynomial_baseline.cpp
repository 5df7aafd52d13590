// The general-purpose polynomial-solver baseline (lab/polynomial_baseline.hpp):
// closed-form answers, and agreement with the analytic method on random
// well-conditioned queries.
#include <catch2/catch.hpp>

#include <cmath>

#include "collide2d/toi/analytic.hpp"
#include "lab/oracle.hpp"
#include "lab/polynomial_baseline.hpp"
#include "lab/random_queries.hpp"

using namespace collide2d;

namespace {
BallState<double> ball(double x, double y, double vx, double vy, double r, double ax = 0, double ay = 0) {
  return {{x, y}, {vx, vy}, {ax, ay}, r};
}
Segment<double> wall(double ax, double ay, double bx, double by) { return {{ax, ay}, {bx, by}}; }
// Simple, well-separated roots of O(1) polynomials: the companion matrix
// gives them to a few ulp; 1e-12 relative leaves a wide margin.
constexpr double textbook_rel = 1e-12;
}  // namespace

TEST_CASE("polynomial baseline: ball-ball head-on at constant speed", "[toi][polynomial]") {
  // Gap 5 − 2t between centres, contact distance 0.5 + 0.75: t = 3.75 / 2.
  const auto r = polynomial_solver_ball_ball(ball(0, 0, 2, 0, 0.5), ball(5, 0, 0, 0, 0.75), 3.0);
  REQUIRE(r.hit());
  CHECK(r.time == Approx(1.875).epsilon(textbook_rel));
  CHECK(r.feature == ContactFeature::ball);
  CHECK(r.normal.x == Approx(-1.0).epsilon(textbook_rel));
  CHECK(std::fabs(r.normal.y) < 1e-12);
  CHECK(r.point.x == Approx(4.25).epsilon(textbook_rel));
  // Both moving, closing at 4: 10 − 4t = 2, t = 2.
  const auto both = polynomial_solver_ball_ball(ball(0, 1, 1, 0, 1), ball(10, 1, -3, 0, 1), 5.0);
  REQUIRE(both.hit());
  CHECK(both.time == Approx(2.0).epsilon(textbook_rel));
  // Same gravity on both: Δa = 0, still the quadratic.
  const auto falling = polynomial_solver_ball_ball(ball(0, 1, 1, 0, 1, 0, -9.81), ball(10, 1, -3, 0, 1, 0, -9.81), 5.0);
  REQUIRE(falling.hit());
  CHECK(falling.time == Approx(2.0).epsilon(textbook_rel));
  // Moving apart, or not moving at all: no contact.
  CHECK_FALSE(polynomial_solver_ball_ball(ball(0, 0, -2, 0, 0.5), ball(5, 0, 0, 0, 0.75), 3.0).hit());
  CHECK_FALSE(polynomial_solver_ball_ball(ball(0, 0, 0, 0, 0.5), ball(5, 0, 0, 0, 0.75), 3.0).hit());
  // Out of the horizon.
  CHECK_FALSE(polynomial_solver_ball_ball(ball(0, 0, 2, 0, 0.5), ball(5, 0, 0, 0, 0.75), 1.8).hit());
}

TEST_CASE("polynomial baseline: ball-ball quartic under gravity", "[toi][polynomial]") {
  // Falling onto a fixed ball 0.6 to the side, R = 1: contact when the height
  // is 0.8, 5 − 5t² = 0.8, t = √0.84 (the quartic 25t⁴ − 50t² + 24.36).
  const auto r = polynomial_solver_ball_ball(ball(0.6, 5, 0, 0, 0.5, 0, -10), ball(0, 0, 0, 0, 0.5), 2.0);
  REQUIRE(r.hit());
  CHECK(r.time == Approx(std::sqrt(0.84)).epsilon(textbook_rel));
  CHECK(r.normal.x == Approx(0.6).epsilon(textbook_rel));
  CHECK(r.normal.y == Approx(0.8).epsilon(textbook_rel));
}

TEST_CASE("polynomial baseline: ball falling onto a horizontal wall", "[toi][polynomial]") {
  // Thrown up at v0 from height h under gravity g: h + v0 t − ½ g t² = r,
  // t = (v0 + √(v0² + 2 g (h − r))) / g (the positive root).
  const double h = 5, v0 = 3, g = 9.81, radius = 1;
  const double want = (v0 + std::sqrt(v0 * v0 + 2 * g * (h - radius))) / g;
  const auto r = polynomial_solver_ball_wall(ball(0, h, 0, v0, radius, 0, -g), wall(-10, 0, 10, 0), 3.0);
  REQUIRE(r.hit());
  CHECK(r.time == Approx(want).epsilon(textbook_rel));
  CHECK(r.feature == ContactFeature::wall_face);
  CHECK(r.normal.x == 0.0);
  CHECK(r.normal.y == 1.0);
  CHECK(std::fabs(r.point.y) < 1e-12);
  // Dropped from rest: ½ g t² = h − r.
  const auto drop = polynomial_solver_ball_wall(ball(0, h, 0, 0, radius, 0, -g), wall(-10, 0, 10, 0), 3.0);
  REQUIRE(drop.hit());
  CHECK(drop.time == Approx(std::sqrt(2 * (h - radius) / g)).epsilon(textbook_rel));
}

TEST_CASE("polynomial baseline: wall faces from both sides and oblique", "[toi][polynomial]") {
  // From below: −3 + 2t = −0.5, t = 1.25; the normal points down, to the ball.
  const auto below = polynomial_solver_ball_wall(ball(1, -3, 0, 2, 0.5), wall(-5, 0, 5, 0), 2.0);
  REQUIRE(below.hit());
  CHECK(below.time == Approx(1.25).epsilon(textbook_rel));
  CHECK(below.feature == ContactFeature::wall_face);
  CHECK(below.normal.y == -1.0);
  // The line y = x; the centre (t, 2) is |t − 2| / √2 from it: r = √2 / 2 at t = 1.
  const double r = std::sqrt(2.0) / 2;
  const auto oblique = polynomial_solver_ball_wall(ball(0, 2, 1, 0, r), wall(0, 0, 4, 4), 2.0);
  REQUIRE(oblique.hit());
  CHECK(oblique.time == Approx(1.0).epsilon(textbook_rel));
  CHECK(oblique.normal.x == Approx(-r).epsilon(textbook_rel));
  CHECK(oblique.normal.y == Approx(r).epsilon(textbook_rel));
  // Parallel to the wall, or at rest: no contact.
  CHECK_FALSE(polynomial_solver_ball_wall(ball(0, 2, 1, 0, 0.5), wall(-5, 0, 5, 0), 2.0).hit());
  CHECK_FALSE(polynomial_solver_ball_wall(ball(0, 2, 0, 0, 0.5), wall(-5, 0, 5, 0), 2.0).hit());
}

TEST_CASE("polynomial baseline: round wall ends", "[toi][polynomial]") {
  // Sliding 0.6 above the wall's line towards its end B = (0, 0): |(3 − t, 0.6)| = 1
  // when 3 − t = 0.8, t = 2.2; the normal is (0.8, 0.6).
  const auto slide = polynomial_solver_ball_wall(ball(3, 0.6, -1, 0, 1), wall(-5, 0, 0, 0), 3.0);
  REQUIRE(slide.hit());
  CHECK(slide.time == Approx(2.2).epsilon(textbook_rel));
  CHECK(slide.feature == ContactFeature::wall_end_b);
  CHECK(slide.point.x == 0.0);
  CHECK(slide.normal.x == Approx(0.8).epsilon(textbook_rel));
  CHECK(slide.normal.y == Approx(0.6).epsilon(textbook_rel));
  // Falling past end A = (0, 0), 0.6 beside it: as the ball-ball quartic, t = √0.84.
  const auto fall = polynomial_solver_ball_wall(ball(-0.6, 5, 0, 0, 1, 0, -10), wall(0, 0, 5, 0), 2.0);
  REQUIRE(fall.hit());
  CHECK(fall.time == Approx(std::sqrt(0.84)).epsilon(textbook_rel));
  CHECK(fall.feature == ContactFeature::wall_end_a);
  // Falling 1.2 beside the end: clear of it.
  CHECK_FALSE(polynomial_solver_ball_wall(ball(-1.2, 5, 0, 0, 1, 0, -10), wall(0, 0, 5, 0), 2.0).hit());
}

// Agreement with the analytic method on 4 × 500 random queries.
//
// Time tolerance 1e-6 · horizon. The eigenvalues of the (balanced) companion
// matrix are backward stable, and so, roughly, are the roots (Edelman and
// Murakami, Math. Comp. 1995): the computed roots are the exact roots of a
// polynomial whose coefficients are perturbed by a modest multiple of ε |c|,
// so a simple root moves by about ε Σ|c_k| |t|^k / |g'(t)|. Here |Δp| < 15,
// |Δv| < 17, |Δa| ≈ 10, H = 1, so Σ|c_k| |t|^k ≲ 2e3; and at contact
// g'(t) = 2 q·q' is 2 R times the normal closing speed v_n. So
// δt ≲ 2e-13 / (R v_n): below 1e-6 unless v_n < ~5e-6 (R ≥ 0.05), that is
// unless the contact is a near-graze. The analytic method's own error is far
// smaller. A tolerance this loose still catches every real failure (a wrong
// root, a missed root, a separation taken for a contact), which are off by
// O(0.01 .. 1).
//
// Near-grazing queries, where a tangency splits into a complex pair (see the
// header), may legitimately differ on hit/miss or time. A disagreement is
// excluded only when the oracle (oracle.hpp) finds the minimum gap over [0, H]
// within 1e-6 · scale of zero; any other disagreement fails. The oracle is
// asked only about disagreements (it costs milliseconds per query).
TEST_CASE("polynomial baseline agrees with the analytic method on random queries", "[toi][polynomial]") {
  SplitMix64 rng(0x5eed2d0011ULL);
  int hits = 0, near_grazing_excluded = 0;
  for (const QueryFamily family : all_query_families()) {
    for (int i = 0; i < 500; ++i) {
      const ToiQuery q = random_query(family, rng);
      const bool wall_query = q.kind == QueryKind::ball_wall;
      const ToiResult<double> analytic = wall_query ? time_of_impact_ball_wall(q.ball, q.wall, q.horizon)
                                                    : time_of_impact_ball_ball(q.ball, q.other, q.horizon);
      const ToiResult<double> baseline = wall_query ? polynomial_solver_ball_wall(q.ball, q.wall, q.horizon)
                                                    : polynomial_solver_ball_ball(q.ball, q.other, q.horizon);
      const double tolerance = 1e-6 * q.horizon;
      const bool agree = analytic.hit() == baseline.hit() &&
                         (!analytic.hit() || std::fabs(analytic.time - baseline.time) <= tolerance);
      if (!agree) {
        const OracleAnswer o = oracle_time_of_impact(q);
        if (std::fabs(o.min_gap) <= 1e-6 * o.scale) {
          ++near_grazing_excluded;
          continue;
        }
      }
      INFO(to_string(family) << " #" << i << ": " << describe(q));
      INFO("analytic: hit=" << analytic.hit() << " t=" << analytic.time << "; baseline: hit=" << baseline.hit()
                            << " t=" << baseline.time);
      REQUIRE(analytic.hit() == baseline.hit());
      if (analytic.hit()) {
        ++hits;
        CHECK(std::fabs(analytic.time - baseline.time) <= tolerance);
      }
    }
  }
  // Not a vacuous comparison: about a quarter of these queries hit (498 of
  // 2000 with this seed).
  CHECK(hits > 400);
  // Only "a few" may be set aside as grazing (none with this seed; in 80 000
  // queries of other seeds the two methods never disagreed on hit/miss and
  // their times differed by at most 1e-13).
  CHECK(near_grazing_excluded <= 5);
}
