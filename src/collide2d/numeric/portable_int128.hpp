// 128-bit integers as two 64-bit words, for compilers without __int128
// (gcc and clang on 32-bit targets such as i686). fixed.hpp takes these as its
// Int128/UInt128 where __int128 does not exist, or when
// COLLIDE2D_PORTABLE_INT128 is defined (tests/numeric/ builds both ways on
// x86-64 and compares them).
//
// Semantics are those of unsigned __int128 and __int128 in gcc, bit for bit:
//   + - * ~ & | << and unary -   modulo 2^128 (two's complement for Int128)
//   >>                           logical for UInt128, arithmetic for Int128
//   comparisons                  unsigned / signed
//   from a built-in integer      sign-extended if the source type is signed
//   to a built-in integer        the low bits (modular, as static_cast does)
// Shift counts must lie in [0, 127], as for the built-in types. There is no
// operator/: fixed.hpp divides only 128 by 64 bits, through div_128_64 below.
//
// The words are stored in memory order (low word first on a little-endian
// machine), so the 16 bytes are those of the built-in type: run-file hashes
// and checkpoints made from the bytes of a raw value do not depend on which
// representation computed it.
#pragma once

#include <compare>
#include <concepts>
#include <cstdint>
#include <type_traits>

namespace collide2d::portable {

namespace detail {

// Full 64 x 64 -> 128-bit product from four 32 x 32 -> 64 products
// (schoolbook, base 2^32): no partial sum can overflow 64 bits because
// (2^32-1)^2 + 2 (2^32-1) = 2^64 - 1.
constexpr void mul_64x64(std::uint64_t a, std::uint64_t b, std::uint64_t& hi, std::uint64_t& lo) {
  const std::uint64_t a0 = a & 0xFFFFFFFFu, a1 = a >> 32, b0 = b & 0xFFFFFFFFu, b1 = b >> 32;
  const std::uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
  const std::uint64_t mid = (p00 >> 32) + (p01 & 0xFFFFFFFFu) + (p10 & 0xFFFFFFFFu);
  lo = (mid << 32) | (p00 & 0xFFFFFFFFu);
  hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
}

// The high word of a built-in integer widened to 128 bits: its sign, copied.
template <std::integral T>
constexpr std::uint64_t sign_fill(T v) {
  if constexpr (std::is_signed_v<T>) return v < 0 ? ~std::uint64_t{0} : 0;
  else return 0;
}

}  // namespace detail

class Int128;

class UInt128 {
 public:
  constexpr UInt128() = default;
  template <std::integral T>
  constexpr UInt128(T v)  // NOLINT: implicit, like the built-in conversion
      : lo_(static_cast<std::uint64_t>(v)), hi_(detail::sign_fill(v)) {}
  explicit constexpr UInt128(const Int128& v);
  static constexpr UInt128 from_words(std::uint64_t hi, std::uint64_t lo) {
    UInt128 r;
    r.hi_ = hi;
    r.lo_ = lo;
    return r;
  }
  constexpr std::uint64_t hi() const { return hi_; }
  constexpr std::uint64_t lo() const { return lo_; }

  template <std::integral T>
  explicit constexpr operator T() const {
    if constexpr (std::same_as<T, bool>) return (lo_ | hi_) != 0;
    else return static_cast<T>(lo_);
  }

