// collide2d: signed Q63.64 fixed-point numbers.
//
// A Fixed holds a signed 128-bit integer `raw` and stands for raw * 2^-64:
//   range       [-2^63, 2^63 - 2^-64]   (lowest() .. max())
//   resolution  2^-64 ~= 5.42e-20        (raw 1)
//
// All arithmetic is done on integers only, so results are the same bits on
// every compiler and optimisation level. Doubles appear only in the boundary
// conversions from_double / to_double, which work on the IEEE-754 bit pattern
// and do no floating-point arithmetic either.
//
// Rounding and errors (1 ulp = 2^-64 = raw 1):
//   + - unary- abs   exact
//   *  /             correctly rounded: nearest, ties away from zero (<= 0.5 ulp)
//   sqrt             correctly rounded: nearest (a tie cannot occur) (< 0.5 ulp)
//   half()           exact when raw is even, else the tie rounds away from zero
// Any result that is not representable throws FixedPointOverflow; nothing
// ever wraps. Division by zero and sqrt of a negative number throw
// std::domain_error (they have no result at all, rather than a too-large one).
#pragma once

#include <array>
#include <bit>
#include <compare>
#include <cstdint>
#include <stdexcept>

#include "collide2d/numeric/portable_int128.hpp"

namespace collide2d {

// Thrown when a result cannot be represented as a Fixed.
struct FixedPointOverflow : std::overflow_error {
  using std::overflow_error::overflow_error;
};

namespace fixed_detail {

// Out-of-line, cold throw helpers: keep the hot arithmetic small enough that
// compilers inline it.
[[noreturn]] [[gnu::cold]] [[gnu::noinline]] inline void throw_overflow(const char* what) {
  throw FixedPointOverflow(what);
}
[[noreturn]] [[gnu::cold]] [[gnu::noinline]] inline void throw_domain(const char* what) {
  throw std::domain_error(what);
}

// The 128-bit integers: the compiler's where it has them; two 64-bit words
// (portable_int128.hpp, the same results bit for bit) where it does not
// (i686), or when COLLIDE2D_PORTABLE_INT128 asks for them (the tests that
// compare the two on x86-64).
#if defined(__SIZEOF_INT128__) && !defined(COLLIDE2D_PORTABLE_INT128)
__extension__ using Int128 = __int128;
__extension__ using UInt128 = unsigned __int128;
inline constexpr bool kNativeInt128 = true;
constexpr bool add_overflows(Int128 a, Int128 b, Int128& r) { return __builtin_add_overflow(a, b, &r); }
constexpr bool sub_overflows(Int128 a, Int128 b, Int128& r) { return __builtin_sub_overflow(a, b, &r); }
#else
using Int128 = portable::Int128;
using UInt128 = portable::UInt128;
inline constexpr bool kNativeInt128 = false;
using portable::add_overflows;
using portable::sub_overflows;
#endif

inline constexpr UInt128 kSignBit = UInt128{1} << 127;  // 2^127

constexpr std::uint64_t lo64(UInt128 v) { return static_cast<std::uint64_t>(v); }
constexpr std::uint64_t hi64(UInt128 v) { return static_cast<std::uint64_t>(v >> 64); }
constexpr UInt128 make128(std::uint64_t hi, std::uint64_t lo) {
  return (UInt128{hi} << 64) | lo;
}

// |v| as an unsigned number; exact for every v including -2^127.
constexpr UInt128 magnitude(Int128 v) {
  return v < 0 ? UInt128{0} - static_cast<UInt128>(v) : static_cast<UInt128>(v);
}

// Signed value with magnitude `mag` (negated if `negative`). Throws unless it
// fits: mag <= 2^127 - 1, or mag <= 2^127 for a negative result.
constexpr Int128 apply_sign_checked(UInt128 mag, bool negative, const char* what) {
  if (mag > kSignBit - (negative ? 0 : 1)) fixed_detail::throw_overflow(what);
  // Two's-complement negation in unsigned arithmetic, then the (C++20 modular)
  // conversion to signed: no undefined behaviour even for -2^127.
  return static_cast<Int128>(negative ? UInt128{0} - mag : mag);
}

// Number of significant bits of v (0 for v == 0).
constexpr int bit_length(UInt128 v) {
  if (hi64(v) != 0) return 128 - std::countl_zero(hi64(v));
  return 64 - std::countl_zero(lo64(v));
}

// Exact 128 x 128 -> 256-bit product of two unsigned numbers, from four
// 64 x 64 -> 128 partial products. Returns the high 128 bits; the low 128
// bits are stored in `low`.
constexpr UInt128 mul_256(UInt128 a, UInt128 b, UInt128& low) {
  const std::uint64_t a0 = lo64(a), a1 = hi64(a), b0 = lo64(b), b1 = hi64(b);
  const UInt128 p00 = UInt128{a0} * b0;
  // One of them below 2^64 (a value below 1 in Fixed: impulses, normals,
  // ratios): two partial products.
  if (a1 == 0 || b1 == 0) {
    const UInt128 p = a1 == 0 ? UInt128{a0} * b1 : UInt128{a1} * b0;
    const UInt128 column = UInt128{hi64(p00)} + lo64(p);
    low = make128(lo64(column), lo64(p00));
    return UInt128{hi64(p)} + hi64(column);
  }
  const UInt128 p01 = UInt128{a0} * b1;
  const UInt128 p10 = UInt128{a1} * b0;
  const UInt128 p11 = UInt128{a1} * b1;
  // Column 1 (bits 64..127): at most 3 * (2^64 - 1), no overflow.
  const UInt128 mid = UInt128{hi64(p00)} + lo64(p01) + lo64(p10);
  low = make128(lo64(mid), lo64(p00));
  // The full product is < 2^256, so the high half cannot overflow.
  return p11 + hi64(p01) + hi64(p10) + hi64(mid);
}

// Hardware 128 / 64 division: returns floor((hi:lo) / d) and stores the
// remainder in `rem`. Precondition: hi < d (so the quotient fits in 64 bits).
// On x86-64 this is one `divq`; without __int128, Knuth's algorithm with 32-bit
// digits (portable_int128.hpp). The exact result is the same everywhere.
inline std::uint64_t div_128_64(std::uint64_t hi, std::uint64_t lo, std::uint64_t d,
                                std::uint64_t& rem) {
#if !(defined(__SIZEOF_INT128__) && !defined(COLLIDE2D_PORTABLE_INT128))
  return portable::div_128_64(hi, lo, d, rem);  // 32-bit digits, no 128-bit type
#elif defined(__x86_64__)
  std::uint64_t q, r;
  __asm__("divq %4" : "=a"(q), "=d"(r) : "a"(lo), "d"(hi), "rm"(d) : "cc");
  rem = r;
  return q;
#else
  const UInt128 n = make128(hi, lo);
  const std::uint64_t q = static_cast<std::uint64_t>(n / d);
  rem = lo64(n - UInt128{q} * d);
  return q;
#endif
}

// One step of Knuth's algorithm D with 64-bit digits: divides the 3-digit
// number (u2:u1:u0) by the normalised 2-digit divisor v = (v1:v0) (top bit of
// v1 set). Precondition: (u2:u1) < v, so the quotient is a single digit.
// Returns the exact quotient digit and stores the exact remainder (< v).
// The estimate from (u2:u1) / v1 is corrected with the test on v0 (exact for a
// 2-digit divisor, at most two corrections), so no add-back step is needed.
inline std::uint64_t div_3by2(std::uint64_t u2, std::uint64_t u1, std::uint64_t u0, UInt128 v,
                              UInt128& rem) {
  const std::uint64_t v1 = hi64(v), v0 = lo64(v);
  std::uint64_t qhat;
  UInt128 rhat;  // (u2:u1) - qhat * v1, may exceed 64 bits
  if (u2 < v1) {
    std::uint64_t r;
    qhat = div_128_64(u2, u1, v1, r);
    rhat = r;
  } else {  // u2 == v1: the digit estimate saturates at 2^64 - 1
    qhat = ~std::uint64_t{0};
    rhat = UInt128{u1} + v1;
  }
  while (hi64(rhat) == 0 && UInt128{qhat} * v0 > make128(lo64(rhat), u0)) {
    --qhat;
    rhat += v1;
  }
  // The true remainder is < v < 2^128, so computing it modulo 2^128 is exact.
  rem = make128(u1, u0) - UInt128{qhat} * v;
  return qhat;
}

// floor(2^64 * a / b) for b != 0, with rounding information: returns the
// quotient (throws FixedPointOverflow if it is >= 2^128) and sets `round_up`
// when the discarded fraction is >= 1/2.
inline UInt128 div_shifted(UInt128 a, UInt128 b, bool& round_up) {
  const std::uint64_t a1 = hi64(a), a0 = lo64(a);
  if (hi64(b) == 0) {
    // Short division of the 3-digit number (a1:a0:0) by one digit d.
    const std::uint64_t d = lo64(b);
    if (a1 >= d) fixed_detail::throw_overflow("fixed-point overflow in division");
    std::uint64_t r;
    const std::uint64_t q1 = div_128_64(a1, a0, d, r);
    const std::uint64_t q0 = div_128_64(r, 0, d, r);
    round_up = r >= d - r;  // (a tie is impossible here: d has fewer than 64 factors of 2)
    return make128(q1, q0);
  }
  // Long division of (a1:a0:0) by the 2-digit b. Normalise so the divisor's
  // top bit is set; the dividend becomes 4 digits (n3:n2:n1:0). Since
  // b >= 2^64 the quotient is <= a < 2^128: two quotient digits.
  const int s = std::countl_zero(hi64(b));
  const UInt128 v = b << s;
  const std::uint64_t n1 = a0 << s;
  const std::uint64_t n2 = s == 0 ? a1 : (a1 << s) | (a0 >> (64 - s));
  const std::uint64_t n3 = s == 0 ? 0 : a1 >> (64 - s);
  UInt128 r;
  const std::uint64_t q1 = div_3by2(n3, n2, n1, v, r);
  const std::uint64_t q0 = div_3by2(hi64(r), lo64(r), 0, v, r);
  round_up = r >= v - r;  // remainder and divisor carry the same 2^s scale
  return make128(q1, q0);
}

// floor(sqrt(i)) for i in [0, 256); used for i in [64, 256) (result 8..15).
inline constexpr std::array<std::uint8_t, 256> kSqrtTable8 = [] {
  std::array<std::uint8_t, 256> t{};
  std::uint8_t r = 0;
  for (unsigned i = 0; i < 256; ++i) {
    while ((r + 1u) * (r + 1u) <= i) ++r;
    t[i] = r;
  }
  return t;
}();

// floor(sqrt(m)) for m in [2^126, 2^128); the result is in [2^63, 2^64).
//
// Built by exact refinement levels, each doubling the number of root bits.
// Level invariant: N has 2w bits with N >= 2^(2w-2), and t = floor(sqrt(N >>
// w)) is exact. Then x0 = (t + 1) * 2^(w/2) >= sqrt(N) with x0 - sqrt(N) <=
// 2^(w/2), and one integer Newton step x1 = floor((x0 + floor(N / x0)) / 2)
// satisfies floor(sqrt(N)) <= x1 <= floor(sqrt(N) + (x0 - sqrt N)^2 / (2 x0))
// <= floor(sqrt(N)) + 1; one comparison x1^2 > N makes it exact. (x0 is
// clamped to 2^w - 1 when t + 1 = 2^(w/2); the bounds still hold.)
// Levels: table (8 -> 4 bits), 16, 32, 64 and 128 bits.
inline std::uint64_t isqrt_normalised_128(UInt128 m) {
  const std::uint64_t m1 = hi64(m);

  // 16-bit level: N = top 16 bits of m.
  const std::uint32_t n16 = static_cast<std::uint32_t>(m1 >> 48);
  std::uint32_t x = kSqrtTable8[n16 >> 8] + 1u;  // table level: root of the top 8 bits, + 1
  x = x == 16 ? 255 : x << 4;
  x = (x + n16 / x) >> 1;
  if (x * x > n16) --x;

  // 32-bit level.
  const std::uint32_t n32 = static_cast<std::uint32_t>(m1 >> 32);
  x = x == 255 ? 65535 : (x + 1) << 8;
  x = (x + n32 / x) >> 1;
  if (std::uint64_t{x} * x > n32) --x;

  // 64-bit level.
  std::uint64_t y = x == 65535 ? 0xFFFFFFFFu : (std::uint64_t{x} + 1) << 16;
  y = (y + m1 / y) >> 1;
  if (UInt128{y} * y > m1) --y;

  // 128-bit level.
  if (y == 0xFFFFFFFFu) {
    // Clamped start 2^64 - 1. If m1 >= 2^64 - 1 the root is 2^64 - 1 (m <
    // 2^128), and the divide below would not fit in 64 bits.
    if (m1 == ~std::uint64_t{0}) return ~std::uint64_t{0};
    y = ~std::uint64_t{0};
  } else {
    y = (y + 1) << 32;  // >= sqrt(m), so hi64(m) < y and the divide fits
  }
  std::uint64_t r;
  const std::uint64_t q = div_128_64(m1, lo64(m), y, r);
  y = static_cast<std::uint64_t>((UInt128{y} + q) >> 1);
  if (UInt128{y} * y > m) --y;
  return y;
}

}  // namespace fixed_detail

class Fixed {
 public:
  using Raw = fixed_detail::Int128;
  static constexpr int fraction_bits = 64;

