// A time-of-impact query line (JSON Lines, docs/formats/query.md) read into a
// ToiQuery: the scene format's parser and its errors, with "horizon".
#pragma once

#include <nlohmann/json_fwd.hpp>

#include "collide2d/scene/scene.hpp"
#include "collide2d/toi/query.hpp"

namespace collide2d {

// From a query line: a scene with one moving ball and one wall or one more
// ball, plus "horizon". Throws SceneError naming the field.
ToiQuery parse_toi_query(const nlohmann::json& line);

}  // namespace collide2d
