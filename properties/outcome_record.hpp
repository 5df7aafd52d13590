// What one property run produced, and where it is kept: deep runs are
// compared over time (analysis/summarise_properties.py reads these files).
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace collide2d::properties {

struct PropertyOutcome {
  std::string property;        // e.g. "energy is kept in elastic scenes"
  std::string mode;            // "strict", "fixed", or "-" where no number mode applies
  std::uint64_t seed = 0;      // RapidCheck's seed for this run
  int max_success = 0;         // cases asked for (RC_PARAMS max_success)
  int max_size = 0;            // RC_PARAMS max_size
  int cases = 0;               // cases judged: a check applied and held (before the end or the failure)
  int discarded = 0;           // cases a check did not apply to (NotApplicable): neither passed nor failed
  int rejected = 0;            // cases a generator's precondition (RC_PRE) threw away before any check
  std::map<std::string, int> discard_reasons;  // why cases were discarded (the reason's words before its first number)
  int failures = 0;            // 0 or 1 (RapidCheck stops at the first failure)
  bool gave_up = false;        // too many cases discarded
  double seconds = 0;          // wall time of the run, shrinking included
  std::map<std::string, int> distribution;  // generated cases per tag (RC_TAG / RC_CLASSIFY), tags joined by ", "
  std::string counterexample;  // the shrunk failing case as RapidCheck prints it; empty on success
};

// Appends the outcome to the HDF5 file named by the environment variable
// COLLIDE2D_PROPERTY_RECORD, creating it if needed; does nothing when the
// variable is unset.
void record_property_outcome(const PropertyOutcome& outcome);

}  // namespace collide2d::properties
