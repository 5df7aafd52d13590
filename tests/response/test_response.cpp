// Collision response: reflection, the two-ball impulse, and the article's
// formula that breaks momentum for unequal masses.
#include <catch2/catch.hpp>

#include <cmath>

#include "collide2d/response/response.hpp"

using namespace collide2d;
using V = Vec2<double>;

TEST_CASE("reflection about a wall normal", "[response]") {
  const V n{0, 1};
  const V elastic = reflect_velocity(V{1, -1}, n, 1.0);
  CHECK(elastic.x == 1.0);
  CHECK(elastic.y == 1.0);
  const V damped = reflect_velocity(V{1, -1}, n, 0.5);
  CHECK(damped.x == 1.0);
  CHECK(damped.y == 0.5);
  // A receding ball is left alone.
  const V away = reflect_velocity(V{1, 2}, n, 0.5);
  CHECK(away.y == 2.0);
}

TEST_CASE("elastic reflection keeps the speed, oblique normal", "[response]") {
  const double s = std::sqrt(0.5);
  const V v{3, -4};
  const V out = reflect_velocity(v, V{s, s}, 1.0);
  CHECK(length(out) == Approx(5.0).epsilon(1e-15));
  // Normal component reversed: (v·n) = −s, so v' = v + 2 s n = (4, −3).
  CHECK(out.x == Approx(4.0).epsilon(1e-15));
  CHECK(out.y == Approx(-3.0).epsilon(1e-15));
}

TEST_CASE("restitution of a contact is the product", "[response]") {
  CHECK(contact_restitution(0.9, 0.5) == 0.45);
}

TEST_CASE("two-ball impulse: textbook answers for unequal masses", "[response]") {
  // Ball 1 (m = 1) at speed 1 hits ball 2 (m = 3) at rest, head on; ball 2
  // lies in +x so the normal from 2 to 1 is −x. Textbook, restitution e:
  //   v1' = (m1 − e m2) / (m1 + m2),  v2' = (1 + e) m1 / (m1 + m2).
  const V n{-1, 0};
  for (double e : {1.0, 0.5, 0.0}) {
    const auto r = two_ball_impulse_response(V{1, 0}, V{0, 0}, 1.0, 3.0, n, e);
    CHECK(r.v1.x == Approx((1 - 3 * e) / 4).margin(1e-15));
    CHECK(r.v2.x == Approx((1 + e) / 4).epsilon(1e-15));
    CHECK(r.v1.y == 0.0);
    // Momentum: 1 · 1 = m1 v1' + m2 v2'.
    CHECK(1.0 * r.v1.x + 3.0 * r.v2.x == Approx(1.0).epsilon(1e-15));
    // Normal closing speed scaled by e.
    CHECK(dot(r.v1 - r.v2, n) == Approx(-e * dot(V{1, 0}, n)).margin(1e-15));
    CHECK(r.impulse == Approx((1 + e) * 0.75).epsilon(1e-15));
  }
}

TEST_CASE("two-ball impulse keeps tangential velocities and ignores receding balls", "[response]") {
  const V n{0, 1};
  const auto r = two_ball_impulse_response(V{2, -1}, V{-3, 1}, 2.0, 5.0, n, 0.8);
  CHECK(r.v1.x == 2.0);
  CHECK(r.v2.x == -3.0);
  const auto apart = two_ball_impulse_response(V{0, 1}, V{0, -1}, 2.0, 5.0, n, 0.8);
  CHECK(apart.v1.y == 1.0);
  CHECK(apart.impulse == 0.0);
}

TEST_CASE("the article's formula agrees for equal masses and breaks momentum otherwise", "[response]") {
  const V n{-1, 0};
  const auto same = article_two_ball_response(V{1, 0}, V{0, 0}, 1.0, 1.0, n, 1.0, 1.0);
  const auto right = two_ball_impulse_response(V{1, 0}, V{0, 0}, 1.0, 1.0, n, 1.0);
  CHECK(same.v1.x == Approx(right.v1.x).margin(1e-15));
  CHECK(same.v2.x == Approx(right.v2.x).margin(1e-15));
  // m1 = 1, m2 = 3, moving ball 2 as well: the article's second ball is wrong.
  const auto wrong = article_two_ball_response(V{1, 0}, V{-1, 0}, 1.0, 3.0, n, 1.0, 1.0);
  const double before = 1.0 * 1 + 3.0 * -1;
  const double after = 1.0 * wrong.v1.x + 3.0 * wrong.v2.x;
  CHECK(std::fabs(after - before) > 1.0);
}
