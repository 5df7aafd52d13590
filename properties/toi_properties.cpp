// Properties of the time-of-impact methods against the Reference oracle
// (lab/oracle.hpp), over random valid queries of every kind. Every number is
// built from small integers (multiples of 1/64, scaled by powers of two) so
// that failing cases shrink to readable ones. Then the article's methods
// against the analytic one (their misses and wrong roots counted by cause),
// and fixed mode on values built from raw Q63.64 bits. Every property runs
// through check_property (property_runner.hpp): fixed CI seed, outcome
// recorded when COLLIDE2D_PROPERTY_RECORD is set.
#include <catch2/catch.hpp>
#include <rapidcheck.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "collide2d/numeric/fixed_words.hpp"

#include "fixed_raw_generators.hpp"
#include "fixed_toi_bound.hpp"
#include "lab/oracle.hpp"
#include "property_runner.hpp"

using namespace collide2d;
using namespace collide2d::properties;

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

// Every length of the query times 2^e (exact: the values are dyadic).
void scale_lengths(ToiQuery& q, int e) {
  for (BallState<double>* b : {&q.ball, &q.other}) {
    b->position = std::ldexp(1.0, e) * b->position;
    b->velocity = std::ldexp(1.0, e) * b->velocity;
    b->acceleration = std::ldexp(1.0, e) * b->acceleration;
    b->radius = std::ldexp(b->radius, e);
  }
  q.wall = {std::ldexp(1.0, e) * q.wall.a, std::ldexp(1.0, e) * q.wall.b};
}

enum Kind { wall, wall_gravity, wall_accel, ball_fixed, ball_same_accel, ball_quartic_fixed, ball_quartic_moving };

// A valid query (apart at t = 0) of a random kind. Half of the balls are aimed
// at the target, some of them to pass it at the contact distance ± 2^-j.
// `wide`: lengths scaled by 2^e (|e| ≤ 20) and positions translated by up to 2^30.
// `walls_only`: ball–wall kinds only (the seed wall method).
ToiQuery random_valid_query(bool wide, bool walls_only = false) {
  const int kind = walls_only ? *rc::gen::element(wall, wall_gravity, wall_accel)
                              : *rc::gen::element(wall, wall_gravity, wall_accel, ball_fixed, ball_same_accel,
                                                  ball_quartic_fixed, ball_quartic_moving);
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
    if (aim == 2) {
      // One draw per statement: the order of operands and arguments is the
      // compiler's choice, and a seed must give the same query everywhere.
      const int sign = centred(1);
      target = target + (contact * (1 + sign * std::ldexp(1.0, -*rc::gen::inRange(0, 41)))) * side;
    }
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
    scale_lengths(q, centred(20));
    if (*rc::gen::arbitrary<bool>()) {
      const double fraction = centred(1024) / 1024.0;  // one draw per statement (above)
      const V offset{std::ldexp(fraction, *rc::gen::inRange(0, 31)), std::ldexp(1.0, centred(30))};
      q.ball.position = q.ball.position + offset;
      q.other.position = q.other.position + offset;
      q.wall = {q.wall.a + offset, q.wall.b + offset};
    }
  }
  RC_PRE(oracle_gap_at(q, Reference(0)) > 0);
  return q;
}

// The analytic answer in `mode` meets the acceptance rule.
void analytic_is_accepted(const ToiQuery& q, NumberMode mode, double rel_tol);

// The derived bound's size against the query's scale, as a tag: how tight
// the claim judged was.
std::string bound_tag(double rel) {
  return rel <= 1e-14 ? "bound <= 1e-14 scale"
         : rel <= 1e-12 ? "bound 1e-14..1e-12 scale"
         : rel <= 1e-10 ? "bound 1e-12..1e-10 scale"
                        : "bound > 1e-10 scale";
}

