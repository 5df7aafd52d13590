// The subcommands of the collide2d executable: each registers its options on
// the CLI11 app and returns the function that runs it (the exit code).
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace collide2d::cli {

using Runner = std::function<int()>;

// Exit codes, as SPEC.md fixes them.
inline constexpr int exit_ok = 0;
inline constexpr int exit_verification_failed = 1;
inline constexpr int exit_bad_input = 2;

Runner add_toi_command(CLI::App& app);
Runner add_check_command(CLI::App& app);
Runner add_bench_command(CLI::App& app);
Runner add_run_command(CLI::App& app);
Runner add_replay_command(CLI::App& app);
Runner add_resume_command(CLI::App& app);
Runner add_hardset_command(CLI::App& app);
Runner add_study_command(CLI::App& app);
Runner add_export_command(CLI::App& app);
// properties/props_command.cpp, linked when the properties are built.
Runner add_props_command(CLI::App& app);

}  // namespace collide2d::cli
