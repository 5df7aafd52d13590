// The scene properties as a table: which check, over which generated
// scenes, in which modes, run by which Catch2 test case. The suite
// (scene_properties.cpp) and the sweep (`collide2d props`, sweep_case.hpp)
// take their properties from here, so a case of the sweep is a case of the
// suite: same generator, same check, same RapidCheck id, and a failure the
// sweep finds is reproduced by the suite from its reproduce string.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace collide2d::properties {

struct SceneProperty {
  std::string slug;       // the check's slug (scene_checks.hpp)
  std::string test_case;  // the Catch2 TEST_CASE of scene_properties.cpp that runs it
  std::string name;       // the check's sentence; RapidCheck's id is "name [mode]"
  std::vector<std::string> modes;  // "strict", "fixed", or "both" (fixed against strict)
  bool expect_counterexample = false;  // the article's formula: a failure is the expected outcome
  bool open = false;      // a pile property (ctest label open, left out of the default sweep)
  int case_share = 1;     // the suite runs max_success / case_share cases of it
  // The RapidCheck testable of one mode: generates a scene, runs the check,
  // RC_FAILs with the check's message (remembering the scene, see
  // last_failing_scene) or discards when the check does not apply.
  std::function<std::function<void()>(const std::string& mode)> testable;
};

// Every scene property, in the order of scene_properties.cpp.
const std::vector<SceneProperty>& scene_property_table();
const SceneProperty* find_scene_property(const std::string& slug);

// The number of balls of the scene the testable generated last on this
// thread (0 before any): the sweep records each case's scene size.
int& last_generated_scene_balls();

}  // namespace collide2d::properties