// Fixed mode: the acceptance rule with the derived bound (fixed_toi_bound.hpp)
// as its tolerance, tol = bound / scale. Over this generator's values (sizes
// 1/16 to ~400) the bound stays below 4e-15 of the scale (20 000 cases
// each of seeds 5, 6, 7: at most 3.6e-15, the true error at most 0.73 of
// the bound); a case where it came out above 1e-10 would say little and is
// discarded, named, instead.
void analytic_fixed_within_bound(const ToiQuery& q) {
  const double rel = fixed_toi_gap_bound(q) / oracle_detail::scale_of(q);
  if (rel > 1e-10) discard_not_applicable("the derived fixed bound is above 1e-10 of the scale (a degenerate motion)");
  RC_TAG(bound_tag(rel));
  analytic_is_accepted(q, NumberMode::fixed, rel);
}

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
  check_property("analytic time of impact meets the acceptance rule (tol 1e-12 scale), scaled and translated", "strict",
                 [] { analytic_is_accepted(random_valid_query(true), NumberMode::strict, 1e-12); });
}

TEST_CASE("properties: analytic fixed time of impact against the oracle", "[toi][property][oracle]") {
  check_property("analytic time of impact meets the acceptance rule (tol: the derived fixed bound), small values", "fixed",
                 [] { analytic_fixed_within_bound(random_valid_query(false)); });
}

// ------------------------------------------------------------------------
// The contact a hit reports. A time-of-impact call answers with the time,
// and with the contact there: the point (ToiResult::point), the unit normal
// (ToiResult::normal) and the feature touched. They are one contact: the
// normal points from the contact point towards the ball's centre at the
// time, the point lies at the ball's radius from that centre and on the
// other object's surface (the wall's segment, at the feature named: its face
// or an end; the other ball's circle). All three follow from the time and
// the geometry, and are checked against them here, in long double from the
// query's own numbers:
//   | |n| − 1 | ≤ δn,  dist(p, other surface) ≤ ε_p,
//   | c(t) − p − r n | ≤ g + ε_p + r δn,
// g the method's bound on the gap at its time (strict: the acceptance rule's
// 1e-12 of the scale; fixed: the derived bound of fixed_toi_bound.hpp for
// its own Fixed time), ε_p the rounding of the positions the method forms
// (c(t) = p + t (v + t/2 a) and the point from it: 64 units of 1 + |p| + |v| H
// + |a| H² + r, strict relative, fixed absolute) and δn the rounding of a
// unit normal d/|d| (strict 4 eps; fixed 8·2^-64 (1 + 1/|d|² + |d|), |d| the
// radius, the wall's length or the contact distance, the shortest for 1/|d|²
// and the longest for |d|, as physics_checks.cpp has it). A normal
// pointing the wrong way misses by 2r.

