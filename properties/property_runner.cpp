#include "property_runner.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "scene_json.hpp"

namespace collide2d::properties {

rc::detail::TestParams property_params() {
  rc::detail::TestParams params = rc::detail::configuration().testParams;
  const char* env = std::getenv("RC_PARAMS");
  if (!env || std::string(env).find("seed") == std::string::npos) params.seed = default_seed;
  return params;
}

std::string regressions_dir() {
  if (const char* env = std::getenv("COLLIDE2D_REGRESSIONS_DIR"); env && *env) return env;
  return COLLIDE2D_SOURCE_REGRESSIONS_DIR;
}

namespace {

std::string slug_of(const std::string& text) {
  std::string slug;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c))) slug += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    else if (!slug.empty() && slug.back() != '-') slug += '-';
  }
  while (!slug.empty() && slug.back() == '-') slug.pop_back();
  return slug;
}

std::string join_tags(const rc::detail::Tags& tags) {
  std::string out;
  for (const std::string& t : tags) out += (out.empty() ? "" : ", ") + t;
  return out;
}

// RC_PARAMS that reproduce this failure (RapidCheck's own reproduce string).
std::string reproduce_string(const std::string& id, const rc::detail::TestParams& params,
                             const rc::detail::FailureResult& failure) {
  rc::detail::Configuration config;
  config.testParams = params;
  config.reproduce[id] = failure.reproduce;
  return rc::detail::configToMinimalString(config);
}

}  // namespace

std::string write_regression(const FailingScene& failing, const std::string& property, const std::string& mode,
                             std::uint64_t seed, const std::string& failure, const std::string& reproduce, bool expected) {
  std::filesystem::path dir = regressions_dir();
  if (expected) dir /= "expected";
  std::filesystem::create_directories(dir);
  const std::string stem = (failing.check.empty() ? slug_of(property) : failing.check) + "-" + mode + "-" + std::to_string(seed);
  const std::filesystem::path scene_path = dir / (stem + ".json"), meta_path = dir / (stem + ".meta.json");
  std::ofstream(scene_path) << scene_to_json(failing.scene) << "\n";
  const nlohmann::json meta = {{"property", property},
                               {"check", failing.check},
                               {"mode", mode},
                               {"seed", seed},
                               {"duration", failing.duration},
                               {"failure", failure},
                               {"reproduce", "RC_PARAMS=\"" + reproduce + "\""},
                               {"expected_failure", expected}};
  std::ofstream(meta_path) << meta.dump(2) << "\n";
  return scene_path.string();
}

namespace {
const std::string not_applicable_prefix = "not applicable: ";
}

int ProgressListener::not_applicable() const {
  int n = 0;
  for (const auto& [why, count] : discard_reasons_)
    if (why.rfind(not_applicable_prefix, 0) == 0) n += count;
  return n;
}

void ProgressListener::onTestCaseFinished(const rc::detail::CaseDescription& description) {
  ++cases_;
  if (description.result.type == rc::detail::CaseResult::Type::Discard) {
    ++discards_;
    // Grouped by the reason's words before its first number ("restitution 1
    // at balls[3]" and "restitution 1 at balls[0]" are one reason).
    const std::string& why = description.result.description;
    std::string key = why.substr(0, why.find_first_of("0123456789"));
    while (!key.empty() && (key.back() == ' ' || key.back() == '(' || key.back() == '[')) key.pop_back();
    ++discard_reasons_[key];
  }
  if (max_success_ > 1000 && cases_ % (max_success_ / 10) == 0) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
    std::cerr << "  " << label_ << ": " << cases_ << "/" << max_success_ << " cases, " << s << " s\n";
  }
}

