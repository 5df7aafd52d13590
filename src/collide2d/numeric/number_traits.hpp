// The number types of collide2d and everything generic code may ask of them.
//
// One traits struct per scalar type (as Eigen does), so the time-of-impact and
// response routines are written once, as templates, and never branch on the
// type:
//   double     "strict": IEEE binary64, bit reproducible (see CMakeLists.txt)
//   Fixed      "fixed":  Q63.64 integers, overflow reported (fixed.hpp)
//   Reference  "reference": 60 decimal digits, the oracle; not in the core:
//              lab/reference.hpp specialises these traits from outside, as a
//              user's own number type would
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "collide2d/numeric/fixed.hpp"

namespace collide2d {

template <class Num>
struct NumberTraits;

// A value split in two: hi + lo is exact where lo is representable.
template <class Num>
struct TwoTerm {
  Num hi;
  Num lo;
};

// Strict mode's counterpart of FixedPointOverflow. IEEE doubles do not trap:
// a square of a length or a speed beyond about 1e154 becomes inf, then NaN,
// and a solver fed with either answers at random (fuzz_toi_query found a hit
// at t = NaN for a speed of 1e199, and `run` collided two balls that never
// meet). The solvers pass the quantities they form through check_in_range,
// which throws this instead; in range it changes nothing, not a bit.
struct StrictOverflow : std::overflow_error {
  using std::overflow_error::overflow_error;
};

// Whether x is a number the solvers can go on with: a finite double. Any
// value of another type is: Fixed throws on overflow by itself, the 60-digit
// reference of the studies has exponents to spare.
template <class Num>
inline bool is_in_range(const Num&) {
  return true;
}
inline bool is_in_range(double x) { return std::isfinite(x); }

// The throw, kept out of line: the check itself is a compare and a branch
// the solvers' hot loops inline (with the string built in place, the
// compiler kept the whole check a call: 2.5 % of a gas's run).
[[noreturn, gnu::cold, gnu::noinline]] inline void throw_strict_overflow(const char* what) {
  throw StrictOverflow(std::string("strict-mode overflow in ") + what);
}

// Throws StrictOverflow naming `what` unless is_in_range(x).
template <class Num>
inline void check_in_range(const Num& x, const char* what) {
  if (!is_in_range(x)) [[unlikely]]
    throw_strict_overflow(what);
}

template <>
struct NumberTraits<double> {
  static constexpr const char* name = "strict";
  static double from_double(double x) { return x; }
  static double to_double(double x) { return x; }
  static double sqrt(double x) { return std::sqrt(x); }  // IEEE: correctly rounded
  static double abs(double x) { return std::fabs(x); }
  static double half(double x) { return 0.5 * x; }

