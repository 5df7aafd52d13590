// Start-up check of the floating-point environment that strict mode relies on.
#pragma once

#include <string>

namespace collide2d {

// Empty when the environment gives IEEE double with round-to-nearest,
// gradual underflow (no flush-to-zero, no denormals-are-zero) and unfused
// a*b+c; otherwise a sentence saying what is wrong. Strict mode refuses to run
// when this is not empty.
std::string strict_environment_problem();

}  // namespace collide2d
