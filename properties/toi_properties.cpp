// Properties of the time-of-impact methods against the Reference oracle
// (toi/oracle.hpp), over random valid queries of every kind. Every number is
// built from small integers (multiples of 1/64, scaled by powers of two) so
// that failing cases shrink to readable ones.
#include <catch2/catch.hpp>
#include <rapidcheck.h>
#include <rapidcheck/catch.h>

#include <cmath>

#include "toi/oracle.hpp"

using namespace collide2d;

namespace {

using V = Vec2<double>;
V operator*(double s, V a) { return {s * a.x, s * a.y}; }

// An integer in [−n, n] that shrinks towards 0.
int centred(int n) {
  const int magnitude = *rc::gen::inRange(0, n + 1);
  return *rc::gen::arbitrary<bool>() ? -magnitude : magnitude;
}
double coordinate() { return centred(512) / 64.0; }  // [−8, 8]
double speed() { return centred(640) / 64.0; }       // [−10, 10]
double radius() { return *rc::gen::inRange(4, 65) / 64.0; }  // [1/16, 1]

enum Kind { wall, wall_gravity, wall_accel, ball_fixed, ball_same_accel, ball_quartic_fixed, ball_quartic_moving };

// A valid query (apart at t = 0) of a random kind. Half of the balls are aimed
// at the target, some of them to pass it at the contact distance ± 2^-j.
// `wide`: lengths scaled by 2^e (|e| ≤ 20) and positions translated by up to 2^30.
ToiQuery random_valid_query(bool wide) {
  const int kind = *rc::gen::element(wall, wall_gravity, wall_accel, ball_fixed, ball_same_accel, ball_quartic_fixed,
                                     ball_quartic_moving);
  const V gravity{0, -9.81};
  ToiQuery q;
  q.horizon = *rc::gen::inRange(1, 9) / 4.0;
  q.ball.position = {coordinate(), coordinate()};
  q.ball.radius = radius();
  V target, side;
  double contact = q.ball.radius;
  if (kind <= wall_accel) {
    q.kind = QueryKind::ball_wall;
    q.wall = {{coordinate(), coordinate()}, {coordinate(), coordinate()}};
    RC_PRE(!(q.wall.a == q.wall.b));
    target = q.wall.a + (*rc::gen::inRange(0, 17) / 16.0) * (q.wall.b - q.wall.a);
    side = normalized(perp(q.wall.b - q.wall.a));
  } else {
    q.kind = QueryKind::ball_ball;
    q.other = {{coordinate(), coordinate()}, {}, {}, radius()};
    target = q.other.position;
    contact += q.other.radius;
    RC_PRE(!(target == q.ball.position));
    side = normalized(perp(target - q.ball.position));
  }
  q.ball.velocity = {speed(), speed()};
  const int aim = *rc::gen::element(0, 1, 1, 2, 2);  // 0: random, 1: at the target, 2: grazing it
  if (aim > 0) {
    if (aim == 2) target = target + (contact * (1 + centred(1) * std::ldexp(1.0, -*rc::gen::inRange(0, 41)))) * side;
    q.ball.velocity = (*rc::gen::inRange(1, 33) / (8.0 * q.horizon)) * (target - q.ball.position);
  }
  const V random_accel{speed(), speed()};
  switch (kind) {
    case wall_gravity: q.ball.acceleration = gravity; break;
    case wall_accel: q.ball.acceleration = random_accel; break;
    case ball_same_accel:
      q.ball.acceleration = q.other.acceleration = gravity;
      q.other.velocity = {speed(), speed()};
      break;
    case ball_quartic_fixed: q.ball.acceleration = gravity; break;
    case ball_quartic_moving:
      q.ball.acceleration = random_accel;
      q.other.velocity = {speed(), speed()};
      q.other.acceleration = gravity;
      break;
    default: break;
  }
  if (wide) {
    const int e = centred(20);
    for (BallState<double>* b : {&q.ball, &q.other}) {
      b->position = std::ldexp(1.0, e) * b->position;
      b->velocity = std::ldexp(1.0, e) * b->velocity;
      b->acceleration = std::ldexp(1.0, e) * b->acceleration;
      b->radius = std::ldexp(b->radius, e);
    }
    q.wall = {std::ldexp(1.0, e) * q.wall.a, std::ldexp(1.0, e) * q.wall.b};
    if (*rc::gen::arbitrary<bool>()) {
      const V offset{std::ldexp(centred(1024) / 1024.0, *rc::gen::inRange(0, 31)), std::ldexp(1.0, centred(30))};
      q.ball.position = q.ball.position + offset;
      q.other.position = q.other.position + offset;
      q.wall = {q.wall.a + offset, q.wall.b + offset};
    }
  }
  RC_PRE(oracle_gap_at(q, Reference(0)) > 0);
  return q;
}

// The analytic answer in `mode` meets the acceptance rule.
void analytic_is_accepted(const ToiQuery& q, NumberMode mode, double rel_tol) {
  QueryAnswer a;
  try {
    a = answer_toi_query(q, ToiMethod::analytic, mode, 1e-9);
  } catch (const std::exception& e) {
    RC_FAIL(std::string(to_string(mode)) + " threw " + e.what() + " on " + describe(q));
  }
  const Verdict v = judge_toi_answer(q, a.hit, a.t, rel_tol);
  RC_TAG(q.kind == QueryKind::ball_wall ? "ball-wall" : "ball-ball", a.hit ? "hit" : "no hit");
  RC_LOG() << v.why << "\n";
  RC_ASSERT(v.ok);
}

}  // namespace

