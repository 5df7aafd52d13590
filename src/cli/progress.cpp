#include "cli/progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace collide2d::cli {

ProgressLine::ProgressLine(std::string what)
    : what_(std::move(what)), start_(std::chrono::steady_clock::now()), last_(start_), terminal_(isatty(STDERR_FILENO) == 1) {}

ProgressLine::~ProgressLine() { finish(); }

std::string duration_text(double seconds) {
  char text[64];
  const long s = std::lround(seconds);
  if (s < 60) std::snprintf(text, sizeof text, "%ld s", s);
  else if (s < 3600) std::snprintf(text, sizeof text, "%ld min %ld s", s / 60, s % 60);
  else std::snprintf(text, sizeof text, "%ld h %ld min", s / 3600, (s % 3600) / 60);
  return text;
}

void ProgressLine::update(double done, double total, const std::string& detail) {
  using namespace std::chrono;
  const auto now = steady_clock::now();
  const auto quiet = terminal_ ? seconds(1) : seconds(10);
  if (now - start_ < seconds(2) || (printed_ && now - last_ < quiet)) return;
  last_ = now;
  printed_ = true;
  const double elapsed = duration<double>(now - start_).count();
  const double fraction = total > 0 ? std::min(1.0, std::max(0.0, done / total)) : 0;
  std::string left = "time left unknown";
  if (fraction > 0) left = "about " + duration_text(elapsed * (1 - fraction) / fraction) + " left";
  char line[512];
  std::snprintf(line, sizeof line, "%s: %.1f%% (%s)%s%s", what_.c_str(), 100 * fraction, left.c_str(),
                detail.empty() ? "" : ", ", detail.c_str());
  if (terminal_) {
    std::fprintf(stderr, "\r\033[K%s", line);
    open_line_ = true;
  } else {
    std::fprintf(stderr, "%s\n", line);
  }
  std::fflush(stderr);
}

void ProgressLine::finish() {
  if (open_line_) std::fprintf(stderr, "\r\033[K");
  open_line_ = false;
  std::fflush(stderr);
}

}  // namespace collide2d::cli
