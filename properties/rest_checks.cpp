// Energy never rises, piles come to rest, a dropped ball wakes a resting pile
// with momentum kept (scene_checks.hpp).
//
// Every bound here is taken from the scene (its radii, masses, accelerations,
// positions, speeds and restitutions) and written in this file, never from
// the engine: not its rest thresholds (h_rest, v_rest, the contact band), not
// its counters (how often a rule acted). An engine that changes its own rules
// cannot loosen these checks. The runs go through simulate<Num>()
// (src/collide2d/sim/simulate.hpp): its frames and its events, nothing else; the wake
// check also reads the collision states of engine_trace.hpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "check_support.hpp"
#include "cone.hpp"
#include "engine_trace.hpp"
#include "scene_checks.hpp"
#include "scene_scales.hpp"

namespace collide2d::properties {
namespace {

using LD = long double;

// The constants of the bounds below, each explained where it is used.
constexpr double overlap_fraction = 1e-6;     // of r_min: the deepest overlap allowed
constexpr double energy_rise_fraction = 1e-12;  // of the energy scale S: the largest rise between frames
constexpr double exchange_factor = 4;         // T_rest = t_fall + 4 t*
constexpr double rest_window = 2;             // seconds: the window the rest rate is counted over
constexpr double rest_rate = 1;               // events per moving ball per simulated second, in that window
constexpr double budget_factor = 256;         // events per ball per bounce series (the run's stop)
constexpr double near_wall_fraction = 1e-3;   // of r_min: a struck ball this close to a wall touches it

std::string where_ball(std::size_t i) { return "balls[" + std::to_string(i) + "]"; }

// The largest restitution of the scene: its default, every ball's (fixed
// ones too) and every wall's, with where it is.
double largest_restitution(const Scene& scene, std::string& where) {
  double e = scene.restitution;
  where = "the scene's default restitution";
  for (std::size_t i = 0; i < scene.balls.size(); ++i)
    if (scene.balls[i].restitution > e) e = scene.balls[i].restitution, where = where_ball(i) + ".restitution";
  for (std::size_t w = 0; w < scene.walls.size(); ++w)
    if (scene.walls[w].restitution > e) e = scene.walls[w].restitution, where = "walls[" + std::to_string(w) + "].restitution";
  return e;
}

// The point of wall w nearest to (px, py), and its distance.
Vec2<LD> nearest_on_wall(LD px, LD py, const WallSpec& w) {
  const LD ax = w.a[0], ay = w.a[1], dx = LD(w.b[0]) - ax, dy = LD(w.b[1]) - ay;
  const LD dd = dx * dx + dy * dy;
  const LD s = dd > 0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / dd, LD(0), LD(1)) : LD(0);
  return {ax + s * dx, ay + s * dy};
}
LD point_segment(LD px, LD py, const WallSpec& w) {
  const Vec2<LD> q = nearest_on_wall(px, py, w);
  return std::hypot(px - q.x, py - q.y);
}

// The sizes of the numbers a scene's run is made of, from the scene alone.
struct SceneSize {
  double X = 0;      // largest |coordinate| of a wall end or a centre, plus r_max
  double D = 0;      // largest side of the bounding box of wall ends and centres, plus 2 r_max
  double r_min = std::numeric_limits<double>::infinity(), r_max = 0;
  double wall_max = 0;  // longest wall
};

SceneSize size_of(const Scene& scene) {
  SceneSize s;
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  auto take = [&](const Point& p) {
    for (int k = 0; k < 2; ++k) {
      s.X = std::max(s.X, std::fabs(p[k]));
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  };
  for (const WallSpec& w : scene.walls) {
    take(w.a), take(w.b);
    s.wall_max = std::max(s.wall_max, std::hypot(w.b[0] - w.a[0], w.b[1] - w.a[1]));
  }
  for (const BallSpec& b : scene.balls) {
    take(b.position);
    s.r_min = std::min(s.r_min, b.radius);
    s.r_max = std::max(s.r_max, b.radius);
  }
  if (!std::isfinite(s.r_min)) s.r_min = 0;
  s.X += s.r_max;
  if (lo[0] <= hi[0]) s.D = std::max(hi[0] - lo[0], hi[1] - lo[1]) + 2 * s.r_max;
  return s;
}

// The energy scale S of a scene, from its own masses, accelerations,
// positions and speeds:
//     S = Σ over moving balls of m (½ V² + |a| X),   V² = max |v0|² + 2 A D,
// X the largest |coordinate| of the scene (wall ends, centres; + r_max), D the
// largest side of its bounding box (+ 2 r_max), A the largest |a|, v0 the
// initial velocities. E = Σ m (½ |v|² − a·p) is a sum of terms of sizes
// ½ m |v|² and m |a| |p|: a ball that falls across the scene gains at most
// 2 A D of |v|² (more only from another ball, by a factor of a few for the
// masses generated), and |p| stays within X while the scene holds it. The
// translation counts: a·p is formed from the absolute coordinates, so their
// size (X, not the scene's width) is what its rounding is relative to. S is
// a scale, not a bound on the motion: a factor of a few either way changes
// nothing below (the bound has 10^4 to spare over rounding).
double energy_scale(const Scene& scene) {
  const SceneSize z = size_of(scene);
  double A = 0, v2 = 0;
  for (const BallSpec& b : scene.balls) {
    if (b.fixed) continue;
    const Point a = effective_acceleration(scene, b);
    A = std::max(A, std::hypot(a[0], a[1]));
    v2 = std::max(v2, b.velocity[0] * b.velocity[0] + b.velocity[1] * b.velocity[1]);
  }
  const double V2 = v2 + 2 * A * z.D;
  double S = 0;
  for (const BallSpec& b : scene.balls) {
    if (b.fixed) continue;
    const Point a = effective_acceleration(scene, b);
    S += b.mass * (V2 / 2 + std::hypot(a[0], a[1]) * z.X);
  }
  return S;
}

// Deepest overlap at a frame (ball–ball r_i + r_j − |p_i − p_j|, ball–wall
// r − distance to the segment, round ends included), with where; 0 if none.
// Pairs swept in order of x − r (only x-overlapping pairs are measured).
struct FrameOverlap {
  LD depth = 0;
  std::string what;
};
FrameOverlap deepest_at(const FrameRecord& f, const Scene& scene) {
  FrameOverlap o;
  const std::size_t n = scene.balls.size();
  auto x = [&](std::size_t i) { return LD(f.position[2 * i]); };
  auto y = [&](std::size_t i) { return LD(f.position[2 * i + 1]); };
  auto r = [&](std::size_t i) { return LD(scene.balls[i].radius); };
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return x(i) - r(i) < x(j) - r(j); });
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k];
    for (std::size_t l = k + 1; l < n && x(order[l]) - r(order[l]) < x(i) + r(i); ++l) {
      const std::size_t j = order[l];
      const LD depth = r(i) + r(j) - std::hypot(x(i) - x(j), y(i) - y(j));
      if (depth > o.depth) o = {depth, "balls " + std::to_string(std::min(i, j)) + " and " + std::to_string(std::max(i, j))};
    }
    for (std::size_t w = 0; w < scene.walls.size(); ++w) {
      const LD depth = r(i) - point_segment(x(i), y(i), scene.walls[w]);
      if (depth > o.depth) o = {depth, "ball " + std::to_string(i) + " and wall " + std::to_string(w)};
    }
  }
  return o;
}

