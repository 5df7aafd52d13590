// No overlap and no tunnelling, on the continuous motion (scene_checks.hpp).
//
// Between two consecutive pieces (engine_trace.hpp) every ball moves on
// p + v τ + ½ a τ². For a pair of balls (or a ball and a wall) on a
// sub-interval [s, s + h], the motion relative to the other is the chord
// c(τ) = P + V τ plus ½ A τ², |½ A τ²| ≤ ½ |A| h². The distance to a convex
// set (a disk's centre, a segment) is 1-Lipschitz, so
//     min gap over [s, s+h] ≥ min over the chord − ½ |A| h² − R,
// and the chord's minimum is closed form (point–segment, segment–segment).
// If that lower bound is ≥ −tolerance the sub-interval is clear; if the true
// gap at a sample is < −tolerance it is a violation; otherwise it is halved
// (at most 48 times; an undecided sliver that deep, 2^-48 of a piece, is
// counted, not failed).
// A ball that went through a wall met it on the way, so this is also the
// tunnelling check.
//
// Tolerance, from the scene and never from the engine (not its rest height,
// not its creep allowance: a bound taken from them loosens with them; with
// the rest height set to 0.5 r_min, Abound overlapped by 0.031 and this
// check, then bounded by that rest height, still passed):
//  - 1e-6 r_min (r_min the smallest radius of the scene), written here: as
//    deep as any rule of the engine (a contact left a hair inside, creep, a
//    ball resting on a support) may sink one object into another, 1e-6 of
//    the smallest object, far below anything visible or physical;
//  - a contact time is a rounded root and the positions at it are rounded:
//    strict, the gap is off by a few ulp of the numbers it is formed from
//    (coordinates up to P, and the distance travelled): 64 eps (P + r_max);
//    fixed, 2^-64 resolution per operation and a long double evaluation here
//    (64 bits: 2^-64 relative of the same sizes): 64·2^-64 (1 + P + r_max).
//    P is the largest coordinate the run held (scene_scales.hpp): the size
//    of the numbers rounded, measured on the motion, not a rule's allowance.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "check_support.hpp"
#include "scene_checks.hpp"
#include "scene_scales.hpp"

