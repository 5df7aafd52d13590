// collide2d run [SCENE.json] -o RUN.h5: simulate a scene, write an H5MD run.
#include <chrono>
#include <filesystem>
#include <iostream>
#include <string>

#include "cli/commands.hpp"
#include "cli/output_path.hpp"
#include "cli/run_support.hpp"
#include "collide2d/scene/builtin_scene.hpp"
#include "collide2d/scene/scene_file.hpp"

namespace collide2d::cli {
namespace {

struct RunCommandOptions {
  std::string scene_path;
  std::string output;
  RunOptions run;
  RunLimits limits;
  bool force = false;  // replace an interrupted run's partial file
};

int run_scene(const RunCommandOptions& o) {
  // The output first: nothing is read or simulated for a file that cannot be written.
  if (const std::string problem = output_path_problem(o.output, {o.scene_path}); !problem.empty()) {
    std::cerr << problem << "\n";
    return exit_bad_input;
  }
  if (const std::string partial = partial_run_path(o.output); !o.force && std::filesystem::exists(partial)) {
    std::cerr << partial << ": an interrupted run is in the way (`collide2d resume " << o.output
              << "` continues it if it has a checkpoint); remove it or pass --force to start afresh\n";
    return exit_bad_input;
  }
  if (o.run.engine == "event" && o.run.method != "analytic") {
    std::cerr << "collide2d run: the event engine is exact: it uses --method analytic (the article's methods run "
                 "with --engine step)\n";
    return exit_bad_input;
  }
  const std::string scene_name = o.scene_path.empty() ? "built-in abound scene" : o.scene_path;
  std::string text = builtin_abound_scene_json();
  if (!o.scene_path.empty()) {
    try {
      text = read_text_file(o.scene_path);
    } catch (const SceneError& e) {
      std::cerr << o.scene_path << ": " << e.what() << "\n";
      return exit_bad_input;
    }
  }
  if (o.force) std::filesystem::remove(partial_run_path(o.output));
  try {
    // The text goes into the run file first and is let go; the scene is
    // then parsed again from its file. A million balls' text (120 bytes a
    // ball) and their parsed balls (88) are never held together, and that
    // pair was the peak of the whole run. The bytes parsed are digested as
    // they are read and must be the bytes the run file holds. A scene
    // refused on the way leaves no file: the writer removes it.
    RunWriter writer = RunWriter::with_scene_text(o.output, text);
    Scene scene;
    try {
      if (o.scene_path.empty()) {
        scene = scene_from_text(text);
      } else {
        const std::size_t expected_balls = count_ball_positions(text);
        const TextDigest written = digest_of(text);
        std::string().swap(text);
        scene = scene_from_file_as_written(o.scene_path, expected_balls, written);
      }
      check_run_size(scene, o.run, o.limits);
    } catch (const SceneError& e) {
      std::cerr << scene_name << ": " << e.what() << "\n";
      return exit_bad_input;
    } catch (const std::invalid_argument& e) {
      std::cerr << "collide2d run: " << e.what() << "\n";
      return exit_bad_input;
    }
    if (o.run.mode == "fixed")
      if (const std::string field = first_field_outside_fixed_range(scene); !field.empty()) {
        std::cerr << scene_name << ": " << field
                  << ": outside the fixed-point range (about ±9.2e18); --mode strict runs it\n";
        return exit_bad_input;
      }
    writer.write_header(run_header(scene, "", o.run));
    return run_into(writer, scene, scene_name, o.run, nullptr);
  } catch (const RunFileError& e) {
    std::cerr << e.what() << "\n";
    return exit_bad_input;
  }
}

}  // namespace

Runner add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunCommandOptions>();
  CLI::App* cmd = app.add_subcommand("run", "simulate a scene (default: the built-in Abound scene) and write an "
                                            "H5MD run file; prints a summary");
  cmd->add_option("SCENE", o->scene_path, "scene file (JSON); omitted: the built-in Abound scene");
  cmd->add_option("-o,--output", o->output, "run file to write (HDF5, H5MD layout)")->required();
  cmd->add_option("--engine", o->run.engine, "event (exact, event-driven) or step (the article's loop)")
      ->check(CLI::IsMember({"event", "step"}))
      ->capture_default_str();
  cmd->add_option("--dt", o->run.dt, "time step of the step engine")->check(finite_positive())->capture_default_str();
  cmd->add_option("--mode", o->run.mode, "strict (IEEE double) or fixed (Q63.64)")
      ->check(CLI::IsMember(number_mode_names()))
      ->capture_default_str();
  cmd->add_option("--method", o->run.method, "time-of-impact method")
      ->check(CLI::IsMember({"analytic", "bisection", "seed"}))
      ->capture_default_str();
  cmd->add_option("--eps", o->run.eps, "tolerance of the bisection method")->check(finite_positive())->capture_default_str();
  cmd->add_option("--until", o->run.until, "simulated time to stop at (default: the scene's duration)")
      ->check(finite_positive());
  cmd->add_option("--checkpoint-every", o->run.checkpoint_every,
                  "simulated time between checkpoints (rounded to whole record intervals); a run killed after one "
                  "is finished by collide2d resume")
      ->check(finite_positive());
  cmd->add_option("--max-frames", o->limits.max_frames, "refuse a run that would record more frames than this")
      ->check(finite_positive())
      ->capture_default_str();
  cmd->add_option("--max-steps", o->limits.max_steps, "refuse a step-engine run of more steps than this")
      ->check(finite_positive())
      ->capture_default_str();
  cmd->add_flag("--force", o->force, "replace OUTPUT.partial, an interrupted run, instead of refusing");
  return [o] { return run_scene(*o); };
}

}  // namespace collide2d::cli
