// Hard cases for the analytic time of impact, judged against the independent
// Reference oracle (lab/oracle.hpp) by one acceptance rule: tol = 1e-12 scale
// (strict) or the bound derived for the query from the Q63.64 format (fixed,
// properties/fixed_toi_bound.hpp: at most 5.6e-16 of the scale over the hard
// set but for tiny radii, 4.5e-11); min gap < −tol ⇒ hit, > +tol ⇒ no hit; a hit
// has |true gap| ≤ tol and lies between the first approach within +tol and
// the first time the gap reaches −tol. Families are generated with fixed
// seeds on both sides of the threshold; the special cases (Kahan's
// discriminant, horizon, corners, separation) are in test_hard_cases_special.cpp.
#include <catch2/catch.hpp>

#include <cmath>

#include "fixed_toi_bound.hpp"
#include "lab/hard_queries.hpp"
#include "lab/oracle.hpp"
#include "lab/random_queries.hpp"

using namespace collide2d;

namespace {

using V = Vec2<double>;
V operator*(double s, V a) { return {s * a.x, s * a.y}; }
V unit(double angle) { return {std::cos(angle), std::sin(angle)}; }

// Judges the analytic method's answer to q in `mode` by the acceptance rule.
void check_accepted(const ToiQuery& q, NumberMode mode) {
  QueryAnswer a;
  try {
    a = answer_toi_query(q, ToiMethod::analytic, mode, 1e-9);
  } catch (const std::exception& e) {
    FAIL_CHECK(to_string(mode) << " threw " << e.what() << " on " << describe(q));
    return;
  }
  const double rel_tol =
      mode == NumberMode::strict ? 1e-12 : properties::fixed_toi_gap_bound(q) / oracle_detail::scale_of(q);
  const Verdict v = judge_toi_answer(q, a.hit, a.t, rel_tol);
  INFO(to_string(mode) << ": " << v.why);
  CHECK(v.ok);
}

void check_both_modes(const ToiQuery& q, bool fixed_too) {
  check_accepted(q, NumberMode::strict);
  if (fixed_too) check_accepted(q, NumberMode::fixed);
}

// The query constructors (passing_through, ball_ball_graze, end_graze,
// face_turnaround, at_relative_gap) are the dataset's, lab/hard_queries.hpp.
// Here a wall end is approached from the side at `side_angle` from the wall's
// direction.
ToiQuery end_graze(V a, V b, double r, double side_angle, double speed, V acc, double t_star, double gap, double horizon) {
  const V d = normalized(b - a);
  return collide2d::end_graze(a, b, r, unit(std::atan2(d.y, d.x) + side_angle), speed, acc, t_star, gap, horizon);
}

// Calls body(k, sign, rng) for k = 3…15, both signs, `n` instances each.
template <class Body>
void for_all_gaps(std::uint64_t seed, int n, Body body) {
  SplitMix64 rng(seed);
  for (int k = 3; k <= 15; ++k)
    for (const int sign : {1, -1})
      for (int i = 0; i < n; ++i) body(k, sign, rng);
}

const V gravity{0, -9.81};

}  // namespace

TEST_CASE("hard: grazing ball-ball, linear and accelerated, moving or fixed other", "[toi][hard][oracle]") {
  for_all_gaps(11, 5, [](int k, int sign, SplitMix64& rng) {
    const V o{rng.uniform(-5, 5), rng.uniform(-5, 5)};
    const double ra = rng.uniform(0.05, 1), rb = rng.uniform(0.05, 1), speed = rng.uniform(1, 10);
    const V n = unit(rng.uniform(0, 6.28)), u{rng.uniform(-3, 3), rng.uniform(-3, 3)};
    const double ts = rng.uniform(0.2, 0.8);
    for (const V da : {V{}, gravity, V{rng.uniform(-10, 10), rng.uniform(-10, 10)}}) {
      const auto fixed_other = [&](double g) { return ball_ball_graze(o, ra, rb, n, speed, da, ts, g, 1.0); };
      const auto moving_other = [&](double g) { return ball_ball_graze(o, ra, rb, n, speed, da, ts, g, 1.0, u, gravity); };
      const ToiQuery q1 = at_relative_gap(fixed_other, k, sign), q2 = at_relative_gap(moving_other, k, sign);
      if (k <= 10) CHECK((oracle_time_of_impact(q1).min_gap < 0) == (sign < 0));  // the oracle sees the graze
      check_both_modes(q1, true);
      check_both_modes(q2, true);
    }
  });
}

