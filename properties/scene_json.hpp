// A scene written back as the JSON that parse_scene reads (SPEC.md "Scene
// file"): failing cases are kept as ordinary scene files that `collide2d
// check` and `collide2d run` accept. Every value is written explicitly (no
// defaults), and doubles in nlohmann's shortest round-trip form, so
// parse_scene(scene_to_json(s)) gives back the same bits.
#pragma once

#include <ostream>
#include <string>

#include "scene/scene.hpp"

namespace collide2d {

std::string scene_to_json(const Scene& scene, int indent = 2);

// How RapidCheck prints a Scene in a counterexample (found by ADL).
void showValue(const Scene& scene, std::ostream& os);

}  // namespace collide2d
