// One case of the property sweep (`collide2d props`, issue 16): a property of
// the table (property_table.hpp) in one mode, its scene generated from a seed
// and a size exactly as RapidCheck generates a case of the suite, judged by
// the same check, and a failure shrunk as RapidCheck shrinks it (the first
// failing shrink at each step, until none fails).
//
// A case is a pure function of (property, mode, seed, size): the same
// outcome on any rank, any machine of the same build, in any order. A
// failure carries RapidCheck's reproduce string, so the ordinary suite runs
// that very case (and its shrink path) on one machine:
//   RC_PARAMS="reproduce=..." collide2d_scene_properties "<test case>"
#pragma once

#include <cstdint>
#include <string>

#include "property_table.hpp"

namespace collide2d::properties {

struct CaseOutcome {
  std::string verdict;         // "pass", "fail" or "discard" (the check does not apply, or a generator rejected)
  std::string detail;          // the failure's message, or why it was discarded
  int scene_balls = 0;         // balls in the generated scene (before shrinking)
  int shrink_steps = 0;        // accepted shrinks of a failure
  bool shrink_cut = false;     // shrinking stopped at max_shrink_tries, not at a local minimum
  std::string counterexample;  // the shrunk scene as a scene file (JSON), for a failure
  std::string reproduce;       // RC_PARAMS for the suite, for a failure
};

// The i-th case seed of a sweep with seed `sweep_seed` (SplitMix64 of
// sweep_seed + i: consecutive seeds give unrelated streams).
std::uint64_t sweep_case_seed(std::uint64_t sweep_seed, std::int64_t i);

// The size of the i-th seed's cases: RapidCheck's sizes cycle 0..max_size.
int sweep_case_size(std::int64_t i, int max_size);

// Runs one case. Shrinking tries at most `max_shrink_tries` candidates.
CaseOutcome run_sweep_case(const SceneProperty& property, const std::string& mode, std::uint64_t seed, int size,
                           int max_shrink_tries);

}  // namespace collide2d::properties
