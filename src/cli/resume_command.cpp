// collide2d resume RUN.h5: finish an interrupted run from its last checkpoint.
#include <filesystem>
#include <iostream>

#include "cli/commands.hpp"
#include "cli/run_support.hpp"

namespace collide2d::cli {
namespace {

int resume(const std::string& given) {
  const std::string suffix = ".partial";
  const bool given_partial = given.size() > suffix.size() && given.compare(given.size() - suffix.size(), suffix.size(), suffix) == 0;
  const std::string path = given_partial ? given.substr(0, given.size() - suffix.size()) : given;
  const std::string partial = partial_run_path(path);
  RunContents old;
  try {
    if (!std::filesystem::exists(partial)) {
      std::cerr << path << ": no interrupted run to resume (" << partial << " does not exist)\n";
      return exit_bad_input;
    }
    old = read_run_file(partial);
  } catch (const RunFileError& e) {
    std::cerr << e.what() << "\n";
    return exit_bad_input;
  }
  RunOptions options;
  Scene scene;
  if (!read_back_parameters(old.header, partial, scene, options)) return exit_bad_input;
  try {
    if (!old.last_checkpoint) {
      // Killed before its first checkpoint: nothing durable, start again.
      std::cerr << "resume: " << partial << " has no checkpoint; running again from the start\n";
      std::filesystem::remove(partial);
      RunWriter writer(path, old.header);
      return run_into(writer, scene, path, options, nullptr);
    }
    ResumedRun run = resume_run_file(path);
    std::cerr << "resume: continuing " << path << " from t = " << run.checkpoint.time << "\n";
    return run_into(run.writer, scene, path, options, &run.checkpoint.engine_state);
  } catch (const RunFileError& e) {
    std::cerr << e.what() << "\n";
    return exit_bad_input;
  } catch (const std::runtime_error& e) {
    std::cerr << partial << ": " << e.what() << "\n";
    return exit_bad_input;
  }
}

}  // namespace

Runner add_resume_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("resume", "finish an interrupted run (killed after a checkpoint) so that the "
                                               "file equals an uninterrupted run's");
  cmd->add_option("RUN", *path, "the run file's name (its RUN.h5.partial holds the interrupted run)")->required();
  return [path] { return resume(*path); };
}

}  // namespace collide2d::cli
