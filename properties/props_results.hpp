// The results of a property sweep (`collide2d props`, issue 16): the plan
// that decides them, the finished cases, and the file they go to (layout:
// docs/formats/props-file.md).
//
// Case c of a plan with N seeds per (property, mode) pair is pair c / N on
// the seed index c mod N: every pair sees the same seeds, and rank r of K,
// taking cases r, r + K, ..., gets every K-th seed of every pair, so the
// ranks' shares cost about the same (pairs differ in cost; seeds, through
// their sizes, too).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/ranks.hpp"
#include "sweep_case.hpp"

namespace collide2d::properties {

struct PropsPlan {
  std::int64_t seeds = 100;                                   // --cases
  std::uint64_t seed = 0;                                     // --seed
  int max_size = 100;                                         // --max-size
  int max_shrink_tries = 2000;                                // --max-shrinks
  std::vector<std::pair<std::string, std::string>> pairs;     // (property slug, mode), table order

  std::int64_t total() const { return seeds * static_cast<std::int64_t>(pairs.size()); }
  std::int64_t seed_index(std::int64_t c) const { return c % seeds; }
  const std::pair<std::string, std::string>& pair(std::int64_t c) const { return pairs[static_cast<std::size_t>(c / seeds)]; }
  std::uint64_t case_seed(std::int64_t c) const { return sweep_case_seed(seed, seed_index(c)); }
  int case_size(std::int64_t c) const { return sweep_case_size(seed_index(c), max_size); }
  // What decides the outcomes: a journal is resumed only with the same.
  nlohmann::json to_json() const;
};

// A finished case as rank 0 records it.
struct PropsCase {
  CaseOutcome outcome;
  double seconds = 0;  // wall time of the case on its rank
  int rank = 0;
  std::string host;
};

// One line of the journal and of a rank's message; and back.
nlohmann::json case_line(std::int64_t c, const PropsCase& done);
std::pair<std::int64_t, PropsCase> case_of_line(const nlohmann::json& line);

// A run of the sweep over some of the cases (the first, then each resume).
struct PropsSession {
  int ranks = 1;
  std::int64_t cases = 0;  // cases it set out to run
  std::string started;     // UTC
  std::string mpi;
};
nlohmann::json session_line(const PropsSession& s);

// The journal's cases and sessions (cli/journal.hpp), read with the plan's options.
struct PropsJournal {
  std::map<std::int64_t, PropsCase> cases;
  std::vector<PropsSession> sessions;
};
PropsJournal read_props_journal(const std::string& path, const PropsPlan& plan);

// Writes the results to `path` (HDF5): every case of the plan in order, a
// case without an outcome as verdict "missing" and listed in /missing.
// `complete` says whether the sweep is over (attribute /complete).
void write_props_file(const std::string& path, const PropsPlan& plan, const PropsJournal& journal, bool complete,
                      const std::string& command);

}  // namespace collide2d::properties
