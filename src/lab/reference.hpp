// The high-precision reference number type: the oracle of tests and studies.
//
// 60 significant decimal digits (about 200 bits of binary mantissa) from
// Boost.Multiprecision's header-only cpp_bin_float. Expression templates are
// off so that generic code can write `auto x = a * b` as it does for double.
// Products of up to four doubles (the quartic's coefficients) need at most
// 4 × 53 = 212 bits, so most of the time-of-impact arithmetic on double inputs
// is exact or nearly so in this type; double roots keep about 100 bits.
#pragma once

#include <algorithm>
#include <cmath>

#include <boost/multiprecision/cpp_bin_float.hpp>

#include "collide2d/numeric/number_traits.hpp"

namespace collide2d {

using Reference = boost::multiprecision::number<
    boost::multiprecision::cpp_bin_float<60>, boost::multiprecision::et_off>;

// What generic code asks of a number type (collide2d/numeric/number_traits.hpp),
// for the reference: it plugs into the core's templates from outside, as any
// user's own number type would.
template <>
struct NumberTraits<Reference> {
  static constexpr const char* name = "reference";
  static Reference from_double(double x) { return Reference(x); }
  static double to_double(const Reference& x) { return x.convert_to<double>(); }
  static Reference sqrt(const Reference& x) { return boost::multiprecision::sqrt(x); }
  static Reference abs(const Reference& x) { return boost::multiprecision::abs(x); }
  static Reference half(const Reference& x) { return x / 2; }
  static Reference diff_of_products(const Reference& a, const Reference& b, const Reference& c,
                                    const Reference& d) {
    return a * b - c * d;
  }
  static TwoTerm<Reference> two_diff(const Reference& x, const Reference& y) {
    return {x - y, Reference(0)};
  }
  // Far below any double resolution: 2^-150 relative to the larger end.
  static bool no_value_between(const Reference& lo, const Reference& hi) {
    const Reference scale = std::max(abs(lo), abs(hi));
    return hi - lo <= scale * Reference(std::ldexp(1.0, -150)) || hi - lo == 0;
  }
  static constexpr int max_root_iterations = 600;
  static constexpr bool rounds_absolutely = false;
};

}  // namespace collide2d
