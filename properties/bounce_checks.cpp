// A ball bouncing on a flat floor comes to rest when the documented rest
// height says, not sooner and not later (scene_checks.hpp).
//
// The bound is the README's contract, written here: by default a rebound
// that would rise less than h = 1e-6 r (r the smallest radius) above the
// face is not flown; the ball stays on it. It is not read from the engine
// (its thresholds, its counters): an engine whose default rest height or
// hop speed is off by a factor of a few puts the ball down at the wrong time
// and fails here.
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

#include "check_support.hpp"
#include "engine_trace.hpp"
#include "scene_checks.hpp"

namespace collide2d::properties {
namespace {

using LD = long double;

constexpr double documented_rest_fraction = 1e-6;  // h_rest = 1e-6 r_min (README, "Rest"), the default

// The scene this check speaks about: one free ball of radius r above one
// horizontal wall at y = 0 (reaching past the ball on both sides), dropped
// from rest under gravity (0, −g), no rest settings of its own. Its contact
// restitution is the product of the ball's and the wall's (SPEC.md).
struct Bounce {
  LD r, g, h, e;  // radius, gravity, drop height of the lowest point, restitution
};
Bounce bounce_or_not_applicable(const Scene& s) {
  auto no = [](const std::string& why) { return NotApplicable("not a ball dropped on a flat floor: " + why); };
  if (s.balls.size() != 1 || s.walls.size() != 1) throw no("one ball and one wall wanted");
  const BallSpec& b = s.balls[0];
  const WallSpec& w = s.walls[0];
  if (b.fixed || b.acceleration || !(s.gravity[0] == 0 && s.gravity[1] < 0)) throw no("a free ball under gravity (0, -g) wanted");
  if (!(w.a[1] == 0 && w.b[1] == 0 && std::fmin(w.a[0], w.b[0]) < b.position[0] - b.radius &&
        b.position[0] + b.radius < std::fmax(w.a[0], w.b[0])))
    throw no("the wall must be y = 0 under the whole ball");
  if (!(b.velocity[0] == 0 && b.velocity[1] == 0 && b.position[1] > b.radius)) throw no("dropped from rest above the wall wanted");
  if (s.rest.height || s.rest.speed || s.rest.band) throw no("the scene sets its own rest scales");
  return {b.radius, -s.gravity[1], b.position[1] - b.radius, LD(b.restitution) * w.restitution};
}

// The bounce series (every bounce exact, restitution e < 1): the ball lands
// first at t1 = sqrt(2h/g) with speed w1 = sqrt(2gh); it lands at bounce k
// with w_k = e^(k−1) w1 and leaves with e w_k, flying 2 e w_k / g. Flown to
// the end the series stops at
//     T∞ = t1 + 2 e w1 / (g (1 − e)),
// and from bounce k on it takes T∞ − T_k = 2 e w_k / (g (1 − e)).
// The rest rule holds the ball at the first bounce whose rebound would rise
// less than h_rest: e w_k < v_h = sqrt(2 g h_rest). That bounce is not the
// first (e w1 ≥ v_h is asked of the scene), so the one before flew:
// w_k = e w_(k−1) ≥ v_h. Hence w_k ∈ [v_h, v_h / e) and the last bounce is at
//     T∞ − T_last ∈ [2 e v_h / (g (1 − e)), 2 v_h / (g (1 − e))).
// The interval is as wide as the rest height allows and no wider: a rest
// height 10× too large moves both ends by √10 (caught when e > 0.32), a hop
// speed 10× too high by 10 (caught when e > 0.1).
//
// Rounding: every bounce time is a root of a quadratic from the state after
// the one before, each good to a few ulps of the time, and the speeds carry
// one rounding per bounce; over k bounces the last time is good to
// 64 k eps (T∞ + 1) (eps = 2^-52; fixed point's 2^-64 is finer), and a
// rebound within rounding of v_h may be held or flown: either lands on an end
// of the interval, within the same tolerance. After the last bounce the
// ball lies on the floor: no speed beyond 64 eps w1.
template <class Num>
CheckResult bounce_comes_to_rest_on_time(const Scene& scene, double duration) {
  const Bounce b = bounce_or_not_applicable(scene);
  if (!(b.e < 1)) throw NotApplicable("restitution 1: the ball never comes to rest");
  const LD w1 = std::sqrt(2 * b.g * b.h), t1 = std::sqrt(2 * b.h / b.g);
  const LD T_inf = t1 + 2 * b.e * w1 / (b.g * (1 - b.e));
  const LD v_h = std::sqrt(2 * b.g * documented_rest_fraction * b.r);
  if (!(b.e * w1 >= v_h)) throw NotApplicable("the first rebound is already below the rest height");
  if (!(duration > T_inf + 0.5)) throw NotApplicable("the run ends before the series does");
  const LD lo = 2 * b.e * v_h / (b.g * (1 - b.e)), hi = 2 * v_h / (b.g * (1 - b.e));

  const EngineTrace<Num> trace = trace_engine<Num>(scene, duration);
  if (auto failure = trace_failure(trace)) return failure;
  std::int64_t bounces = 0;
  LD last = -1;
  for (const TracedCollision<Num>& c : trace.collisions)
    if (c.collision.kind == EventKind::ball_wall) ++bounces, last = to_long_double(c.collision.time);
  const LD eps = std::numeric_limits<double>::epsilon();
  const LD tol = 64 * LD(std::max<std::int64_t>(bounces, 1)) * eps * (T_inf + 1);
  const std::string series = "a ball of radius " + g17(b.r) + " dropped from " + g17(b.h) + " under g = " + g17(b.g) +
                             ", restitution " + g17(b.e) + ": ";
  if (bounces < 2) return series + std::to_string(bounces) + " bounces; the series has many above the rest height";
  const LD before_end = T_inf - last;
  if (!(lo - tol <= before_end && before_end <= hi + tol))
    return series + "the last of " + std::to_string(bounces) + " bounces at t = " + g17(last) + " is " + g17(before_end) +
           " s before the series' end T = " + g17(T_inf) + "; a rest height of 1e-6 r puts it between " + g17(lo) + " and " +
           g17(hi) + " s before (tolerance " + g17(tol) + ")";
  const Body<Num>& final_state = trace.pieces[0].back().body;
  const LD speed = std::hypot(to_long_double(final_state.velocity.x), to_long_double(final_state.velocity.y));
  if (!(speed <= 64 * eps * w1))
    return series + "after its last bounce at t = " + g17(last) + " the ball still moves at " + g17(speed);
  return std::nullopt;
}

// The scene of the struck-sleeper check: ball 0 lying on the wall y = 0
// (touching it, at rest), ball 1 dropped from rest above it, off its centre
// line, under gravity (0, −g); one wall, no rest settings.
void struck_sleeper_or_not_applicable(const Scene& s) {
  auto no = [](const std::string& why) { return NotApplicable("not a ball dropped on a ball lying on a floor: " + why); };
  if (s.balls.size() != 2 || s.walls.size() != 1) throw no("two balls and one wall wanted");
  const WallSpec& w = s.walls[0];
  if (!(w.a[1] == 0 && w.b[1] == 0)) throw no("the wall must be y = 0");
  if (!(s.gravity[0] == 0 && s.gravity[1] < 0)) throw no("gravity (0, -g) wanted");
  for (const BallSpec& b : s.balls)
    if (b.fixed || b.acceleration || !(b.velocity[0] == 0 && b.velocity[1] == 0)) throw no("two free balls at rest wanted");
  if (!(s.balls[0].position[1] == s.balls[0].radius)) throw no("ball 0 must lie on the wall");
  if (s.rest.height || s.rest.speed || s.rest.band) throw no("the scene sets its own rest scales");
}

// A ball lying still on a floor (asleep, or held on the face: either way at
// rest) is struck by a ball dropped onto it. The floor pushes along its
// normal (0, 1) only, so at the strike the pair's horizontal momentum
//     m0 v0x + m1 v1x
// is kept, and the struck ball takes its share: it moves. A strike that
// does not wake the lying ball bounces the dropped one off it as off a
// fixed ball and reverses its horizontal momentum. Applies when the strike
// is at least the documented wake speed sqrt(2 g 1e-6 r_min) (README,
// "Rest"), which the drop height makes certain. Rounding: one impulse per
// contact (the pair's and the floor's), each rounded as in momentum-kept:
// 3 × 8 eps Σ m (|v| + |v'|) (strict), 3 × 16 · 2^-64 Σ m (fixed).
template <class Num>
CheckResult struck_sleeper_keeps_momentum(const Scene& scene, double duration) {
  struck_sleeper_or_not_applicable(scene);
  const EngineTrace<Num> trace = trace_engine<Num>(scene, duration);
  if (auto failure = trace_failure(trace)) return failure;
  const TracedCollision<Num>* strike = nullptr;
  for (const TracedCollision<Num>& c : trace.collisions)
    if (c.collision.kind == EventKind::ball_ball) {
      strike = &c;
      break;
    }
  if (!strike) throw NotApplicable("the dropped ball never met the lying one");
  const bool zero_first = strike->collision.a == 0;
  const Body<Num>& lying_before = zero_first ? strike->before_a : strike->before_b;
  const Body<Num>& lying_after = zero_first ? strike->after_a : strike->after_b;
  const Body<Num>& dropped_before = zero_first ? strike->before_b : strike->before_a;
  const Body<Num>& dropped_after = zero_first ? strike->after_b : strike->after_a;
  auto ld = [](const Num& x) { return to_long_double(x); };
  const LD r_min = std::fmin(scene.balls[0].radius, scene.balls[1].radius);
  const LD g = -scene.gravity[1];
  const LD wake_speed = std::sqrt(2 * g * documented_rest_fraction * r_min);
  const LD closing = std::hypot(ld(dropped_before.velocity.x - lying_before.velocity.x),
                                ld(dropped_before.velocity.y - lying_before.velocity.y));
  if (!(closing >= 2 * wake_speed)) throw NotApplicable("the strike is slower than twice the wake speed");
  const LD m0 = ld(lying_before.mass), m1 = ld(dropped_before.mass);
  const LD before = m0 * ld(lying_before.velocity.x) + m1 * ld(dropped_before.velocity.x);
  const LD after = m0 * ld(lying_after.velocity.x) + m1 * ld(dropped_after.velocity.x);
  auto speed = [&](const Body<Num>& b) { return std::hypot(ld(b.velocity.x), ld(b.velocity.y)); };
  const LD size = m0 * (speed(lying_before) + speed(lying_after)) + m1 * (speed(dropped_before) + speed(dropped_after));
  const LD bound = std::is_same_v<Num, double> ? 3 * 8 * LD(std::numeric_limits<double>::epsilon()) * size
                                               : 3 * 16 * 0x1p-64L * (m0 + m1);
  const std::string where = "ball 1 struck ball 0 lying on the floor at t = " + g17(ld(strike->collision.time)) +
                            " (closing speed " + g17(closing) + "): ";
  if (!(std::fabs(after - before) <= bound))
    return where + "the pair's horizontal momentum went from " + g17(before) + " to " + g17(after) + " (bound " + g17(bound) +
           "); the lying ball's velocity after is (" + g17(ld(lying_after.velocity.x)) + ", " +
           g17(ld(lying_after.velocity.y)) + ")";
  if (speed(lying_after) == 0) return where + "the lying ball did not move";
  return std::nullopt;
}

}  // namespace

CheckResult check_struck_sleeper_keeps_momentum(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) { return struck_sleeper_keeps_momentum<decltype(zero)>(scene, duration); });
}

CheckResult check_bounce_comes_to_rest_on_time(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) { return bounce_comes_to_rest_on_time<decltype(zero)>(scene, duration); });
}

}  // namespace collide2d::properties
