// A journal of finished work, for commands that must survive a kill (study,
// props): JSON Lines, first the options that decide the results, then one
// line per finished piece, each written and flushed as it ends. A line cut
// short by a kill is the piece that was being written: the lines before it
// stand. Resuming with other options is refused, naming the file.
#pragma once

#include <fstream>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

namespace collide2d::cli {

// Reads `path`, checks its options line against `options`, and hands every
// later complete line to `take` (an exception from `take` is reported with
// the file and line). Throws std::runtime_error naming the file.
void read_journal(const std::string& path, const nlohmann::json& options, const std::function<void(const nlohmann::json&)>& take);

class JournalWriter {
 public:
  // Starts a new journal with the options line (truncating), or, with
  // `append`, continues one. Throws std::runtime_error naming it.
  JournalWriter(const std::string& path, const nlohmann::json& options, bool append);
  void write(const nlohmann::json& line);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ofstream out_;
};

}  // namespace collide2d::cli
