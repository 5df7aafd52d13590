// The scene properties as plain functions: a scene (and a number mode, and a
// simulated duration) in, a failure description out (nullopt: it holds). The
// same function runs under RapidCheck (scene_properties.cpp) and in the
// regression replay (tests/regressions/test_regressions.cpp), so a stored
// counterexample is checked by exactly the code that found it.
//
// Each check states its tolerance and derives it in the comment above its
// definition. Modes: "strict" (IEEE double) and "fixed" (Q63.64).
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "collide2d/scene/scene.hpp"

namespace collide2d::properties {

using CheckResult = std::optional<std::string>;

// Elastic scenes keep their total energy (physics_checks.cpp).
CheckResult check_energy_kept(const Scene& scene, const std::string& mode, double duration);
// Every ball–ball collision between free balls keeps momentum (physics_checks.cpp).
CheckResult check_momentum_kept(const Scene& scene, const std::string& mode, double duration);
// The seed article's response applied to the same collisions: momentum is
// NOT kept for unequal masses. Expected to fail (physics_checks.cpp).
CheckResult check_article_momentum_kept(const Scene& scene, const std::string& mode, double duration);
// Walls and fixed balls: speed kept when elastic; the normal speed scaled by
// exactly e otherwise, tangential part kept (physics_checks.cpp).
CheckResult check_reflection_speed(const Scene& scene, const std::string& mode, double duration);
// No ball overlaps another or a wall beyond the tolerance at any time of the
// continuous motion (a ball through a wall overlaps it) (motion_checks.cpp).
CheckResult check_no_overlap(const Scene& scene, const std::string& mode, double duration);
// Same bits twice; same bits after a run-file round trip; resume from a
// checkpoint equals the uninterrupted run (determinism_checks.cpp).
CheckResult check_deterministic(const Scene& scene, const std::string& mode, double duration);
CheckResult check_run_file_replay(const Scene& scene, const std::string& mode, double duration);
CheckResult check_resume_equals_uninterrupted(const Scene& scene, const std::string& mode, double duration);
// In a gas (no ball accelerates) the plain gas path of the engine gives the
// general path's frames, events and counts to the bit (determinism_checks.cpp).
CheckResult check_gas_fast_path_same_bits(const Scene& scene, const std::string& mode, double duration);
// Every impulse, whichever rule applied it (a collision, a held strike, a
// plastic impact, a renewed contact, a hold): the momentum of the balls it
// moved changes only by what walls and static balls touching them can push
// (impulse_checks.cpp).
CheckResult check_impulses_keep_momentum(const Scene& scene, const std::string& mode, double duration);
// Fixed and strict agree on a short horizon within a derived bound; `mode`
// is ignored ("-") (determinism_checks.cpp).
CheckResult check_fixed_matches_strict(const Scene& scene, const std::string& mode, double duration);

// A check whose claim says nothing about a scene (an elastic contact for
// the energy-never-rises check, a dropped ball that misses the pile) throws
// NotApplicable: the property discards the case (RC_DISCARD), neither a pass
// nor a failure; in_mode (check_support.hpp) lets it through. A stored
// regression file it does not apply to is an error of the file: the replay
// sees the exception.
struct NotApplicable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Every restitution below 1 (the scene's default, every ball's, every
// wall's): the total energy Σ ½ m|v|² − m a·p of the moving balls never rises
// from one frame to the next by more than 1e-12 of the scene's energy scale
// (rest_checks.cpp). NotApplicable otherwise.
CheckResult check_energy_never_rises(const Scene& scene, const std::string& mode, double duration);
// A pile (every moving ball under an acceleration, walls below it, every
// restitution below 1) comes to rest within T_rest, a bound from the scene
// (pile_bounds): over [T_rest, T_rest + 2 s] at most one event per moving
// ball per simulated second, and no overlap deeper than 1e-6 r_min at any
// frame (rest_checks.cpp). Runs until max(duration, T_rest + 2 s).
CheckResult check_pile_comes_to_rest(const Scene& scene, const std::string& mode, double duration);
// The pile settled as above, restarted from its last frame with one more
// ball dropped onto its top: at the dropped ball's first ball–ball collision
// the pair's momentum is kept within rounding (rest_checks.cpp).
CheckResult check_wake_keeps_momentum(const Scene& scene, const std::string& mode, double duration);
// One ball dropped from rest onto a flat floor under gravity, no rest
// settings in the scene: its last bounce comes where the README's default
// rest height (1e-6 r) puts it, within a window derived from the bounce
// series, and the ball then lies still (bounce_checks.cpp).
CheckResult check_bounce_comes_to_rest_on_time(const Scene& scene, const std::string& mode, double duration);
// A ball lying on a flat floor struck by one dropped on it off its centre
// line: at the strike the pair's horizontal momentum is kept (the floor
// pushes vertically) and the lying ball moves (bounce_checks.cpp).
CheckResult check_struck_sleeper_keeps_momentum(const Scene& scene, const std::string& mode, double duration);

// The bounds of a settling scene, from the scene alone (rest_checks.cpp,
// where each is derived): nullopt when the scene does not settle (a moving
// ball without acceleration, no wall below a ball, a restitution of 1).
struct PileBounds {
  int moving = 0;             // balls not fixed
  double g = 0;               // smallest |acceleration| of a moving ball
  double e = 0;               // largest restitution in the scene
  double r_min = 0;           // smallest radius
  double impact_speed = 0;    // V: the fastest a ball can arrive at the lowest wall point
  double fall_time = 0;       // t_fall: the longest a ball can take to get there
  double series_time = 0;     // t* = 2 e V / (g (1 − e)): a bounce series from V, summed to the end
  double rest_speed = 0;      // v_rest = sqrt(2 g · 1e-6 r_min)
  double bounces = 0;         // k: bounces from V down to v_rest, ln(V / v_rest) / ln(1 / e)
  double settle_time = 0;     // T_rest = t_fall + exchange_factor · t*
  double window = 0;          // the rest window after T_rest
  std::int64_t event_budget(double until) const;  // a run making more events is stopped (and fails)
  double until() const { return settle_time + window; }
};
std::optional<PileBounds> pile_bounds(const Scene& scene);

// Every check by its slug, for the regression replay: the slug is what the
// regression file names start with.
struct NamedCheck {
  std::string slug;      // e.g. "energy-kept"
  std::string property;  // a sentence
  CheckResult (*check)(const Scene&, const std::string&, double);
};
const std::vector<NamedCheck>& named_checks();
const NamedCheck* find_check(const std::string& slug);

}  // namespace collide2d::properties