TEST_CASE("hard: grazing ball-wall faces (turnaround) and round ends, oblique walls", "[toi][hard][oracle]") {
  for_all_gaps(12, 6, [](int k, int sign, SplitMix64& rng) {
    const double angle = rng.uniform(0, 6.28), half = rng.uniform(3, 10), r = rng.uniform(0.05, 1);
    const V centre{rng.uniform(-3, 3), rng.uniform(-3, 3)};
    const V a = centre - half * unit(angle), b = centre + half * unit(angle);
    const double g = rng.uniform(1, 20), slide = rng.uniform(-2, 2), ts = rng.uniform(0.2, 0.8);
    const double along = rng.uniform(0.3, 0.7);
    const int side = rng.uniform(0, 1) < 0.5 ? 1 : -1;
    const double side_angle = rng.uniform(-1.2, 1.2), speed = rng.uniform(1, 10);
    const V acc{rng.uniform(-10, 10), rng.uniform(-10, 10)};
    const auto face = [&](double gp) { return face_turnaround(a, b, r, along, g, slide, ts, gp, 1.0, side); };
    const auto end = [&](double gp) { return end_graze(a, b, r, side_angle, speed, V{}, ts, gp, 1.0); };
    const auto end_acc = [&](double gp) { return end_graze(a, b, r, side_angle, speed, acc, ts, gp, 1.0); };
    const ToiQuery qf = at_relative_gap(face, k, sign), qe = at_relative_gap(end, k, sign);
    if (k <= 10) {
      CHECK((oracle_time_of_impact(qf).min_gap < 0) == (sign < 0));
      CHECK((oracle_time_of_impact(qe).min_gap < 0) == (sign < 0));
    }
    check_both_modes(qf, true);
    check_both_modes(qe, true);
    check_both_modes(at_relative_gap(end_acc, k, sign), true);
  });
}

TEST_CASE("hard: tiny relative acceleration (1e-14 of the velocity scale)", "[toi][hard][oracle]") {
  for_all_gaps(13, 4, [](int k, int sign, SplitMix64& rng) {
    const double speed = rng.uniform(4, 10);  // speed ts > 2 > R: apart at t = 0 even when aimed at the centre
    const V da = (1e-14 * speed) * unit(rng.uniform(0, 6.28));
    const V o{rng.uniform(-5, 5), rng.uniform(-5, 5)}, n = unit(rng.uniform(0, 6.28));
    const double ra = rng.uniform(0.05, 1), rb = rng.uniform(0.05, 1), ts = rng.uniform(0.5, 0.9);
    const V u{rng.uniform(-3, 3), rng.uniform(-3, 3)};
    const auto make = [&](double g) { return ball_ball_graze(o, ra, rb, n, speed, da, ts, g, 1.0, u, gravity); };
    check_both_modes(at_relative_gap(make, k, sign), true);
    // And straight through the middle: a certain hit.
    check_both_modes(make(-ra - rb), true);
  });
}

