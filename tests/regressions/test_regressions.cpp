// Replays every stored counterexample through the check that found it
// (properties/scene_checks.hpp; docs/PROPERTIES.md):
//   datasets/regressions/NAME.json            must pass now (the bug is fixed)
//   datasets/regressions/expected/NAME.json   must still fail (a property shown
//                                             to catch what it claims to)
// Each scene file has a sibling NAME.meta.json naming the check, the mode and
// the duration. No files is fine: the test says so and passes.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

#include "collide2d/scene/query_parse.hpp"
#include "fixed_toi_bound.hpp"
#include "lab/oracle.hpp"
#include "scene_checks.hpp"
#include "scene_json.hpp"

using namespace collide2d;
using namespace collide2d::properties;
namespace fs = std::filesystem;

namespace {

std::vector<fs::path> scene_files(const fs::path& dir) {
  std::vector<fs::path> files;
  if (!fs::is_directory(dir)) return files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && entry.path().extension() == ".json" && name.find(".meta.json") == std::string::npos)
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

struct Replayed {
  std::string check, mode;
  CheckResult result;
  std::string not_applicable;  // set when the check no longer applies to the file (NotApplicable)
};

Replayed replay(const fs::path& scene_path) {
  fs::path meta_path = scene_path;
  meta_path.replace_extension(".meta.json");
  INFO("regression file " << scene_path.string());
  REQUIRE(fs::exists(meta_path));
  std::ifstream in(meta_path);
  const nlohmann::json meta = nlohmann::json::parse(in);
  const Scene scene = load_scene_file(scene_path.string());  // what `collide2d check` accepts
  const std::string slug = meta.at("check").get<std::string>();
  const NamedCheck* check = find_check(slug);
  INFO("check " << slug);
  REQUIRE(check != nullptr);
  const std::string mode = meta.at("mode").get<std::string>();
  // A stored file the check does not apply to any more could never fail
  // again: an error of the file (replace it with one the check judges).
  try {
    return {slug, mode, check->check(scene, mode, meta.at("duration").get<double>()), ""};
  } catch (const NotApplicable& e) {
    return {slug, mode, std::nullopt, e.what()};
  }
}

}  // namespace

TEST_CASE("regressions: every stored counterexample passes now", "[regressions]") {
  const auto files = scene_files(COLLIDE2D_REGRESSIONS_REPLAY_DIR);
  std::cout << "regressions: " << files.size() << " files in " << COLLIDE2D_REGRESSIONS_REPLAY_DIR << "\n";
  for (const fs::path& file : files) {
    const Replayed r = replay(file);
    INFO(file.filename().string() << " (" << r.check << ", " << r.mode << "): " << r.result.value_or("passes"));
    INFO("the check no longer applies (a discard, so the file can never fail): " << r.not_applicable);
    CHECK(r.not_applicable.empty());
    CHECK(!r.result.has_value());
  }
}

TEST_CASE("regressions: every expected counterexample still fails", "[regressions]") {
  const auto files = scene_files(fs::path(COLLIDE2D_REGRESSIONS_REPLAY_DIR) / "expected");
  std::cout << "regressions: " << files.size() << " expected failures\n";
  for (const fs::path& file : files) {
    const Replayed r = replay(file);
    INFO(file.filename().string() << " (" << r.check << ", " << r.mode << ") should still fail");
    INFO("the check no longer applies: " << r.not_applicable);
    CHECK(r.not_applicable.empty());
    CHECK(r.result.has_value());
  }
}

TEST_CASE("regressions: scene_to_json writes what parse_scene reads back bit for bit", "[regressions]") {
  Scene s;
  s.name = "round trip";
  s.gravity = {0.1, -9.81};
  s.duration = 1.0 / 3;
  s.record_interval = 0.02;
  s.walls = {{{0, 0}, {1e-7, 3.0e30}, 0.9}};
  BallSpec b;
  b.position = {0.1 + 0.2, 1073741824.000000119};
  b.velocity = {-1.0 / 7, 5e-324};
  b.radius = 0.3;
  b.mass = 2.5;
  b.restitution = 0.7;
  b.acceleration = Point{1, 2};
  BallSpec fixed;
  fixed.position = {5, 5};
  fixed.radius = 1;
  fixed.fixed = true;
  s.balls = {b, fixed};
  const Scene back = parse_scene(parse_json_text(scene_to_json(s)));
  CHECK(scene_to_json(back) == scene_to_json(s));
  CHECK(back.balls[0].position == s.balls[0].position);
  CHECK(back.balls[0].velocity == s.balls[0].velocity);
  CHECK(back.balls[0].acceleration == s.balls[0].acceleration);
  CHECK(back.balls[1].fixed);
  CHECK(back.walls[0].b == s.walls[0].b);
  CHECK(back.duration == s.duration);
}

// Time-of-impact counterexamples (datasets/regressions/toi/*.jsonl, one
// `collide2d toi` query a line with a "note" on what went wrong): the
// analytic answer in both modes meets the acceptance rule against the oracle
// (tol 1e-12 of the scale strict; fixed, the bound derived for the query in
// properties/fixed_toi_bound.hpp), and never throws.
TEST_CASE("regressions: every stored time-of-impact counterexample passes now", "[regressions]") {
  const fs::path dir = fs::path(COLLIDE2D_REGRESSIONS_REPLAY_DIR) / "toi";
  int queries = 0;
  if (fs::is_directory(dir))
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (entry.path().extension() != ".jsonl") continue;
      std::ifstream in(entry.path());
      std::string line;
      while (std::getline(in, line)) {
        if (line.empty()) continue;
        const nlohmann::json j = nlohmann::json::parse(line);
        const ToiQuery q = parse_toi_query(j);
        ++queries;
        for (const NumberMode mode : {NumberMode::strict, NumberMode::fixed}) {
          INFO(entry.path().filename().string() << ": " << j.value("note", "") << " (" << to_string(mode) << ")");
          QueryAnswer a;
          REQUIRE_NOTHROW(a = answer_toi_query(q, ToiMethod::analytic, mode, 1e-9));
          const double rel_tol = mode == NumberMode::strict ? 1e-12 : fixed_toi_gap_bound(q) / oracle_detail::scale_of(q);
          INFO("tolerance " << rel_tol << " of the scale");
          const Verdict v = judge_toi_answer(q, a.hit, a.t, rel_tol);
          INFO(v.why);
          CHECK(v.ok);
        }
      }
    }
  std::cout << "regressions: " << queries << " time-of-impact queries in " << dir.string() << "\n";
}