// The no-overlap tolerance at frames: 1e-6 r_min (the depth the checks allow
// any contact, written here: motion_checks.cpp uses the same) plus the
// rounding of a gap formed in doubles from coordinates up to X (frames are
// doubles in both modes): 64 eps (X + r_max).
LD frame_overlap_tolerance(const SceneSize& z) {
  return overlap_fraction * z.r_min + 64 * strict_eps * (z.X + z.r_max);
}

// Thrown from a frame or event callback to stop a run whose verdict is in.
struct Stop {};


// ---------------------------------------------------------------------------
// Pile bounds (PileBounds, scene_checks.hpp). A scene settles when every
// moving ball is under an acceleration, some wall lies below every ball
// (along the ball's own acceleration) and every restitution is below 1. Then,
// from the scene alone:
//  - fall: ball i starts H_i = max over wall ends q of â_i·(q − p_i) − r_i
//    above the lowest wall point along â_i = a_i / |a_i| (a segment's lowest
//    point along a direction is one of its ends), at speed |v_i|. It arrives
//    there no faster than V_i = sqrt(|v_i|² + 2 |a_i| H_i), within
//    t_i = (|v_i| + V_i) / |a_i| (the slowest start is straight up).
//    V = max V_i, t_fall = max t_i, g = min |a_i|.
//  - bounce series: a ball striking at ≤ V with restitution ≤ e (the largest
//    restitution in the scene: a contact's is a product of two restitutions,
//    each ≤ e ≤ 1) rebounds at ≤ e V and flies ≤ 2 e V / g before its next
//    bounce, then ≤ 2 e² V / g, ...: the whole series, summed to its end,
//        t* = Σ_{k≥1} 2 e^k V / g = 2 e V / (g (1 − e)).
//    (On a face tilted by θ the flight is 1/cos θ longer: θ ≤ 27° for the
//    generated slopes ≤ 1/2, 12 %, inside the factor below.)
//  - ball–ball exchanges: a ball landing on another restarts the other's
//    series, but every exchange dissipates too (e < 1), and no series starts
//    faster than V. A stated, generous factor 4 for the exchanges:
//        T_rest = t_fall + 4 t*.
//  - rest window: over [T_rest, T_rest + 2 s] a pile at rest makes no events;
//    the check allows one per moving ball per simulated second (2 N in all),
//    far more than rest needs (none) and far fewer than chatter makes (a ball
//    hopping 1e-6 r on another bounces thousands of times a second).
//  - event budget, a stop for CI time (part of the claim: a settling pile
//    needs far fewer): a lone ball's series from V down to the speed
//    v_rest = sqrt(2 g · 1e-6 r_min) that rises 1e-6 r_min (the overlap
//    scale of these checks) is k = ⌈ln(V / v_rest) / ln(1 / e)⌉ bounces. A
//    run making more than 256 N (k + 2) events (256 whole series per ball),
//    plus one per ball per second after T_rest, is stopped and fails: it is
//    chattering, and running it on would only take longer to say so.
std::optional<PileBounds> pile_bounds_or_why(const Scene& scene, std::string& why) {
  PileBounds p;
  std::string where;
  p.e = largest_restitution(scene, where);
  if (!(p.e < 1)) {
    why = "restitution " + g17(p.e) + " at " + where + " (an elastic bounce series never ends)";
    return std::nullopt;
  }
  if (scene.walls.empty()) {
    why = "no walls";
    return std::nullopt;
  }
  const SceneSize z = size_of(scene);
  p.r_min = z.r_min;
  p.g = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < scene.balls.size(); ++i) {
    const BallSpec& b = scene.balls[i];
    if (b.fixed) continue;
    ++p.moving;
    const Point a = effective_acceleration(scene, b);
    const double A = std::hypot(a[0], a[1]);
    if (!(A > 0)) {
      why = where_ball(i) + " moves under no acceleration";
      return std::nullopt;
    }
    double H = -std::numeric_limits<double>::infinity();
    for (const WallSpec& w : scene.walls)
      for (const Point& q : {w.a, w.b})
        H = std::max(H, (a[0] * (q[0] - b.position[0]) + a[1] * (q[1] - b.position[1])) / A - b.radius);
    if (!(H >= 0)) {
      why = "no wall below " + where_ball(i);
      return std::nullopt;
    }
    const double v = std::hypot(b.velocity[0], b.velocity[1]);
    const double V = std::sqrt(v * v + 2 * A * H);
    p.impact_speed = std::max(p.impact_speed, V);
    p.fall_time = std::max(p.fall_time, (v + V) / A);
    p.g = std::min(p.g, A);
  }
  if (p.moving == 0) {
    why = "no moving ball";
    return std::nullopt;
  }
  p.series_time = 2 * p.e * p.impact_speed / (p.g * (1 - p.e));
  p.rest_speed = std::sqrt(2 * p.g * overlap_fraction * p.r_min);
  p.bounces = p.impact_speed > p.rest_speed && p.e > 0
                  ? std::ceil(std::log(p.impact_speed / p.rest_speed) / std::log(1 / p.e))
                  : 0;
  p.settle_time = p.fall_time + exchange_factor * p.series_time;
  p.window = rest_window;
  return p;
}