  constexpr Fixed() = default;  // zero
  constexpr explicit Fixed(int n) : raw_(static_cast<Raw>(n) * (Raw{1} << fraction_bits)) {}

  static constexpr Fixed from_raw(Raw r) {
    Fixed f;
    f.raw_ = r;
    return f;
  }
  constexpr Raw raw() const { return raw_; }

  // Exact when x is a multiple of 2^-64; otherwise rounds to the nearest
  // Fixed, ties away from zero (so e.g. |x| < 2^-65 gives 0). Throws
  // FixedPointOverflow if x is NaN, infinite, or |x| >= 2^63.
  static constexpr Fixed from_double(double x);
  // The double nearest to the value (ties to even); exact when the value has
  // at most 53 significant bits. Never overflows (|value| <= 2^63).
  constexpr double to_double() const;

  static constexpr Fixed resolution() { return from_raw(1); }
  static constexpr Fixed max() { return from_raw(static_cast<Raw>(fixed_detail::kSignBit - 1)); }
  static constexpr Fixed lowest() { return from_raw(static_cast<Raw>(fixed_detail::kSignBit)); }

  friend constexpr bool operator==(Fixed, Fixed) = default;
  friend constexpr std::strong_ordering operator<=>(Fixed a, Fixed b) {
    return a.raw_ < b.raw_ ? std::strong_ordering::less
           : a.raw_ > b.raw_ ? std::strong_ordering::greater
                             : std::strong_ordering::equal;
  }

