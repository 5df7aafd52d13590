// What a property's case leaves behind for whoever runs it (the Catch2
// runner, property_runner.hpp, or the sweep, sweep_case.hpp): the failing
// scene, and the discard of a case a check does not apply to. Free of
// Catch2, so that the program's `props` command links it.
#pragma once

#include <optional>
#include <string>

#include <rapidcheck.h>

#include "collide2d/scene/scene.hpp"

namespace collide2d::properties {

// Inside a scene property: remember the scene whenever the check fails.
// Shrinking ends on the last failing candidate, so after a failed run the
// scene remembered last is the shrunk counterexample.
struct FailingScene {
  Scene scene;
  std::string check;  // the check's slug (scene_checks.hpp), for the replay
  double duration = 0;
};
std::optional<FailingScene>& last_failing_scene();  // thread_local

// Inside a property: this case is one the claim does not apply to. It is
// discarded and counted with its reason as not applicable (neither a pass
// nor a failure), apart from a generator's rejections.
[[noreturn]] inline void discard_not_applicable(const std::string& why) {
  throw rc::detail::CaseResult(rc::detail::CaseResult::Type::Discard, "not applicable: " + why);
}

}  // namespace collide2d::properties