std::string pile_figures(const PileBounds& p) {
  return "T_rest = t_fall + 4 t* = " + g17(p.fall_time) + " + 4 * " + g17(p.series_time) + " = " + g17(p.settle_time) +
         " s (V = " + g17(p.impact_speed) + ", e = " + g17(p.e) + ", g = " + g17(p.g) + ", " + std::to_string(p.moving) +
         " moving balls)";
}

PileBounds require_pile(const Scene& scene) {
  std::string why;
  const std::optional<PileBounds> p = pile_bounds_or_why(scene, why);
  if (!p) throw NotApplicable("not a settling scene: " + why);
  return *p;
}

// Counts the events at the latest event time: a long run of them is a stall
// (time does not advance), which the budget message names.
struct SameTime {
  double time = -1;
  std::int64_t count = 0;
  void see(double t) { count = t == time ? count + 1 : 1, time = t; }
  std::string text() const {
    return count > 1 ? " (the last " + std::to_string(count) + " of them all at t = " + g17(time) + ": a stall)" : "";
  }
};

std::string budget_text(const PileBounds& p, std::int64_t budget, const SameTime& last) {
  return "stopped after " + std::to_string(budget) + " events at t = " + g17(last.time) + last.text() +
         ": the budget of this settling scene, " +
         g17(budget_factor) + " bounce series of k = " + g17(p.bounces) + " bounces per moving ball (V = " +
         g17(p.impact_speed) + " down to v_rest = " + g17(p.rest_speed) + ", e = " + g17(p.e) +
         "), plus one event per ball per second after T_rest = " + g17(p.settle_time) + " s: the pile is not settling";
}

