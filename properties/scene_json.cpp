#include "scene_json.hpp"

namespace collide2d {

void showValue(const Scene& scene, std::ostream& os) { os << scene_to_json(scene, -1); }

}  // namespace collide2d
