#include "cli/datasets.hpp"

#include <cstdlib>
#include <filesystem>

namespace collide2d::cli {
namespace fs = std::filesystem;

std::string datasets_dir() {
  std::error_code ec;
  auto usable = [&](const fs::path& p) { return !p.empty() && fs::is_directory(p, ec); };
  if (const char* env = std::getenv("COLLIDE2D_DATASETS"); env && usable(env)) return env;
#ifdef COLLIDE2D_SOURCE_DATASETS_DIR
  if (usable(COLLIDE2D_SOURCE_DATASETS_DIR)) return COLLIDE2D_SOURCE_DATASETS_DIR;
#endif
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / "share" / "collide2d" / "datasets";
    if (usable(installed)) return installed.string();
  }
  if (usable("datasets")) return "datasets";
  return "";
}

std::string dataset_path(const std::string& relative) {
  const std::string dir = datasets_dir();
  return (fs::path(dir.empty() ? "datasets" : dir) / relative).string();
}

}  // namespace collide2d::cli