  friend constexpr UInt128 operator+(UInt128 a, UInt128 b) {
    const std::uint64_t lo = a.lo_ + b.lo_;
    return from_words(a.hi_ + b.hi_ + (lo < a.lo_ ? 1 : 0), lo);
  }
  friend constexpr UInt128 operator-(UInt128 a, UInt128 b) {
    return from_words(a.hi_ - b.hi_ - (a.lo_ < b.lo_ ? 1 : 0), a.lo_ - b.lo_);
  }
  friend constexpr UInt128 operator-(UInt128 a) { return UInt128{} - a; }
  friend constexpr UInt128 operator~(UInt128 a) { return from_words(~a.hi_, ~a.lo_); }
  // Modulo 2^128: the low 128 bits of the product; a.hi * b.hi * 2^128 and
  // the high halves of the cross products fall off the top.
  friend constexpr UInt128 operator*(UInt128 a, UInt128 b) {
    std::uint64_t hi = 0, lo = 0;
    detail::mul_64x64(a.lo_, b.lo_, hi, lo);
    return from_words(hi + a.lo_ * b.hi_ + a.hi_ * b.lo_, lo);
  }
  friend constexpr UInt128 operator&(UInt128 a, UInt128 b) { return from_words(a.hi_ & b.hi_, a.lo_ & b.lo_); }
  friend constexpr UInt128 operator|(UInt128 a, UInt128 b) { return from_words(a.hi_ | b.hi_, a.lo_ | b.lo_); }
  friend constexpr UInt128 operator^(UInt128 a, UInt128 b) { return from_words(a.hi_ ^ b.hi_, a.lo_ ^ b.lo_); }
  // s in [0, 127]. A 64-bit shift by 64 would be undefined, hence the cases.
  friend constexpr UInt128 operator<<(UInt128 a, int s) {
    if (s == 0) return a;
    if (s >= 64) return from_words(a.lo_ << (s - 64), 0);
    return from_words((a.hi_ << s) | (a.lo_ >> (64 - s)), a.lo_ << s);
  }
  friend constexpr UInt128 operator>>(UInt128 a, int s) {
    if (s == 0) return a;
    if (s >= 64) return from_words(0, a.hi_ >> (s - 64));
    return from_words(a.hi_ >> s, (a.lo_ >> s) | (a.hi_ << (64 - s)));
  }
  friend constexpr bool operator==(UInt128 a, UInt128 b) { return a.hi_ == b.hi_ && a.lo_ == b.lo_; }
  friend constexpr std::strong_ordering operator<=>(UInt128 a, UInt128 b) {
    return a.hi_ != b.hi_ ? a.hi_ <=> b.hi_ : a.lo_ <=> b.lo_;
  }

  constexpr UInt128& operator+=(UInt128 b) { return *this = *this + b; }
  constexpr UInt128& operator-=(UInt128 b) { return *this = *this - b; }
  constexpr UInt128& operator*=(UInt128 b) { return *this = *this * b; }
  constexpr UInt128& operator&=(UInt128 b) { return *this = *this & b; }
  constexpr UInt128& operator|=(UInt128 b) { return *this = *this | b; }
  constexpr UInt128& operator<<=(int s) { return *this = *this << s; }
  constexpr UInt128& operator>>=(int s) { return *this = *this >> s; }
  constexpr UInt128& operator++() { return *this += 1; }
  constexpr UInt128& operator--() { return *this -= 1; }

 private:
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  std::uint64_t lo_ = 0, hi_ = 0;
#else
  std::uint64_t hi_ = 0, lo_ = 0;
#endif
};

// The same 128 bits read as two's complement. Every operation that does not
// depend on the sign (+ - * and the bitwise ones) is UInt128's.
class Int128 {
 public:
  constexpr Int128() = default;
  template <std::integral T>
  constexpr Int128(T v) : bits_(v) {}  // NOLINT: implicit, like the built-in conversion
  explicit constexpr Int128(UInt128 bits) : bits_(bits) {}
  constexpr UInt128 bits() const { return bits_; }
  constexpr bool negative() const { return (bits_.hi() >> 63) != 0; }

  template <std::integral T>
  explicit constexpr operator T() const { return static_cast<T>(bits_); }