  // Exact; throws FixedPointOverflow if out of range.
  friend constexpr Fixed operator+(Fixed a, Fixed b) {
    Raw r = 0;
    if (fixed_detail::add_overflows(a.raw_, b.raw_, r))
      fixed_detail::throw_overflow("fixed-point overflow in addition");
    return from_raw(r);
  }
  friend constexpr Fixed operator-(Fixed a, Fixed b) {
    Raw r = 0;
    if (fixed_detail::sub_overflows(a.raw_, b.raw_, r))
      fixed_detail::throw_overflow("fixed-point overflow in subtraction");
    return from_raw(r);
  }
  friend constexpr Fixed operator-(Fixed a) {
    if (a == lowest()) fixed_detail::throw_overflow("fixed-point overflow in negation");
    return from_raw(-a.raw_);
  }
  friend constexpr Fixed operator+(Fixed a) { return a; }

  // Correctly rounded product: the exact 256-bit product of the magnitudes,
  // rounded to nearest (ties away from zero) at 2^-64. Error <= 0.5 ulp.
  friend constexpr Fixed operator*(Fixed a, Fixed b) {
    using namespace fixed_detail;
    // A zero factor (an idle contact's force, an empty matrix entry) makes
    // an exact zero: no partial products.
    if (a.raw_ == 0 || b.raw_ == 0) return Fixed{};
    UInt128 low = 0;
    const UInt128 high = mul_256(magnitude(a.raw_), magnitude(b.raw_), low);
    // Result magnitude = bits 64..191 of the product, plus the rounding bit 63.
    if (hi64(high) != 0)  // product >= 2^192, i.e. |result| >= 2^64
      fixed_detail::throw_overflow("fixed-point overflow in multiplication");
    const UInt128 mag = make128(lo64(high), hi64(low));
    const bool round_up = (lo64(low) >> 63) != 0;
    if (mag == ~UInt128{0} && round_up)  // the increment itself would wrap
      fixed_detail::throw_overflow("fixed-point overflow in multiplication");
    return from_raw(apply_sign_checked(mag + round_up, (a.raw_ < 0) != (b.raw_ < 0),
                                       "fixed-point overflow in multiplication"));
  }

