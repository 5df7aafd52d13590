// The scene properties as plain functions: a scene (and a number mode, and a
// simulated duration) in, a failure description out (nullopt: it holds). The
// same function runs under RapidCheck (scene_properties.cpp) and in the
// regression replay (tests/regressions/test_regressions.cpp), so a stored
// counterexample is checked by exactly the code that found it.
//
// Each check states its tolerance and derives it in the comment above its
// definition. Modes: "strict" (IEEE double) and "fixed" (Q63.64).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/scene.hpp"

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
// Fixed and strict agree on a short horizon within a derived bound; `mode`
// is ignored ("-") (determinism_checks.cpp).
CheckResult check_fixed_matches_strict(const Scene& scene, const std::string& mode, double duration);

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
