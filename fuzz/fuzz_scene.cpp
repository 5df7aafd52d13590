// fuzz_scene: a scene file's text through exactly what `collide2d check` runs
// (scene_from_text: the JSON, every field, the overlap at t = 0), and, for a
// scene it accepts, what `collide2d run` does with it before the first event
// (simulate.hpp): the world in both number modes, the rest scales, the event
// engine with its cell grid, frame 0 and its deepest overlap.
//
// The outcomes the commands handle: SceneError (check and run exit 2 naming
// the field) and, in fixed mode only, FixedPointOverflow (run exits 2: a value
// outside Q63.64's range; the conversion must report it, never wrap, which
// UBSan would see). Any other exception, a sanitizer report or a failed
// contract below is a finding.
//
// The contract checked besides: the overlap check names the same pair as the
// plain double loop over all pairs would (scene.cpp promises it; its grid must
// never miss a pair). The loop is quadratic, so only for small scenes.
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "collide2d/scene/scene.hpp"
#include "collide2d/geometry/segment_distance.hpp"
#include "collide2d/sim/simulate.hpp"

namespace {

using namespace collide2d;

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_scene: %s\n", what.c_str());
  std::abort();
}

// The first overlap as the plain loop finds it: the lowest ball i with a
// problem, for it the lowest ball k > i, else the lowest wall. The tests are
// those of check_no_initial_overlap (a penetration beyond 8 eps of the
// distances involved); "" if none.
std::string first_overlap_by_plain_loop(const Scene& s) {
  const double rounding = 8 * std::numeric_limits<double>::epsilon();
  for (std::size_t i = 0; i < s.balls.size(); ++i) {
    const Vec2<double> pi{s.balls[i].position[0], s.balls[i].position[1]};
    for (std::size_t k = i + 1; k < s.balls.size(); ++k) {
      const double R = s.balls[i].radius + s.balls[k].radius;
      const double distance = length(Vec2<double>{s.balls[k].position[0] - pi.x, s.balls[k].position[1] - pi.y});
      if (R - distance > rounding * (distance + R))
        return "balls[" + std::to_string(k) + "]: overlaps balls[" + std::to_string(i) + "] at t = 0";
    }
    for (std::size_t w = 0; w < s.walls.size(); ++w) {
      const Segment<double> seg{{s.walls[w].a[0], s.walls[w].a[1]}, {s.walls[w].b[0], s.walls[w].b[1]}};
      const double distance = distance_to_segment(pi, seg);
      const double extent = length(pi - seg.a) + length(seg.b - seg.a) + s.balls[i].radius;
      if (s.balls[i].radius - distance > rounding * extent)
        return "balls[" + std::to_string(i) + "]: overlaps walls[" + std::to_string(w) + "] at t = 0";
    }
  }
  return "";
}

// What simulate<Num> does before its first event.
template <class Num>
void start_run(const Scene& scene) {
  const RestScales scales = rest_scales(scene);
  EventEngine<Num> engine(make_world<Num>(scene), scales.in<Num>(), ToiMethod::analytic, num<Num>(1e-9));
  std::vector<double> radius;
  for (const BallSpec& b : scene.balls) radius.push_back(b.radius);
  std::vector<std::array<double, 4>> walls;
  for (const WallSpec& w : scene.walls) walls.push_back({w.a[0], w.a[1], w.b[0], w.b[1]});
  const FrameRecord frame0 = make_frame(engine.world(), 0, Num{});
  if (frame0.position.size() != 2 * scene.balls.size()) finding("frame 0 does not hold every ball");
  deepest_overlap(frame0, radius, walls);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::optional<Scene> scene;
  std::string refusal;
  try {
    scene = scene_from_text(text);
  } catch (const SceneError& e) {
    refusal = e.what();
  }

  // The overlap check against the plain loop, when the fields are valid.
  if (!scene) {
    std::optional<Scene> fields;
    try {
      fields = parse_scene(parse_json_text(text));
    } catch (const SceneError&) {
    }
    if (fields && fields->balls.size() <= 64) {
      const std::string plain = first_overlap_by_plain_loop(*fields);
      if (plain != refusal) finding("overlap check said \"" + refusal + "\", the plain loop \"" + plain + "\"");
    }
    return 0;
  }
  if (scene->balls.size() <= 64) {
    const std::string plain = first_overlap_by_plain_loop(*scene);
    if (!plain.empty()) finding("overlap check accepted a scene in which the plain loop finds: " + plain);
  }

  start_run<double>(*scene);
  try {
    start_run<Fixed>(*scene);
  } catch (const FixedPointOverflow&) {
    // run --mode fixed: exit 2, "fixed-point overflow in ..."
  }
  return 0;
}
