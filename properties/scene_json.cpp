#include "scene_json.hpp"

#include <nlohmann/json.hpp>

namespace collide2d {

std::string scene_to_json(const Scene& s, int indent) {
  using nlohmann::json;
  json walls = json::array(), balls = json::array();
  for (const WallSpec& w : s.walls) walls.push_back({{"a", w.a}, {"b", w.b}, {"restitution", w.restitution}});
  for (const BallSpec& b : s.balls) {
    json j = {{"position", b.position}, {"velocity", b.velocity}, {"radius", b.radius},
              {"mass", b.mass},         {"restitution", b.restitution}, {"fixed", b.fixed}};
    if (b.acceleration) j["acceleration"] = *b.acceleration;
    balls.push_back(j);
  }
  const json doc = {{"name", s.name},       {"gravity", s.gravity}, {"duration", s.duration},
                    {"restitution", s.restitution}, {"walls", walls},  {"balls", balls},
                    {"record", {{"interval", s.record_interval}}}};
  return doc.dump(indent);
}

void showValue(const Scene& scene, std::ostream& os) { os << scene_to_json(scene, -1); }

}  // namespace collide2d
