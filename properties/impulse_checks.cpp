// Momentum across every impulse, whichever rule applied it
// (scene_checks.hpp).
//
// momentum-kept judges the collisions of two free balls out of contact. The
// rest rules apply impulses too: a strike answered by a ball's whole island
// (held contacts), the plastic impact that makes a contact (rule 1), a
// contact renewed where it slid off a round partner, the hold of a sleeper's
// partners (rule 2), and the refinement step and the wedge's "free part" of
// a strike (contact_graph.hpp). Whatever applied them, frictionless contact
// impulses obey Newton's third law: between two moving balls they are equal
// and opposite, so they cancel in the sum; only what the moving balls touch
// and cannot move (walls, fixed balls, sleeping balls) can change the total
// momentum, and only by pushing along their normals.
//
// The check reads every change of motion the engine told (engine_trace.hpp,
// nothing else): at each instant, the balls whose velocity changed (their
// velocity just after the instant minus their path's just before), grouped
// by touch (within 1e-3 r_min of each other, as the wake check has it, plus
// the rounding of the positions, 64 units of 1 + P as no-overlap's, P the
// largest coordinate of the run: an impulse passes only between balls in
// contact), and for each group
//     Σ m Δv  ∈  cone{ n_k : the normals of the walls and static balls
//                      as near a ball of the group, towards it }
// (none: Σ m Δv = 0). A ball falling asleep (rule 2) drops its velocity by
// design (below v_rest, its energy counted): it is left out of the sum and
// becomes a support of the others, as it is for them. The group takes in
// every moving ball changed at the instant, also one an impulse passed
// through unchanged (the middle of a row struck from both ends).
// One documented pull: a held contact that would part slower than v_rest
// (a rise too low to count) is held at zero whatever the sign of its
// impulse (README, "strike on an island"; contact_graph.hpp, impact), so a
// support may also pull, by at most what stops a parting below v_rest of
// the group: M v_rest per support (M the group's mass; v_rest =
// sqrt(2 g_max h) from the scene, h its rest height or the README's default
// 1e-6 r_min, or its own rest.speed), added to the tolerance below. A plant
// that halves one ball's share of an impact misses by half the impulse,
// m |Δv|, far above that but for strikes as slow as v_rest.
//
// Tolerance: momentum-kept's rounding per impulse (physics_checks.cpp: strict
// 8 eps Σ m (|v| + |v'|), fixed 16·2^-64 Σ m), once per impulse a velocity
// can take: 2 K + 1 per change told (K the most contacts of one ball of the
// group, from the geometry: an impact, its refinement step and the strike),
// plus what the contact solver may leave of a wall's pull: it lets an impulse
// pass as a push while it is above −2^-40 of its row's scale (lcp.hpp), the
// row's speeds |v| + |v'|, times the mass: 2^-40 K Σ m (|v| + |v'|); plus
// the direction of the engine's normals, each off ours (formed here from the
// positions in long double) by δn (reflection-speed's, physics_checks.cpp:
// strict 4 eps (1 + P / r_min), P the largest coordinate of the run; fixed
// 8·2^-64 (1 + 1/r_min² + L)), over impulses that sum to at most 2 K of the
// momentum involved: 2 K δn Σ m (|v| + |v'|). Away from huge translations
// that is ~1e-12 of the momentum involved; a rule that gives one ball an
// impulse and its partner less (the kind of bug this is for) misses by a
// fraction of it.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
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

template <class Num>
LD ld(const Num& x) { return to_long_double(x); }
template <class Num>
Vec2<LD> ld(const Vec2<Num>& v) { return {ld(v.x), ld(v.y)}; }

LD length(const Vec2<LD>& v) { return std::hypot(v.x, v.y); }

// The offset of a point from the nearest point of a wall, given the
// point relative to the wall's end a (formed in Num: exact in fixed point,
// where a long double of a coordinate near 2^20 keeps only 2^-43).
Vec2<LD> offset_from_wall(const WallSpec& w, const Vec2<LD>& rel) {
  const LD dx = LD(w.b[0]) - w.a[0], dy = LD(w.b[1]) - w.a[1];
  const LD dd = dx * dx + dy * dy;
  const LD s = dd > 0 ? std::clamp((rel.x * dx + rel.y * dy) / dd, LD(0), LD(1)) : LD(0);
  return {rel.x - s * dx, rel.y - s * dy};
}

