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
  std::int64_t limit = 0;  // collisions: the run is stopped when it passes this
  std::int64_t balls = 0;  // N: motion changes are capped at N times the limit
  std::string estimate;    // how the limit was made, for the message
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
  if (moving == 0) return {static_cast<std::int64_t>(event_cap_factor * (n + 1)), static_cast<std::int64_t>(n), "no moving ball"};
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
  return {static_cast<std::int64_t>(std::min(limit, 9e15)), static_cast<std::int64_t>(n),
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
  void collision(long double time) { count(collisions_, cap_.limit, time, "collisions"); }
  void motion_change(long double time) { count(changes_, cap_.limit * std::max<std::int64_t>(cap_.balls, 1), time, "motion changes"); }
  const EventCap& cap() const { return cap_; }

 private:
  void count(std::int64_t& n, std::int64_t limit, long double time, const char* what) {
    same_time_ = time == last_time_ ? same_time_ + 1 : 1;
    last_time_ = time;
    if (++n <= limit) return;
    char at[64];
    std::snprintf(at, sizeof at, "%.17Lg", time);
    throw RunawayRun("run stopped at t = " + std::string(at) + " after " + std::to_string(n) + " " + what +
                     (same_time_ > 1 ? " (the last " + std::to_string(same_time_) + " events all at that time: a stall)" : "") +
                     ", past the scene's cap of " + std::to_string(limit) + " (collisions: " + cap_.estimate +
                     "; motion changes: N times that): the run makes far more events than its balls can account for");
  }
  EventCap cap_;
  std::int64_t collisions_ = 0, changes_ = 0, same_time_ = 0;
  long double last_time_ = -1;
};

}  // namespace collide2d::properties
