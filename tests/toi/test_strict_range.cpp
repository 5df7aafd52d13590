// Strict mode's range: the analytic method squares lengths and speeds, and a
// square beyond the double range (about 1e308) becomes inf, then NaN. That is
// reported as StrictOverflow, as fixed point reports FixedPointOverflow, and
// never answered: `collide2d toi` once printed "0,1,-nan" for a relative
// speed of 1e199 (fuzz_toi_query, datasets/fuzz/toi_query/).
#include <catch2/catch.hpp>

#include <cmath>

#include "collide2d/toi/analytic.hpp"

using namespace collide2d;

namespace {
BallState<double> ball(double x, double y, double vx, double vy, double r, double ay = 0) {
  return {{x, y}, {vx, vy}, {0, ay}, r};
}
}  // namespace

TEST_CASE("strict range: a speed whose square overflows is StrictOverflow, never a NaN time", "[toi][strict_range]") {
  // The fuzzer's query: ball b passes far below ball a at 1e199 (no contact).
  const auto a = ball(-1.030657356979394, -3.080791886409533, 0.20746843316988642, 4.918463139343466, 0.41);
  const auto b = ball(-1.811864636727043, 0.7114979494257501, 1e199, 0, 0.52);
  CHECK_THROWS_AS(time_of_impact_ball_ball(a, b, 1.0), StrictOverflow);
  // The same under gravity for one of them: the quartic's cascade.
  CHECK_THROWS_AS(time_of_impact_ball_ball(a, ball(-1.811864636727043, 0.7114979494257501, 1e199, 0, 0.52, -9.81), 1.0),
                  StrictOverflow);
}

TEST_CASE("strict range: balls too far apart to square their distance are still told apart", "[toi][strict_range]") {
  // |Δp|² = 1e600 overflows, but the trajectory box shows no contact is
  // possible within the horizon: a miss, as before, not an error.
  const auto r = time_of_impact_ball_ball(ball(-1e300, 0, 1, 0, 0.5), ball(0, 0, 0, 0, 0.5), 10.0);
  CHECK_FALSE(r.hit());
}

TEST_CASE("strict range: a wall face met at 1e200 needs no square and is answered", "[toi][strict_range]") {
  // S(t) = |d| (2 − 1e200 t) for d = (10, 0); the band of half-width 0.5 is
  // reached at t = 1.5 / 1e200.
  const auto r = time_of_impact_ball_wall(ball(5, 2, 0, -1e200, 0.5), Segment<double>{{0, 0}, {10, 0}}, 1.0);
  REQUIRE(r.hit());
  CHECK(r.feature == ContactFeature::wall_face);
  CHECK(std::fabs(r.time - 1.5e-200) <= 4 * std::numeric_limits<double>::epsilon() * 1.5e-200);
}
