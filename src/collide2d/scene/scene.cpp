#include "collide2d/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <istream>
#include <limits>
#include <optional>
#include <string_view>

#include <nlohmann/json.hpp>

#include "collide2d/geometry/nearby_pairs.hpp"
#include "collide2d/geometry/segment_distance.hpp"
#include "collide2d/geometry/vec2.hpp"

namespace collide2d {
namespace {

using nlohmann::json;

// A JSON path (`balls[3].velocity[0]`) kept as the steps that lead to it
// and written out only when a message names it: reading a valid scene
// builds no string (a million-ball scene built some fifteen a ball). A step
// refers to its parent, so a path lives no longer than the full expression
// that made it, as every use here does.
class JsonPath {
 public:
  JsonPath(const char* root) : name_(root) {}
  JsonPath(const std::string& root) : name_(root) {}
  JsonPath(const JsonPath& parent, std::string_view key) : parent_(&parent), name_(key) {}
  JsonPath(const JsonPath& parent, std::size_t i) : parent_(&parent), index_(i), is_index_(true) {}
  std::string str() const {
    if (!parent_) return std::string(name_);
    const std::string base = parent_->str();
    if (is_index_) return base + "[" + std::to_string(index_) + "]";
    return base.empty() ? std::string(name_) : base + "." + std::string(name_);
  }
  operator std::string() const { return str(); }

 private:
  const JsonPath* parent_ = nullptr;
  std::string_view name_;
  std::size_t index_ = 0;
  bool is_index_ = false;
};

JsonPath join(const JsonPath& base, std::string_view key) { return {base, key}; }
JsonPath index(const JsonPath& base, std::size_t i) { return {base, i}; }

// The allowed fields are a braced list of names: no set is built at each call.
void require_object(const json& j, const JsonPath& path, std::initializer_list<std::string_view> allowed,
                    bool ignore_unknown) {
  if (!j.is_object()) throw SceneError(path, "must be an object");
  if (ignore_unknown) return;
  for (const auto& item : j.items())
    if (std::find(allowed.begin(), allowed.end(), item.key()) == allowed.end())
      throw SceneError(join(path, item.key()), "unknown field");
}

double read_number(const json& j, const JsonPath& path) {
  if (!j.is_number()) throw SceneError(path, "must be a number");
  const double x = j.get<double>();
  if (!std::isfinite(x)) throw SceneError(path, "must be finite");
  return x;
}

Point read_point(const json& j, const JsonPath& path) {
  if (!j.is_array() || j.size() != 2) throw SceneError(path, "must be an array of two numbers");
  return {read_number(j[0], index(path, 0)), read_number(j[1], index(path, 1))};
}

double read_restitution(const json& j, const JsonPath& path) {
  const double e = read_number(j, path);
  if (e < 0 || e > 1) throw SceneError(path, "must lie in [0, 1]");
  return e;
}

double read_non_negative(const json& j, const JsonPath& path) {
  const double x = read_number(j, path);
  if (x < 0) throw SceneError(path, "must be >= 0");
  return x;
}

double read_positive(const json& j, const JsonPath& path) {
  const double x = read_number(j, path);
  if (!(x > 0)) throw SceneError(path, "must be > 0");
  return x;
}

const json& required(const json& j, const std::string& key, const JsonPath& path) {
  const auto it = j.find(key);
  if (it == j.end()) throw SceneError(join(path, key), "missing");
  return *it;
}

BallSpec parse_ball(const json& j, const JsonPath& path, double default_restitution) {
  require_object(j, path, {"position", "velocity", "radius", "mass", "restitution", "fixed", "acceleration"}, false);
  BallSpec b;
  b.restitution = default_restitution;
  b.position = read_point(required(j, "position", path), join(path, "position"));
  b.radius = read_positive(required(j, "radius", path), join(path, "radius"));
  if (j.contains("velocity")) b.velocity = read_point(j["velocity"], join(path, "velocity"));
  if (j.contains("mass")) b.mass = read_positive(j["mass"], join(path, "mass"));
  if (j.contains("restitution")) b.restitution = read_restitution(j["restitution"], join(path, "restitution"));
  if (j.contains("fixed")) {
    if (!j["fixed"].is_boolean()) throw SceneError(join(path, "fixed"), "must be true or false");
    b.fixed = j["fixed"].get<bool>();
  }
  if (j.contains("acceleration")) b.acceleration = read_point(j["acceleration"], join(path, "acceleration"));
  if (b.fixed && (b.velocity != Point{0, 0}))
    throw SceneError(join(path, "velocity"), "a fixed ball cannot move: velocity must be [0, 0]");
  return b;
}

WallSpec parse_wall(const json& j, const JsonPath& path, double default_restitution) {
  require_object(j, path, {"a", "b", "restitution"}, false);
  WallSpec w;
  w.restitution = default_restitution;
  w.a = read_point(required(j, "a", path), join(path, "a"));
  w.b = read_point(required(j, "b", path), join(path, "b"));
  if (j.contains("restitution")) w.restitution = read_restitution(j["restitution"], join(path, "restitution"));
  if (w.a == w.b) throw SceneError(path, "zero-length wall (a equals b)");
  return w;
}

// The JSON path of the first null in j (depth first), or "" if none.
std::string path_of_first_null(const json& j, const std::string& path) {
  if (j.is_null()) return path.empty() ? "(document)" : path;
  if (j.is_object())
    for (const auto& item : j.items())
      if (auto p = path_of_first_null(item.value(), join(path, item.key())); !p.empty()) return p;
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i)
      if (auto p = path_of_first_null(j[i], index(path, i)); !p.empty()) return p;
  return "";
}

}  // namespace

