// Generators of Q63.64 values from raw bits (numeric/fixed.hpp), for the
// fixed-mode properties: values a few ulps (2^-64) away from interesting ones.
// The oracle reads doubles, so a value is kept only when it is exactly a
// double too (every Fixed below 2^-11 in magnitude is).
#pragma once

#include <rapidcheck.h>

#include "collide2d/numeric/fixed.hpp"

namespace collide2d::properties {

// A raw offset: ±1..4 ulps, or ±2^k ulps (k < 63), shrinking towards +1.
inline Fixed::Raw raw_offset() {
  const bool power = *rc::gen::element(false, false, true);
  const Fixed::Raw magnitude = power ? Fixed::Raw{1} << *rc::gen::inRange(0, 63) : *rc::gen::inRange(1, 5);
  return *rc::gen::arbitrary<bool>() ? -magnitude : magnitude;
}

// `base` moved by raw_offset() ulps.
inline Fixed raw_near(Fixed base) { return Fixed::from_raw(base.raw() + raw_offset()); }

// The double whose Fixed value is exactly `f`, if there is one.
inline bool exactly_double(Fixed f, double& out) {
  out = f.to_double();
  return Fixed::from_double(out).raw() == f.raw();
}

// x moved by a few raw ulps when the result is still exactly a double, else x.
inline double nudged_by_raw_ulps(double x) {
  double out;
  return exactly_double(raw_near(Fixed::from_double(x)), out) ? out : x;
}

// A value a few ulps from zero: the smallest non-zero accelerations and
// speeds Q63.64 holds (a quadratic coefficient that is almost, not quite, 0).
inline double few_ulps_from_zero() {
  double out;
  const Fixed f = raw_near(Fixed{});
  return exactly_double(f, out) ? out : 0.0;
}

}  // namespace collide2d::properties
