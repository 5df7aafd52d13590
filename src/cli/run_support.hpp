// What `run` and `replay` share: the options that shape a run, the scene they
// came from, and the simulation in the chosen number mode.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "cli/parse_options.hpp"
#include "collide2d/io/run_file.hpp"
#include "collide2d/scene/scene.hpp"
#include "collide2d/sim/simulate.hpp"
#include "collide2d/toi/query.hpp"

namespace collide2d::cli {

struct RunOptions {
  std::string engine = "event";
  std::string mode = "strict";
  std::string method = "analytic";
  double until = -1;  // < 0: the scene's duration
  double dt = 0.02;   // the step engine's step
  double eps = 1e-9;  // the bisection method's tolerance
  double checkpoint_every = 0;  // simulated time between checkpoints; 0: none
  nlohmann::json to_json() const {
    return {{"engine", engine}, {"mode", mode},   {"method", method},
            {"until", until},   {"dt", dt},       {"eps", eps},
            {"checkpoint_every", checkpoint_every}};
  }
  static RunOptions from_json(const nlohmann::json& j) {
    RunOptions o;
    o.engine = j.at("engine").get<std::string>();
    o.mode = j.at("mode").get<std::string>();
    o.method = j.at("method").get<std::string>();
    o.until = j.at("until").get<double>();
    o.dt = j.at("dt").get<double>();
    o.eps = j.at("eps").get<double>();
    o.checkpoint_every = j.value("checkpoint_every", 0.0);
    // A run file from elsewhere may name what this build does not know.
    number_mode_of(o.mode);
    if (!method_names.count(o.method)) throw std::invalid_argument("unknown method \"" + o.method + "\"");
    if (o.engine != "event" && o.engine != "step") throw std::invalid_argument("unknown engine \"" + o.engine + "\"");
    return o;
  }
};

// What an overflow means, said after its message (run, resume, replay).
inline constexpr const char* fixed_range_note = "a value lies outside the fixed format's range, about ±9.2e18";
inline constexpr const char* strict_range_note =
    "the squares of the scene's lengths and speeds exceed the double range, about 1e308";

// The scene and options a run file was written with, from its header
// (replay and resume). False, with one line on stderr naming `file`, if
// /parameters cannot be read back, or if its scene_json is not the scene its
// radius, mass, walls and wall_restitution describe.
bool read_back_parameters(const RunHeader& header, const std::string& file, Scene& scene, RunOptions& options);

// The header of a run file for this scene and these options.
// It takes the scene's text (a large scene's is a quarter of a kilobyte a
// ball): moved in, the text is held once, not twice, while the file is made.
RunHeader run_header(const Scene& scene, std::string scene_text, const RunOptions& options);

// Runs the scene in the options' mode, handing frames and events on.
// `owned`: the scene itself, whose balls go once the world is made.
template <class OnFrame, class OnEvent>
SimulationSummary simulate_in_mode_owning(const Scene& scene, Scene* owned, const RunOptions& o, OnFrame on_frame,
                                          OnEvent on_event, const CheckpointControl& checkpoints) {
  const double until = o.until < 0 ? scene.duration : o.until;
  const EngineChoice choice{o.engine == "step", o.dt, method_names.at(o.method), o.eps};
  return with_number_type(number_mode_of(o.mode), [&](auto type) {
    return simulate_detail::simulate<typename decltype(type)::type>(scene, owned, until, on_frame, on_event, choice,
                                                                    checkpoints);
  });
}
template <class OnFrame, class OnEvent>
SimulationSummary simulate_in_mode(const Scene& scene, const RunOptions& o, OnFrame on_frame, OnEvent on_event,
                                   const CheckpointControl& checkpoints = {}) {
  return simulate_in_mode_owning(scene, nullptr, o, on_frame, on_event, checkpoints);
}
// The same, letting the scene's balls go once the world is made
// (simulate_releasing_balls): `scene.balls` is empty after it.
template <class OnFrame, class OnEvent>
SimulationSummary simulate_in_mode_releasing_balls(Scene& scene, const RunOptions& o, OnFrame on_frame,
                                                   OnEvent on_event, const CheckpointControl& checkpoints = {}) {
  return simulate_in_mode_owning(scene, &scene, o, on_frame, on_event, checkpoints);
}

// Limits on what a run may produce, checked before it starts (a record
// interval of 1e-12 would otherwise write a terabyte). Both can be raised on
// the command line: --max-frames, --max-steps.
struct RunLimits {
  double max_frames = 1e6;
  double max_steps = 1e8;
};
inline constexpr RunLimits default_run_limits{};

// The JSON path of the first value of the scene that the fixed-point format
// cannot hold (|x| >= 2^63), or "".
std::string first_field_outside_fixed_range(const Scene& scene);

// Throws SceneError (record.interval: too many frames) or
// std::invalid_argument (--dt: too many steps of the step engine).
void check_run_size(const Scene& scene, const RunOptions& o, const RunLimits& limits);

// Runs (or, given a checkpoint, continues) a scene into `writer`: frames,
// events, checkpoints every o.checkpoint_every of simulated time, progress
// on stderr for runs longer than two seconds, and finish() with the summary.
// Prints the summary. Exit code as SPEC.md says; 1 if the run went
// non-finite; 128 + the signal after SIGINT or SIGTERM, leaving the partial
// file only if a checkpoint made it resumable (the message says which).
// The scene's balls are let go once the run's world is made (a large
// scene's 88 bytes a ball): `scene.balls` is empty after it.
int run_into(RunWriter& writer, Scene& scene, const std::string& scene_name, const RunOptions& o,
             const std::vector<std::uint8_t>* resume_from);

nlohmann::json summary_json(const SimulationSummary& s, std::int64_t events);
void print_summary(const SimulationSummary& s, std::int64_t events);

}  // namespace collide2d::cli