json parse_json_text(const std::string& text) {
  try {
    return json::parse(text);
  } catch (const json::out_of_range& e) {
    // "number overflow parsing '1e999'": put a null in its place to find
    // which field held it.
    const std::string what = e.what();
    const auto open = what.find('\''), close = what.rfind('\'');
    if (e.id == 406 && open != std::string::npos && close > open) {
      const std::string token = what.substr(open + 1, close - open - 1);
      std::string patched = text;
      if (const auto at = patched.find(token); at != std::string::npos) {
        patched.replace(at, token.size(), "null");
        try {
          const std::string path = path_of_first_null(json::parse(patched), "");
          if (!path.empty()) throw SceneError(path, "must be a finite number (" + token + " overflows a double)");
        } catch (const json::exception&) {
        }
      }
    }
    throw SceneError("", std::string("not valid JSON: ") + e.what());
  } catch (const json::exception& e) {
    throw SceneError("", std::string("not valid JSON: ") + e.what());
  }
}

Point effective_acceleration(const Scene& scene, const BallSpec& ball) {
  if (ball.fixed) return {0, 0};
  return ball.acceleration ? *ball.acceleration : scene.gravity;
}

// Every value is finite, yet the energy (SPEC.md: kinetic 1/2 m |v|^2 plus
// potential -m a.p per moving ball) can still overflow a double: a speed of
// 1e200 squares to infinity. Such a scene could only produce a run whose
// energy is inf or NaN, so it is refused up front, naming the ball.
static void check_energy_is_finite(const Scene& s) {
  double total = 0;
  for (std::size_t i = 0; i < s.balls.size(); ++i) {
    const BallSpec& b = s.balls[i];
    if (b.fixed) continue;
    const Point a = effective_acceleration(s, b);
    const double kinetic = 0.5 * b.mass * (b.velocity[0] * b.velocity[0] + b.velocity[1] * b.velocity[1]);
    const double potential = -b.mass * (a[0] * b.position[0] + a[1] * b.position[1]);
    if (!std::isfinite(kinetic))
      throw SceneError(join(index("balls", i), "velocity"), "kinetic energy 1/2 m |v|^2 overflows a double");
    if (!std::isfinite(potential))
      throw SceneError(index("balls", i), "potential energy -m a.p overflows a double");
    total += kinetic + potential;
    if (!std::isfinite(total))
      throw SceneError(index("balls", i), "the scene's total energy overflows a double at this ball");
  }
}