// ---------------------------------------------------------------------------
// Energy never rises.
//
// Claim: in a scene where every restitution (the default, every ball's and
// every wall's) is below 1, the total energy of the moving balls,
// E = Σ ½ m|v|² − m a·p (a the ball's own acceleration or gravity, as the
// frames compute it), never rises from one frame to the next by more than
//     1e-12 S     (S the energy scale, energy_scale above).
// Exact motion keeps E along a parabola; every collision with e < 1 takes
// energy out (½ (1 − e²) μ v_n² for a pair, μ the reduced mass); a rule that
// ends a bounce series may take energy out but may not put any in.
// Rounding, strict: a frame's E is a sum of N terms, each formed to a few eps
// of its own m (½|v|² + |a||p|) ≤ its share of S, so two frames differ by
// rounding by ≲ 2 (N + 3) eps S ≤ 1e-13 S for N ≤ 200. Between frames each
// step (a ball carried to a new clock, a response) moves that ball's energy
// by ≤ 4 eps of its share (physics_checks.cpp, energy-kept): 1e-12 S allows
// ~10^3 such steps per frame on the largest share even if none dissipated,
// and here nearly every collision dissipates far more than it rounds (a
// graze, the exception, dissipates nothing and rounds nothing).
// Fixed: 2^-64 absolute per operation, far below 1e-12 S; but the unit
// normal of a contact is off by δn ≤ 8·2^-64 (1 + 1/r_min² + L)
// (scene_scales.hpp, L the longest wall or diameter), which turns a
// reflected velocity and moves its kinetic energy by ~2 δn of itself. The
// claim is made in fixed mode only where δn ≤ 1e-13 (r_min ≳ 2^-9 for the
// scenes generated): elsewhere fixed point itself rounds coarser than the
// claim, and the case is NotApplicable (a discard), never a pass.
// A settling scene (pile_bounds) whose run makes more events than its budget
// is stopped and fails (see above).
template <class Num>
CheckResult energy_never_rises(const Scene& scene, double duration) {
  std::string where;
  const double e = largest_restitution(scene, where);
  if (!(e < 1))
    throw NotApplicable("restitution " + g17(e) + " at " + where +
                        ": an elastic contact keeps energy only to rounding, event after event");
  const SceneSize z = size_of(scene);
  if constexpr (!std::is_same_v<Num, double>) {
    const double dn = 8 * fixed_resolution * (1 + 1 / (z.r_min * z.r_min) + std::max(z.wall_max, 2 * z.r_max));
    if (dn > 1e-13)
      throw NotApplicable("fixed mode: unit normals round by up to " + g17(dn) + " (r_min " + g17(z.r_min) +
                          "), coarser than the 1e-12 claim");
  }
  const double S = energy_scale(scene);
  const double bound = energy_rise_fraction * S;
  std::string not_pile;
  const std::optional<PileBounds> pile = pile_bounds_or_why(scene, not_pile);
  const std::int64_t budget = pile ? pile->event_budget(duration) : std::numeric_limits<std::int64_t>::max();
  CheckResult failure;
  bool first = true;
  double previous = 0, previous_time = 0;
  std::int64_t frame = 0, events = 0;
  SameTime last;
  try {
    simulate<Num>(
        scene, duration,
        [&](const FrameRecord& f) {
          if (!first && f.energy - previous > bound) {
            failure = "energy rose by " + g17(f.energy - previous) + " (" + g17((f.energy - previous) / S) +
                      " of the energy scale S = " + g17(S) + "; bound 1e-12 S = " + g17(bound) + ") from frame " +
                      std::to_string(frame - 1) + " (t = " + g17(previous_time) + ", E = " + g17(previous) +
                      ") to frame " + std::to_string(frame) + " (t = " + g17(f.time) + ", E = " + g17(f.energy) +
                      "); " + std::to_string(events) + " events so far; largest restitution " + g17(e);
            throw Stop{};
          }
          first = false;
          previous = f.energy;
          previous_time = f.time;
          ++frame;
        },
        [&](const EventRecord& ev) {
          last.see(ev.time);
          if (++events > budget) {
            failure = budget_text(*pile, budget, last) + "; the energy never rose by more than 1e-12 S up to t = " +
                      g17(previous_time);
            throw Stop{};
          }
        });
  } catch (const Stop&) {
  }
  return failure;
}