  // Correctly rounded quotient a / b: nearest, ties away from zero. Error <=
  // 0.5 ulp. Throws std::domain_error if b == 0 and FixedPointOverflow if the
  // quotient is out of range. Knuth long division with 64-bit digits (two or
  // three hardware 128/64 divides).
  friend Fixed operator/(Fixed a, Fixed b) {
    using namespace fixed_detail;
    if (b.raw_ == 0) fixed_detail::throw_domain("fixed-point division by zero");
    bool round_up = false;
    const UInt128 q = div_shifted(magnitude(a.raw_), magnitude(b.raw_), round_up);
    if (q == ~UInt128{0} && round_up)  // the increment itself would wrap
      fixed_detail::throw_overflow("fixed-point overflow in division");
    return from_raw(apply_sign_checked(q + round_up, (a.raw_ < 0) != (b.raw_ < 0),
                                       "fixed-point overflow in division"));
  }

  Fixed& operator+=(Fixed b) { return *this = *this + b; }
  Fixed& operator-=(Fixed b) { return *this = *this - b; }
  Fixed& operator*=(Fixed b) { return *this = *this * b; }
  Fixed& operator/=(Fixed b) { return *this = *this / b; }

  // Correctly rounded square root (nearest; the exact root is never halfway
  // between two Fixed values). Error < 0.5 ulp. Throws std::domain_error for a
  // negative argument. Never overflows (sqrt(max()) ~ 3.04e9).
  friend Fixed sqrt(Fixed a) {
    using namespace fixed_detail;
    if (a.raw_ < 0) fixed_detail::throw_domain("fixed-point square root of a negative number");
    if (a.raw_ == 0) return a;
    // Result raw = round(sqrt(R * 2^64)) = (floor(sqrt(R * 2^66)) + 1) >> 1
    // for R = a.raw_ (no ties: R * 2^64 is an integer).
    // Write R * 2^66 * 4^k = m * 2^128 with m in [2^126, 2^128): m = R << sh.
    // Then floor(sqrt(R * 2^66)) = floor(sqrt(m * 2^128)) >> k.
    const UInt128 r = static_cast<UInt128>(a.raw_);
    const int sh = (128 - bit_length(r)) & ~1;  // even, in [0, 126]
    const int k = sh / 2 + 31;                    // in [31, 94]
    const UInt128 m = r << sh;
    const std::uint64_t m1 = hi64(m), m0 = lo64(m);

    // s = floor(sqrt(m)) in [2^63, 2^64). One Newton step from x = s * 2^64
    // (x <= sqrt(m) * 2^64 =: T, T - x < 2^64) gives y with
    // floor(T) <= y <= floor(T + (T - x)^2 / (2x)) <= floor(T) + 1.
    const std::uint64_t s = isqrt_normalised_128(m);
    // q = floor(m * 2^128 / x) = floor((m1:m0:0) / s) >= x. Since m < (s+1)^2,
    // m1 <= s, so the top quotient digit is 0 or 1.
    const std::uint64_t q2 = m1 == s ? 1 : 0;
    std::uint64_t rem = m1 - (q2 ? s : 0);
    const std::uint64_t q1 = div_128_64(rem, m0, s, rem);
    const std::uint64_t q0 = div_128_64(rem, 0, s, rem);
    // y = (x + q) / 2 = x + (q - x) / 2, where q - x < 3 * 2^64.
    const UInt128 excess_hi = (UInt128{q2} << 64) + q1 - s;
    const UInt128 excess = make128(lo64(excess_hi), q0);
    UInt128 y = (UInt128{s} << 64) + (excess >> 1);
    // Fix the possible +1: compare y^2 with m * 2^128.
    UInt128 y2_low = 0;
    const UInt128 y2_high = mul_256(y, y, y2_low);
    if (y2_high > m || (y2_high == m && y2_low != 0)) --y;
    return from_raw(static_cast<Raw>(((y >> k) + 1) >> 1));
  }