// One ball's change over an instant: its state just before the instant and
// just after its last change in it.
template <class Num>
struct BallChange {
  Body<Num> before, after;
  int changes = 0;
  bool slept = false;
};

template <class Num>
CheckResult impulses_keep_momentum(const Scene& scene, double duration) {
  const EngineTrace<Num> trace = trace_engine<Num>(scene, duration);
  if (auto failure = trace_failure(trace)) return failure;
  double r_min = std::numeric_limits<double>::infinity();
  for (const BallSpec& b : scene.balls) r_min = std::min(r_min, b.radius);
  const bool strict = std::is_same_v<Num, double>;
  const RunScales sc = scales_of(scene, trace);
  const LD near = LD(1e-3) * r_min + 64 * (strict ? strict_eps : fixed_resolution) * (1 + sc.position);
  const LD dn = strict ? 4 * strict_eps * (1 + sc.position / sc.r_min)
                       : 8 * fixed_resolution * (1 + 1 / (sc.r_min * sc.r_min) + sc.normal_length);
  // v_rest as the README defines it, from the scene.
  double g_max = std::hypot(scene.gravity[0], scene.gravity[1]);
  for (const BallSpec& b : scene.balls)
    if (b.acceleration) g_max = std::max(g_max, std::hypot((*b.acceleration)[0], (*b.acceleration)[1]));
  const LD v_rest = scene.rest.speed.value_or(std::sqrt(2 * g_max * scene.rest.height.value_or(1e-6 * r_min)));
  const std::size_t n = scene.balls.size();
  // Each ball's piece in force at time t (the last begun by then).
  std::vector<std::size_t> at(n, 0);
  auto body_at = [&](std::size_t i, const Num& t) {
    const auto& list = trace.pieces[i];
    while (at[i] + 1 < list.size() && !(t < list[at[i] + 1].body.time)) ++at[i];
    Body<Num> b = list[at[i]].body;
    if (!b.is_static()) collide2d::advance_to(b, t);
    return b;
  };
  std::int64_t judged = 0;
  const auto& changes = trace.changes;
  for (std::size_t first = 0; first < changes.size();) {
    // One instant: every change told at this time.
    const Num t = changes[first].after.time;
    std::size_t last = first;
    while (last < changes.size() && changes[last].after.time == t) ++last;
    std::map<int, BallChange<Num>> moved;
    for (std::size_t k = first; k < last; ++k) {
      const TracedChange<Num>& c = changes[k];
      auto [it, fresh] = moved.try_emplace(c.ball);
      if (fresh) it->second.before = c.before;
      it->second.after = c.after;
      ++it->second.changes;
      it->second.slept = it->second.slept || c.why == MotionChange::sleep;
    }
    first = last;
    // The moving balls the engine changed at this instant (a sleeper's drop
    // aside): a ball an impulse passed through without changing its
    // velocity (the middle of a row struck from both ends) is one of them.
    std::vector<int> kicked;
    bool any_kick = false;
    for (const auto& [i, m] : moved) {
      if (m.slept || m.after.is_static()) continue;
      kicked.push_back(i);
      any_kick = any_kick || !(m.before.velocity == m.after.velocity);
    }
    if (!any_kick) continue;
    // Everything's position at the instant; static: fixed, asleep now.
    // Differences are formed in Num, then converted.
    std::vector<Vec2<Num>> position(n);
    std::vector<bool> is_static(n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto found = moved.find(static_cast<int>(i));
      const Body<Num> b = found != moved.end() ? found->second.after : body_at(i, t);
      position[i] = b.position;
      is_static[i] = b.is_static();
    }
    auto offset = [&](int i, int j) { return ld(Vec2<Num>(position[i] - position[j])); };
    auto touching = [&](int i, int j) {
      return length(offset(i, j)) - scene.balls[i].radius - scene.balls[j].radius <= near;
    };
    // Groups of kicked balls in touch (union by scanning: a handful each).
    std::vector<int> group_of(kicked.size());
    std::iota(group_of.begin(), group_of.end(), 0);
    std::function<int(int)> root = [&](int g) { return group_of[g] == g ? g : group_of[g] = root(group_of[g]); };
    for (std::size_t a = 0; a < kicked.size(); ++a)
      for (std::size_t b = a + 1; b < kicked.size(); ++b)
        if (touching(kicked[a], kicked[b])) group_of[root(static_cast<int>(a))] = root(static_cast<int>(b));
    std::map<int, std::vector<int>> groups;
    for (std::size_t a = 0; a < kicked.size(); ++a) groups[root(static_cast<int>(a))].push_back(kicked[a]);
    for (const auto& [g, members] : groups) {
      if (std::all_of(members.begin(), members.end(),
                      [&](int i) { return moved.at(i).before.velocity == moved.at(i).after.velocity; }))
        continue;  // forces only: no impulse
      ++judged;
      Vec2<LD> change{0, 0};
      LD size = 0, mass = 0;
      int told = 0;
      std::size_t most_touches = 0;
      std::vector<Vec2<LD>> supports;
      for (int i : members) {
        const BallChange<Num>& m = moved.at(i);
        const LD mi = ld(m.after.mass);
        const Vec2<LD> v = ld(m.before.velocity), w = ld(m.after.velocity);
        change.x += mi * (w.x - v.x);
        change.y += mi * (w.y - v.y);
        size += mi * (length(v) + length(w));
        mass += mi;
        told += m.changes;
        std::size_t touches = 0;
        const LD r = scene.balls[i].radius;
        for (const WallSpec& wall : scene.walls) {
          const Vec2<LD> d = offset_from_wall(wall, ld(Vec2<Num>(position[i] - vec2_from_double<Num>(wall.a[0], wall.a[1]))));
          const LD dist = length(d);
          if (dist - r > near || !(dist > 0)) continue;
          ++touches;
          supports.push_back({d.x / dist, d.y / dist});
        }
        for (std::size_t j = 0; j < n; ++j) {
          if (static_cast<int>(j) == i || !touching(i, static_cast<int>(j))) continue;
          ++touches;
          const auto found = moved.find(static_cast<int>(j));
          const bool support = is_static[j] || (found != moved.end() && found->second.slept);
          if (!support) continue;
          const Vec2<LD> d = offset(i, static_cast<int>(j));
          const LD dist = length(d);
          if (dist > 0) supports.push_back({d.x / dist, d.y / dist});
        }
        most_touches = std::max(most_touches, touches);
      }
      const LD miss = distance_to_cone(change, supports);
      const LD per = strict ? 8 * strict_eps * size : 16 * fixed_resolution * mass;
      const LD K = static_cast<LD>(most_touches);
      const LD held_pull = static_cast<LD>(supports.size()) * mass * v_rest;
      const LD bound = per * (2 * K + 1) * told + LD(0x1p-40) * K * size + 2 * K * dn * size + held_pull;
      if (!(miss <= bound)) {
        std::string who;
        for (int i : members) who += (who.empty() ? "" : ", ") + std::to_string(i);
        return "at t = " + g17(ld(t)) + " the momentum of ball" + (members.size() > 1 ? "s " : " ") + who +
               " changed by (" + g17(change.x) + ", " + g17(change.y) + "), " + g17(miss) + " outside what its " +
               std::to_string(supports.size()) +  " supports (walls and static balls within " + g17(near) + ") can push (bound " +
               g17(bound) + ", of which held contacts' pull " + g17(held_pull) + "; " + std::to_string(told) +
               " changes told at that instant)";
      }
    }
  }
  if (judged == 0) throw NotApplicable("no impulse changed a moving ball's velocity");
  return std::nullopt;
}

}  // namespace

CheckResult check_impulses_keep_momentum(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) { return impulses_keep_momentum<decltype(zero)>(scene, duration); });
}

}  // namespace collide2d::properties
