// Hard cases with a known answer: Kahan's near-double root, contact exactly
// at the horizon, corners, turnaround under a ceiling, contacts that must not
// be confused with separations; and checks that the oracle and the
// acceptance rule (lab/oracle.hpp) are themselves right and have teeth.
#include <catch2/catch.hpp>

#include <cmath>

#include "fixed_toi_bound.hpp"
#include "lab/oracle.hpp"
#include "lab/random_queries.hpp"

using namespace collide2d;

namespace {

using V = Vec2<double>;
V operator*(double s, V a) { return {s * a.x, s * a.y}; }
V unit(double angle) { return {std::cos(angle), std::sin(angle)}; }

ToiQuery wall_query(V a, V b, BallState<double> ball, double horizon) {
  ToiQuery q;
  q.kind = QueryKind::ball_wall;
  q.wall = {a, b};
  q.ball = ball;
  q.horizon = horizon;
  return q;
}
ToiQuery ball_query(BallState<double> ball, BallState<double> other, double horizon) {
  ToiQuery q;
  q.kind = QueryKind::ball_ball;
  q.ball = ball;
  q.other = other;
  q.horizon = horizon;
  return q;
}

// The times below are compared with closed forms evaluated in doubles, whose
// own rounding is of the order of the strict tolerance: within 1e-12 of the
// scale (strict) or 1e-7 (fixed, as the acceptance rule once was).
double rel_tol(NumberMode mode) { return mode == NumberMode::strict ? 1e-12 : 1e-7; }

// The analytic answer in `mode`, judged by the acceptance rule against the
// oracle: 1e-12 of the scale strict, the derived bound fixed
// (properties/fixed_toi_bound.hpp).
QueryAnswer accepted_answer(const ToiQuery& q, NumberMode mode) {
  const QueryAnswer a = answer_toi_query(q, ToiMethod::analytic, mode, 1e-9);
  const double acceptance =
      mode == NumberMode::strict ? 1e-12 : properties::fixed_toi_gap_bound(q) / oracle_detail::scale_of(q);
  const Verdict v = judge_toi_answer(q, a.hit, a.t, acceptance);
  INFO(to_string(mode) << ": " << v.why);
  CHECK(v.ok);
  return a;
}

// A hit at `expected`, to within the time the tolerance allows at `speed`.
void check_hit_at(const ToiQuery& q, NumberMode mode, double expected, double speed) {
  const QueryAnswer a = accepted_answer(q, mode);
  INFO(to_string(mode) << ": " << describe(q) << " expected t = " << expected << ", got hit " << a.hit << " t = " << a.t);
  CHECK(a.hit);
  CHECK(std::fabs(a.t - expected) <= 2 * rel_tol(mode) * oracle_detail::scale_of(q) / speed);
}

constexpr NumberMode both_modes[] = {NumberMode::strict, NumberMode::fixed};

}  // namespace

TEST_CASE("oracle agrees with closed forms", "[toi][hard][oracle]") {
  // Head-on: centres 12 apart, R = 2, speed 5: t = 2, then passes through (min gap −2).
  const OracleAnswer head_on = oracle_time_of_impact(ball_query({{0, 0}, {5, 0}, {}, 1}, {{12, 0}, {}, {}, 1}, 3));
  CHECK(head_on.hit);
  CHECK(head_on.t == 2.0);
  CHECK(head_on.min_gap == -2.0);
  CHECK(head_on.scale == 15.0);
  // Falling onto a floor: y = 5 − t², contact at y = 1.
  const OracleAnswer fall = oracle_time_of_impact(wall_query({-10, 0}, {10, 0}, {{0, 5}, {}, {0, -2}, 1}, 3));
  CHECK(fall.hit);
  CHECK(fall.t == 2.0);
  // Passing the round end (10, 0) at distance 1.25 with r = 1: a miss by 0.25,
  // though the centre's line crosses the wall's line within the radius.
  const OracleAnswer miss = oracle_time_of_impact(wall_query({0, 0}, {10, 0}, {{11.25, -5}, {0, 4}, {}, 1}, 3));
  CHECK_FALSE(miss.hit);
  CHECK(std::fabs(miss.min_gap - 0.25) < 1e-15);
  // Parabola whose apex is 0.5 from a ceiling: y = 4t − t², ceiling at 5, r = 0.5.
  const OracleAnswer apex = oracle_time_of_impact(wall_query({-10, 5}, {10, 5}, {{0, 0}, {0, 4}, {0, -2}, 0.5}, 4));
  CHECK_FALSE(apex.hit);
  CHECK(std::fabs(apex.min_gap - 0.5) < 1e-15);
  // Quartic: falling past a fixed ball, offset 0.6 sideways, R = 1: contact at
  // height 0.8, y = 5 − t², t = √4.2.
  const OracleAnswer quartic = oracle_time_of_impact(ball_query({{0.6, 5}, {}, {0, -2}, 0.5}, {{0, 0}, {}, {}, 0.5}, 5));
  CHECK(quartic.hit);
  CHECK(std::fabs(quartic.t - std::sqrt(4.2)) < 1e-15);
}

