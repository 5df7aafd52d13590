// The contact root of a quadratic: hand-derived answers, and Kahan's test.
#include <catch2/catch.hpp>

#include "collide2d/toi/quadratic.hpp"

using namespace collide2d;

namespace {
RootSearch<double> down(double A, double b, double C, double H = 10) {
  return first_downward_root(A, b, C, [&] { return compensated_discriminant(A, b, C); }, H);
}
}  // namespace

TEST_CASE("quadratic: opening upwards, the contact is the smaller root", "[toi][quadratic]") {
  // (t − 1)(t − 3) = t² − 4t + 3: falls through zero at 1, rises at 3.
  const auto r = down(1, -2, 3);
  REQUIRE(r.found);
  CHECK(r.t == 1.0);
}

TEST_CASE("quadratic: opening downwards, the contact is the larger root", "[toi][quadratic]") {
  // −(t − 1)(t + 3) = −t² − 2t + 3: positive at 0, falls through zero at 1.
  const auto r = down(-1, -1, 3);
  REQUIRE(r.found);
  CHECK(r.t == 1.0);
  // A ball thrown up from contact, pulled back: w = −5t² + t, b = ½: return at 0.2.
  const auto back = down(-5, 0.5, 0);
  REQUIRE(back.found);
  CHECK(back.t == Approx(0.2).epsilon(1e-15));
}

TEST_CASE("quadratic: linear and rootless cases", "[toi][quadratic]") {
  const auto linear = down(0, -1, 2);  // 2 − 2t
  REQUIRE(linear.found);
  CHECK(linear.t == 1.0);
  CHECK_FALSE(down(0, 1, 2).found);   // 2 + 2t never reaches zero
  CHECK_FALSE(down(1, 0, 1).found);   // t² + 1
  CHECK_FALSE(down(1, 2, 3).found);   // roots −1 and −3: both in the past
  CHECK_FALSE(down(1, -2, 3, 0.5).found);  // root 1 lies beyond the horizon 0.5
  CHECK(down(1, -2, 3, 1.0).found);        // ... and exactly on the horizon 1 counts
}

TEST_CASE("quadratic: never a separation", "[toi][quadratic]") {
  // w = t² − 1: already inside at t = 0, leaving at t = 1. No contact.
  CHECK_FALSE(down(1, 0, -1).found);
}

TEST_CASE("quadratic: Kahan's near-double root needs the compensated discriminant", "[toi][quadratic]") {
  // a x² − 2 b x + c with (a, b, c) = (94906265.625, 94906267, 94906268.375):
  // b² − ac = 1.890625 exactly, so the roots are (b ∓ 1.375) / a = 1 and
  // 94906268.375 / 94906265.625. In doubles b*b − a*c is 0 (or garbage).
  const double a = 94906265.625, b = 94906267, c = 94906268.375;
  volatile double vb = b, va = a, vc = c;
  const double naive = vb * vb - va * vc;
  CHECK(naive != 1.890625);
  CHECK(compensated_discriminant(a, -b, c) == 1.890625);
  const auto r = down(a, -b, c);
  REQUIRE(r.found);
  CHECK(r.t == 1.0);
}
