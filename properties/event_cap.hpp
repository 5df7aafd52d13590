// A per-scene cap on the events of a run: a run that makes far more events
// than its scene can account for (a planted bug ringing between two walls,
// a contact made and left at one instant for ever) is stopped at once with
// a clear message, instead of running on until a timeout.
//
// The cap comes from the scene alone (never from the engine's counters or
// thresholds), as a generous multiple of a physical estimate of how many
// events its balls can make in the duration T:
//   V    the fastest any ball can go: all of the scene's kinetic energy and
//        the potential energy of a fall across the scene in the lightest
//        ball, V² = Σ m (|v0|² + 2 A D) / m_min (A the largest acceleration,
//        D the side of the scene's bounding box): restitutions ≤ 1 add none;
//   free flight: one event per r_min the ball travels, V T / r_min (a ball
//        in a crowd meets a neighbour about once per radius it moves);
//   bounces under gravity g (the smallest acceleration of a moving ball):
//        a bounce series from V ends after k = ln(V / v_h) / ln(1 / e)
//        bounces, e the largest restitution below 1 and v_h = sqrt(2 g h)
//        the speed that rises the rest height h (the scene's own, or the
//        README's default 1e-6 r_min); an elastic series (e = 1) never
//        ends, and a ball hopping at least h high bounces at most
//        T sqrt(g / (8 h)) times; k is the smaller;
//   per ball:  E0 = 2 + k + V T / r_min, in all N_moving E0.
// The cap on collisions is 1024 (N_moving E0 + N): over a hundred times the
// most any generated scene made (the largest ratio of collisions to
// N_moving E0 + N seen, deep runs included, was 2.9: docs/PROPERTIES.md),
// reached in a second or two by a run that rings. A trace (engine_trace.hpp)
// also counts the changes of motion the engine tells, outside collisions
// too (a contact left and renewed at advancing times, for ever): each event
// changes the motion of at most the N balls of an island, so N times the
// cap on collisions.
// At one instant (a stall: time does not advance), a pair (of balls, or a
// ball and a wall) meets a few times at most before the jammed-strike rule
// makes it one plastic impact (rest.hpp, rule 1): 64 (N (N + W) + 1)
// collisions at one time, W the walls, stop the run long before the
// engine's own stall limit of 10^5 would.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "collide2d/scene/scene.hpp"

namespace collide2d::properties {

struct EventCap {
  std::int64_t limit = 0;      // collisions: the run is stopped when it passes this
  std::int64_t balls = 0;      // N: motion changes are capped at N times the limit
  std::int64_t same_time = 0;  // collisions at one time (N times that for motion changes)
  std::string estimate;        // how the limit was made, for the message
};

// The factor over the physical estimate (above).
inline constexpr double event_cap_factor = 1024;

inline EventCap event_cap(const Scene& scene, double duration) {
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  auto take = [&](const Point& p) {
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  };
  double r_min = std::numeric_limits<double>::infinity(), r_max = 0, m_min = std::numeric_limits<double>::infinity();
  double A = 0, g = std::numeric_limits<double>::infinity(), e = scene.restitution;
  int moving = 0;
  for (const WallSpec& w : scene.walls) take(w.a), take(w.b), e = std::max(e, w.restitution);
  for (const BallSpec& b : scene.balls) {
    take(b.position);
    r_min = std::min(r_min, b.radius), r_max = std::max(r_max, b.radius);
    e = std::max(e, b.restitution);
    if (b.fixed) continue;
    ++moving;
    m_min = std::min(m_min, b.mass);
    const Point a = effective_acceleration(scene, b);
    const double a_len = std::hypot(a[0], a[1]);
    A = std::max(A, a_len);
    g = std::min(g, a_len);
  }
  const double n = static_cast<double>(scene.balls.size());
  const auto same_time = static_cast<std::int64_t>(64 * (n * (n + static_cast<double>(scene.walls.size())) + 1));
  if (moving == 0)
    return {static_cast<std::int64_t>(event_cap_factor * (n + 1)), static_cast<std::int64_t>(n), same_time, "no moving ball"};
  const double D = std::max(hi[0] - lo[0], hi[1] - lo[1]) + 2 * r_max;
  double energy = 0;  // Σ m (|v0|² + 2 A D)
  for (const BallSpec& b : scene.balls)
    if (!b.fixed) energy += b.mass * (b.velocity[0] * b.velocity[0] + b.velocity[1] * b.velocity[1] + 2 * A * D);
  const double V = std::sqrt(energy / m_min);
  const double T = duration;
  const double free_flight = V * T / r_min;
  double bounces = 0;
  if (g > 0) {
    const double h = scene.rest.height.value_or(1e-6 * r_min);
    const double hopping = T * std::sqrt(g / (8 * h));
    const double v_h = std::sqrt(2 * g * h);
    const double series = e < 1 && e > 0 && V > v_h ? std::log(V / v_h) / std::log(1 / e) : (e < 1 ? 0.0 : hopping);
    bounces = std::min(series, hopping);
  }
  const double per_ball = 2 + bounces + free_flight;
  const double limit = event_cap_factor * (moving * per_ball + n);
  return {static_cast<std::int64_t>(std::min(limit, 9e15)), static_cast<std::int64_t>(n), same_time,
          std::to_string(static_cast<long long>(event_cap_factor)) + " (N_moving E0 + N), E0 = 2 + k + V T / r_min = 2 + " +
              std::to_string(bounces) + " + " + std::to_string(free_flight) + " per moving ball (" + std::to_string(moving) +
              " moving, V = " + std::to_string(V) + ", T = " + std::to_string(T) + ", r_min = " + std::to_string(r_min) + ")"};
}

// Thrown when a run passes its scene's cap: the check's failure.
struct RunawayRun : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Counts a run's collisions (and, for a trace, its motion changes) against
// the cap; the message says where the run was when it passed it.
class EventCount {
 public:
  explicit EventCount(EventCap cap) : cap_(std::move(cap)) {}
  void collision(long double time) { count(collisions_, same_collisions_, 1, time, "collisions"); }
  void motion_change(long double time) { count(changes_, same_changes_, std::max<std::int64_t>(cap_.balls, 1), time, "motion changes"); }
  const EventCap& cap() const { return cap_; }

 private:
  // `per`: the caps are `per` times those on collisions (N for motion changes).
  void count(std::int64_t& n, std::int64_t& same, std::int64_t per, long double time, const char* what) {
    if (time != last_time_) same_collisions_ = same_changes_ = 0, last_time_ = time;
    ++same;
    const bool over_all = ++n > cap_.limit * per, over_instant = same > cap_.same_time * per;
    if (!over_all && !over_instant) return;
    char at[64];
    std::snprintf(at, sizeof at, "%.17Lg", time);
    const std::string head = "run stopped at t = " + std::string(at) + ": ";
    if (over_instant)
      throw RunawayRun(head + std::to_string(same) + " " + what + " at that one time (a stall), past the scene's cap of " +
                       std::to_string(cap_.same_time * per) + " = 64 (N (N + W) + 1)" + (per > 1 ? " times N" : "") +
                       " at one instant");
    throw RunawayRun(head + std::to_string(n) + " " + what + ", past the scene's cap of " + std::to_string(cap_.limit * per) +
                     " (collisions: " + cap_.estimate + (per > 1 ? "; motion changes: N times that" : "") +
                     "): the run makes far more events than its balls can account for");
  }
  EventCap cap_;
  std::int64_t collisions_ = 0, changes_ = 0, same_collisions_ = 0, same_changes_ = 0;
  long double last_time_ = -1;
};

}  // namespace collide2d::properties
