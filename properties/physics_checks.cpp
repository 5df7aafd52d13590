// Energy, momentum and reflection checks (scene_checks.hpp). Each bound is
// derived in the comment above the check that uses it.
#include <cmath>
#include <sstream>
#include <vector>

#include "check_support.hpp"
#include "scene_checks.hpp"
#include "scene_scales.hpp"

namespace collide2d::properties {
namespace {

template <class Num>
long double ld(const Num& x) { return to_long_double(x); }

// Energy. Elastic scenes only (every restitution 1; the check refuses others).
//
// Exact arithmetic keeps E = Σ ½ m|v|² − m a·p exactly: along a parabola,
// through an elastic reflection and an elastic two-ball impulse. What changes
// it is rounding at each *step*: a ball carried to a new clock (at an event it
// takes part in, at each record time for every ball) and a response.
//  strict: p + v t + ½ a t² rounds 4 times, each ≤ eps/2 of the largest term,
//    so |δp| ≤ 2 eps P (P: largest coordinate), |δv| ≤ eps (V + A T); the
//    energy moves by m(|v||δv| + |a||δp|) ≤ 2 eps m (V² + A P). A response
//    (normal rounded ≤ 2 eps, then v − (1+e)(v·n)n) moves |v| by ≤ 4 eps V,
//    KE by ≤ 4 eps m V². So per step ≤ 4 eps m (V² + A P + A) and over
//    steps = 2·events + N·frames: 8 eps · steps · Σm (V² + A P + A), a factor
//    2 to spare. The frame energies are doubles: + 4 eps S for the sums.
//  fixed: every operation rounds to 2^-65 absolute. |δp| ≤ 4·2^-65, |δv| ≤
//    2^-64; the unit normal n = d/|d| is off by ≤ 4·2^-64 (1 + 1/r_min² + L)
//    (scene_scales.hpp; L the longest wall or diameter; 1/r² from |d|² of a
//    short d having 2^-64 absolute resolution), turning v by twice
//    that. Per step ≤ 2^-64 m (V² 8(1 + 1/r_min² + L) + 4 V + 2 A); over all steps times 8 (spare), plus the double
//    conversion of the energies, 4 eps S.
//  Both: no rest rule adds energy (src/collide2d/sim/rest.hpp), so a rise beyond the
//    rounding bound fails whatever the rules did. The rules may remove some:
//    coming to rest, a plastic pair or sleep each takes a motion that would
//    rise less than h = 1e-6 r_min (the scene's scale of rest, written here,
//    not read from the engine) against at most 2 A: below 2 M A h each, so a
//    fall may also take (rule actions) · 2 · 2 M A h.
template <class Num>
CheckResult energy_kept(const Scene& scene, double duration) {
  // Not an elastic scene: nothing is claimed, and the case is discarded
  // (NotApplicable), never counted as a pass.
  for (std::size_t i = 0; i < scene.balls.size(); ++i)
    if (scene.balls[i].restitution != 1)
      throw NotApplicable("inelastic: restitution " + g17(scene.balls[i].restitution) + " at balls[" + std::to_string(i) + "]");
  for (std::size_t w = 0; w < scene.walls.size(); ++w)
    if (scene.walls[w].restitution != 1)
      throw NotApplicable("inelastic: restitution " + g17(scene.walls[w].restitution) + " at walls[" + std::to_string(w) + "]");
  std::vector<double> energy;
  std::int64_t events = 0;
  EventCount cap(event_cap(scene, duration));
  const SimulationSummary summary = simulate<Num>(scene, duration, [&](const FrameRecord& f) { energy.push_back(f.energy); },
                                                  [&](const EventRecord& e) { ++events, cap.collision(e.time); });
  const EngineTrace<Num> trace = trace_engine<Num>(scene, duration);
  if (auto failure = trace_failure(trace)) return failure;
  const RunScales s = scales_of(scene, trace);
  const EngineCounters& c = summary.counters;
  const double steps = 2.0 * static_cast<double>(c.ball_ball + c.ball_wall + c.leave_wall + c.leave_pair) +
                       static_cast<double>(scene.balls.size()) * static_cast<double>(summary.frames);
  double size = 0, fixed_size = 0;  // Σ m (V² + A P + A), and the fixed-mode sum
  for (const BallSpec& b : scene.balls) {
    if (b.fixed) continue;
    size += b.mass * (s.speed * s.speed + s.acceleration * s.position + s.acceleration);
    fixed_size += b.mass * (8 * s.speed * s.speed * (1 + 1 / (s.r_min * s.r_min) + s.normal_length) + 4 * s.speed + 2 * s.acceleration + 1);
  }
  const double h = 1e-6 * s.r_min;
  const double rules = static_cast<double>(c.rest.plastic_pairs + c.rest.came_to_rest + c.rest.fell_asleep) * 4 * s.mass_max * s.acceleration * h;
  const double rounding = std::is_same_v<Num, double> ? 8 * strict_eps * steps * size + 4 * strict_eps * size
                                                      : 8 * fixed_resolution * steps * fixed_size + 4 * strict_eps * size;
  for (std::size_t k = 0; k < energy.size(); ++k) {
    const double bound = energy[k] > energy[0] ? rounding : rounding + rules;
    if (!(std::fabs(energy[k] - energy[0]) <= bound))
      return "energy at frame " + std::to_string(k) + " is " + g17(energy[k]) + ", at the start " + g17(energy[0]) +
             ": change " + g17(energy[k] - energy[0]) + " exceeds the bound " + g17(bound) + " (" +
             std::to_string(events) + " events, " + std::to_string(c.rest.plastic_pairs) + " plastic pairs, " +
             std::to_string(c.rest.came_to_rest) + " came to rest)";
  }
  return std::nullopt;
}

// Momentum, per ball–ball collision of two free balls whose states just
// before are known (engine_trace.hpp). A ball in contact with a wall or
// other balls (its island answers the strike at once,
// src/collide2d/sim/contact_graph.hpp) shares the impulse with them: not claimed, skipped.
//  strict: v1' = v1 + (J/m1) n rounds twice per component, each ≤ eps/2 of
//    |v1'| + |J/m1|; our own m (v' − v) rounds twice more. So |Δ(m1 v1 + m2 v2)|
//    ≤ 2 eps Σ m(|v| + |v'|) + 2 eps |J|; we allow 8 eps Σ m(|v| + |v'|).
//  fixed: J/m and (J/m) n_x round to 2^-65 each, per ball, m times that;
//    the same J and n act on both balls, so only these roundings remain, and
//    our m (v' − v) adds 2^-65 m per ball: ≤ 2^-64 · 2 (m1 + m2). We allow 16.
// The hop impulse (separate_at_least) is equal and opposite too: same bound.
// A run without a single such collision judged nothing: NotApplicable.
template <class Num, class Response>
CheckResult momentum_kept(const Scene& scene, double duration, Response response) {
  const EngineTrace<Num> trace = trace_engine<Num>(scene, duration);
  if (auto failure = trace_failure(trace)) return failure;
  std::int64_t judged = 0;
  for (std::size_t k = 0; k < trace.collisions.size(); ++k) {
    const TracedCollision<Num>& c = trace.collisions[k];
    // A static partner (fixed, or asleep and struck too slowly to wake:
    // rest.hpp, rule 3) takes the impulse like the ground: not claimed.
    if (c.collision.kind != EventKind::ball_ball || c.after_a.is_static() || c.after_b.is_static() || c.held)
      continue;
    ++judged;
    const auto [va, vb] = response(c);
    const Num ma = c.before_a.mass, mb = c.before_b.mass;
    const Vec2<Num> change = (ma * (va - c.before_a.velocity)) + (mb * (vb - c.before_b.velocity));
    const long double size = ld(ma) * (std::hypot(ld(va.x), ld(va.y)) + std::hypot(ld(c.before_a.velocity.x), ld(c.before_a.velocity.y))) +
                             ld(mb) * (std::hypot(ld(vb.x), ld(vb.y)) + std::hypot(ld(c.before_b.velocity.x), ld(c.before_b.velocity.y)));
    const long double bound = std::is_same_v<Num, double> ? 8 * strict_eps * size : 16 * fixed_resolution * (ld(ma) + ld(mb));
    const long double error = std::hypot(ld(change.x), ld(change.y));
    if (!(error <= bound))
      return "collision " + std::to_string(k) + " (t = " + g17(ld(c.collision.time)) + ", balls " +
             std::to_string(c.collision.a) + " and " + std::to_string(c.collision.b) + ", masses " + g17(ld(ma)) + ", " +
             g17(ld(mb)) + "): momentum changed by " + g17(error) + " > bound " + g17(bound);
  }
  if (judged == 0)
    throw NotApplicable("no collision of two free balls out of contact to judge (" + std::to_string(trace.collisions.size()) +
                        " collisions in all)");
  return std::nullopt;
}

// Reflections off walls and fixed balls, and the normal relative speed of two
// free balls: with restitution e (the product of the two) the normal (relative) speed becomes −e times what it was, the
// tangential part is kept; e = 1 keeps the speed. Collisions where a rest
// rule acted (restitution raised, a hop, coming to rest, a ball held on its
// face, where the face takes part of the impulse, sleep or wake) are not claimed and skipped, and so are grazes
// (velocity unchanged, not closing on a touched feature).
// The normal n is recomputed here (centre to centre, or centre to the
// nearest point of the wall): it differs from the engine's by δn.
//  strict: δn ≤ 4 eps (1 + P / r) (the centre and the contact point are
//    ~P in size, their difference r); v' = v − (1+e)(v·n)n rounds ≤ 4 eps V.
//    Components along our n move by ≤ 2 V δn: bound 8 eps V + 4 V δn. For
//    two free balls V is their relative speed, but each velocity rounds on
//    its own scale: the rounding term takes |v_a| + |v_b| where that is larger.
//  fixed: the engine's normal is off by 2^-64 (1/r + L) (scene_scales.hpp;
//    L the longest wall or diameter), ours by 2^-64 relative (long double);
//    and |d|² of a short d (d ~ r, |d|² ~ r²) has only 2^-64 absolute, so
//    relative 2^-64 / r²: δn ≤ 8·2^-64 (1 + 1/r² + L). For r = 2^-11 that
//    is ~2^-38: fixed mode is coarser than strict for small balls.; v' rounds ≤ 4·2^-64: bound 8·2^-64 (1 + V) + 4 V δn.
template <class Num>
CheckResult reflection_speed(const Scene& scene, double duration) {
  const EngineTrace<Num> trace = trace_engine<Num>(scene, duration);
  if (auto failure = trace_failure(trace)) return failure;
  const RunScales sc = scales_of(scene, trace);
  const bool strict = std::is_same_v<Num, double>;
  const double unit = strict ? strict_eps : fixed_resolution;
  std::int64_t judged = 0;
  for (std::size_t k = 0; k < trace.collisions.size(); ++k) {
    const TracedCollision<Num>& c = trace.collisions[k];
    if (c.rule_acted()) continue;
    const int a = c.collision.a, b = c.collision.b;
    long double r = 0, extent = 0;
    std::vector<Vec2<long double>> normals;  // candidate normals (unnormalised)
    Vec2<long double> v, w;  // the normal-relevant velocity before and after
    long double own_speeds = 0;  // what each velocity rounds on: |v_a| + |v_b|, before or after
    long double e = 0;
    const Body<Num>& ball = c.after_a;
    if (c.collision.kind == EventKind::ball_wall) {
      const WallSpec& wall = scene.walls[b];
      // Centre relative to the wall's end a, formed in Num (exact in fixed).
      const Vec2<Num> rel = ball.position - vec2_from_double<Num>(wall.a[0], wall.a[1]);
      const long double px = ld(rel.x), py = ld(rel.y);
      const long double dx = static_cast<long double>(wall.b[0]) - wall.a[0], dy = static_cast<long double>(wall.b[1]) - wall.a[1];
      const long double along = (px * dx + py * dy) / (dx * dx + dy * dy);
      r = ld(ball.radius);
      // The feature touched: the face, or an end. Where they meet, which
      // one the engine took is decided by rounding of the contact point, so
      // every feature the ball touches (to 1e-9 r) is a candidate normal.
      const long double s_clamped = std::clamp(along, 0.0L, 1.0L);
      normals.push_back({px - s_clamped * dx, py - s_clamped * dy});
      const long double seam = 1e-9L;
      if (along > -seam && along < 1 + seam) normals.push_back({px - along * dx, py - along * dy});
      for (const long double end : {0.0L, 1.0L})
        if (std::fabs(std::hypot(px - end * dx, py - end * dy) - r) <= seam * r) normals.push_back({px - end * dx, py - end * dy});
      extent = std::max({std::fabs(ld(ball.position.x)), std::fabs(ld(ball.position.y)), std::fabs((long double)wall.a[0]),
                         std::fabs((long double)wall.a[1]), std::fabs((long double)wall.b[0]), std::fabs((long double)wall.b[1])});
      v = {ld(c.before_a.velocity.x), ld(c.before_a.velocity.y)};
      w = {ld(c.after_a.velocity.x), ld(c.after_a.velocity.y)};
      e = ld(c.before_a.restitution) * wall.restitution;
    } else {
      const Vec2<Num> rel = c.after_a.position - c.after_b.position;
      normals.push_back({ld(rel.x), ld(rel.y)});
      r = std::min(ld(c.after_a.radius), ld(c.after_b.radius));
      extent = std::max({std::fabs(ld(c.after_a.position.x)), std::fabs(ld(c.after_a.position.y)),
                         std::fabs(ld(c.after_b.position.x)), std::fabs(ld(c.after_b.position.y))});
      // Relative velocity of a with respect to b (b fixed: b's is zero).
      v = {ld(c.before_a.velocity.x) - ld(c.before_b.velocity.x), ld(c.before_a.velocity.y) - ld(c.before_b.velocity.y)};
      w = {ld(c.after_a.velocity.x) - ld(c.after_b.velocity.x), ld(c.after_a.velocity.y) - ld(c.after_b.velocity.y)};
      e = ld(c.before_a.restitution) * ld(c.before_b.restitution);
      auto speed = [](const Body<Num>& x) { return std::hypot(ld(x.velocity.x), ld(x.velocity.y)); };
      own_speeds = std::max(speed(c.before_a) + speed(c.before_b), speed(c.after_a) + speed(c.after_b));
    }
    const long double V = std::max(std::hypot(v.x, v.y), std::hypot(w.x, w.y));
    const long double V_round = std::max(V, own_speeds);
    const long double dn = strict ? 4 * unit * (1 + extent / r) : 8 * unit * (1 + 1 / (r * r) + sc.normal_length);
    const long double bound = (strict ? 8 * unit * V_round : 8 * unit * (1 + V_round)) + 4 * V * dn;
    // A graze: the velocity is left as it was and the ball is not closing on
    // a feature it touches (a ball sliding along a wall past its round end
    // touches the end tangentially): there is no reflection to check.
    if (v.x == w.x && v.y == w.y) {
      bool grazing = false;
      for (const Vec2<long double>& normal : normals)
        grazing = grazing || v.x * normal.x + v.y * normal.y >= -bound * std::hypot(normal.x, normal.y);
      if (grazing) continue;
    }
    ++judged;
    std::string what;
    for (const Vec2<long double>& normal : normals) {
      const long double len = std::hypot(normal.x, normal.y);
      const long double nx = normal.x / len, ny = normal.y / len;
      const long double vn = v.x * nx + v.y * ny, vt = -v.x * ny + v.y * nx;
      const long double wn = w.x * nx + w.y * ny, wt = -w.x * ny + w.y * nx;
      what.clear();
      if (std::fabs(wn + e * vn) > bound)
        what = "normal speed " + g17(wn) + " is not -e times " + g17(vn) + " (e = " + g17(e) + "; off by " + g17(wn + e * vn) + ")";
      else if (std::fabs(wt - vt) > bound) what = "tangential speed changed from " + g17(vt) + " to " + g17(wt);
      else if (e == 1 && std::fabs(std::hypot(w.x, w.y) - std::hypot(v.x, v.y)) > bound)
        what = "elastic: speed changed from " + g17(std::hypot(v.x, v.y)) + " to " + g17(std::hypot(w.x, w.y));
      if (what.empty()) break;  // one touched feature explains the reflection
    }
    if (!what.empty())
      return "collision " + std::to_string(k) + " (t = " + g17(ld(c.collision.time)) +
             (c.collision.kind == EventKind::ball_wall ? ", ball " + std::to_string(a) + " and wall " : ", balls " + std::to_string(a) + " and ") +
             std::to_string(b) + "): " + what + ", bound " + g17(bound) + "; ball at (" + g17(ld(ball.position.x)) + ", " +
             g17(ld(ball.position.y)) + "), velocity before (" + g17(v.x) + ", " + g17(v.y) + "), after (" + g17(w.x) +
             ", " + g17(w.y) + ")" + (c.collision.impulse == Num{} ? ", impulse 0" : "");
  }
  if (judged == 0)
    throw NotApplicable("no reflection to judge (" + std::to_string(trace.collisions.size()) +
                        " collisions, each a graze or one where a rest rule acted)");
  return std::nullopt;
}

// The engine's own result, as the momentum check's response.
template <class Num>
std::pair<Vec2<Num>, Vec2<Num>> engine_response(const TracedCollision<Num>& c) {
  return {c.after_a.velocity, c.after_b.velocity};
}

// The article's formula from the same states just before (n from b to a, the
// balls' own restitutions, as the article takes them).
template <class Num>
std::pair<Vec2<Num>, Vec2<Num>> article_response(const TracedCollision<Num>& c) {
  const Vec2<Num> n = normalized(c.after_a.position - c.after_b.position);
  const TwoBallVelocities<Num> out = article_two_ball_response(c.before_a.velocity, c.before_b.velocity, c.before_a.mass,
                                                               c.before_b.mass, n, c.before_a.restitution, c.before_b.restitution);
  return {out.v1, out.v2};
}

}  // namespace

CheckResult check_energy_kept(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) { return energy_kept<decltype(zero)>(scene, duration); });
}

CheckResult check_momentum_kept(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) {
    using Num = decltype(zero);
    return momentum_kept<Num>(scene, duration, engine_response<Num>);
  });
}

CheckResult check_article_momentum_kept(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) {
    using Num = decltype(zero);
    return momentum_kept<Num>(scene, duration, article_response<Num>);
  });
}

CheckResult check_reflection_speed(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) { return reflection_speed<decltype(zero)>(scene, duration); });
}

}  // namespace collide2d::properties