// ---------------------------------------------------------------------------
// A pile comes to rest (pile bounds above): run to until = max(duration,
// T_rest + 2 s); over [until − 2 s, until] at most one event per moving ball
// per simulated second; at every frame no overlap deeper than 1e-6 r_min +
// 64 eps (X + r_max) (frame_overlap_tolerance); the run within its budget.
struct PileRun {
  std::optional<std::string> failure;
  std::int64_t events = 0, in_window = 0;
  double window_from = 0, until = 0;
  FrameRecord last;
};

template <class Num>
PileRun run_pile(const Scene& scene, const PileBounds& p, double duration, bool check_overlap) {
  PileRun run;
  run.until = std::max(duration, p.until());
  run.window_from = run.until - p.window;
  const std::int64_t budget = p.event_budget(run.until);
  const SceneSize z = size_of(scene);
  const LD tolerance = frame_overlap_tolerance(z);
  SameTime last;
  try {
    simulate<Num>(
        scene, run.until,
        [&](const FrameRecord& f) {
          if (check_overlap) {
            const FrameOverlap o = deepest_at(f, scene);
            if (o.depth > tolerance) {
              run.failure = o.what + " overlap by " + g17(o.depth) + " (" + g17(o.depth / z.r_min) +
                            " r_min) at the frame t = " + g17(f.time) + ", more than 1e-6 r_min + rounding = " +
                            g17(tolerance);
              throw Stop{};
            }
          }
          run.last = f;
        },
        [&](const EventRecord& ev) {
          last.see(ev.time);
          if (++run.events > budget) {
            run.failure = budget_text(p, budget, last);
            throw Stop{};
          }
          if (ev.time >= run.window_from) ++run.in_window;
        });
  } catch (const Stop&) {
  }
  return run;
}

// How many events the rest window allows: one per moving ball per second.
std::int64_t window_allowance(const PileBounds& p) {
  return static_cast<std::int64_t>(std::floor(rest_rate * p.moving * p.window));
}

std::string rest_verdict(const PileBounds& p, const PileRun& run) {
  return std::to_string(run.in_window) + " events in the last " + g17(p.window) + " s (t from " + g17(run.window_from) +
         " to " + g17(run.until) + "), more than one per moving ball per second (" + std::to_string(window_allowance(p)) +
         "); " + pile_figures(p) + "; " + std::to_string(run.events) + " events in all";
}

// Every ball lying still at the end of the run (velocity exactly zero) is
// in equilibrium: frictionless contacts push along their normals only, so
// −a (a its acceleration) lies in the cone of the normals of the walls and
// balls touching it (within 1e-3 r_min, as in the wake check; more normals
// only widen the cone). The normals come from frame positions (doubles),
// each good to eps |p| / 1e-3 r_min in direction; 1e-6 of |a| is far above
// that and far below a support missing (a ball on a slope of 1/8 misses the
// cone by 1/8 of |a|).
CheckResult still_balls_supported(const Scene& scene, const FrameRecord& f) {
  const SceneSize z = size_of(scene);
  const LD near = near_wall_fraction * z.r_min;
  for (std::size_t i = 0; i < scene.balls.size(); ++i) {
    const BallSpec& b = scene.balls[i];
    if (b.fixed || f.velocity[2 * i] != 0 || f.velocity[2 * i + 1] != 0) continue;
    const Point a = effective_acceleration(scene, b);
    const LD g = std::hypot(LD(a[0]), LD(a[1]));
    if (g == 0) continue;
    const LD px = f.position[2 * i], py = f.position[2 * i + 1];
    std::vector<Vec2<LD>> normals;
    for (const WallSpec& w : scene.walls) {
      const Vec2<LD> q = nearest_on_wall(px, py, w);
      const LD d = std::hypot(px - q.x, py - q.y);
      if (d > 0 && d - b.radius <= near) normals.push_back({(px - q.x) / d, (py - q.y) / d});
    }
    for (std::size_t j = 0; j < scene.balls.size(); ++j) {
      if (j == i) continue;
      const LD dx = px - LD(f.position[2 * j]), dy = py - LD(f.position[2 * j + 1]);
      const LD d = std::hypot(dx, dy);
      if (d > 0 && d - b.radius - scene.balls[j].radius <= near) normals.push_back({dx / d, dy / d});
    }
    const LD miss = distance_to_cone({-a[0] / g, -a[1] / g}, normals);
    if (miss > 1e-6L)
      return where_ball(i) + " lies still at (" + g17(px) + ", " + g17(py) + ") at t = " + g17(f.time) + " with " +
             std::to_string(normals.size()) + " supports that cannot carry it: its weight misses their cone by " +
             g17(miss) + " of |a|";
  }
  return std::nullopt;
}

