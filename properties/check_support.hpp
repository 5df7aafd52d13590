// What every scene check shares: running a check in the named number mode
// (an exception from the engine is the check's failure, not a crash; a
// NotApplicable goes through to the property, which discards the case), and
// numbers printed to 17 digits in failure messages.
#pragma once

#include <optional>
#include <sstream>
#include <string>

#include "collide2d/numeric/fixed.hpp"
#include "collide2d/numeric/number_mode.hpp"
#include "scene_checks.hpp"

namespace collide2d::properties {

// f(Num{}) with Num the mode's type; "strict" or "fixed".
template <class F>
CheckResult in_mode(const std::string& mode, F f) {
  try {
    const std::optional<NumberMode> known = number_mode_named(mode);
    if (!known) return "unknown mode " + mode;
    return with_number_type(*known, [&](auto type) { return f(typename decltype(type)::type{}); });
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
