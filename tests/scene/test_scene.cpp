// Scene parsing: defaults, JSON-path errors, and what counts as overlap.
#include <catch2/catch.hpp>

#include <cmath>

#include <nlohmann/json.hpp>

#include "collide2d/scene/scene.hpp"

using namespace collide2d;
using nlohmann::json;

namespace {
std::string error_of(const std::string& text) {
  try {
    const Scene s = parse_scene(parse_json_text(text));
    check_no_initial_overlap(s);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("scene defaults follow SPEC.md", "[scene]") {
  const Scene s = parse_scene(json::parse(R"({"restitution": 0.8, "balls": [{"position": [1, 2], "radius": 0.5}],
                                              "walls": [{"a": [0, 0], "b": [4, 0]}]})"));
  REQUIRE(s.balls.size() == 1);
  CHECK(s.gravity == Point{0, 0});
  CHECK(s.balls[0].mass == 1.0);
  CHECK(s.balls[0].restitution == 0.8);  // the scene default
  CHECK(s.walls[0].restitution == 0.8);
  CHECK_FALSE(s.balls[0].fixed);
  CHECK(effective_acceleration(s, s.balls[0]) == Point{0, 0});
}

TEST_CASE("scene errors name the JSON path", "[scene]") {
  CHECK(error_of(R"({"balls": [{"position": [0, 0], "radius": 1}, {"position": [5, 0], "radius": 0}]})") ==
        "balls[1].radius: must be > 0");
  CHECK(error_of(R"({"balls": [{"position": [0, 0], "radius": 1, "mass": -2}]})") == "balls[0].mass: must be > 0");
  CHECK(error_of(R"({"walls": [{"a": [0, 0], "b": [1, 0], "restitution": 1.5}]})") ==
        "walls[0].restitution: must lie in [0, 1]");
  CHECK(error_of(R"({"walls": [{"a": [1, 1], "b": [1, 1]}]})") == "walls[0]: zero-length wall (a equals b)");
  CHECK(error_of(R"({"gravty": [0, -9.81]})") == "gravty: unknown field");
  CHECK(error_of(R"({"balls": [{"position": [0, 1e999], "radius": 1}]})").rfind("balls[0].position[1]: must be a finite", 0) == 0);
  CHECK(error_of(R"({"balls": [{"position": [0], "radius": 1}]})") == "balls[0].position: must be an array of two numbers");
  CHECK(error_of(R"({"balls": [{"radius": 1}]})") == "balls[0].position: missing");
}

TEST_CASE("overlap at t = 0 is refused, exact contact is not", "[scene]") {
  CHECK(error_of(R"({"balls": [{"position": [0, 0], "radius": 1}, {"position": [1.5, 0], "radius": 1}]})") ==
        "balls[1]: overlaps balls[0] at t = 0");
  CHECK(error_of(R"({"balls": [{"position": [0, 0.4], "radius": 0.5}], "walls": [{"a": [-1, 0], "b": [1, 0]}]})") ==
        "balls[0]: overlaps walls[0] at t = 0");
  // Touching an oblique wall: the centre at distance r along the normal of
  // y = x, which the computed distance may round either way.
  const double r = 0.5, h = r / std::sqrt(2.0);
  json touching = {{"balls", {{{"position", {0.3 - h, 0.3 + h}}, {"radius", r}}}},
                   {"walls", {{{"a", {0, 0}}, {"b", {1, 1}}}}}};
  CHECK(error_of(touching.dump()) == "");
  // Balls touching exactly.
  CHECK(error_of(R"({"balls": [{"position": [0, 0], "radius": 1}, {"position": [2, 0], "radius": 1}]})") == "");
}

// Two balls 6.4e-7 apart with radii 6.7e-7, far from a third: the overlap
// check's grid once put them two cells apart (rounding of their offsets from
// the lowest ball exceeded a cell) and check accepted the scene. Found by
// review and confirmed by fuzz_scene's plain-loop contract
// (datasets/fuzz/scene/far_overlap_missed_by_grid.json).
TEST_CASE("overlap at t = 0 is refused however far the balls are from the others", "[scene]") {
  CHECK(error_of(R"({"balls": [{"position": [-256858701592.45715, 0], "radius": 6.666767359982674e-07},
                              {"position": [114162891.00669804, 0], "radius": 6.666767359982674e-07},
                              {"position": [114162891.00669868, 0], "radius": 6.666767359982674e-07}]})") ==
        "balls[2]: overlaps balls[1] at t = 0");
}

// scene_from_text reads each ball as the parser finishes it and keeps none of
// them in the document (a million balls would take a gigabyte as JSON
// objects); it must answer exactly as parsing the whole document does.
TEST_CASE("a scene read ball by ball is the scene the whole document gives, errors included", "[scene]") {
  auto whole = [](const std::string& text) -> std::string {
    try {
      const Scene s = parse_scene(parse_json_text(text));
      check_no_initial_overlap(s);
      return scene_to_json(s);
    } catch (const SceneError& e) {
      return std::string("error: ") + e.what();
    }
  };
  auto streamed = [](const std::string& text) -> std::string {
    try {
      return scene_to_json(scene_from_text(text));
    } catch (const SceneError& e) {
      return std::string("error: ") + e.what();
    }
  };
  const std::vector<std::string> texts{
      // the scene's restitution after the balls: a ball without its own takes it
      R"({"balls": [{"position": [0, 0], "radius": 1}, {"position": [5, 0], "radius": 1, "restitution": 0.3}],
          "restitution": 0.6, "gravity": [0, -1]})",
      // a repeated "balls" key: the last one counts
      R"({"balls": [{"position": [0, 0], "radius": 1}], "balls": [{"position": [9, 9], "radius": 2}]})",
      // an error in a top-level field after a wrong ball is reported first, as before
      R"({"balls": [{"position": [0, 0], "radius": -1}], "duration": -3})",
      R"({"balls": [{"position": [0, 0], "radius": -1}], "gravty": 1})",
      // the first wrong ball is the one named
      R"({"balls": [{"position": [0, 0], "radius": 1}, 7, {"position": [0, 0]}]})",
      R"({"balls": {"position": [0, 0], "radius": 1}})",
      R"({"balls": []})",
      R"({"balls": [{"position": [0, 0], "radius": 1, "fixed": true, "velocity": [1, 0]}]})",
      R"({"balls": [{"position": [0, 1e999], "radius": 1}]})",
      R"({"balls": [{"position": [0, 0], "radius": 1}, {"position": [1, 0], "radius": 1}]})",  // overlap
      R"({"balls": [{"position": [0, 0], "radius": 1, "acceleration": [0, 2]}], "walls": [{"a": [-3, -2], "b": [3, -2]}]})",
      R"({"balls": [{"position": [0, 0], "radius": 1}],)",  // not JSON
      R"([1, 2])",
  };
  for (const std::string& text : texts) {
    INFO(text);
    CHECK(streamed(text) == whole(text));
  }
  // And some of them are what they claim to be.
  const Scene s = scene_from_text(texts[0]);
  CHECK(s.balls[0].restitution == 0.6);
  CHECK(s.balls[1].restitution == 0.3);
  CHECK(scene_from_text(texts[1]).balls.size() == 1);
  CHECK(streamed(texts[2]) == "error: duration: must be > 0");
  CHECK(streamed(texts[4]) == "error: balls[1]: must be an object");
}