namespace {

// The balls of a scene file read while its text was parsed (scene_from_text),
// so that the parsed document never holds them all: a ball costs about a
// kilobyte as a JSON object and 88 bytes as a BallSpec. A ball without its
// own restitution is read with a NaN there (JSON has no NaN: it can only be
// this mark) and given the scene's after the parse, which may name it later
// in the file; the first ball that is wrong is kept, to be reported where
// parse_scene would have reported it (after every other top-level field).
struct StreamedBalls {
  std::vector<BallSpec> balls;
  std::optional<SceneError> first_error;
};

Scene parse_scene_fields(const json& j, const ParseOptions& options, StreamedBalls* streamed) {
  require_object(j, "", {"name", "gravity", "duration", "restitution", "walls", "balls", "record", "rest"},
                 options.ignore_unknown_top_level_keys);
  Scene s;
  if (j.contains("name")) {
    if (!j["name"].is_string()) throw SceneError("name", "must be a string");
    s.name = j["name"].get<std::string>();
  }
  if (j.contains("gravity")) s.gravity = read_point(j["gravity"], "gravity");
  if (j.contains("duration")) s.duration = read_positive(j["duration"], "duration");
  if (j.contains("restitution")) s.restitution = read_restitution(j["restitution"], "restitution");
  if (j.contains("record")) {
    require_object(j["record"], "record", {"interval"}, false);
    if (j["record"].contains("interval")) s.record_interval = read_positive(j["record"]["interval"], "record.interval");
  }
  if (j.contains("rest")) {
    // The rest rules' scales (src/collide2d/sim/rest.hpp), each in the scene's units;
    // left out, they follow from the scene (README, "Rest").
    require_object(j["rest"], "rest", {"height", "speed", "band"}, false);
    const json& r = j["rest"];
    if (r.contains("height")) s.rest.height = read_positive(r["height"], "rest.height");
    if (r.contains("speed")) s.rest.speed = read_non_negative(r["speed"], "rest.speed");
    if (r.contains("band")) s.rest.band = read_non_negative(r["band"], "rest.band");
  }
  if (j.contains("walls")) {
    if (!j["walls"].is_array()) throw SceneError("walls", "must be an array");
    for (std::size_t i = 0; i < j["walls"].size(); ++i)
      s.walls.push_back(parse_wall(j["walls"][i], index("walls", i), s.restitution));
  }
  if (j.contains("balls")) {
    if (!j["balls"].is_array()) throw SceneError("balls", "must be an array");
    if (streamed) {
      if (streamed->first_error) throw *streamed->first_error;
      streamed->balls.shrink_to_fit();
      s.balls = std::move(streamed->balls);
      for (BallSpec& b : s.balls)
        if (std::isnan(b.restitution)) b.restitution = s.restitution;
    }
    for (std::size_t i = 0; i < j["balls"].size(); ++i)
      s.balls.push_back(parse_ball(j["balls"][i], index("balls", i), s.restitution));
  }
  if (s.balls.empty()) throw SceneError("balls", "a scene needs at least one ball");
  check_energy_is_finite(s);
  return s;
}

}  // namespace

Scene parse_scene(const json& j, const ParseOptions& options) { return parse_scene_fields(j, options, nullptr); }