TEST_CASE("properties: analytic strict time of impact against the oracle", "[toi][property][oracle]") {
  rc::prop("strict: the acceptance rule holds (tol 1e-12 scale), scaled and translated queries",
           [] { analytic_is_accepted(random_valid_query(true), NumberMode::strict, 1e-12); });
}

TEST_CASE("properties: analytic fixed time of impact against the oracle", "[toi][property][oracle]") {
  rc::prop("fixed: the acceptance rule holds (tol 1e-7 scale) on small-valued queries",
           [] { analytic_is_accepted(random_valid_query(false), NumberMode::fixed, 1e-7); });
}

TEST_CASE("properties: bisection hits are within eps and never early", "[toi][property][oracle]") {
  rc::prop("strict bisection: |true gap(t)| <= eps + rounding, t >= first time the gap is <= eps", [] {
    ToiQuery q = random_valid_query(true);
    // Half of the time, end the horizon just after the oracle's contact, so
    // that the step overlaps (bisection only looks when it ends overlapping).
    const OracleAnswer o = oracle_time_of_impact(q);
    if (o.hit && *rc::gen::arbitrary<bool>())
      q.horizon = o.t + std::ldexp(q.horizon - o.t, -*rc::gen::inRange(0, 41));
    const double scale = oracle_detail::scale_of(q);
    const double eps = std::ldexp(1.0, -*rc::gen::inRange(5, 31)) * scale;
    const auto r = solve_toi_query<double>(convert_query<double>(q), ToiMethod::bisection, eps);
    RC_TAG(r.hit() ? "hit" : "no hit");
    if (!r.hit()) return;
    // The method's gap is a double evaluation: allow rounding of the order of
    // 1e-12 of the largest coordinate or distance involved.
    double extent = scale;
    for (const V& p : {q.ball.position, q.other.position, q.wall.a, q.wall.b})
      extent = std::max({extent, std::fabs(p.x), std::fabs(p.y)});
    const double slack = eps * 1e-9 + 1e-12 * extent;
    const Reference gap = oracle_gap_at(q, Reference(r.time));
    RC_LOG() << describe(q) << "\n eps=" << eps << " t=" << r.time << " true gap=" << gap.str(6) << "\n";
    RC_ASSERT(abs(gap) <= Reference(eps + slack));
    const auto earliest = oracle_first_time_gap_at_most(q, Reference(eps + slack));
    RC_ASSERT(earliest.has_value());
    RC_ASSERT(Reference(r.time) >= *earliest);
  });
}