namespace {

using LD = long double;

LD as_ld(double x) { return x; }
LD as_ld(const Fixed& x) {
  const FixedWords w = to_words(x);
  return static_cast<LD>(w.hi) + static_cast<LD>(static_cast<std::uint64_t>(w.lo)) * 0x1p-64L;
}

const char* feature_name(ContactFeature f) {
  switch (f) {
    case ContactFeature::ball: return "a ball";
    case ContactFeature::wall_face: return "a face";
    case ContactFeature::wall_end_a: return "an end";
    case ContactFeature::wall_end_b: return "an end";
    default: return "no feature";
  }
}

template <class Num>
void hit_reports_its_contact(const ToiQuery& q, bool fixed) {
  const ToiResult<Num> r = solve_toi_query<Num>(convert_query<Num>(q), ToiMethod::analytic, Num{});
  if (!r.hit()) discard_not_applicable("no hit: no contact to report");
  const double scale = oracle_detail::scale_of(q);
  const LD g = fixed ? fixed_toi_gap_bound(q, false) : 1e-12 * scale;
  const LD t = as_ld(r.time), H = q.horizon;
  auto centre = [&](const BallState<double>& b) {
    return Vec2<LD>{b.position.x + t * (b.velocity.x + t / 2 * b.acceleration.x),
                    b.position.y + t * (b.velocity.y + t / 2 * b.acceleration.y)};
  };
  const Vec2<LD> c = centre(q.ball), p{as_ld(r.point.x), as_ld(r.point.y)}, n{as_ld(r.normal.x), as_ld(r.normal.y)};
  const LD radius = q.ball.radius;
  LD size = std::max(std::fabs(q.ball.position.x), std::fabs(q.ball.position.y)) + std::hypot(q.ball.velocity.x, q.ball.velocity.y) * H +
            std::hypot(q.ball.acceleration.x, q.ball.acceleration.y) * H * H + radius;
  // What a unit normal is formed from: the radius (an end), the wall (its
  // face), the contact distance (a ball); the shortest and the longest.
  LD d_short = radius, d_long = radius;
  if (q.kind == QueryKind::ball_wall) {
    size = std::max({size, LD(std::fabs(q.wall.a.x)), LD(std::fabs(q.wall.a.y)), LD(std::fabs(q.wall.b.x)), LD(std::fabs(q.wall.b.y))});
    const LD wall = std::hypot(q.wall.b.x - q.wall.a.x, q.wall.b.y - q.wall.a.y);
    d_short = std::min(d_short, wall), d_long = std::max(d_long, wall);
  } else {
    size += std::max(std::fabs(q.other.position.x), std::fabs(q.other.position.y)) + q.other.radius;
    d_short = d_long = radius + q.other.radius;
  }
  const LD unit = fixed ? LD(0x1p-64) : LD(std::numeric_limits<double>::epsilon());
  const LD eps_p = 64 * unit * (1 + size);
  const LD dn = fixed ? 8 * unit * (1 + 1 / (d_short * d_short) + d_long) : 4 * unit;
  RC_TAG(q.kind == QueryKind::ball_wall ? "ball-wall" : "ball-ball", feature_name(r.feature));
  RC_LOG() << describe(q) << "\n t = " << static_cast<double>(t) << " point (" << static_cast<double>(p.x) << ", "
           << static_cast<double>(p.y) << ") normal (" << static_cast<double>(n.x) << ", " << static_cast<double>(n.y)
           << "), centre (" << static_cast<double>(c.x) << ", " << static_cast<double>(c.y) << "), g " << static_cast<double>(g)
           << ", eps_p " << static_cast<double>(eps_p) << "\n";
  // A unit normal.
  RC_ASSERT(std::fabs(std::hypot(n.x, n.y) - 1) <= dn);
  // On the other object's surface, at the feature named.
  if (q.kind == QueryKind::ball_wall) {
    RC_ASSERT(r.feature == ContactFeature::wall_face || r.feature == ContactFeature::wall_end_a ||
              r.feature == ContactFeature::wall_end_b);
    const LD ax = q.wall.a.x, ay = q.wall.a.y, dx = LD(q.wall.b.x) - ax, dy = LD(q.wall.b.y) - ay;
    const LD along = ((p.x - ax) * dx + (p.y - ay) * dy) / (dx * dx + dy * dy);
    const LD s_clamped = std::clamp(along, LD(0), LD(1));
    const LD off = std::hypot(p.x - ax - s_clamped * dx, p.y - ay - s_clamped * dy);
    RC_ASSERT(off <= eps_p);
    if (r.feature == ContactFeature::wall_end_a) RC_ASSERT(std::hypot(p.x - ax, p.y - ay) <= eps_p);
    if (r.feature == ContactFeature::wall_end_b) RC_ASSERT(std::hypot(p.x - q.wall.b.x, p.y - q.wall.b.y) <= eps_p);
  } else {
    RC_ASSERT(r.feature == ContactFeature::ball);
    const Vec2<LD> o = centre(q.other);
    RC_ASSERT(std::fabs(std::hypot(p.x - o.x, p.y - o.y) - q.other.radius) <= g + eps_p + q.other.radius * dn);
  }
  // From the point towards the centre, a radius long: c(t) − p = r n.
  const LD miss = std::hypot(c.x - p.x - radius * n.x, c.y - p.y - radius * n.y);
  RC_LOG() << "|c - p - r n| = " << static_cast<double>(miss) << "\n";
  RC_ASSERT(miss <= g + eps_p + radius * dn);
}

}  // namespace

