// Ball–wall time of impact: faces (quadratic), round ends (quadratic or
// quartic), hand-derived answers.
#include <catch2/catch.hpp>

#include <cmath>

#include "collide2d/toi/analytic.hpp"

using namespace collide2d;

namespace {
BallState<double> ball(double x, double y, double vx, double vy, double r, double ax = 0, double ay = 0) {
  return {{x, y}, {vx, vy}, {ax, ay}, r};
}
Segment<double> wall(double ax, double ay, double bx, double by) { return {{ax, ay}, {bx, by}}; }
bool ulps_close(double got, double want, double k = 4) {
  return std::fabs(got - want) <= k * std::numeric_limits<double>::epsilon() * std::fabs(want);
}
}  // namespace

TEST_CASE("ball-wall face, no gravity: both sides", "[toi][ball_wall]") {
  const auto floor = wall(-5, 0, 5, 0);
  const auto from_above = time_of_impact_ball_wall(ball(0, 2, 0, -1, 0.5), floor, 2.0);
  REQUIRE(from_above.hit());
  CHECK(from_above.time == 1.5);
  CHECK(from_above.feature == ContactFeature::wall_face);
  CHECK(from_above.normal.x == 0.0);
  CHECK(from_above.normal.y == 1.0);
  CHECK(from_above.point.y == 0.0);
  const auto from_below = time_of_impact_ball_wall(ball(0, -2, 0, 1, 0.5), floor, 2.0);
  REQUIRE(from_below.hit());
  CHECK(from_below.time == 1.5);
  CHECK(from_below.normal.y == -1.0);
}

TEST_CASE("ball-wall face under gravity", "[toi][ball_wall]") {
  // Fall 4 = ½ 10 t².
  const auto r = time_of_impact_ball_wall(ball(0, 5, 0, 0, 1, 0, -10), wall(-5, 0, 5, 0), 2.0);
  REQUIRE(r.hit());
  CHECK(ulps_close(r.time, std::sqrt(0.8)));
}

TEST_CASE("ball-wall face of an oblique wall", "[toi][ball_wall]") {
  // The line y = x; the centre (t, 2) is |t − 2| / √2 from it: contact with
  // r = √2 / 2 when t = 1.
  const double r = std::sqrt(2.0) / 2;
  const auto hit = time_of_impact_ball_wall(ball(0, 2, 1, 0, r), wall(0, 0, 4, 4), 2.0);
  REQUIRE(hit.hit());
  CHECK(ulps_close(hit.time, 1.0));
  CHECK(ulps_close(hit.normal.x, -r));
  CHECK(ulps_close(hit.normal.y, r));
}

TEST_CASE("ball-wall round end, linear and quartic", "[toi][ball_wall]") {
  // Along the wall's line towards its end b = (0, 0): gap 2 − 0.5 at speed 1.
  const auto linear = time_of_impact_ball_wall(ball(2, 0, -1, 0, 0.5), wall(-5, 0, 0, 0), 3.0);
  REQUIRE(linear.hit());
  CHECK(linear.time == 1.5);
  CHECK(linear.feature == ContactFeature::wall_end_b);
  CHECK(linear.normal.x == 1.0);
  // Falling past the end a = (0, 0) of a wall spanning x in [−5, 0], 0.5 to
  // its right: contact with the end when y = √(1 − 0.25), after a fall of
  // 5 − √0.75 = ½ 10 t².
  const auto quartic = time_of_impact_ball_wall(ball(0.5, 5, 0, 0, 1, 0, -10), wall(0, 0, -5, 0), 2.0);
  REQUIRE(quartic.hit());
  CHECK(quartic.feature == ContactFeature::wall_end_a);
  CHECK(ulps_close(quartic.time, std::sqrt((5 - std::sqrt(0.75)) / 5), 8));
  CHECK(ulps_close(quartic.normal.x, 0.5, 16));
  // Falling 1.5 beyond the end: never touches.
  CHECK_FALSE(time_of_impact_ball_wall(ball(1.5, 5, 0, 0, 1, 0, -10), wall(0, 0, -5, 0), 2.0).hit());
}

TEST_CASE("ball-wall: a ball thrown past the end lands on the far face", "[toi][ball_wall]") {
  // x = 1 − t, y = −1 + 10t − 5t², r = 0.1, wall on x in [−5, 0]. The ball
  // rises beside the wall's end, clear of it, and lands on the top face when
  // y = 0.1: 5t² − 10t + 1.1 = 0, the later root t = 1 + √78 / 10.
  const auto r = time_of_impact_ball_wall(ball(1, -1, -1, 10, 0.1, 0, -10), wall(-5, 0, 0, 0), 3.0);
  REQUIRE(r.hit());
  CHECK(r.feature == ContactFeature::wall_face);
  CHECK(ulps_close(r.time, 1 + std::sqrt(78.0) / 10));
  CHECK(r.normal.y == 1.0);
}

TEST_CASE("ball-wall: starting in the band beside an end, the end comes first", "[toi][ball_wall]") {
  // 0.3 below the line of a wall on x in [−5, 0], 0.55 beyond its end, r = 0.5:
  // within r of the line but not of the wall. Thrown up and back over the
  // wall, it clips the end (0, 0) at once; its later landing on the top face
  // (t ≈ 0.656) must not hide that.
  const auto r = time_of_impact_ball_wall(ball(0.55, -0.3, -1, 4.5, 0.5, 0, -10), wall(-5, 0, 0, 0), 2.0);
  REQUIRE(r.hit());
  CHECK(r.feature == ContactFeature::wall_end_b);
  CHECK(r.time < 0.1);
  const double x = 0.55 - r.time, y = -0.3 + 4.5 * r.time - 5 * r.time * r.time;
  CHECK(std::hypot(x, y) == Approx(0.5).epsilon(1e-14));
}

TEST_CASE("ball-wall: only contacts, never separations", "[toi][ball_wall]") {
  const auto floor = wall(-5, 0, 5, 0);
  // Touching the floor and leaving it.
  CHECK_FALSE(time_of_impact_ball_wall(ball(0, 0.5, 0, 1, 0.5), floor, 5.0).hit());
  // Touching and moving into it: contact now.
  const auto now = time_of_impact_ball_wall(ball(0, 0.5, 0, -1, 0.5), floor, 5.0);
  REQUIRE(now.hit());
  CHECK(now.time == 0.0);
  // Leaving at 1 under gravity 10: back at t = 0.2.
  const auto back = time_of_impact_ball_wall(ball(0, 0.5, 0, 1, 0.5, 0, -10), floor, 5.0);
  REQUIRE(back.hit());
  CHECK(back.time == Approx(0.2).epsilon(1e-15));
  // Sliding along at constant height, clear of the floor: nothing.
  CHECK_FALSE(time_of_impact_ball_wall(ball(-4, 0.6, 1, 0, 0.5), floor, 20.0).hit());
}