std::string conclude_property(const std::string& name, const std::string& mode, const rc::detail::TestParams& params,
                              const rc::detail::TestResult& result, const ProgressListener& progress, double seconds,
                              Expect expect) {
  using namespace rc::detail;
  const std::string id = name + " [" + mode + "]";
  PropertyOutcome outcome;
  outcome.property = name;
  outcome.mode = mode;
  outcome.seed = params.seed;
  outcome.max_success = params.maxSuccess;
  outcome.max_size = params.maxSize;
  outcome.seconds = seconds;
  // A case a check did not apply to is neither a pass nor a failure: it is
  // counted apart (discarded), and so are a generator's rejections. Only the
  // cases judged count as cases.
  outcome.discarded = progress.not_applicable();
  outcome.rejected = progress.discards() - outcome.discarded;
  for (const auto& [why, count] : progress.discard_reasons())
    if (why.rfind(not_applicable_prefix, 0) == 0) outcome.discard_reasons[why.substr(not_applicable_prefix.size())] += count;
  std::ostringstream line, message;
  line.precision(3);
  line << "property " << id << ": ";
  std::string failure;
  if (result.template is<SuccessResult>()) {
    const SuccessResult& ok = result.template get<SuccessResult>();
    outcome.cases = ok.numSuccess;
    for (const auto& [tags, count] : ok.distribution) outcome.distribution[join_tags(tags)] += count;
    line << (expect == Expect::pass ? "OK, " : "NO COUNTEREXAMPLE (one was expected), ") << ok.numSuccess << " cases judged, "
         << outcome.discarded << " discarded (not applicable), " << outcome.rejected << " rejected by the generator";
    if (expect == Expect::counterexample)
      failure = id + ": expected RapidCheck to find a counterexample, none in " + std::to_string(ok.numSuccess) + " cases";
  } else if (result.template is<FailureResult>()) {
    const FailureResult& bad = result.template get<FailureResult>();
    outcome.cases = bad.numSuccess;
    outcome.failures = 1;
    std::ostringstream shown;
    printResultMessage(result, shown);
    outcome.counterexample = shown.str();
    const std::string reproduce = reproduce_string(id, params, bad);
    std::string file = "(not a scene property: no regression file)";
    if (last_failing_scene())
      file = write_regression(*last_failing_scene(), name, mode, params.seed, bad.description, reproduce,
                              expect == Expect::counterexample);
    if (expect == Expect::counterexample) {
      line << "counterexample found as expected after " << bad.numSuccess << " cases judged (" << outcome.discarded
           << " discarded), shrunk in "
           << progress.shrinks_accepted() << " steps -> " << file;
    } else {
      line << "FAILED after " << bad.numSuccess << " cases judged (" << outcome.discarded << " discarded) -> " << file;
      message << id << " failed (seed " << params.seed << ")\n" << shown.str() << "\nshrunk scene: " << file
              << "\nreproduce: RC_PARAMS=\"" << reproduce << "\"";
      failure = message.str();
    }
  } else if (result.template is<GaveUpResult>()) {
    const GaveUpResult& gave_up = result.template get<GaveUpResult>();
    outcome.cases = gave_up.numSuccess;
    outcome.gave_up = true;
    line << "GAVE UP after " << gave_up.numSuccess << " cases judged, " << outcome.discarded << " discarded: "
         << gave_up.description;
    failure = id + ": RapidCheck gave up: " + gave_up.description;
  } else {
    line << "ERROR " << result.template get<Error>().description;
    failure = id + ": " + result.template get<Error>().description;
  }
  line << " in " << seconds << " s (seed " << params.seed << ", max_size " << params.maxSize << ")";
  std::cout << line.str() << std::endl;
  // Discards by a check that does not apply (scene_properties.cpp: the
  // description starts "not applicable: "), with their reasons; a
  // generator's RC_PRE discards are not listed.
  {
    std::ostringstream reasons;
    int listed = 0;
    for (const auto& [why, count] : outcome.discard_reasons) reasons << (listed++ ? "; " : "") << count << " x " << why;
    if (listed) std::cout << "    discarded, not applicable: " << reasons.str() << "\n";
  }
  // The distribution, one line: the share of cases carrying each tag.
  if (result.template is<SuccessResult>()) {
    std::map<std::string, int> per_tag;
    for (const auto& [tags, count] : result.template get<SuccessResult>().distribution)
      for (const std::string& tag : tags) per_tag[tag] += count;
    if (!per_tag.empty()) {
      std::cout << "    ";
      for (const auto& [tag, count] : per_tag) std::cout << tag << " " << 100 * count / std::max(outcome.cases, 1) << "%; ";
      std::cout << "\n";
    }
  }
  record_property_outcome(outcome);
  return failure;
}

}  // namespace collide2d::properties
