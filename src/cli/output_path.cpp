#include "cli/output_path.hpp"

#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace collide2d::cli {
namespace fs = std::filesystem;

namespace {

// The same file: by inode when both exist, else by their absolute, normal
// spelled paths (an output about to be created over an input given twice).
bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::absolute(a, ec).lexically_normal() == fs::absolute(b, ec).lexically_normal();
}

}  // namespace

std::string output_path_problem(const std::string& output, const std::vector<std::string>& inputs) {
  if (output.empty()) return "the output file name is empty";
  const fs::path out(output);
  std::error_code ec;
  if (fs::is_directory(out, ec)) return output + ": is a directory (give a file name)";
  for (const std::string& in : inputs)
    if (!in.empty() && same_file(out, in)) return output + ": is also an input of this command; it would be overwritten";
  fs::path folder = out.parent_path();
  if (folder.empty()) folder = ".";
  if (!fs::is_directory(folder, ec)) return output + ": folder " + folder.string() + " does not exist";
  if (access(folder.c_str(), W_OK) != 0) return output + ": folder " + folder.string() + " is not writable";
  if (fs::exists(out, ec) && access(out.c_str(), W_OK) != 0) return output + ": exists and is not writable";
  return "";
}

void require_writable_output(const std::string& output, const std::vector<std::string>& inputs) {
  if (std::string problem = output_path_problem(output, inputs); !problem.empty()) throw std::runtime_error(problem);
}

void rename_into_place(const std::string& from, const std::string& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) throw std::runtime_error("cannot rename " + from + " to " + to + ": " + ec.message());
}

}  // namespace collide2d::cli
