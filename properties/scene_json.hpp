// How RapidCheck prints a Scene in a counterexample: as the scene file that
// `collide2d check` and `collide2d run` accept (scene_to_json, scene/scene.hpp).
#pragma once

#include <ostream>

#include "collide2d/scene/scene.hpp"

namespace collide2d {

// Found by ADL.
void showValue(const Scene& scene, std::ostream& os);

}  // namespace collide2d