TEST_CASE("the acceptance rule rejects wrong answers", "[toi][hard][oracle]") {
  const ToiQuery fall = wall_query({-10, 0}, {10, 0}, {{0, 5}, {}, {0, -2}, 1}, 3);  // contact at t = 2
  CHECK(judge_toi_answer(fall, true, 2.0, 1e-12).ok);
  CHECK_FALSE(judge_toi_answer(fall, false, 0.0, 1e-12).ok);          // missed
  CHECK_FALSE(judge_toi_answer(fall, true, 2.0 + 1e-9, 1e-12).ok);    // late
  CHECK_FALSE(judge_toi_answer(fall, true, 2.0 - 1e-9, 1e-12).ok);    // early
  CHECK_FALSE(judge_toi_answer(fall, true, 2.8, 1e-12).ok);           // the wall's far side
  const ToiQuery miss = wall_query({0, 0}, {10, 0}, {{11.25, -5}, {0, 4}, {}, 1}, 3);
  CHECK(judge_toi_answer(miss, false, 0.0, 1e-12).ok);
  CHECK_FALSE(judge_toi_answer(miss, true, 1.25, 1e-12).ok);          // spurious
  // Touching at t = 0 but leaving, pulled back at t = 6/9.81: t = 0 is a separation.
  const ToiQuery back = wall_query({-10, 0}, {10, 0}, {{0, 1}, {0.5, 3}, {0, -9.81}, 1}, 1);
  CHECK_FALSE(judge_toi_answer(back, true, 0.0, 1e-12).ok);
  CHECK(judge_toi_answer(back, true, 6 / 9.81, 1e-12).ok);
}

TEST_CASE("hard: Kahan's near-double root inside a ball-wall face query", "[toi][hard][oracle]") {
  // Clearance w(t) = s(t) − r = a t² − 2 b t + c with (a, b, c) =
  // (94906265.625, 94906267, 94906268.375): b² − ac = 1.890625 exactly, roots
  // (b ∓ 1.375)/a = 1 and c/a = 1 + 2.9e-8. Wall along y = 0 (length 2048, so
  // s(t) = y(t) exactly), r = 1: y(0) = c + 1, v_y = −2b, a_y = 2a.
  const double a = 94906265.625, b = 94906267, c = 94906268.375;
  const ToiQuery kahan = wall_query({-1024, 0}, {1024, 0}, {{0, c + 1}, {0, -2 * b}, {0, 2 * a}, 1}, 2);
  const OracleAnswer o = oracle_time_of_impact(kahan);
  CHECK(o.hit);
  CHECK(o.t == 1.0);
  CHECK(o.min_gap < 0);
  const QueryAnswer got = accepted_answer(kahan, NumberMode::strict);
  INFO("strict: hit " << got.hit << " t = " << got.t);
  CHECK(got.hit);
  CHECK(std::fabs(got.t - 1.0) <= 1e-12);
  // c + 0.125: the discriminant is −1.2e7 and the minimum clearance +0.125: no contact.
  const ToiQuery apart = wall_query({-1024, 0}, {1024, 0}, {{0, c + 1.125}, {0, -2 * b}, {0, 2 * a}, 1}, 2);
  CHECK_FALSE(accepted_answer(apart, NumberMode::strict).hit);
}

TEST_CASE("hard: contact exactly at the horizon", "[toi][hard][oracle]") {
  // Each query touches exactly at t = 2.
  const ToiQuery queries[] = {
      ball_query({{0, 0}, {5, 0}, {}, 1}, {{12, 0}, {}, {}, 1}, 2),             // linear ball
      ball_query({{0, 5}, {}, {0, -2}, 0.5}, {{0, 0}, {}, {}, 0.5}, 2),         // quartic ball
      wall_query({-10, 0}, {10, 0}, {{0, 5}, {0, -2}, {}, 1}, 2),               // linear face
      wall_query({-10, 0}, {10, 0}, {{0, 5}, {}, {0, -2}, 1}, 2),               // falling face
      wall_query({-10, 0}, {2, 0}, {{13, 0}, {-5, 0}, {}, 1}, 2),               // round end
  };
  const double closing_speed[] = {5, 4, 2, 4, 5};
  for (const NumberMode mode : both_modes)
    for (int i = 0; i < 5; ++i) {
      ToiQuery q = queries[i];
      const double speed = closing_speed[i];
      check_hit_at(q, mode, 2.0, speed);
      q.horizon = 2 - 1e-6;  // the contact just out of reach: gap 4e-6 at H
      CHECK_FALSE(accepted_answer(q, mode).hit);
      q.horizon = 2 + 1e-6;
      check_hit_at(q, mode, 2.0, speed);
    }
}

