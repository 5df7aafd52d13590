// What every scene check shares: running a check in the named number mode
// (an exception from the engine is the check's failure, not a crash; a
// NotApplicable goes through to the property, which discards the case), and
// numbers printed to 17 digits in failure messages.
#pragma once

#include <sstream>
#include <string>

#include "collide2d/numeric/fixed.hpp"
#include "scene_checks.hpp"

namespace collide2d::properties {

// f(Num{}) with Num the mode's type; "strict" or "fixed".
template <class F>
CheckResult in_mode(const std::string& mode, F f) {
  try {
    if (mode == "fixed") return f(Fixed{});
    if (mode == "strict") return f(0.0);
    return "unknown mode " + mode;
  } catch (const NotApplicable&) {
    throw;  // not a failure: the property discards the case (scene_checks.hpp)
  } catch (const std::exception& e) {
    return mode + " run threw: " + e.what();
  }
}

inline std::string g17(long double x) {
  std::ostringstream os;
  os.precision(17);
  os << static_cast<double>(x);
  return os.str();
}

}  // namespace collide2d::properties