TEST_CASE("properties: a hit reports its contact: normal from the point towards the centre, point on both surfaces",
          "[toi][property][oracle]") {
  check_property("a hit's normal points from its contact point towards the ball's centre, the point on both surfaces", "strict",
                 [] { hit_reports_its_contact<double>(random_valid_query(true), false); });
  check_property("a hit's normal points from its contact point towards the ball's centre, the point on both surfaces", "fixed",
                 [] { hit_reports_its_contact<Fixed>(random_valid_query(false), true); });
}

TEST_CASE("properties: bisection hits are within eps and never early", "[toi][property][oracle]") {
  // |true gap(t)| <= eps + rounding, t >= the first time the gap is <= eps.
  check_property("bisection hits are within eps and never early", "strict",
                 [] {
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

// ------------------------------------------------------------------------
// The article's methods against the analytic one: where they agree, and why
// they do not. Their blind spots are not failures; they are counted, by
// cause, in the distribution RapidCheck prints (RC_TAG). A failure is a
// contact one method sees for certain and the analytic method misses or
// places later.

namespace {

// Rounding room of a double evaluation of the gap: ~1e-12 of the largest
// coordinate or distance involved.
double rounding_slack(const ToiQuery& q) {
  double extent = oracle_detail::scale_of(q);
  for (const V& p : {q.ball.position, q.other.position, q.wall.a, q.wall.b})
    extent = std::max({extent, std::fabs(p.x), std::fabs(p.y)});
  return 1e-12 * extent;
}

// The true gap is at most `level` at 33 evenly spaced times of [t0, t1]:
// one contact, not two separated by a gap that opens wider than `level`.
bool stays_within(const ToiQuery& q, double t0, double t1, const Reference& level) {
  for (int i = 0; i <= 32; ++i) {
    const Reference t = Reference(t0) + (Reference(t1) - Reference(t0)) * i / 32;
    if (oracle_gap_at(q, t) > level) return false;
  }
  return true;
}

const char* kind_name(const ToiQuery& q) { return q.kind == QueryKind::ball_wall ? "ball-wall" : "ball-ball"; }

bool at_wall_end(ContactFeature f) { return f == ContactFeature::wall_end_a || f == ContactFeature::wall_end_b; }

// Why step-and-bisect missed the contact the analytic method found (`tol`:
// the analytic method's bound). Bisection only looks when the step ends
// overlapping, so every cause is a contact over before the step ends.
const char* bisection_miss_cause(const ToiQuery& q, const ToiResult<double>& analytic, const OracleAnswer& o,
                                 double tol) {
  if (o.min_gap >= -tol) return "miss: a touch within tolerance only";
  if (oracle_gap_at(q, Reference(q.horizon)) <= 0) return "miss: overlap at the step end within rounding";
  const bool wall = q.kind == QueryKind::ball_wall;
  const double contact = wall ? q.ball.radius : q.ball.radius + q.other.radius;
  if (o.min_gap < -(wall ? 1.0 : 0.5) * contact) return "miss: passes through within a step";
  if (at_wall_end(analytic.feature)) return "miss: round end clipped within the step";
  return "miss: grazing, contact shorter than the step";
}

// Why the seed wall method missed the contact the analytic method found.
const char* seed_miss_cause(const ToiQuery& q, const ToiResult<double>& analytic, const OracleAnswer& o, double tol) {
  if (o.min_gap >= -tol) return "miss: a touch within tolerance only";
  if (at_wall_end(analytic.feature)) return "miss: round end (never hit by this method)";
  if (!(q.ball.acceleration == V{})) return "miss: face, curved path (chord test or root choice)";
  return "miss: face, straight path";
}

// The seed method's own rule: the wall moved towards the ball by its radius,
// and the chord from the centre's start to its position at the horizon. When
// the chord crosses the moved wall clearly (both ends farther than `margin`
// from its line, the crossing inside the segment by `margin`), the textbook
// quadratic changes sign on [0, H] and has a root there: the method must hit.
bool chord_clearly_crosses_moved_wall(const ToiQuery& q, double margin) {
  const V d = q.wall.b - q.wall.a;
  const double length = std::sqrt(dot(d, d));
  V n = (1.0 / length) * perp(d);
  if (dot(n, q.ball.position - q.wall.a) < 0) n = -1.0 * n;
  const V a = q.wall.a + q.ball.radius * n;  // the moved wall starts here
  const V p0 = q.ball.position;
  const V p1 = position_at(q.ball.position, q.ball.velocity, q.ball.acceleration, q.horizon);
  const double s0 = dot(n, p0 - a), s1 = dot(n, p1 - a);  // signed distances to the moved line
  if (!(s0 > margin && s1 < -margin)) return false;
  const V x = p0 + (s0 / (s0 - s1)) * (p1 - p0);
  const double along = dot(d, x - a) / length;
  return along > margin && along < length - margin;
}

}  // namespace

TEST_CASE("properties: bisection agrees with the analytic method, its misses classified", "[toi][property][oracle]") {
  // A hit is the analytic contact or a later one, never a contact the analytic
  // method misses; misses counted by cause.
  check_property("bisection agrees with the analytic method, misses classified", "strict",
                 [] {
             const ToiQuery q = random_valid_query(true);
             const double scale = oracle_detail::scale_of(q);
             const double eps = std::ldexp(1.0, -*rc::gen::inRange(5, 31)) * scale;
             const double tol = 1e-12 * scale;  // the analytic method's bound
             const double slack = eps * 1e-9 + rounding_slack(q);
             const auto qd = convert_query<double>(q);
             const auto b = solve_toi_query<double>(qd, ToiMethod::bisection, eps);
             const auto a = solve_toi_query<double>(qd, ToiMethod::analytic, eps);
             const OracleAnswer o = oracle_time_of_impact(q);
             RC_LOG() << describe(q) << "\n eps=" << eps << " bisection hit=" << b.hit() << " t=" << b.time
                      << "; analytic hit=" << a.hit() << " t=" << a.time << "; oracle min_gap=" << o.min_gap << "\n";
             if (!b.hit()) {
               RC_TAG(kind_name(q), a.hit() ? bisection_miss_cause(q, a, o, tol) : "no contact (both agree)");
               return;
             }
             if (!a.hit()) {
               RC_ASSERT(o.min_gap >= -tol);  // else bisection found a contact the analytic method missed
               RC_TAG(kind_name(q), "hit: a touch within tolerance, analytic says none");
               return;
             }
             const Reference same_contact(eps + slack + tol);
             if (b.time >= a.time) {
               RC_TAG(kind_name(q), stays_within(q, a.time, b.time, same_contact)
                                        ? "hit: the analytic contact"
                                        : "hit: a later contact (an earlier one inside the step missed)");
               return;
             }
             // Before the analytic contact: only a near-graze within eps, never a real overlap.
             RC_ASSERT(oracle_gap_at(q, Reference(b.time)) >= Reference(-(slack + tol)));
             RC_TAG(kind_name(q), stays_within(q, b.time, a.time, same_contact)
                                      ? "hit: the analytic contact"
                                      : "hit: stopped in a near-graze within eps before the contact");
           });
}

TEST_CASE("properties: the seed wall method against the analytic method, misses and wrong roots classified",
          "[toi][property][oracle]") {
  // A genuine approaching face contact it reports is never one the analytic
  // method misses or places later; misses and wrong roots counted by cause.
  check_property("seed wall method against the analytic method, misses and wrong roots classified", "strict",
                 [] {
             const ToiQuery q = random_valid_query(true, true);
             const double scale = oracle_detail::scale_of(q);
             const double tol = 1e-12 * scale;
             const double seed_tol = 1e-9 * scale + rounding_slack(q);  // the textbook formula cancels
             const auto qd = convert_query<double>(q);
             const auto s = solve_toi_query<double>(qd, ToiMethod::seed, 0.0);
             const auto a = solve_toi_query<double>(qd, ToiMethod::analytic, 0.0);
             const OracleAnswer o = oracle_time_of_impact(q);
             RC_LOG() << describe(q) << "\n seed hit=" << s.hit() << " t=" << s.time << "; analytic hit=" << a.hit()
                      << " t=" << a.time << "; oracle min_gap=" << o.min_gap << "\n";
             if (!s.hit()) {
               // Not one of its blind spots (round ends, a parabola whose chord does not cross):
               RC_ASSERT(!chord_clearly_crosses_moved_wall(q, 1e-9 * scale));
               RC_TAG(a.hit() ? seed_miss_cause(q, a, o, tol) : "no contact (both agree)");
               return;
             }
             if (!(dot(velocity_at(q.ball, s.time), s.normal) < 0)) {
               RC_TAG("wrong root: a separation (moving apart)");
               return;
             }
             if (abs(oracle_gap_at(q, Reference(s.time))) > Reference(seed_tol)) {
               RC_TAG("wrong root: not touching at t (off by more than 1e-9 scale)");
               return;
             }
             // A genuine approaching face contact at s.time.
             if (!a.hit()) {
               RC_ASSERT(o.min_gap >= -tol);  // else the analytic method missed it
               RC_TAG("hit: a touch within tolerance, analytic says none");
               return;
             }
             const Reference same_contact(seed_tol + tol);
             if (a.time <= s.time) {
               RC_TAG(stays_within(q, a.time, s.time, same_contact) ? "hit: the analytic contact"
                      : at_wall_end(a.feature)                         ? "late: a round end was hit first"
                                                                       : "late: an earlier face contact missed");
               return;
             }
             RC_ASSERT(stays_within(q, s.time, a.time, same_contact));  // else the analytic contact is too late
             RC_TAG("hit: the analytic contact");
           });
}

// ------------------------------------------------------------------------
// Fixed mode on values built from raw Q63.64 bits: tiny worlds whose
// coordinates sit a few ulps (2^-64) from grid values, accelerations and
// speeds a few ulps from zero (a quadratic coefficient almost 0), and huge
// worlds near the top of the range, where overflow must be refused, never
// wrapped into a wrong answer.

namespace {

enum class RawFamily { tiny_nudged, near_zero_coefficients, huge, micro_short_horizon };

const char* family_name(RawFamily f) {
  switch (f) {
    case RawFamily::tiny_nudged: return "small world (lengths times 2^-18..2^-5), coordinates nudged by raw ulps";
    case RawFamily::near_zero_coefficients: return "accelerations and speeds a few ulps from 0";
    case RawFamily::huge: return "huge world (2^16..2^56)";
    case RawFamily::micro_short_horizon: return "micro world (2^-22..2^-12), speeds and accelerations O(1), short horizon";
  }
  return "?";
}

ToiQuery raw_bits_query(RawFamily family) {
  ToiQuery q = random_valid_query(false);
  if (family == RawFamily::huge) {
    scale_lengths(q, *rc::gen::inRange(16, 57));
    return q;
  }
  if (family == RawFamily::micro_short_horizon) {
    // Lengths and the horizon shrink by 2^-k, speeds stay as they were
    // (the same motion seen over a short time), accelerations too: the
    // products the solver forms from O(1) speeds and accelerations must
    // stay in range when it scales tiny lengths up (found in review).
    const int k = *rc::gen::inRange(12, 23);
    const ToiQuery original = q;
    scale_lengths(q, -k);
    for (auto [b, o] : {std::pair{&q.ball, &original.ball}, std::pair{&q.other, &original.other}}) {
      b->velocity = o->velocity;
      b->acceleration = o->acceleration;
    }
    q.horizon = std::ldexp(q.horizon, -k);
    return q;
  }
  // Small: a wall's quadratic has coefficients of degree 2 in lengths (|d|
  // times a distance) and its discriminant degree 4, so at lengths ~2^-16
  // the discriminant would be a few ulps of 2^-64 had the solver not scaled
  // the quadratic up first (normalise_quadratic, quadratic.hpp); scales down
  // to 2^-18 check that it does. Below 2^-11 every Fixed is a double, so
  // nudges of small coordinates and speeds survive the trip to the oracle;
  // larger ones move by 2^k ulps.
  scale_lengths(q, *rc::gen::inRange(-18, -5));
  for (BallState<double>* b : {&q.ball, &q.other}) {
    const bool moving = b == &q.ball || !(b->velocity == V{}) || !(b->acceleration == V{});
    if (family == RawFamily::tiny_nudged) {
      b->position = {nudged_by_raw_ulps(b->position.x), nudged_by_raw_ulps(b->position.y)};
      if (moving) b->velocity = {nudged_by_raw_ulps(b->velocity.x), nudged_by_raw_ulps(b->velocity.y)};
    } else if (moving) {
      if (*rc::gen::arbitrary<bool>()) b->acceleration = {few_ulps_from_zero(), few_ulps_from_zero()};
      if (*rc::gen::arbitrary<bool>()) b->velocity.x = few_ulps_from_zero();
    }
  }
  if (family == RawFamily::tiny_nudged)
    q.wall = {{nudged_by_raw_ulps(q.wall.a.x), nudged_by_raw_ulps(q.wall.a.y)}, q.wall.b};
  return q;
}

}  // namespace

TEST_CASE("properties: analytic fixed time of impact on raw-bit values", "[toi][property][oracle][fixed]") {
  // The acceptance rule (tol: the derived fixed bound, fixed_toi_bound.hpp)
  // on values a few raw ulps from interesting ones; overflow refused, and
  // only in huge worlds.
  check_property("analytic time of impact on raw-bit values, overflow refused", "fixed",
                 [] {
             const auto family = *rc::gen::element(RawFamily::tiny_nudged, RawFamily::near_zero_coefficients,
                                                   RawFamily::huge, RawFamily::micro_short_horizon);
             const ToiQuery q = raw_bits_query(family);
             RC_PRE(q.kind != QueryKind::ball_wall || !(q.wall.a == q.wall.b));
             RC_PRE(oracle_gap_at(q, Reference(0)) > 0);
             RC_LOG() << family_name(family) << ": " << describe(q) << "\n";
             QueryAnswer a;
             try {
               a = answer_toi_query(q, ToiMethod::analytic, NumberMode::fixed, 1e-9);
             } catch (const FixedPointOverflow& e) {
               RC_TAG(family_name(family), "overflow refused");
               RC_ASSERT(family == RawFamily::huge);
               return;
             }
             // The derived bound (fixed_toi_bound.hpp): where it exceeds 1e-10
             // of the scale (motions a few ulps from zero, where the closed
             // forms' leading coefficients vanish) the acceptance rule would
             // claim next to nothing: discarded, named, not passed.
             const double rel = fixed_toi_gap_bound(q) / oracle_detail::scale_of(q);
             if (rel > 1e-10) discard_not_applicable("the derived fixed bound is above 1e-10 of the scale (a degenerate motion)");
             const Verdict v = judge_toi_answer(q, a.hit, a.t, rel);
             RC_TAG(family_name(family), a.hit ? "hit" : "no hit", bound_tag(rel));
             RC_LOG() << v.why << "\n";
             RC_ASSERT(v.ok);
           });
}
