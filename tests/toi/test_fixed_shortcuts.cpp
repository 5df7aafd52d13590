// Fixed point's shortcuts in the contact search (point_contact.hpp): each
// skips work whose result was never used, so each must give what the full
// computation gives.
//  - unit_scale_exponent stops at a length of at least 1 (|Δp| or R): k = 0
//    there whatever the motion. Held against the whole rule, restated here.
//  - first_contact_linear answers a receding pair (Δp·Δv ≥ 0) before it
//    forms C and the discriminant: no contact, touching at t = 0 or not.
//    Held on motions built to meet (the true gap at the answer within the
//    bound of properties/fixed_toi_bound.hpp) or to recede (none), and on
//    pairs touching at t = 0.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "collide2d/numeric/number_traits.hpp"
#include "collide2d/toi/analytic.hpp"
#include "collide2d/toi/point_contact.hpp"
#include "collide2d/toi/query.hpp"
#include "fixed_toi_bound.hpp"

using namespace collide2d;

namespace {

using T = NumberTraits<Fixed>;

// The scaling rule as point_contact.hpp states it, every term formed: the
// largest length over the horizon (|Δp|, R, |Δv| H, |Δa| H²) brought to 2^0,
// within the limits that keep the solver's squares in range.
int full_scale_rule(const RelativeMotion<Fixed>& m, const Fixed& horizon) {
  const int e_v = std::max(T::exponent(m.velocity.x), T::exponent(m.velocity.y));
  const int e_a = std::max(T::exponent(m.acceleration.x), T::exponent(m.acceleration.y));
  const int e_h = T::exponent(horizon);
  const int largest = std::max({T::exponent(m.offset.hi.x), T::exponent(m.offset.hi.y), T::exponent(m.radius),
                                e_v + e_h + 1, e_a + 2 * e_h + 2});
  return std::max(0, std::min({-largest, 28 - e_v, 28 - e_a, (24 - e_v - e_a) / 2, 60}));
}

Fixed fx(double x) { return Fixed::from_double(x); }

}  // namespace

TEST_CASE("fixed point: the scaling stops early only where the whole rule gives 0", "[toi][fixed][scaling]") {
  std::mt19937_64 rng(20261201);
  std::uniform_real_distribution<double> u(-1.0, 1.0), mantissa(0.5, 1.0);
  std::uniform_int_distribution<int> octave(-30, 8);
  int scaled = 0, long_enough = 0;
  for (int k = 0; k < 200000; ++k) {
    // Each length at its own scale, 2^-30 to 2^8, so that every term of the
    // rule is sometimes the largest; a fifth without acceleration (a gas).
    auto length = [&] { return std::ldexp(mantissa(rng), octave(rng)) * (u(rng) < 0 ? -1 : 1); };
    const bool linear = u(rng) < -0.6;
    const RelativeMotion<Fixed> m{{{fx(length()), fx(length())}, {}},
                                  {fx(length()), fx(length())},
                                  {linear ? Fixed{} : fx(length()), linear ? Fixed{} : fx(length())},
                                  fx(std::fabs(length()))};
    const Fixed horizon = fx(std::ldexp(mantissa(rng), octave(rng) / 3));
    const int expected = full_scale_rule(m, horizon);
    INFO("case " << k);
    REQUIRE(unit_scale_exponent(m, horizon) == expected);
    scaled += expected > 0;
    long_enough += std::max({T::exponent(m.offset.hi.x), T::exponent(m.offset.hi.y), T::exponent(m.radius)}) >= 0;
  }
  // Both branches were exercised, many times.
  CHECK(scaled > 10000);
  CHECK(long_enough > 10000);
}

TEST_CASE("fixed point: a receding pair is no contact; a closing one meets within the format's bound",
          "[toi][fixed][linear]") {
  std::mt19937_64 rng(20261202);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.1, 1.0);
  int met = 0, receded = 0;
  for (double scale : {1e-3, 1.0, 30.0}) {
    for (int k = 0; k < 20000; ++k) {
      // Ball 1 moves along a line passing at most 0.9 R from ball 2 (at
      // rest at the origin), starting 1.5 to 5 R behind it: closing, it
      // meets it; reversed, it recedes, from the first instant on.
      const double R = scale * pos(rng);
      const double angle = 3.14159265358979 * u(rng);
      const double dx = std::cos(angle), dy = std::sin(angle);  // test data only
      const double miss = 0.9 * R * u(rng), back = R * (1.5 + 3.5 * pos(rng));
      const double speed = scale * (0.2 + 2 * pos(rng));
      const double px = -dy * miss - dx * back, py = dx * miss - dy * back;
      const double horizon = 20.0;  // beyond the latest contact, 5 R / (0.4 scale) = 12.5
      for (int direction : {1, -1}) {
        ToiQuery q;
        q.kind = QueryKind::ball_ball;
        q.ball = {{px, py}, {direction * speed * dx, direction * speed * dy}, {}, R / 2};
        q.other = {{0, 0}, {}, {}, R / 2};
        q.horizon = horizon;
        const ToiResult<Fixed> r =
            time_of_impact_ball_ball(convert_ball<Fixed>(q.ball), convert_ball<Fixed>(q.other), fx(horizon));
        INFO("scale " << scale << ", case " << k << ", direction " << direction);
        if (direction < 0) {  // moving away: never within R again
          REQUIRE_FALSE(r.hit());
          ++receded;
          continue;
        }
        REQUIRE(r.hit());
        // The true gap at the reported time, against the bound the format
        // and the method's arithmetic give for this query
        // (properties/fixed_toi_bound.hpp, the time read as a double).
        const long double t = T::to_double(r.time);
        const long double gap = std::hypot(px + q.ball.velocity.x * t, py + q.ball.velocity.y * t) - R;
        REQUIRE(std::fabs(gap) <= properties::fixed_toi_gap_bound(q));
        ++met;
      }
    }
  }
  CHECK(met == 60000);
  CHECK(receded == 60000);
}

TEST_CASE("fixed point: pairs touching at t = 0 meet now only when closing", "[toi][fixed][linear]") {
  // Touching (|Δp| = R exactly) and overlapping by a little, each moving
  // out, along the tangent, or in.
  for (double overlap : {0.0, 1e-9}) {
    const Fixed R = fx(0.5), p = fx(0.5 - overlap);
    auto contact = [&](double vx, double vy) {
      return first_contact(RelativeMotion<Fixed>{{{p, Fixed{}}, {}}, {fx(vx), fx(vy)}, {}, R}, fx(5.0));
    };
    CHECK_FALSE(contact(1.0, 0.0).found);  // moving apart
    CHECK_FALSE(contact(0.0, 1.0).found);  // along the tangent (Δp·Δv = 0): it leaves at once
    const RootSearch<Fixed> now = contact(-1.0, 0.3);
    REQUIRE(now.found);
    CHECK(now.t == Fixed{});
  }
}