namespace collide2d::properties {
namespace {

using LD = long double;
struct V2 {
  LD x = 0, y = 0;
};
V2 operator+(V2 a, V2 b) { return {a.x + b.x, a.y + b.y}; }
V2 operator-(V2 a, V2 b) { return {a.x - b.x, a.y - b.y}; }
V2 operator*(LD s, V2 a) { return {s * a.x, s * a.y}; }
LD dot(V2 a, V2 b) { return a.x * b.x + a.y * b.y; }
LD cross(V2 a, V2 b) { return a.x * b.y - a.y * b.x; }
LD norm(V2 a) { return std::hypot(a.x, a.y); }

LD point_segment(V2 p, V2 a, V2 b) {
  const V2 d = b - a;
  const LD dd = dot(d, d);
  const LD s = dd > 0 ? std::clamp(dot(p - a, d) / dd, LD(0), LD(1)) : LD(0);
  return norm(p - (a + s * d));
}

LD segment_segment(V2 a, V2 b, V2 c, V2 d) {
  const LD d1 = cross(b - a, c - a), d2 = cross(b - a, d - a), d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 0;
  return std::min({point_segment(a, c, d), point_segment(b, c, d), point_segment(c, a, b), point_segment(d, a, b)});
}

// The relative motion on one sub-interval: q(τ) = P + V τ + ½ A τ², τ ∈ [0, h],
// against a target: a point (another centre, at the origin) or the segment
// from the origin to D (a wall, relative to its end a).
struct RelativeMotion {
  V2 P, V, A;
  bool wall = false;
  V2 D;
  LD R = 0;  // contact distance
  V2 at(LD t) const { return P + t * V + (t * t / 2) * A; }
  LD gap(V2 q) const { return (wall ? point_segment(q, {}, D) : norm(q)) - R; }
};

struct Verdict {
  bool overlap = false;
  LD deepest = 0, when = 0;
  int undecided = 0;
};

// Lower bound of the gap over [t0, t0 + h] and a witness, recursively.
void scan(const RelativeMotion& m, LD t0, LD h, LD tolerance, int depth, Verdict& v) {
  const V2 q0 = m.at(t0), q1 = m.at(t0 + h);
  // The chord of this sub-interval: from q0 along the velocity at t0.
  const V2 vel = m.V + t0 * m.A;
  const V2 end = q0 + h * vel;
  LD chord = 0;
  if (m.wall) {
    chord = segment_segment(q0, end, {}, m.D);
  } else {
    const LD vv = dot(vel, vel);
    const LD s = vv > 0 ? std::clamp(-dot(q0, vel) / vv, LD(0), h) : LD(0);
    chord = norm(q0 + s * vel);
  }
  const LD lower = chord - norm(m.A) * h * h / 2 - m.R;
  if (lower >= -tolerance) return;
  for (const auto& [t, q] : {std::pair{t0, q0}, std::pair{t0 + h, q1}, std::pair{t0 + h / 2, m.at(t0 + h / 2)}}) {
    const LD g = m.gap(q);
    if (g < -tolerance && g < v.deepest) {
      v.overlap = true;
      v.deepest = g;
      v.when = t;
    }
  }
  if (v.overlap) return;
  if (depth >= 48) {
    ++v.undecided;
    return;
  }
  scan(m, t0, h / 2, tolerance, depth + 1, v);
  scan(m, t0 + h / 2, h / 2, tolerance, depth + 1, v);
}

template <class Num>
LD ld(const Num& x) { return to_long_double(x); }
template <class Num>
V2 ld(const Vec2<Num>& a) { return {ld(a.x), ld(a.y)}; }

// Walks two piece lists (b may be null: a wall) over their common
// sub-intervals and scans each; `relative` builds the motion of one.
template <class Num, class Relative>
std::optional<std::string> walk(const std::vector<MotionPiece<Num>>& a, const std::vector<MotionPiece<Num>>* b, const Num& end,
                                LD tolerance, std::int64_t& skipped, Relative relative, const std::string& what) {
  std::size_t i = 0, j = 0;
  Num t = a.front().body.time;
  if (b && t < b->front().body.time) t = b->front().body.time;
  while (t < end) {
    while (i + 1 < a.size() && !(t < a[i + 1].body.time)) ++i;
    if (b) while (j + 1 < b->size() && !(t < (*b)[j + 1].body.time)) ++j;
    Num next = end;
    if (i + 1 < a.size() && a[i + 1].body.time < next) next = a[i + 1].body.time;
    if (b && j + 1 < b->size() && (*b)[j + 1].body.time < next) next = (*b)[j + 1].body.time;
    const Body<Num>* other = b ? &(*b)[j].body : nullptr;
    const RelativeMotion m = relative(a[i].body, other, t);
    Verdict v;
    scan(m, 0, ld(Num(next - t)), tolerance, 0, v);
    if (v.overlap)
      return what + " overlap by " + g17(-v.deepest) + " (tolerance " + g17(tolerance) + ") at t = " +
             g17(ld(t) + v.when) + ", in the motion from t = " + g17(ld(t)) + " to " + g17(ld(next));
    skipped += v.undecided;
    t = next;
  }
  return std::nullopt;
}

// Every stretch of every path is walked: the trace sees every change of
// motion the engine makes (engine_trace.hpp), and a change it did not see
// fails the check (trace_failure) rather than leaving a stretch unknown.
template <class Num>
CheckResult no_overlap(const Scene& scene, double duration) {
  const EngineTrace<Num> trace = trace_engine<Num>(scene, duration);
  if (auto failure = trace_failure(trace)) return failure;
  const RunScales s = scales_of(scene, trace);
  double r_max = 0, r_min = std::numeric_limits<double>::infinity();
  for (const BallSpec& b : scene.balls) r_max = std::max(r_max, b.radius), r_min = std::min(r_min, b.radius);
  const LD rounding = std::is_same_v<Num, double> ? 64 * strict_eps * (s.position + r_max)
                                                  : 64 * fixed_resolution * (1 + s.position + r_max);
  // From the scene, never from the engine: 1e-6 of the smallest radius (above).
  const LD tolerance = 1e-6L * r_min + rounding;
  std::int64_t skipped = 0, judged = 0;  // stretches skipped; pairs (ball–ball, ball–wall) walked
  const auto& pieces = trace.pieces;
  // The state of body x carried from its clock to time t (τ from there):
  // position relative to a reference point `origin`, formed in Num first
  // (exact in fixed; exact in strict when the two are close, Sterbenz).
  auto motion_of = [](const Body<Num>& x, const Num& t, const Vec2<Num>& origin, V2& P, V2& V, V2& A) {
    const LD tau = ld(Num(t - x.time));
    const V2 v = ld(x.velocity), a = ld(x.acceleration);
    P = ld(Vec2<Num>(x.position - origin)) + tau * v + (tau * tau / 2) * a;
    V = v + tau * a;
    A = a;
    if (x.fixed) V = A = {};
  };
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (std::size_t j = i + 1; j < pieces.size(); ++j) {
      if (scene.balls[i].fixed && scene.balls[j].fixed) continue;
      ++judged;
      auto relative = [&](const Body<Num>& x, const Body<Num>* y, const Num& t) {
        RelativeMotion m;
        V2 Px, Vx, Ax, Py, Vy, Ay;
        motion_of(x, t, y->position, Px, Vx, Ax);
        motion_of(*y, t, y->position, Py, Vy, Ay);
        m.P = Px - Py, m.V = Vx - Vy, m.A = Ax - Ay;
        m.R = ld(x.radius) + ld(y->radius);
        return m;
      };
      if (auto r = walk<Num>(pieces[i], &pieces[j], trace.end, tolerance, skipped, relative,
                             "balls " + std::to_string(i) + " and " + std::to_string(j)))
        return r;
    }
    if (scene.balls[i].fixed) continue;
    for (std::size_t w = 0; w < scene.walls.size(); ++w) {
      ++judged;
      const WallSpec& wall = scene.walls[w];
      const Vec2<Num> wa = vec2_from_double<Num>(wall.a[0], wall.a[1]), wb = vec2_from_double<Num>(wall.b[0], wall.b[1]);
      auto relative = [&](const Body<Num>& x, const Body<Num>*, const Num& t) {
        RelativeMotion m;
        motion_of(x, t, wa, m.P, m.V, m.A);
        m.wall = true;
        m.D = ld(Vec2<Num>(wb - wa));
        m.R = ld(x.radius);
        return m;
      };
      if (auto r = walk<Num>(pieces[i], nullptr, trace.end, tolerance, skipped, relative,
                             "ball " + std::to_string(i) + " and wall " + std::to_string(w)))
        return r;
    }
  }
  if (judged == 0) throw NotApplicable("nothing to overlap: no pair of balls not both fixed, no moving ball with a wall");
  return std::nullopt;
}

}  // namespace

CheckResult check_no_overlap(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) { return no_overlap<decltype(zero)>(scene, duration); });
}

}  // namespace collide2d::properties
