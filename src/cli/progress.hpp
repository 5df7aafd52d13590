// Progress of long work on stderr: silent for the first two seconds, then a
// line at most once a second with the fraction done and an estimate of the
// time left (elapsed × remaining / done, which assumes a steady rate). On a
// terminal the line is rewritten in place (\r); into a file or pipe each
// update is a line of its own, the first after two seconds and then at most
// one per ten seconds, so a log stays readable.
#pragma once

#include <chrono>
#include <string>

namespace collide2d::cli {

class ProgressLine {
 public:
  explicit ProgressLine(std::string what);
  ~ProgressLine();
  // `done` of `total` (any unit); `detail` is appended as is.
  void update(double done, double total, const std::string& detail = "");
  // Ends the line (on a terminal) before other output.
  void finish();

 private:
  std::string what_;
  std::chrono::steady_clock::time_point start_, last_;
  bool terminal_;
  bool open_line_ = false;
  bool printed_ = false;
};

// "12 s", "3 min 5 s", "2 h 10 min".
std::string duration_text(double seconds);

}  // namespace collide2d::cli
