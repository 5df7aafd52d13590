// Runs one RapidCheck property inside a Catch2 TEST_CASE (instead of
// rc::prop): the configuration's parameters (RC_PARAMS), a fixed default seed
// when RC_PARAMS gives none (so CI is reproducible), one outcome line per
// property, progress lines for deep runs, the outcome recorded
// (outcome_record.hpp), and on failure the shrunk scene written as a
// regression file (docs/PROPERTIES.md) and the test failed.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>
#include <rapidcheck.h>

#include "collide2d/scene/scene.hpp"
#include "outcome_record.hpp"
#include "property_case.hpp"

namespace collide2d::properties {

// The seed CI uses when RC_PARAMS names none: "collide2" in ASCII.
inline constexpr std::uint64_t default_seed = 0x636f6c6c69646532ULL;

enum class Expect { pass, counterexample };

// The parameters of this run: RapidCheck's configuration (RC_PARAMS), with
// default_seed if RC_PARAMS sets no seed.
rc::detail::TestParams property_params();

// Where regression files go: $COLLIDE2D_REGRESSIONS_DIR, else the source
// tree's datasets/regressions.
std::string regressions_dir();

// Writes <dir>/<slug>-<mode>-<seed>.json (the scene) and .meta.json (what
// failed and how to reproduce it); expected failures go to <dir>/expected/.
// Returns the scene file's path.
std::string write_regression(const FailingScene& failing, const std::string& property, const std::string& mode,
                             std::uint64_t seed, const std::string& failure, const std::string& reproduce,
                             bool expected);

// Counts cases; prints progress every tenth of a deep run (max_success > 1000).
class ProgressListener : public rc::detail::TestListener {
 public:
  ProgressListener(std::string label, int max_success)
      : label_(std::move(label)), max_success_(max_success), started_(std::chrono::steady_clock::now()) {}
  void onTestCaseFinished(const rc::detail::CaseDescription& description) override;
  void onShrinkTried(const rc::detail::CaseDescription&, bool accepted) override {
    ++shrinks_tried_;
    shrinks_accepted_ += accepted ? 1 : 0;
  }
  void onTestFinished(const rc::detail::TestMetadata&, const rc::detail::TestResult&) override {}
  int cases() const { return cases_; }
  int shrinks_accepted() const { return shrinks_accepted_; }
  // Cases discarded (RC_PRE in a generator, RC_DISCARD for a check that
  // does not apply), and how many for each reason.
  int discards() const { return discards_; }
  const std::map<std::string, int>& discard_reasons() const { return discard_reasons_; }
  // Of those, the cases a check did not apply to (NotApplicable: the reason
  // starts "not applicable: "): generated, run, and not judged. The rest
  // were rejected by a generator's precondition before any check ran.
  int not_applicable() const;

 private:
  std::string label_;
  int max_success_;
  std::chrono::steady_clock::time_point started_;
  int cases_ = 0, shrinks_tried_ = 0, shrinks_accepted_ = 0, discards_ = 0;
  std::map<std::string, int> discard_reasons_;
};

// What the runner does with a finished run (property_runner.cpp): prints,
// records, writes the regression file; returns the Catch2 failure message
// or "" when the test passes.
std::string conclude_property(const std::string& name, const std::string& mode, const rc::detail::TestParams& params,
                              const rc::detail::TestResult& result, const ProgressListener& progress, double seconds,
                              Expect expect);

// `case_share`: the property runs max_success / case_share cases (at least
// one): the long properties (piles) take a share of what RC_PARAMS asks.
template <class Testable>
void check_property(const std::string& name, const std::string& mode, Testable&& testable, Expect expect = Expect::pass,
                    int case_share = 1) {
  rc::detail::TestParams params = property_params();
  params.maxSuccess = std::max(1, params.maxSuccess / std::max(1, case_share));
  rc::detail::TestMetadata metadata;
  metadata.id = name + " [" + mode + "]";
  metadata.description = metadata.id;
  ProgressListener progress(metadata.id, params.maxSuccess);
  last_failing_scene().reset();
  const auto started = std::chrono::steady_clock::now();
  const rc::detail::TestResult result =
      rc::detail::checkProperty(rc::detail::toProperty(std::forward<Testable>(testable)), metadata, params, progress,
                                rc::detail::configuration().reproduce);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const std::string failure = conclude_property(name, mode, params, result, progress, seconds, expect);
  if (!failure.empty()) FAIL(failure);
  SUCCEED();
}

}  // namespace collide2d::properties