template <class Num>
CheckResult pile_comes_to_rest(const Scene& scene, double duration) {
  const PileBounds p = require_pile(scene);
  const PileRun run = run_pile<Num>(scene, p, duration, true);
  if (run.failure) return run.failure;
  if (run.in_window > window_allowance(p)) return "not at rest: " + rest_verdict(p, run);
  return still_balls_supported(scene, run.last);
}

// ---------------------------------------------------------------------------
// A dropped ball wakes a resting pile, and momentum is kept.
//
// The pile is run as in pile-comes-to-rest (until max(duration, T_rest +
// 2 s)) and must be at rest by that check's rate; if it is not, it is run
// again to 2 T_rest + 2 s and to 4 T_rest + 2 s, and a pile still moving
// then is not claimed (NotApplicable: there is no resting pile to wake; a
// pile late to rest is pile-comes-to-rest's failure, not this claim's). A
// run over its event budget fails, as there. A new scene is built from its
// last frame: every ball where the frame has it, with the frame's velocity,
// plus one ball (the material of the first moving ball: radius, mass,
// restitution, acceleration) above the top of the pile: over the highest
// ball not near a wall (its top
// highest along −a), offset sideways by a quarter of the smaller radius (an
// oblique strike), its lowest point c = max(2 r_max, ½ g (1 s)²) above the
// pile's highest point (c halved while the ball would come within r_max of a
// wall, not below 2 r_max). It falls at least c before it meets a ball:
// it strikes at ≥ sqrt(2 g c) ≥ 2 sqrt(g r_max), twenty times 0.1 sqrt(g r),
// far above any speed of rest; with room, after about a second of fall, in
// which the restarted pile is back at rest.
// It runs until the dropped ball could have fallen to the lowest wall point,
// plus 1 s, traced (engine_trace.hpp). At the dropped ball's first
// collision, if it is with a ball: the struck ball moves (it was woken),
// and the momentum Σ m v of every ball the strike moved (the engine's list
// of them, with their velocities just before) changes only by what their
// supports can push: the change lies in the cone of the normals of the
// walls and other balls within 1e-3 r_min of them (each pushes along its
// normal, never pulls; none touching: momentum kept), to within rounding:
// momentum-kept's bound (physics_checks.cpp: strict 8 eps Σ m (|v| + |v'|),
// fixed 16·2^-64 Σ m) once per impulse a velocity takes, 2 K + 1 (K the
// most contacts of one ball, counted from the geometry; an impact and its
// refinement step). Not claimed (a discard, NotApplicable): a first
// contact with a wall (it missed the pile), no contact at all, a closing
// speed below 0.1 sqrt(g r) (a strike that slow may find a resting ball
// immovable).
template <class Num>
CheckResult wake_keeps_momentum(const Scene& scene, double duration) {
  const PileBounds p = require_pile(scene);
  // The claim needs a resting pile; whether it rests by T_rest is
  // pile-comes-to-rest's claim. A frictionless pile can keep a mode that no
  // collision damps (a raft rocking in a V, datasets/regressions/open/) and
  // come to rest later: it is run on, to 2 T_rest and 4 T_rest (each plus
  // the window, from the start, the same budget), until it rests.
  PileBounds rest = p;
  PileRun settled;
  for (const double stretch : {1.0, 2.0, 4.0}) {
    rest.settle_time = stretch * p.settle_time;
    settled = run_pile<Num>(scene, rest, duration, false);
    if (settled.failure) return "the pile never settled, nothing to wake: " + *settled.failure;
    if (settled.in_window <= window_allowance(rest)) break;
  }
  if (settled.in_window > window_allowance(rest))
    throw NotApplicable("no resting pile to wake: still moving at 4 T_rest + 2 s = " + g17(settled.until) + " s, " +
                        std::to_string(settled.in_window) + " events in its last " + g17(p.window) +
                        " s, more than one per moving ball per second (" + std::to_string(window_allowance(p)) + "); " +
                        pile_figures(p));
  const SceneSize z = size_of(scene);
  const std::size_t n = scene.balls.size();
  Scene woken = scene;
  woken.name = scene.name + " + a dropped ball";
  for (std::size_t i = 0; i < n; ++i) {
    woken.balls[i].position = {settled.last.position[2 * i], settled.last.position[2 * i + 1]};
    woken.balls[i].velocity = {settled.last.velocity[2 * i], settled.last.velocity[2 * i + 1]};
  }
  std::size_t ref = 0;
  while (scene.balls[ref].fixed) ++ref;  // require_pile: one moving ball at least
  const Point a = effective_acceleration(scene, scene.balls[ref]);
  const double g = std::hypot(a[0], a[1]);
  const double up[2] = {-a[0] / g, -a[1] / g}, side[2] = {up[1], -up[0]};
  auto height = [&](const Point& q) { return up[0] * q[0] + up[1] * q[1]; };
  auto wall_gap = [&](const Point& q, double r) {
    LD gap = std::numeric_limits<LD>::infinity();
    for (const WallSpec& w : woken.walls) gap = std::min(gap, point_segment(q[0], q[1], w) - r);
    return gap;
  };
  const LD near_wall = near_wall_fraction * z.r_min;
  double top = -std::numeric_limits<double>::infinity();
  std::optional<std::size_t> target;
  for (std::size_t i = 0; i < n; ++i) {
    const BallSpec& b = woken.balls[i];
    if (b.fixed) continue;
    top = std::max(top, height(b.position) + b.radius);
    if (wall_gap(b.position, b.radius) > near_wall &&
        (!target || height(b.position) + b.radius > height(woken.balls[*target].position) + woken.balls[*target].radius))
      target = i;
  }
  if (!target) throw NotApplicable("every ball of the settled pile is within 1e-3 r_min of a wall");
  BallSpec drop = scene.balls[ref];
  const BallSpec& t = woken.balls[*target];
  const double offset = std::min(t.radius, drop.radius) / 4;
  double clearance = std::max(2 * z.r_max, g / 2);
  for (;; clearance /= 2) {
    clearance = std::max(clearance, 2 * z.r_max);
    const double lift = top + clearance + drop.radius - height(t.position);
    drop.position = {t.position[0] + up[0] * lift + side[0] * offset, t.position[1] + up[1] * lift + side[1] * offset};
    if (wall_gap(drop.position, drop.radius) >= z.r_max) break;
    if (clearance <= 2 * z.r_max) throw NotApplicable("no room above the settled pile for the dropped ball");
  }
  drop.velocity = {0, 0};
  woken.balls.push_back(drop);
  const int d = static_cast<int>(n);
  // Until it could have fallen to the lowest wall point, plus 1 s.
  double H = 0;
  for (const WallSpec& w : woken.walls)
    for (const Point& q : {w.a, w.b}) H = std::max(H, height(drop.position) - height(q));
  const double until = std::sqrt(2 * H / g) + 1;
  woken.duration = until;
  woken.record_interval = 1.0 / 64;
  const EngineTrace<Num> trace = trace_engine<Num>(woken, until);
  if (auto failure = trace_failure(trace)) return failure;
  for (std::size_t k = 0; k < trace.collisions.size(); ++k) {
    const TracedCollision<Num>& c = trace.collisions[k];
    const bool ball_ball = c.collision.kind == EventKind::ball_ball;
    if (c.collision.a != d && !(ball_ball && c.collision.b == d)) continue;
    if (!ball_ball) throw NotApplicable("the dropped ball missed the pile: it first met wall " + std::to_string(c.collision.b));
    const int j = c.collision.a == d ? c.collision.b : c.collision.a;
    const Vec2<Num> dp = c.after_a.position - c.after_b.position;
    const LD len = std::hypot(to_long_double(dp.x), to_long_double(dp.y));
    const Vec2<Num> dv = c.before_a.velocity - c.before_b.velocity;
    const LD closing = -(to_long_double(dp.x) * to_long_double(dv.x) + to_long_double(dp.y) * to_long_double(dv.y)) / len;
    const LD slow = 0.1L * std::sqrt(LD(g) * std::min(woken.balls[j].radius, drop.radius));
    if (closing < slow)
      throw NotApplicable("struck at a closing speed " + g17(closing) + " below 0.1 sqrt(g r) = " + g17(slow));
    // The struck ball must take part: a strike this fast wakes it.
    const std::vector<int>& island = c.collision.island;
    if (std::find(island.begin(), island.end(), j) == island.end())
      return "the dropped ball " + std::to_string(d) + " struck ball " + std::to_string(j) + " at t = " +
             g17(to_long_double(c.collision.time)) + " at closing speed " + g17(closing) +
             " and the struck ball did not move: it was treated as immovable, not woken";
    // Supports: walls and balls outside the island within 1e-3 r_min of an
    // island ball, each pushing along its normal (towards the island ball).
    // Every ball's position at the strike: from the last piece of its motion
    // begun by then.
    auto point = [](const Vec2<Num>& v) { return Vec2<LD>{to_long_double(v.x), to_long_double(v.y)}; };
    std::vector<Vec2<LD>> at_strike;
    std::vector<LD> radius;
    for (const auto& pieces : trace.pieces) {
      Body<Num> body = pieces.front().body;
      for (const MotionPiece<Num>& piece : pieces)
        if (!(c.collision.time < piece.body.time)) body = piece.body;
      if (!body.is_static()) collide2d::advance_to(body, c.collision.time);
      at_strike.push_back(point(body.position));
      radius.push_back(to_long_double(body.radius));
    }
    std::vector<Vec2<LD>> supports;
    std::size_t most_touches = 0;
    for (std::size_t k = 0; k < island.size(); ++k) {
      const Vec2<LD> x = point(c.island_after[k].position);
      const LD r = to_long_double(c.island_after[k].radius);
      std::size_t touches = 0;
      // A contact of ball k with the wall point or ball centre q; only one
      // with something outside the island is a support.
      auto touch = [&](const Vec2<LD>& q, LD reach, bool outside) {
        const Vec2<LD> n{x.x - q.x, x.y - q.y};
        const LD dist = std::hypot(n.x, n.y);
        if (dist - reach > near_wall) return;
        ++touches;
        if (outside) supports.push_back({n.x / dist, n.y / dist});
      };
      for (const WallSpec& w : woken.walls) touch(nearest_on_wall(x.x, x.y, w), r, true);
      for (std::size_t y = 0; y < at_strike.size(); ++y)
        if (static_cast<int>(y) != island[k])
          touch(at_strike[y], r + radius[y], std::find(island.begin(), island.end(), static_cast<int>(y)) == island.end());
      most_touches = std::max(most_touches, touches);
    }
    // The island's momentum changes only by what the supports push.
    Vec2<LD> change{0, 0};
    LD size = 0, mass = 0;
    auto speed = [](const Vec2<Num>& v) { return std::hypot(to_long_double(v.x), to_long_double(v.y)); };
    for (std::size_t k = 0; k < island.size(); ++k) {
      const LD m = to_long_double(c.island_after[k].mass);
      const Vec2<Num>& v = c.island_before[k].velocity;
      const Vec2<Num>& w = c.island_after[k].velocity;
      change.x += m * (to_long_double(w.x) - to_long_double(v.x));
      change.y += m * (to_long_double(w.y) - to_long_double(v.y));
      size += m * (speed(v) + speed(w));
      mass += m;
    }
    const LD miss = distance_to_cone(change, supports);
    // Each velocity takes one impulse per contact, twice (the impact and its
    // refinement), each rounded as in momentum-kept: that bound times
    // 2 K + 1, K the most contacts any island ball has (from the geometry).
    const LD per = std::is_same_v<Num, double> ? 8 * strict_eps * size : 16 * fixed_resolution * mass;
    const LD bound = per * LD(2 * most_touches + 1);
    if (!(miss <= bound))
      return "the dropped ball " + std::to_string(d) + " struck ball " + std::to_string(j) + " of the settled pile at t = " +
             g17(to_long_double(c.collision.time)) + " (closing speed " + g17(closing) + "): the momentum of the " +
             std::to_string(island.size()) + " balls it moved changed by (" + g17(change.x) + ", " + g17(change.y) + "), " +
             g17(miss) + " outside what its " + std::to_string(supports.size()) + " supports can push (bound " + g17(bound) + ")";
    return std::nullopt;
  }
  throw NotApplicable("the dropped ball met nothing in " + g17(until) + " s");
}

}  // namespace

std::int64_t PileBounds::event_budget(double until) const {
  const double settle = budget_factor * moving * (bounces + 2);
  const double after = std::ceil(rest_rate * moving * std::max(0.0, until - settle_time));
  return static_cast<std::int64_t>(std::min(settle + after, 9e18));
}

std::optional<PileBounds> pile_bounds(const Scene& scene) {
  std::string why;
  return pile_bounds_or_why(scene, why);
}

CheckResult check_energy_never_rises(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) { return energy_never_rises<decltype(zero)>(scene, duration); });
}

CheckResult check_pile_comes_to_rest(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) { return pile_comes_to_rest<decltype(zero)>(scene, duration); });
}

CheckResult check_wake_keeps_momentum(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) { return wake_keeps_momentum<decltype(zero)>(scene, duration); });
}

}  // namespace collide2d::properties
