// A downstream program: loads a scene, asks one time of impact, simulates a
// second, using only the installed collide2d package.
//
//   drop_two_balls [SCENE.json]   (default: a ball dropped onto another)
#include <collide2d/numeric/number_mode.hpp>
#include <collide2d/scene/query_parse.hpp>
#include <collide2d/scene/scene.hpp>
#include <collide2d/sim/simulate.hpp>
#include <collide2d/toi/query.hpp>
#include <collide2d/version.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace c2 = collide2d;

// A ball 1 above a fixed ball, falling under gravity: the surfaces touch when
// it has fallen the gap of 1 - 2 r = 0.5, at t = sqrt(2 * 0.5 / 9.81).
constexpr const char* kDefaultScene = R"({
  "name": "drop", "gravity": [0, -9.81], "duration": 1,
  "balls": [ {"position": [0, 1], "velocity": [0, 0], "radius": 0.25},
             {"position": [0, 0], "velocity": [0, 0], "radius": 0.25, "fixed": true} ]
})";

int main(int argc, char** argv) {
  std::string text = kDefaultScene;
  if (argc > 1) {
    std::ifstream in(argv[1]);
    if (!in) {
      std::cerr << argv[1] << ": cannot open\n";
      return 2;
    }
    std::stringstream s;
    s << in.rdbuf();
    text = s.str();
  }
  try {
    // The scene, checked as `collide2d check` checks it.
    const c2::Scene scene = c2::parse_scene(c2::parse_json_text(text));
    c2::check_no_initial_overlap(scene);
    std::printf("collide2d %s: scene %s, %zu balls, %zu walls\n", COLLIDE2D_VERSION, scene.name.c_str(),
                scene.balls.size(), scene.walls.size());

    // One time of impact: the scene's first two balls as a query line (if
    // one of them moves), in both number modes.
    if (scene.balls.size() >= 2 && !(scene.balls[0].fixed && scene.balls[1].fixed)) {
      nlohmann::json line = c2::parse_json_text(text);
      line["balls"] = {line["balls"][0], line["balls"][1]};
      line["walls"] = nlohmann::json::array();
      line["horizon"] = scene.duration;
      const c2::ToiQuery query = c2::parse_toi_query(line);
      for (c2::NumberMode mode : {c2::NumberMode::strict, c2::NumberMode::fixed}) {
        const c2::QueryAnswer a = c2::answer_toi_query(query, c2::ToiMethod::analytic, mode, 1e-9);
        std::printf("time of impact (%s): %s %.17g\n", std::string(c2::to_string(mode)).c_str(),
                    a.hit ? "hit at" : "no hit within", a.hit ? a.t : scene.duration);
      }
    }

    // A second of simulated time with the event engine in strict mode.
    std::size_t collisions = 0;
    const c2::SimulationSummary s = c2::simulate<double>(
        scene, 1.0, [](const c2::FrameRecord&) {}, [&](const c2::EventRecord&) { ++collisions; });
    std::printf("simulated 1 s: %zu collisions, %lld frames, energy %.17g -> %.17g, final hash %016llx\n",
                collisions, static_cast<long long>(s.frames), s.energy_start, s.energy_end,
                static_cast<unsigned long long>(s.final_hash));
  } catch (const c2::SceneError& e) {
    std::cerr << "scene: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {  // e.g. a value beyond the fixed-point range
    std::cerr << e.what() << "\n";
    return 2;
  }
  return 0;
}
