// Output files are checked before any work is done: a run of an hour must
// not end in "cannot rename onto a directory", and no command may write over
// one of its own inputs. Every output is written under a temporary name
// (OUT.partial) and renamed into place when complete (SPEC.md: a command
// that fails leaves no partial output under the requested name).
#pragma once

#include <string>
#include <vector>

namespace collide2d::cli {

// Why `output` cannot be written, or "" if it can: it is empty, a directory,
// its folder does not exist or is not writable, or it is the same file as
// one of `inputs` (or as their names, before they exist).
std::string output_path_problem(const std::string& output, const std::vector<std::string>& inputs);

// Throws std::runtime_error with the problem, if there is one.
void require_writable_output(const std::string& output, const std::vector<std::string>& inputs);

// Renames `from` onto `to` (same folder, so atomic); throws
// std::runtime_error naming both on failure.
void rename_into_place(const std::string& from, const std::string& to);

}  // namespace collide2d::cli