  // Exact; throws FixedPointOverflow for lowest().
  friend constexpr Fixed abs(Fixed a) {
    if (a == lowest()) fixed_detail::throw_overflow("fixed-point overflow in absolute value");
    return a.raw_ < 0 ? from_raw(-a.raw_) : a;
  }

  // a / 2: exact when raw is even; otherwise the exact value lies halfway
  // between two Fixed values and is rounded away from zero. Never overflows.
  constexpr Fixed half() const {
    // floor(raw / 2) + (odd and positive): arithmetic shift floors.
    const Raw floor_half = raw_ >> 1;
    return from_raw(floor_half + ((raw_ & 1) != 0 && raw_ > 0 ? 1 : 0));
  }

 private:
  Raw raw_ = 0;
};

// Whether Fixed::from_double accepts x: finite and |x| < 2^63 (so that a
// scene or query can be checked, field by field, before any conversion).
constexpr bool fixed_range_holds(double x) { return x > -0x1p63 && x < 0x1p63; }

constexpr Fixed Fixed::from_double(double x) {
  using namespace fixed_detail;
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const bool negative = (bits >> 63) != 0;
  const int biased_exp = static_cast<int>((bits >> 52) & 0x7FF);
  const std::uint64_t fraction = bits & ((std::uint64_t{1} << 52) - 1);
  if (biased_exp == 0x7FF)
    fixed_detail::throw_overflow("fixed-point overflow in conversion from double (not finite)");
  if (biased_exp == 0) return Fixed{};  // zero or subnormal (< 2^-1022): rounds to 0
  // |x| = mant * 2^e with mant in [2^52, 2^53).
  const std::uint64_t mant = fraction | (std::uint64_t{1} << 52);
  const int e = biased_exp - 1075;
  if (e + 52 >= 63)  // |x| >= 2^63
    fixed_detail::throw_overflow("fixed-point overflow in conversion from double");
  UInt128 mag = 0;
  const int shift = e + fraction_bits;  // raw = mant * 2^shift
  if (shift >= 0) {
    mag = UInt128{mant} << shift;  // exact, < 2^127
  } else if (-shift < 54) {
    const int rs = -shift;  // round to nearest, ties away from zero
    mag = (mant + (std::uint64_t{1} << (rs - 1))) >> rs;
  }  // else raw = mant * 2^shift < 2^53 * 2^-54 = 1/2: rounds to 0
  return from_raw(static_cast<Raw>(negative ? UInt128{0} - mag : mag));
}

constexpr double Fixed::to_double() const {
  using namespace fixed_detail;
  if (raw_ == 0) return 0.0;
  UInt128 mag = magnitude(raw_);
  const int len = bit_length(mag);  // 1..128
  int exp2 = -fraction_bits;        // value = mag * 2^exp2
  if (len > 53) {
    // Keep 53 significant bits, round to nearest, ties to even.
    const int drop = len - 53;
    const UInt128 rest = mag & ((UInt128{1} << drop) - 1);
    const UInt128 halfway = UInt128{1} << (drop - 1);
    mag >>= drop;
    exp2 += drop;
    if (rest > halfway || (rest == halfway && (mag & 1) != 0)) ++mag;
    if (mag == (UInt128{1} << 53)) {  // rounding carried into a new bit
      mag >>= 1;
      ++exp2;
    }
  } else {
    mag <<= 53 - len;
    exp2 -= 53 - len;
  }
  // Now value = mag * 2^exp2 with mag in [2^52, 2^53); the unbiased exponent
  // exp2 + 52 lies in [-64, 63], always a normal double.
  const auto biased = static_cast<std::uint64_t>(exp2 + 52 + 1023);
  const std::uint64_t bits = (raw_ < 0 ? std::uint64_t{1} << 63 : 0) | (biased << 52) |
                             (lo64(mag) & ((std::uint64_t{1} << 52) - 1));
  return std::bit_cast<double>(bits);
}

}  // namespace collide2d