TEST_CASE("hard: far apart (1e7), small radii, huge constant terms", "[toi][hard][oracle]") {
  // Radii 1e-3 (linear and under gravity), and 1e-6 under gravity: the tol
  // 1e-12 scale is 1e-5, so direct hits are checked separately below.
  for_all_gaps(14, 3, [](int k, int sign, SplitMix64& rng) {
    if (k > 11) return;  // beyond 1e-12 of the scale: below the tolerance here
    const double ts = rng.uniform(0.5, 0.95), dist = 1e7;
    const V n = unit(rng.uniform(0, 6.28)), o = dist * unit(rng.uniform(0, 6.28));
    for (const double radius : {1e-3, 1e-6})
      for (const V da : {V{}, gravity}) {
        const auto make = [&](double g) { return ball_ball_graze(o, radius, radius, n, dist / ts, da, ts, g, 1.0); };
        check_accepted(at_relative_gap(make, k, sign), NumberMode::strict);
      }
    // A wall end 1e7 away, ball radius 1e-6, under gravity.
    const auto wall_end = [&](double g) {
      return end_graze(o - V{1, 0}, o, 1e-6, rng.uniform(-1, 1), dist / ts, gravity, ts, g, 1.0);
    };
    check_accepted(at_relative_gap(wall_end, k, sign), NumberMode::strict);
  });
  SECTION("direct hits through the centre are found, at the right time") {
    SplitMix64 rng(15);
    for (int i = 0; i < 40; ++i) {
      const double radius = i % 2 ? 1e-3 : 1e-6, ts = rng.uniform(0.5, 0.95);
      const V n = unit(rng.uniform(0, 6.28)), o = 1e7 * unit(rng.uniform(0, 6.28));
      const V da = i % 4 < 2 ? gravity : V{};
      const ToiQuery q = ball_ball_graze(o, radius, radius, n, 1e7 / ts, da, ts, -2 * radius * rng.uniform(0.1, 1), 1.0);
      const QueryAnswer got = answer_toi_query(q, ToiMethod::analytic, NumberMode::strict, 0);
      INFO(describe(q));
      CHECK(got.hit);
      check_accepted(q, NumberMode::strict);
    }
  }
}

TEST_CASE("hard: large absolute coordinates (offset 1e8)", "[toi][hard][oracle]") {
  const V offset{1e8, 1e8};
  const auto shift = [&](ToiQuery q) {
    q.ball.position = q.ball.position + offset;
    q.other.position = q.other.position + offset;
    q.wall = {q.wall.a + offset, q.wall.b + offset};
    return q;
  };
  for_all_gaps(16, 2, [&](int k, int sign, SplitMix64& rng) {
    const V o{rng.uniform(-5, 5), rng.uniform(-5, 5)}, n = unit(rng.uniform(0, 6.28));
    const double ra = rng.uniform(0.05, 1), rb = rng.uniform(0.05, 1), speed = rng.uniform(1, 10), ts = rng.uniform(0.2, 0.8);
    const V a = o - 5 * unit(rng.uniform(0, 6.28)), g{rng.uniform(-10, 10), rng.uniform(-10, 10)};
    const double side_angle = rng.uniform(-1.2, 1.2);
    const auto balls = [&](double gp) { return shift(ball_ball_graze(o, ra, rb, n, speed, g, ts, gp, 1.0)); };
    const auto face = [&](double gp) { return shift(face_turnaround(a, o, ra, 0.5, 9.81, 1.0, ts, gp, 1.0, 1)); };
    const auto end = [&](double gp) { return shift(end_graze(a, o, ra, side_angle, speed, V{}, ts, gp, 1.0)); };
    check_accepted(at_relative_gap(balls, k, sign), NumberMode::strict);
    check_accepted(at_relative_gap(face, k, sign), NumberMode::strict);
    check_accepted(at_relative_gap(end, k, sign), NumberMode::strict);
  });
}

