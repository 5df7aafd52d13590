// Ball–ball time of impact: hand-derived answers for every degree.
#include <catch2/catch.hpp>

#include <cmath>

#include "collide2d/toi/analytic.hpp"
#include "lab/reference.hpp"

using namespace collide2d;

namespace {
BallState<double> ball(double x, double y, double vx, double vy, double r, double ax = 0, double ay = 0) {
  return {{x, y}, {vx, vy}, {ax, ay}, r};
}
BallState<double> fixed_ball(double x, double y, double r) { return ball(x, y, 0, 0, r); }
// Within k units in the last place of the expected value.
bool ulps_close(double got, double want, double k = 4) {
  return std::fabs(got - want) <= k * std::numeric_limits<double>::epsilon() * std::fabs(want);
}
}  // namespace

TEST_CASE("ball-ball linear: head-on against a fixed ball", "[toi][ball_ball]") {
  // Centres 3 apart, contact distance 1, speed 1: t = 2.
  const auto r = time_of_impact_ball_ball(ball(0, 0, 1, 0, 0.5), fixed_ball(3, 0, 0.5), 3.0);
  REQUIRE(r.hit());
  CHECK(r.time == 2.0);
  CHECK(r.feature == ContactFeature::ball);
  CHECK(r.normal.x == -1.0);
  CHECK(r.normal.y == 0.0);
  CHECK(r.point.x == 2.5);
}

TEST_CASE("ball-ball linear: two moving balls, oblique", "[toi][ball_ball]") {
  // Closing speed 2 along x, gap 4 − 1 = 3: t = 1.5.
  const auto head_on = time_of_impact_ball_ball(ball(0, 0, 1, 0, 0.5), ball(4, 0, -1, 0, 0.5), 2.0);
  REQUIRE(head_on.hit());
  CHECK(head_on.time == 1.5);
  // Impact parameter 0.6 with R = 1: contact when the x gap is √(1 − 0.36) = 0.8,
  // t = (4 − 0.8) / 2 = 1.6.
  const auto oblique = time_of_impact_ball_ball(ball(0, 0, 1, 0, 0.5), ball(4, 0.6, -1, 0, 0.5), 2.0);
  REQUIRE(oblique.hit());
  CHECK(ulps_close(oblique.time, 1.6));
  CHECK(ulps_close(oblique.normal.x, -0.8));
  CHECK(ulps_close(oblique.normal.y, -0.6));
  // Impact parameter 1.5 > R: a miss.
  CHECK_FALSE(time_of_impact_ball_ball(ball(0, 0, 1, 0, 0.5), ball(4, 1.5, -1, 0, 0.5), 10.0).hit());
}

TEST_CASE("ball-ball: equal accelerations give the linear answer bit for bit", "[toi][ball_ball]") {
  // Both under gravity: the relative motion is linear, no quartic is formed.
  const auto free = time_of_impact_ball_ball(ball(0, 0, 1, 0.3, 0.5), ball(4, 0.6, -1, 0.3, 0.5), 2.0);
  const auto fall = time_of_impact_ball_ball(ball(0, 0, 1, 0.3, 0.5, 0, -9.81), ball(4, 0.6, -1, 0.3, 0.5, 0, -9.81), 2.0);
  REQUIRE(free.hit());
  REQUIRE(fall.hit());
  CHECK(free.time == fall.time);
}

TEST_CASE("ball-ball quartic: falling onto a fixed ball", "[toi][ball_ball]") {
  // From 5 above, contact distance 1: fall 4 = ½ 10 t², t = √0.8.
  const auto r = time_of_impact_ball_ball(ball(0, 5, 0, 0, 0.5, 0, -10), fixed_ball(0, 0, 0.5), 5.0);
  REQUIRE(r.hit());
  CHECK(ulps_close(r.time, std::sqrt(0.8)));
  CHECK(ulps_close(r.normal.y, 1.0));
}

TEST_CASE("ball-ball quartic: two balls with different accelerations", "[toi][ball_ball]") {
  // Δp = −10, Δa = 2 along x, R = 2: |−10 + t²| = 2 first at t² = 8.
  const auto r = time_of_impact_ball_ball(ball(0, 0, 0, 0, 1, 1, 0), ball(10, 0, 0, 0, 1, -1, 0), 5.0);
  REQUIRE(r.hit());
  CHECK(ulps_close(r.time, std::sqrt(8.0)));
}

TEST_CASE("ball-ball quartic: the first of several contacts", "[toi][ball_ball]") {
  // A ball thrown past a fixed ball, up and back: x(t) = −3 + 2t, y(t) = 4t − 2t².
  // Its path crosses the fixed ball at (0, 0) twice; the first contact is
  // when |(x, y)| = 1, which a scan of the exact motion pins to 1e-12.
  const auto r = time_of_impact_ball_ball(ball(-3, 0, 2, 4, 0.5, 0, -4), fixed_ball(0, 0, 0.5), 3.0);
  REQUIRE(r.hit());
  auto dist = [](double t) { return std::hypot(-3 + 2 * t, 4 * t - 2 * t * t); };
  CHECK(std::fabs(dist(r.time) - 1.0) < 1e-14);
  for (double t = 0; t < r.time - 1e-9; t += 1e-4) REQUIRE(dist(t) > 1.0);
}

TEST_CASE("ball-ball: only contacts, never separations", "[toi][ball_ball]") {
  // Touching at t = 0 and moving apart: no contact.
  CHECK_FALSE(time_of_impact_ball_ball(ball(0, 1, 0, 1, 0.5), fixed_ball(0, 0, 0.5), 5.0).hit());
  // Touching and approaching: contact now.
  const auto now = time_of_impact_ball_ball(ball(0, 1, 0, -1, 0.5), fixed_ball(0, 0, 0.5), 5.0);
  REQUIRE(now.hit());
  CHECK(now.time == 0.0);
  // Touching, moving up at 1 under gravity 10: it comes back at t = 0.2 (quartic).
  const auto back = time_of_impact_ball_ball(ball(0, 1, 0, 1, 0.5, 0, -10), fixed_ball(0, 0, 0.5), 5.0);
  REQUIRE(back.hit());
  CHECK(back.time == Approx(0.2).epsilon(1e-12));
}

TEST_CASE("ball-ball: the horizon bounds the search", "[toi][ball_ball]") {
  CHECK_FALSE(time_of_impact_ball_ball(ball(0, 0, 1, 0, 0.5), fixed_ball(3, 0, 0.5), 1.999).hit());
  const auto at_horizon = time_of_impact_ball_ball(ball(0, 0, 1, 0, 0.5), fixed_ball(3, 0, 0.5), 2.0);
  REQUIRE(at_horizon.hit());
  CHECK(at_horizon.time == 2.0);
}

TEST_CASE("ball-ball: the same answer in the reference type", "[toi][ball_ball][reference]") {
  using R = Reference;
  const BallState<R> a{{R(0), R(5)}, {R(0), R(0)}, {R(0), R(-10)}, R(0.5)};
  const BallState<R> b{{R(0), R(0)}, {R(0), R(0)}, {R(0), R(0)}, R(0.5)};
  const auto r = time_of_impact_ball_ball(a, b, R(5));
  REQUIRE(r.hit());
  CHECK(abs(r.time - sqrt(R(8) / R(10))) < R(1e-50));
}