  // a*b as hi + lo exactly (Dekker's TwoProduct with Veltkamp's splitting:
  // plain multiplies and adds, inlined; no fma call, no -mfma needed).
  // Exact unless a product overflows or falls into the subnormal range.
  static TwoTerm<double> two_product(double a, double b) {
    auto split = [](double x) {
      const double c = 134217729.0 * x;  // 2^27 + 1
      const double hi = c - (c - x);
      return TwoTerm<double>{hi, x - hi};
    };
    const double p = a * b;
    const auto [ah, al] = split(a);
    const auto [bh, bl] = split(b);
    const double err = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    return {p, err};
  }
  // a*b - c*d to within about 2 ulp, whatever the cancellation: both products
  // exact as hi + lo; when they cancel, hi_ab − hi_cd is exact (Sterbenz) and
  // the lo terms carry what is left.
  static double diff_of_products(double a, double b, double c, double d) {
    const auto ab = two_product(a, b);
    const auto cd = two_product(c, d);
    return (ab.hi - cd.hi) + (ab.lo - cd.lo);
  }
  // x - y as hi + lo with hi = fl(x - y) and lo its exact rounding error
  // (Knuth's TwoSum; branch free).
  static TwoTerm<double> two_diff(double x, double y) {
    const double hi = x - y;
    const double y_virtual = x - hi;
    const double x_virtual = hi + y_virtual;
    const double lo = (x - x_virtual) + (y_virtual - y);
    return {hi, lo};
  }
  // Two times are "the same" for the root polish when no double lies between.
  static bool no_value_between(double lo, double hi) {
    const double mid = lo + 0.5 * (hi - lo);
    return mid <= lo || mid >= hi;
  }
  static constexpr int max_root_iterations = 200;
  static constexpr bool rounds_absolutely = false;
};

namespace detail {
// Fixed's sqrt and abs are found by argument-dependent lookup only.
inline Fixed fixed_sqrt(Fixed x) { return sqrt(x); }
inline Fixed fixed_abs(Fixed x) { return abs(x); }
}  // namespace detail

template <>
struct NumberTraits<Fixed> {
  static constexpr const char* name = "fixed";
  static Fixed from_double(double x) { return Fixed::from_double(x); }
  static double to_double(Fixed x) { return x.to_double(); }
  static Fixed sqrt(Fixed x) { return detail::fixed_sqrt(x); }
  static Fixed abs(Fixed x) { return detail::fixed_abs(x); }
  static Fixed half(Fixed x) { return x.half(); }
  // Integer subtraction is exact; a product rounds once to 2^-64.
  static Fixed diff_of_products(Fixed a, Fixed b, Fixed c, Fixed d) { return a * b - c * d; }
  static TwoTerm<Fixed> two_diff(Fixed x, Fixed y) { return {x - y, Fixed()}; }
  static bool no_value_between(Fixed lo, Fixed hi) { return hi.raw() - lo.raw() <= 1; }
  static constexpr int max_root_iterations = 200;
  // Rounding is to an absolute 2^-64, not relative: small quantities keep
  // few significant bits unless scaled up first (normalise_quadratic).
  static constexpr bool rounds_absolutely = true;
  // A product is a 128 × 128-bit multiply with overflow checks, several
  // times a double's: conservative screens that only decide which pairs are
  // worth an exact search may run in doubles (certainly_out_of_reach).
  static constexpr bool screens_in_double = true;
  // x as a double within 3 · 2^-53 of |x| (not always the nearest double,
  // which to_double gives at several times the cost): the integer and
  // fraction words of |x| converted apart and added, no cancellation. For
  // the screens only.
  static double screen_double(Fixed x) {
    const fixed_detail::UInt128 mag = fixed_detail::magnitude(x.raw());
    const double v = static_cast<double>(fixed_detail::hi64(mag)) + static_cast<double>(fixed_detail::lo64(mag)) * 0x1p-64;
    return x.raw() < 0 ? -v : v;
  }
  // The absolute resolution, one unit in the last place: 2^-64.
  static Fixed resolution() { return Fixed::resolution(); }
  // ⌊log2 |x|⌋ (−64 for the resolution 2^-64); a very negative number for 0.
  static int exponent(Fixed x) {
    return fixed_detail::bit_length(fixed_detail::magnitude(x.raw())) - 1 - Fixed::fraction_bits;
  }
  // x · 2^k for k ≥ 0, exact (a shift); throws on overflow, never wraps.
  static Fixed times_power_of_two(Fixed x, int k) {
    const fixed_detail::UInt128 mag = fixed_detail::magnitude(x.raw());
    if (k > 0 && fixed_detail::bit_length(mag) + k > 127) fixed_detail::throw_overflow("fixed-point overflow in scaling");
    return Fixed::from_raw(fixed_detail::apply_sign_checked(mag << k, x.raw() < 0, "fixed-point overflow in scaling"));
  }
};

// Shorthand for generic code: the constant 0.5 as a Num is num<Num>(0.5).
template <class Num>
inline Num num(double x) {
  return NumberTraits<Num>::from_double(x);
}

}  // namespace collide2d
