// A scene as the user wrote it: plain data in doubles, validated.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace collide2d {

using Point = std::array<double, 2>;

struct BallSpec {
  Point position{};
  Point velocity{};
  double radius = 0;
  double mass = 1;
  double restitution = 1;
  bool fixed = false;
  std::optional<Point> acceleration;  // unset: the scene's gravity
};

struct WallSpec {
  Point a{};
  Point b{};
  double restitution = 1;
};

struct Scene {
  std::string name = "unnamed";
  Point gravity{0, 0};
  double duration = 10;
  double restitution = 1;  // the default for balls and walls that give none
  std::vector<WallSpec> walls;
  std::vector<BallSpec> balls;
  double record_interval = 0.02;
  // The rest rules' scales, when the scene sets them ("rest": {...});
  // otherwise they follow from the scene (sim/simulate.cpp, rest_scales).
  struct RestSettings {
    std::optional<double> height, speed, band;
  } rest;
};

// The acceleration a ball moves with: its own, else gravity; none if fixed.
Point effective_acceleration(const Scene& scene, const BallSpec& ball);

// A scene or query that cannot be accepted: the JSON path of the offending
// field (such as "balls[3].radius") and what is wrong with it.
struct SceneError : std::runtime_error {
  std::string path;
  SceneError(std::string json_path, const std::string& what)
      : std::runtime_error(json_path.empty() ? what : json_path + ": " + what), path(std::move(json_path)) {}
};

struct ParseOptions {
  // Time-of-impact query lines carry extra keys (the horizon, labels, expected
  // answers); SPEC.md says they are ignored. Scene files reject unknown keys.
  bool ignore_unknown_top_level_keys = false;
};

// Parses JSON text; a syntax error or a number that overflows a double
// (1e999: JSON has no NaN or infinity) throws SceneError, the latter naming
// the field that holds it.
nlohmann::json parse_json_text(const std::string& text);

// Builds and validates a scene; throws SceneError.
Scene parse_scene(const nlohmann::json& document, const ParseOptions& options = {});

// A scene file's text, parsed and checked as every command that takes a
// scene does (check, run, replay, resume): parse_json_text, parse_scene,
// check_no_initial_overlap. Throws SceneError.
Scene scene_from_text(const std::string& text);

// How many balls a scene's text may hold, as it names a "position" (every
// ball has one): the room scene_from_text makes before it parses.
std::size_t count_ball_positions(const std::string& text);

// scene_from_text for a text read from a stream, for a scene too large to
// hold its text beside its balls. Room is made for `expected_balls`; a text
// the parser refuses is handed to `explain_refusal`, which should throw the
// SceneError scene_from_text gives (from the text read again).
Scene scene_from_stream(std::istream& in, std::size_t expected_balls, const std::function<void()>& explain_refusal);

// A whole file's bytes, read straight into one string of its size (a scene
// of a million balls is 270 MB of text: no second copy in a stream buffer).
// Throws SceneError("", "cannot open file") if it cannot be read, or "is a
// directory, not a scene file".
std::string read_text_file(const std::string& path);

// Reads a file and parses it with scene_from_text; SceneError paths are
// prefixed by nothing, the caller names the file.
Scene load_scene_file(const std::string& path);

// Rejects what SPEC.md rejects beyond the field types: overlaps at t = 0.
void check_no_initial_overlap(const Scene& scene);

// The scene as a scene file holds it (SPEC.md "Scene file"): every value
// written explicitly (no defaults; "rest" where the scene sets it), doubles in
// nlohmann's shortest round-trip form, so parse_scene(scene_to_json(s)) gives
// back the same bits. indent < 0: one line.
std::string scene_to_json(const Scene& scene, int indent = 2);

// The same scene as one would keep a large one: the scene's own fields one a
// line, then one ball a line holding only what differs from the defaults
// (mass 1, the scene's restitution, not fixed, the scene's gravity); the
// same bits back. A million balls of bench sim's gas take 120 bytes each
// this way and 268 in scene_to_json's form, which is all in memory while
// `collide2d run` parses it.
std::string scene_to_json_one_ball_a_line(const Scene& scene);

}  // namespace collide2d
