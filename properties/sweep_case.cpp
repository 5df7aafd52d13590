#include "sweep_case.hpp"

#include <rapidcheck.h>
#include <rapidcheck/detail/Configuration.h>
#include <rapidcheck/detail/Property.h>

#include "collide2d/scene/scene.hpp"
#include "property_case.hpp"

namespace collide2d::properties {
namespace {

using rc::detail::CaseDescription;
using rc::detail::CaseResult;

bool failed(const CaseDescription& d) { return d.result.type == CaseResult::Type::Failure; }

// RapidCheck's description of an RC_FAIL starts with where it was raised
// ("file:line:\nRC_FAIL(...)\n\n"); the check's own message follows.
std::string message_of(const CaseDescription& d) {
  const std::string& text = d.result.description;
  const auto blank = text.find("\n\n");
  return blank == std::string::npos ? text : text.substr(blank + 2);
}

}  // namespace

std::uint64_t sweep_case_seed(std::uint64_t sweep_seed, std::int64_t i) {
  std::uint64_t z = sweep_seed + 0x9e3779b97f4a7c15ULL * (static_cast<std::uint64_t>(i) + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

int sweep_case_size(std::int64_t i, int max_size) { return static_cast<int>(i % (static_cast<std::int64_t>(max_size) + 1)); }

CaseOutcome run_sweep_case(const SceneProperty& property, const std::string& mode, std::uint64_t seed, int size,
                           int max_shrink_tries) {
  const rc::detail::Property gen = rc::detail::toProperty(property.testable(mode));
  const rc::Random random(seed);
  last_failing_scene().reset();
  last_generated_scene_balls() = 0;
  rc::Shrinkable<CaseDescription> current = gen(random, size);
  const CaseDescription first = current.value();
  CaseOutcome out;
  out.scene_balls = last_generated_scene_balls();
  if (first.result.type == CaseResult::Type::Success) {
    out.verdict = "pass";
    return out;
  }
  if (first.result.type == CaseResult::Type::Discard) {
    out.verdict = "discard";
    out.detail = first.result.description;
    return out;
  }
  // Shrink: take the first failing candidate at each step, as RapidCheck
  // does, and remember its index for the reproduce string's shrink path.
  out.verdict = "fail";
  out.detail = message_of(first);
  std::vector<std::size_t> path;
  int tries = 0;
  for (bool shrunk = true; shrunk;) {
    shrunk = false;
    auto candidates = current.shrinks();
    std::size_t index = 0;
    while (auto candidate = candidates.next()) {
      if (tries++ >= max_shrink_tries) {
        out.shrink_cut = true;
        break;
      }
      const CaseDescription d = candidate->value();
      if (failed(d)) {
        current = std::move(*candidate);
        path.push_back(index);
        out.detail = message_of(d);
        shrunk = true;
        break;
      }
      ++index;
    }
    if (out.shrink_cut) break;
  }
  out.shrink_steps = static_cast<int>(path.size());
  // Only a failing evaluation sets last_failing_scene (property_table.cpp),
  // and the last failing one evaluated is `current`: the scene remembered is
  // its own, with no need to run it again.
  if (last_failing_scene()) out.counterexample = scene_to_json(last_failing_scene()->scene);
  rc::detail::Configuration config;
  config.reproduce[property.name + " [" + mode + "]"] = rc::detail::Reproduce{random, size, path};
  out.reproduce = rc::detail::configToMinimalString(config);
  return out;
}

}  // namespace collide2d::properties
