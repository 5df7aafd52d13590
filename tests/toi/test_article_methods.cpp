// The article's methods, faithful: right where they work, blind where the
// article was blind.
#include <catch2/catch.hpp>

#include <cmath>

#include "collide2d/toi/analytic.hpp"
#include "collide2d/toi/article_methods.hpp"

using namespace collide2d;

namespace {
BallState<double> ball(double x, double y, double vx, double vy, double r, double ax = 0, double ay = 0) {
  return {{x, y}, {vx, vy}, {ax, ay}, r};
}
}  // namespace

TEST_CASE("bisection finds a head-on contact to within its tolerance", "[toi][article]") {
  const double eps = 1e-9;
  const auto r = bisection_ball_ball(ball(0, 0, 1, 0, 0.5), ball(3, 0, 0, 0, 0.5), 3.0, eps);
  REQUIRE(r.hit());
  // Gap = distance − 1 = (3 − t) − 1: within ±eps of zero.
  CHECK(std::fabs((3 - r.time) - 1) <= eps);
}

TEST_CASE("bisection misses a graze that ends inside the step", "[toi][article]") {
  // Passing 0.9 from a fixed ball's centre, contact distance 1: the balls
  // overlap for a while in the middle of the step but not at its end.
  const auto a = ball(-2, 0.9, 1, 0, 0.5), b = ball(0, 0, 0, 0, 0.5);
  CHECK(time_of_impact_ball_ball(a, b, 4.0).hit());
  CHECK_FALSE(bisection_ball_ball(a, b, 4.0, 1e-9).hit());
}

TEST_CASE("the article's wall method hits a floor under gravity", "[toi][article]") {
  const Segment<double> floor{{-5, 0}, {5, 0}};
  const auto r = seed_ball_wall(ball(0, 5, 0, 0, 1, 0, -10), floor, 2.0);
  REQUIRE(r.hit());
  CHECK(r.time == Approx(std::sqrt(0.8)).epsilon(1e-14));
}

TEST_CASE("the article's wall method never sees a round end", "[toi][article]") {
  const Segment<double> w{{-5, 0}, {0, 0}};
  const auto b = ball(0.5, 5, 0, 0, 1, 0, -10);
  CHECK(time_of_impact_ball_wall(b, w, 2.0).hit());
  CHECK_FALSE(seed_ball_wall(b, w, 2.0).hit());
}

TEST_CASE("the article's textbook root cancels where the q-form does not", "[toi][article]") {
  // Tiny acceleration along the normal (1e-10), closing speed 1, gap 1:
  // w(t) = 1 − t − 1e-10 t². The textbook (−B − √(B² − 4AC)) / 2A subtracts two
  // nearly equal numbers and keeps only about six digits.
  const Segment<double> floor{{-100, 0}, {100, 0}};
  const auto b = ball(0, 1.5, 0, -1, 0.5, 0, -2e-10);
  const auto exact = time_of_impact_ball_wall(b, floor, 2.0);
  const auto seed = seed_ball_wall(b, floor, 2.0);
  REQUIRE(exact.hit());
  REQUIRE(seed.hit());
  const double truth = 1.0 - 1e-10;  // root of 1 − t − 1e-10 t² is 1 − 1e-10 + 2e-20 − …
  CHECK(std::fabs(exact.time - truth) < 1e-15);
  CHECK(std::fabs(seed.time - truth) > 1e-9);
}
