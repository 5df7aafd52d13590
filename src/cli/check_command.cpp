// collide2d check SCENE.json: validate a scene without running it. It
// refuses what `collide2d run SCENE.json` with default options would refuse,
// the run's size limits included, and notes what only --mode fixed refuses.
#include <iostream>

#include "cli/commands.hpp"
#include "cli/run_support.hpp"
#include "collide2d/scene/scene.hpp"

namespace collide2d::cli {

Runner add_check_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("check", "validate a scene file (exit 0: valid; 2: the first problem, "
                                              "named by its JSON path)");
  cmd->add_option("SCENE", *path, "scene file (JSON)")->required();
  return [path] {
    try {
      const Scene s = load_scene_file(*path);
      check_run_size(s, RunOptions{}, default_run_limits);
      std::cout << *path << ": valid scene '" << s.name << "': " << s.balls.size() << " balls, " << s.walls.size()
                << " walls\n";
      if (const std::string field = first_field_outside_fixed_range(s); !field.empty())
        std::cout << *path << ": note: " << field << " lies outside the fixed-point range (about ±9.2e18): --mode fixed "
                  << "will refuse this scene\n";
      return exit_ok;
    } catch (const SceneError& e) {
      std::cerr << *path << ": " << e.what() << "\n";
      return exit_bad_input;
    }
  };
}

}  // namespace collide2d::cli
