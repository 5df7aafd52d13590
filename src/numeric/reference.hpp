// The high-precision reference number type: the oracle of tests and studies.
//
// 60 significant decimal digits (about 200 bits of binary mantissa) from
// Boost.Multiprecision's header-only cpp_bin_float. Expression templates are
// off so that generic code can write `auto x = a * b` as it does for double.
// Products of up to four doubles (the quartic's coefficients) need at most
// 4 × 53 = 212 bits, so most of the time-of-impact arithmetic on double inputs
// is exact or nearly so in this type; double roots keep about 100 bits.
#pragma once

#include <boost/multiprecision/cpp_bin_float.hpp>

namespace collide2d {

using Reference = boost::multiprecision::number<
    boost::multiprecision::cpp_bin_float<60>, boost::multiprecision::et_off>;

}  // namespace collide2d