// Overlap means a penetration larger than the rounding of the check itself
// (a few ulp of the distances involved): objects placed exactly in contact,
// whose computed distance may round either way, are touching, not
// overlapping, and a contact query on them is answered, not refused.
//
// Pairs are found through a grid (geometry/nearby_pairs.hpp), so a million
// balls take a second, not hours. The error names the same pair as the plain
// double loop would: the lowest ball i with a problem, and for it the lowest
// ball k > i, else the lowest wall.
void check_no_initial_overlap(const Scene& s) {
  const double rounding = 8 * std::numeric_limits<double>::epsilon();
  const std::size_t n = s.balls.size();
  auto balls_overlap = [&](std::size_t i, std::size_t k) {
    const auto& bi = s.balls[i];
    const auto& bk = s.balls[k];
    const double R = bi.radius + bk.radius;
    const double distance = length(Vec2<double>{bk.position[0] - bi.position[0], bk.position[1] - bi.position[1]});
    return R - distance > rounding * (distance + R);
  };
  // The lowest k > i overlapping ball i, n if none (32 bits: for_each_nearby_pair takes fewer than 2^30 balls).
  std::vector<std::uint32_t> first_ball(n, static_cast<std::uint32_t>(n));
  double r_max = 0;
  for (const BallSpec& b : s.balls) r_max = std::max(r_max, b.radius);
  auto centre = [&](std::size_t i) { return Vec2<double>{s.balls[i].position[0], s.balls[i].position[1]}; };
  for_each_nearby_pair(n, r_max, centre, [&](std::size_t i, std::size_t k) {
    if (k < first_ball[i] && balls_overlap(i, k)) first_ball[i] = static_cast<std::uint32_t>(k);
  });
  for (std::size_t i = 0; i < n; ++i) {
    const auto& bi = s.balls[i];
    const Vec2<double> pi{bi.position[0], bi.position[1]};
    if (first_ball[i] < n)
      throw SceneError(index("balls", first_ball[i]), "overlaps balls[" + std::to_string(i) + "] at t = 0");
    for (std::size_t w = 0; w < s.walls.size(); ++w) {
      const Segment<double> seg{{s.walls[w].a[0], s.walls[w].a[1]}, {s.walls[w].b[0], s.walls[w].b[1]}};
      const double distance = distance_to_segment(pi, seg);
      const double extent = length(pi - seg.a) + length(seg.b - seg.a) + bi.radius;
      if (bi.radius - distance > rounding * extent)
        throw SceneError(index("balls", i), "overlaps walls[" + std::to_string(w) + "] at t = 0");
    }
  }
}

namespace {
// Every field of the scene but its balls, as scene_to_json writes them.
json scene_fields_json(const Scene& s) {
  json walls = json::array();
  for (const WallSpec& w : s.walls) walls.push_back({{"a", w.a}, {"b", w.b}, {"restitution", w.restitution}});
  json doc = {{"name", s.name},         {"gravity", s.gravity}, {"duration", s.duration},
              {"restitution", s.restitution}, {"walls", walls},
              {"record", {{"interval", s.record_interval}}}};
  json rest = json::object();
  if (s.rest.height) rest["height"] = *s.rest.height;
  if (s.rest.speed) rest["speed"] = *s.rest.speed;
  if (s.rest.band) rest["band"] = *s.rest.band;
  if (!rest.empty()) doc["rest"] = rest;
  return doc;
}
}  // namespace

std::string scene_to_json(const Scene& s, int indent) {
  json doc = scene_fields_json(s), balls = json::array();
  for (const BallSpec& b : s.balls) {
    json ball = {{"position", b.position}, {"velocity", b.velocity},       {"radius", b.radius},
                 {"mass", b.mass},         {"restitution", b.restitution}, {"fixed", b.fixed}};
    if (b.acceleration) ball["acceleration"] = *b.acceleration;
    balls.push_back(ball);
  }
  doc["balls"] = std::move(balls);
  return doc.dump(indent);
}