  friend constexpr Int128 operator+(Int128 a, Int128 b) { return Int128(a.bits_ + b.bits_); }
  friend constexpr Int128 operator-(Int128 a, Int128 b) { return Int128(a.bits_ - b.bits_); }
  friend constexpr Int128 operator-(Int128 a) { return Int128(-a.bits_); }
  friend constexpr Int128 operator~(Int128 a) { return Int128(~a.bits_); }
  friend constexpr Int128 operator*(Int128 a, Int128 b) { return Int128(a.bits_ * b.bits_); }
  friend constexpr Int128 operator&(Int128 a, Int128 b) { return Int128(a.bits_ & b.bits_); }
  friend constexpr Int128 operator|(Int128 a, Int128 b) { return Int128(a.bits_ | b.bits_); }
  friend constexpr Int128 operator^(Int128 a, Int128 b) { return Int128(a.bits_ ^ b.bits_); }
  // gcc defines << on negative values as the bit shift (C++20 does too).
  friend constexpr Int128 operator<<(Int128 a, int s) { return Int128(a.bits_ << s); }
  // Arithmetic: the vacated high bits copy the sign.
  friend constexpr Int128 operator>>(Int128 a, int s) {
    if (s == 0) return a;
    const auto hi = static_cast<std::int64_t>(a.bits_.hi());
    const std::uint64_t lo = a.bits_.lo();
    if (s >= 64)
      return Int128(UInt128::from_words(static_cast<std::uint64_t>(hi >> 63), static_cast<std::uint64_t>(hi >> (s - 64))));
    return Int128(UInt128::from_words(static_cast<std::uint64_t>(hi >> s), (lo >> s) | (static_cast<std::uint64_t>(hi) << (64 - s))));
  }
  friend constexpr bool operator==(Int128 a, Int128 b) { return a.bits_ == b.bits_; }
  friend constexpr std::strong_ordering operator<=>(Int128 a, Int128 b) {
    const auto ahi = static_cast<std::int64_t>(a.bits_.hi()), bhi = static_cast<std::int64_t>(b.bits_.hi());
    return ahi != bhi ? ahi <=> bhi : a.bits_.lo() <=> b.bits_.lo();
  }

  constexpr Int128& operator+=(Int128 b) { return *this = *this + b; }
  constexpr Int128& operator-=(Int128 b) { return *this = *this - b; }
  constexpr Int128& operator*=(Int128 b) { return *this = *this * b; }
  constexpr Int128& operator<<=(int s) { return *this = *this << s; }
  constexpr Int128& operator>>=(int s) { return *this = *this >> s; }

 private:
  UInt128 bits_;
};

constexpr UInt128::UInt128(const Int128& v) : UInt128(v.bits()) {}

static_assert(sizeof(UInt128) == 16 && sizeof(Int128) == 16);

// Signed overflow of a + b and a - b, as __builtin_add_overflow and
// __builtin_sub_overflow report it: the wrapped result is stored in r; the
// true sum overflows exactly when both operands have one sign and the wrapped
// result the other (for a - b: a and -b have one sign).
constexpr bool add_overflows(Int128 a, Int128 b, Int128& r) {
  r = a + b;
  return a.negative() == b.negative() && r.negative() != a.negative();
}
constexpr bool sub_overflows(Int128 a, Int128 b, Int128& r) {
  r = a - b;
  return a.negative() != b.negative() && r.negative() != a.negative();
}

// floor((hi:lo) / d) with the remainder in rem, for hi < d (the quotient fits
// in 64 bits). Knuth's algorithm D with 32-bit digits (Hacker's Delight,
// divlu): normalise d so its top bit is set, then two quotient digits, each
// estimated from the top two dividend digits by one 64/32 division and
// corrected at most twice by the test on the divisor's low digit.
constexpr std::uint64_t div_128_64(std::uint64_t hi, std::uint64_t lo, std::uint64_t d, std::uint64_t& rem) {
  constexpr std::uint64_t b = std::uint64_t{1} << 32;
  int s = 0;
  while ((d << s) >> 63 == 0) ++s;  // d != 0 since hi < d
  d <<= s;
  const std::uint64_t d1 = d >> 32, d0 = d & 0xFFFFFFFFu;
  // Dividend digits: (un64 : un1 : un0), un64 the top 64 bits after the shift.
  const std::uint64_t un64 = s == 0 ? hi : (hi << s) | (lo >> (64 - s));
  const std::uint64_t un10 = lo << s;
  const std::uint64_t un1 = un10 >> 32, un0 = un10 & 0xFFFFFFFFu;

  std::uint64_t q1 = un64 / d1, rhat = un64 - q1 * d1;
  while (q1 >= b || q1 * d0 > ((rhat << 32) | un1)) {
    --q1;
    rhat += d1;
    if (rhat >= b) break;
  }
  const std::uint64_t un21 = (un64 << 32) + un1 - q1 * d;  // modulo 2^64: exact, < d

  std::uint64_t q0 = un21 / d1;
  rhat = un21 - q0 * d1;
  while (q0 >= b || q0 * d0 > ((rhat << 32) | un0)) {
    --q0;
    rhat += d1;
    if (rhat >= b) break;
  }
  rem = ((un21 << 32) + un0 - q0 * d) >> s;
  return (q1 << 32) | q0;
}

}  // namespace collide2d::portable
