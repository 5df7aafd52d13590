// The screen that spares the exact contact search of pairs which cannot meet
// (certainly_out_of_reach, point_contact.hpp): it may keep a pair that never
// meets, never clear one that does. Fixed point runs it in doubles on its
// data converted by screen_double, which these tests check too.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "collide2d/numeric/number_traits.hpp"
#include "collide2d/toi/point_contact.hpp"

using namespace collide2d;

namespace {

// A relative motion built to touch: at t* in (0, T] the offset is
// (R + gap) n for a unit n, the offset at 0 taken back along the parabola.
// gap = 0 touches; a gap below the screen's 2^-40 of the lengths is a graze
// the screen cannot tell from a touch and must keep too.
template <class Num>
RelativeMotion<Num> built_to_touch(std::mt19937_64& rng, double scale, double gap_ratio, double& horizon) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.05, 1.0);
  const double R = scale * pos(rng), T = pos(rng) * 4, t_star = T * pos(rng);
  const double angle = 3.14159265358979 * u(rng);
  const double nx = std::cos(angle), ny = std::sin(angle);  // test data only: the core uses no libm
  const double vx = scale * 3 * u(rng), vy = scale * 3 * u(rng);
  const bool linear = u(rng) < -0.5;  // a quarter with no relative acceleration
  const double ax = linear ? 0.0 : scale * 10 * u(rng), ay = linear ? 0.0 : scale * 10 * u(rng);
  const double qx = (R * (1 + gap_ratio)) * nx, qy = (R * (1 + gap_ratio)) * ny;
  const double px = qx - vx * t_star - 0.5 * ax * t_star * t_star, py = qy - vy * t_star - 0.5 * ay * t_star * t_star;
  horizon = T;
  const auto n = [](double x) { return num<Num>(x); };
  return {{{n(px), n(py)}, {}}, {n(vx), n(vy)}, {n(ax), n(ay)}, n(R)};
}

template <class Num>
void check_never_clears_a_touch() {
  std::mt19937_64 rng(20261129);
  for (double scale : {1e-4, 1e-2, 1.0, 100.0}) {
    for (double gap_ratio : {0.0, 0x1p-46, -0x1p-46, -1e-3}) {
      for (int trial = 0; trial < 500; ++trial) {
        double T = 0;
        const RelativeMotion<Num> m = built_to_touch<Num>(rng, scale, gap_ratio, T);
        INFO("scale " << scale << ", gap " << gap_ratio << ", trial " << trial);
        REQUIRE_FALSE(certainly_out_of_reach(m, num<Num>(T)));
      }
    }
  }
}

template <class Num>
void check_clears_pairs_far_apart() {
  // Ten radii apart and moving apart, no relative acceleration: the box of
  // the path stays 9 R away. And far apart under acceleration: the path is
  // within 1 + 0.5 of its start over T = 1, which is 10 R + 2 away.
  const auto n = [](double x) { return num<Num>(x); };
  const RelativeMotion<Num> apart{{{n(10), n(0)}, {}}, {n(1), n(0)}, {n(0), n(0)}, n(1)};
  CHECK(certainly_out_of_reach(apart, n(5)));
  const RelativeMotion<Num> falling{{{n(-12), n(3)}, {}}, {n(-1), n(0)}, {n(0), n(-1)}, n(1)};
  CHECK(certainly_out_of_reach(falling, n(1)));
  // Heading straight in (x = 10 - 4 t - t²/2 reaches 1 by t = 2): kept.
  const RelativeMotion<Num> closing{{{n(10), n(0)}, {}}, {n(-4), n(0)}, {n(-1), n(0)}, n(1)};
  CHECK_FALSE(certainly_out_of_reach(closing, n(5)));
}

}  // namespace

TEST_CASE("reach screen: never clears a pair that touches or grazes, in doubles", "[toi][screen]") {
  check_never_clears_a_touch<double>();
  check_clears_pairs_far_apart<double>();
}

TEST_CASE("reach screen: never clears a pair that touches or grazes, fixed point screened in doubles", "[toi][screen]") {
  STATIC_REQUIRE(screens_in_double<Fixed>);
  STATIC_REQUIRE_FALSE(screens_in_double<double>);
  check_never_clears_a_touch<Fixed>();
  check_clears_pairs_far_apart<Fixed>();
}

TEST_CASE("reach screen: a Fixed converts for the screen within 3 * 2^-53 of itself", "[toi][screen][fixed]") {
  // Against to_double, the nearest double (within 2^-53 of the value): the
  // two differ by at most 2^-51 of it. Raw values over the whole range,
  // with signs, across the integer and fraction words.
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20000; ++trial) {
    const int bits = 1 + static_cast<int>(rng() % 126);
    const fixed_detail::UInt128 mag =
        ((fixed_detail::UInt128{rng()} << 64) | rng()) >> (128 - bits);
    const auto raw = static_cast<Fixed::Raw>(rng() % 2 ? mag : fixed_detail::UInt128{0} - mag);
    const Fixed x = Fixed::from_raw(raw);
    const double nearest = x.to_double(), screened = NumberTraits<Fixed>::screen_double(x);
    INFO("raw bits " << bits << ", value " << nearest);
    CHECK(std::fabs(screened - nearest) <= 0x1p-51 * std::fabs(nearest));
    CHECK(std::signbit(screened) == std::signbit(nearest));
  }
  CHECK(NumberTraits<Fixed>::screen_double(Fixed{}) == 0.0);
}