TEST_CASE("hard: wall corners, hit from inside (faces) and outside (shared round end)", "[toi][hard][oracle]") {
  SplitMix64 rng(21);
  for (int i = 0; i < 60; ++i) {
    const double theta = rng.uniform(0, 6.28), phi = i == 0 ? 1.5707963267948966 : rng.uniform(0.4, 2.7);
    const V corner{rng.uniform(-3, 3), rng.uniform(-3, 3)};
    const V d1 = unit(theta), d2 = unit(theta + phi), bisector = unit(theta + phi / 2);
    const double r = rng.uniform(0.05, 0.5), speed = rng.uniform(1, 10), dist = 5;
    for (const int outside : {0, 1}) {
      const V start = corner + ((outside ? -dist : dist)) * bisector;
      const BallState<double> ball{start, (outside ? speed : -speed) * bisector, {}, r};
      const double horizon = 6 / speed;
      const ToiQuery q1 = wall_query(corner, corner + 8 * d1, ball, horizon);
      const ToiQuery q2 = wall_query(corner + 8 * d2, corner, ball, horizon);
      // Inside: both faces at distance |c − corner| sin(φ/2) = r; outside: the corner itself at r.
      const double expected = (dist - (outside ? r : r / std::sin(phi / 2))) / speed;
      for (const NumberMode mode : both_modes) {
        const QueryAnswer a1 = accepted_answer(q1, mode), a2 = accepted_answer(q2, mode);
        const double dt = 4 * rel_tol(mode) * oracle_detail::scale_of(q1) / speed;
        INFO(to_string(mode) << " corner " << describe(q1) << " / " << describe(q2) << " expected " << expected);
        CHECK((a1.hit && a2.hit));
        CHECK(std::fabs(a1.t - expected) <= dt);
        CHECK(std::fabs(a2.t - expected) <= dt);
      }
    }
  }
}

TEST_CASE("hard: turnaround under gravity below a ceiling", "[toi][hard][oracle]") {
  // Ceiling y = 10, r = 0.5; the ball rises from y = 0 with v_y = √(2 g (9.5 − δ)):
  // its apex is δ below contact height.
  const double g = 9.81;
  for (const double delta : {1e-3, 1e-6, 1e-9, 0.0, -1e-9, -1e-6, -1e-3}) {
    const double vy = std::sqrt(2 * g * (9.5 - delta));
    const ToiQuery q = wall_query({-10, 10}, {10, 10}, {{0, 0}, {0.25, vy}, {0, -g}, 0.5}, 2);
    const QueryAnswer a = accepted_answer(q, NumberMode::strict);
    INFO(describe(q) << " got hit " << a.hit << " t = " << a.t);
    if (delta > 1e-9) CHECK_FALSE(a.hit);
    if (delta < -1e-9) {
      CHECK(a.hit);
      CHECK(std::fabs(a.t - (vy - std::sqrt(vy * vy - 2 * g * 9.5)) / g) < 1e-6);
    }
  }
  // Exactly touching in exact arithmetic: clearance (t − 2)², double root at the apex.
  const ToiQuery touch = wall_query({-10, 4.5}, {10, 4.5}, {{0, 0}, {0, 4}, {0, -2}, 0.5}, 3);
  for (const NumberMode mode : both_modes) accepted_answer(touch, mode);
}

TEST_CASE("hard: a contact is reported, never a separation", "[toi][hard][oracle]") {
  // Touching exactly at t = 0 and moving away at speed 3:
  // no force, no contact; pulled back by 9.81, the contact is at t = 6/9.81.
  const V away_up{0.5, 3}, away_left{-3, 0};  // (a slide along a face changes nothing)
  const ToiQuery leaving[] = {
      wall_query({-10, 0}, {10, 0}, {{0, 1}, away_up, {}, 1}, 1),                 // face
      wall_query({0, 0}, {10, 0}, {{-1, 0}, away_left, {}, 1}, 1),                 // round end
      ball_query({{0, 0}, away_left, {}, 1}, {{2, 0}, {}, {}, 1}, 1),             // fixed ball
      ball_query({{0, 0}, away_left, {}, 1}, {{2, 0}, {1, 0}, {}, 1}, 1),        // moving ball
  };
  const V back[] = {{0, -9.81}, {9.81, 0}, {9.81, 0}, {9.81, 0}};
  for (const NumberMode mode : both_modes)
    for (int i = 0; i < 4; ++i) {
      ToiQuery q = leaving[i];
      INFO(to_string(mode) << ": " << describe(q));
      CHECK_FALSE(answer_toi_query(q, ToiMethod::analytic, mode, 0).hit);
      accepted_answer(q, mode);
      q.ball.acceleration = back[i];
      const double speed_back = i == 3 ? 4 : 3;  // against the moving ball: relative speed 4
      check_hit_at(q, mode, 2 * speed_back / 9.81, speed_back);
    }
}