TEST_CASE("hard: tiny radii (1e-8)", "[toi][hard][oracle]") {
  for_all_gaps(17, 3, [](int k, int sign, SplitMix64& rng) {
    const double r = 1e-8, speed = rng.uniform(1, 10), ts = rng.uniform(0.2, 0.8);
    const V o{rng.uniform(-5, 5), rng.uniform(-5, 5)}, n = unit(rng.uniform(0, 6.28));
    const V a = o - 5 * unit(rng.uniform(0, 6.28));
    const double side_angle = rng.uniform(-1.2, 1.2);
    for (const V da : {V{}, gravity}) {
      const auto balls = [&](double g) { return ball_ball_graze(o, r, r, n, speed, da, ts, g, 1.0); };
      const auto end = [&](double g) { return end_graze(a, o, r, side_angle, speed, da, ts, g, 1.0); };
      check_accepted(at_relative_gap(balls, k, sign), NumberMode::strict);
      check_accepted(at_relative_gap(end, k, sign), NumberMode::strict);
    }
    const auto face = [&](double g) { return face_turnaround(a, o, r, 0.5, 9.81, 0.5, ts, g, 1.0, -1); };
    check_accepted(at_relative_gap(face, k, sign), NumberMode::strict);
  });
}

TEST_CASE("hard: parallel sliding along a wall at gap ±tol, entering over its round end", "[toi][hard][oracle]") {
  // Wall [A, B] of length 10; the ball starts 3 before A on the wall's line
  // offset by r + gap and slides parallel at speed 5 for H = 2.
  SplitMix64 rng(18);
  for (int k = 8; k <= 15; ++k)
    for (const int sign : {1, -1})
      for (int i = 0; i < 6; ++i) {
        const double angle = i == 0 ? 0.0 : rng.uniform(0, 6.28), r = rng.uniform(0.05, 1);
        const V a{rng.uniform(-3, 3), rng.uniform(-3, 3)}, d = unit(angle), b = a + 10 * d;
        const double scale = std::max(r, 10.0), gap = sign * std::pow(10.0, -k) * scale;
        ToiQuery q;
        q.kind = QueryKind::ball_wall;
        q.horizon = 2;
        q.wall = {a, b};
        q.ball = {a - 3 * d + (r + gap) * perp(d), 5 * d, {}, r};
        check_both_modes(q, true);
      }
}

TEST_CASE("hard: near-contact starts (gap 1e-12 at t = 0), approaching and receding", "[toi][hard][oracle]") {
  SplitMix64 rng(19);
  for (int i = 0; i < 60; ++i) {
    const V o{rng.uniform(-5, 5), rng.uniform(-5, 5)}, n = unit(rng.uniform(0, 6.28));
    const double ra = rng.uniform(0.05, 1), rb = rng.uniform(0.05, 1), speed = rng.uniform(1, 10);
    const V tangential = rng.uniform(-2, 2) * perp(n);
    for (const int dir : {-1, 1}) {  // −1: approaching, +1: receding
      ToiQuery q;
      q.kind = QueryKind::ball_ball;
      q.horizon = 1;
      q.other = {o, {}, {}, rb};
      q.ball = {o + (ra + rb + 1e-12) * n, (dir * speed) * n + tangential, {}, ra};
      check_both_modes(q, true);
      const QueryAnswer got = answer_toi_query(q, ToiMethod::analytic, NumberMode::strict, 0);
      INFO(describe(q));
      CHECK(got.hit == (dir < 0));  // receding without force: never a contact
      // The same against a wall face, with and without an acceleration back.
      const V wa = o - 4 * perp(n), wb = o + 4 * perp(n);
      ToiQuery w;
      w.kind = QueryKind::ball_wall;
      w.horizon = 1;
      w.wall = {wa, wb};
      w.ball = {o + (ra + 1e-12) * n, (dir * speed) * n + tangential, {}, ra};
      check_both_modes(w, true);
      w.ball.acceleration = (-2.5 * speed) * n;  // receding ones come back at t ≈ 0.8
      check_both_modes(w, true);
      const QueryAnswer back = answer_toi_query(w, ToiMethod::analytic, NumberMode::strict, 0);
      INFO(describe(w));
      REQUIRE(back.hit);
      if (dir > 0) CHECK(std::fabs(back.t - 0.8) < 1e-9);
    }
  }
}
