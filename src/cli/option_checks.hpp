// Checks of numeric option values, stricter than CLI11's PositiveNumber:
// those compare with `<= 0`, which NaN passes, and their range message
// prints DBL_MAX in full. Every check here refuses NaN and infinities and
// says in one short line what it wanted and what it got.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

#include <CLI/CLI.hpp>

namespace collide2d::cli {

// The value of an option's text as a double; false if it is not a number.
inline bool parse_option_double(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

// A finite number in (lowest, highest) or [lowest, highest), as `closed_low` says.
inline CLI::Validator finite_number_in(double lowest, bool closed_low, double highest, const std::string& wanted) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double v = 0;
        if (!parse_option_double(text, v)) return "\"" + text + "\" is not a number (wanted " + wanted + ")";
        if (!std::isfinite(v)) return "\"" + text + "\" is not finite (wanted " + wanted + ")";
        if (v < lowest || (!closed_low && v == lowest) || !(v < highest))
          return "\"" + text + "\" is out of range (wanted " + wanted + ")";
        return {};
      },
      wanted);
}

// A finite number > 0 (times, steps, tolerances, speeds).
inline CLI::Validator finite_positive() { return finite_number_in(0.0, false, HUGE_VAL, "a finite number > 0"); }

// A finite number >= 0.
inline CLI::Validator finite_non_negative() { return finite_number_in(0.0, true, HUGE_VAL, "a finite number >= 0"); }

}  // namespace collide2d::cli