std::string scene_to_json_one_ball_a_line(const Scene& s) {
  const json doc = scene_fields_json(s);
  std::string out = "{\n";
  for (const auto& [key, value] : doc.items()) out += " \"" + key + "\": " + value.dump() + ",\n";
  out += " \"balls\": [";
  for (std::size_t i = 0; i < s.balls.size(); ++i) {
    const BallSpec& b = s.balls[i];
    json ball = {{"position", b.position}, {"velocity", b.velocity}, {"radius", b.radius}};
    if (b.mass != 1) ball["mass"] = b.mass;
    // The restitution compared by its bits: a default is left out only where
    // reading it back gives the same double.
    if (std::memcmp(&b.restitution, &s.restitution, sizeof(double)) != 0) ball["restitution"] = b.restitution;
    if (b.fixed) ball["fixed"] = true;
    if (b.acceleration) ball["acceleration"] = *b.acceleration;
    out += (i == 0 ? "\n  " : ",\n  ") + ball.dump();
  }
  out += "\n ]\n}\n";
  return out;
}

namespace {
// The top-level "balls" array's elements are read as the parser finishes
// each (depth 2 under the key "balls" at depth 1) and left out of the
// document; a text the parser refuses is handed to `explain_refusal`, which
// throws the SceneError a plain parse gives. Room is made before the parse
// for `expected_balls`: a vector grown by doubling would hold up to twice
// the balls, and that was the peak of a run of a million balls.
template <class Input>
Scene scene_from_json_input(Input&& input, std::size_t expected_balls, const std::function<void()>& explain_refusal) {
  StreamedBalls streamed;
  streamed.balls.reserve(expected_balls);
  bool next_is_balls = false, in_balls = false;
  const json::parser_callback_t read_ball = [&](int depth, json::parse_event_t event, json& parsed) {
    using E = json::parse_event_t;
    if (depth == 1 && event == E::key) {
      next_is_balls = parsed == "balls";
      if (next_is_balls) streamed.balls.clear(), streamed.first_error.reset();  // a repeated key: the last one counts
      return true;
    }
    if (depth == 1 && event == E::array_start) in_balls = next_is_balls;
    if (depth == 1 && event == E::array_end) in_balls = false;
    if (!in_balls || depth != 2 || (event != E::object_end && event != E::array_end && event != E::value)) return true;
    const std::size_t i = streamed.balls.size();
    try {
      streamed.balls.push_back(parse_ball(parsed, index("balls", i), std::numeric_limits<double>::quiet_NaN()));
    } catch (const SceneError& e) {
      if (!streamed.first_error) streamed.first_error = e;
      streamed.balls.push_back({});
    }
    return false;  // not kept in the document
  };
  json document;
  try {
    document = json::parse(std::forward<Input>(input), read_ball);
  } catch (const json::exception&) {
    explain_refusal();
    throw;
  }
  Scene s = parse_scene_fields(document, {}, &streamed);
  check_no_initial_overlap(s);
  return s;
}
}  // namespace

std::size_t count_ball_positions(const std::string& text) {
  std::size_t positions = 0;
  for (std::size_t at = text.find("\"position\""); at != std::string::npos; at = text.find("\"position\"", at + 10))
    ++positions;
  return positions;
}

Scene scene_from_text(const std::string& text) {
  return scene_from_json_input(text, count_ball_positions(text), [&] { parse_json_text(text); });
}

Scene scene_from_stream(std::istream& in, std::size_t expected_balls, const std::function<void()>& explain_refusal) {
  return scene_from_json_input(in, expected_balls, explain_refusal);
}

std::string read_text_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw SceneError("", "is a directory, not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError("", "cannot open file");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw SceneError("", "cannot open file");
  std::string text(static_cast<std::size_t>(size), '\0');
  in.seekg(0, std::ios::beg);
  if (!in.read(text.data(), size)) throw SceneError("", "cannot open file");
  return text;
}

Scene load_scene_file(const std::string& path) { return scene_from_text(read_text_file(path)); }

}  // namespace collide2d
