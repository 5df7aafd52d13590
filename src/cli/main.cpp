// collide2d: exact, reproducible 2D collision detection between balls and walls.
#include <cstdio>
#include <exception>
#include <iostream>
#include <map>
#include <vector>

#include "cli/build_info.hpp"
#include "cli/commands.hpp"
#include "cli/huge_pages.hpp"
#include "collide2d/numeric/strict_environment.hpp"

int main(int argc, char** argv) {
  using namespace collide2d::cli;
  restart_with_huge_pages(argv);  // once, before anything else (huge_pages.hpp)
  CLI::App app{"collide2d: exact, reproducible time of impact and collision response for balls and walls"};
  app.set_version_flag("--version", version_text() + "\n" + memory_pages_line());
  app.require_subcommand(1);
  std::map<const CLI::App*, Runner> runners;
  std::vector<Runner (*)(CLI::App&)> commands{add_run_command,     add_replay_command, add_resume_command,
                                              add_toi_command,     add_check_command,  add_bench_command,
                                              add_hardset_command, add_study_command,  add_export_command};
#ifdef COLLIDE2D_HAVE_PROPS
  commands.push_back(add_props_command);  // built with the properties (properties/props_command.cpp)
#endif
  for (auto add : commands) {
    const std::size_t before = app.get_subcommands({}).size();
    Runner run = add(app);
    runners[app.get_subcommands({})[before]] = std::move(run);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "collide2d: " << e.what() << " (see collide2d --help)\n";
    return exit_bad_input;
  }
  // Strict mode promises IEEE double with gradual underflow: refuse to run in
  // an environment that would break that promise.
  if (const std::string problem = collide2d::strict_environment_problem(); !problem.empty()) {
    std::cerr << "collide2d: floating-point environment refused: " << problem << "\n";
    return exit_bad_input;
  }
  for (const auto& [command, run] : runners)
    if (command->parsed()) {
      try {
        return run();
      } catch (const std::exception& e) {
        std::cerr << "collide2d " << command->get_name() << ": " << e.what() << "\n";
        return exit_bad_input;
      }
    }
  return exit_bad_input;
}
