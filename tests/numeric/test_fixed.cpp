// Tests for collide2d::Fixed (Q63.64) against an exact Boost.Multiprecision
// oracle. Operands come from a fixed-seed splitmix64, so every run (and every
// compiler) sees the same cases.
#include <catch2/catch.hpp>

#include <boost/multiprecision/cpp_int.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "collide2d/numeric/fixed.hpp"

namespace {

using collide2d::Fixed;
using collide2d::FixedPointOverflow;
using boost::multiprecision::cpp_int;
using Raw = Fixed::Raw;
using URaw = collide2d::fixed_detail::UInt128;  // unsigned __int128, or its two-word stand-in

// ---------------------------------------------------------------- helpers --

struct SplitMix64 {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // uniform in [lo, hi] (the tiny modulo bias is irrelevant here)
  int range(int lo, int hi) { return lo + static_cast<int>(next() % static_cast<std::uint64_t>(hi - lo + 1)); }
};

const cpp_int kTwo64 = cpp_int(1) << 64;
const cpp_int kTwo127 = cpp_int(1) << 127;

cpp_int to_big(Raw r) {
  const bool neg = r < 0;
  const URaw m = neg ? URaw{0} - static_cast<URaw>(r) : static_cast<URaw>(r);
  cpp_int v = cpp_int(static_cast<std::uint64_t>(m >> 64));
  v <<= 64;
  v += cpp_int(static_cast<std::uint64_t>(m));
  return neg ? cpp_int(-v) : v;
}

bool fits(const cpp_int& v) { return v >= -kTwo127 && v < kTwo127; }

Raw from_big(const cpp_int& v) {
  REQUIRE(fits(v));
  const cpp_int m = abs(v);
  const auto hi = static_cast<std::uint64_t>(m >> 64);
  const auto lo = static_cast<std::uint64_t>(m & cpp_int(~std::uint64_t{0}));
  const URaw u = (URaw{hi} << 64) | lo;
  return static_cast<Raw>(v < 0 ? URaw{0} - u : u);
}

// n / d rounded to nearest, ties away from zero (d != 0).
cpp_int div_round_away(const cpp_int& n, const cpp_int& d) {
  const cpp_int an = abs(n), ad = abs(d);
  cpp_int q = an / ad;
  const cpp_int r = an % ad;
  if (2 * r >= ad) ++q;
  return ((n < 0) != (d < 0)) ? cpp_int(-q) : q;
}

std::string hex(Raw r) {
  const URaw u = static_cast<URaw>(r);
  char buf[64];
  std::snprintf(buf, sizeof buf, "0x%016llx%016llx", static_cast<unsigned long long>(u >> 64),
                static_cast<unsigned long long>(u));
  return buf;
}

// A Fixed of magnitude in [2^e, 2^(e+1)) with e uniform in [emin, emax], random
// sign. A quarter of the values have many trailing zero bits (short
// mantissas: exact products/quotients and rounding ties become likely).
Fixed random_fixed(SplitMix64& g, int emin = -60, int emax = 62, bool allow_negative = true) {
  const int e = g.range(emin, emax);
  const int top = e + 64;  // bit index of the leading 1 of raw, 4..126
  URaw m = (URaw{g.next()} << 64) | g.next();
  m &= (URaw{1} << top) - 1;
  m |= URaw{1} << top;
  if (g.next() % 4 == 0) {
    const int keep = g.range(1, top + 1);  // significant bits kept
    m &= ~((URaw{1} << (top + 1 - keep)) - 1);
  }
  const bool neg = allow_negative && (g.next() & 1) != 0;
  return Fixed::from_raw(static_cast<Raw>(neg ? URaw{0} - m : m));
}

// Two operands drawn in a fixed order. (Function arguments are evaluated in
// an unspecified order: check(random_fixed(g), random_fixed(g)) would make gcc
// and clang test different pairs.)
std::pair<Fixed, Fixed> random_pair(SplitMix64& g, int emin1 = -60, int emax1 = 62, int emin2 = -60,
                                    int emax2 = 62) {
  const Fixed a = random_fixed(g, emin1, emax1);
  const Fixed b = random_fixed(g, emin2, emax2);
  return {a, b};
}

// Interesting fixed values used in addition to the random ones.
std::vector<Fixed> edge_values() {
  std::vector<Fixed> v = {Fixed(), Fixed::resolution(), -Fixed::resolution(), Fixed::max(),
                          Fixed::lowest(), Fixed(1), Fixed(-1), Fixed(2), Fixed(-3),
                          Fixed::from_raw(Raw{1} << 63), Fixed::from_raw(-(Raw{1} << 63)),
                          Fixed::from_raw(3), Fixed::from_raw(-(Raw{1} << 126)),
                          Fixed::from_raw(Raw{1} << 126), Fixed::max() - Fixed(1),
                          Fixed::lowest() + Fixed::resolution(),
                          Fixed::from_raw((Raw{1} << 64) - 1), Fixed::from_raw((Raw{1} << 64) + 1)};
  return v;
}

// d * 2^K as an exact integer (d must be a multiple of 2^-K).
cpp_int double_scaled(double d, int K) {
  const auto bits = std::bit_cast<std::uint64_t>(d);
  const int be = static_cast<int>((bits >> 52) & 0x7FF);
  std::uint64_t mant = bits & ((std::uint64_t{1} << 52) - 1);
  int e = -1074;
  if (be != 0) {
    mant |= std::uint64_t{1} << 52;
    e = be - 1075;
  }
  while (mant != 0 && (mant & 1) == 0 && e + K < 0) {  // drop trailing zero bits
    mant >>= 1;
    ++e;
  }
  REQUIRE(e + K >= 0);
  cpp_int v = cpp_int(mant) << (e + K);
  return (bits >> 63) ? cpp_int(-v) : v;
}

}  // namespace

// ------------------------------------------------------------------ tests --

TEST_CASE("Fixed: construction, constants and raw access", "[fixed]") {
  STATIC_REQUIRE(Fixed::fraction_bits == 64);
  STATIC_REQUIRE(Fixed().raw() == 0);
  STATIC_REQUIRE(Fixed(1).raw() == Raw{1} << 64);
  STATIC_REQUIRE(Fixed(-7).raw() == -(Raw{7} << 64));
  STATIC_REQUIRE(Fixed::resolution().raw() == 1);
  STATIC_REQUIRE(Fixed::from_raw(-5).raw() == -5);
  STATIC_REQUIRE(Fixed(2) + Fixed(3) == Fixed(5));
  STATIC_REQUIRE(Fixed(-4) * Fixed(3) == Fixed(-12));
  CHECK(to_big(Fixed::max().raw()) == kTwo127 - 1);
  CHECK(to_big(Fixed::lowest().raw()) == -kTwo127);
  CHECK(to_big(Fixed(std::numeric_limits<int>::max()).raw()) ==
        cpp_int(std::numeric_limits<int>::max()) * kTwo64);
  CHECK(to_big(Fixed(std::numeric_limits<int>::min()).raw()) ==
        cpp_int(std::numeric_limits<int>::min()) * kTwo64);
}

TEST_CASE("Fixed: comparisons order by value", "[fixed]") {
  STATIC_REQUIRE(Fixed(-1) < Fixed(0));
  STATIC_REQUIRE(Fixed::lowest() < Fixed::max());
  SplitMix64 g{11};
  for (int i = 0; i < 5000; ++i) {
    const Fixed a = random_fixed(g), b = random_fixed(g);
    const cpp_int x = to_big(a.raw()), y = to_big(b.raw());
    if ((a < b) != (x < y) || (a == b) != (x == y) || (a >= b) != (x >= y) ||
        (a != b) != (x != y) || (a > b) != (x > y) || (a <= b) != (x <= y))
      FAIL("comparison mismatch for " << hex(a.raw()) << " vs " << hex(b.raw()));
  }
  CHECK(Fixed(3) == Fixed(3));
  CHECK_FALSE(Fixed(3) != Fixed(3));
  CHECK((Fixed::from_raw(-1) <=> Fixed()) == std::strong_ordering::less);
}

TEST_CASE("Fixed: + and - are exact and report overflow", "[fixed]") {
  SplitMix64 g{1};
  int representable = 0, overflowed = 0;
  auto check = [&](Fixed a, Fixed b) {
    const cpp_int x = to_big(a.raw()), y = to_big(b.raw());
    for (int op = 0; op < 2; ++op) {
      const cpp_int exact = op == 0 ? cpp_int(x + y) : cpp_int(x - y);
      if (fits(exact)) {
        const Fixed got = op == 0 ? a + b : a - b;
        Fixed acc = a;
        if (op == 0) acc += b; else acc -= b;
        if (to_big(got.raw()) != exact || acc != got)
          FAIL("op " << op << " wrong for " << hex(a.raw()) << ", " << hex(b.raw()));
        ++representable;
      } else {
        if (op == 0) { REQUIRE_THROWS_AS(a + b, FixedPointOverflow); }
        else { REQUIRE_THROWS_AS(a - b, FixedPointOverflow); }
        ++overflowed;
      }
    }
  };
  for (int i = 0; i < 20000; ++i) { const auto [a, b] = random_pair(g); check(a, b); }
  for (Fixed a : edge_values())
    for (Fixed b : edge_values()) check(a, b);
  CHECK(representable > 20000);
  CHECK(overflowed > 0);
}

TEST_CASE("Fixed: multiplication is correctly rounded (ties away from zero)", "[fixed]") {
  SplitMix64 g{2};
  int exact_count = 0, overflowed = 0, ties = 0;
  auto check = [&](Fixed a, Fixed b) {
    const cpp_int product = to_big(a.raw()) * to_big(b.raw());  // value * 2^128
    const cpp_int expected = div_round_away(product, kTwo64);
    if (!fits(expected)) {
      REQUIRE_THROWS_AS(a * b, FixedPointOverflow);
      ++overflowed;
      return;
    }
    const Fixed got = a * b;
    const cpp_int err = abs(to_big(got.raw()) * kTwo64 - product);  // in units of 2^-128
    if (to_big(got.raw()) != expected || err > kTwo64 / 2 || (b * a) != got)
      FAIL("mul wrong: " << hex(a.raw()) << " * " << hex(b.raw()) << " = " << hex(got.raw())
                         << ", expected " << hex(from_big(expected)));
    if (err == kTwo64 / 2) ++ties;
    Fixed acc = a;
    acc *= b;
    if (acc != got) FAIL("*= differs from *");
    ++exact_count;
  };
  for (int i = 0; i < 60000; ++i) { const auto [a, b] = random_pair(g); check(a, b); }
  // Small by small (result underflows to 0 or a few ulps) and mid-range pairs.
  for (int i = 0; i < 5000; ++i) { const auto [a, b] = random_pair(g, -60, -20, -60, -20); check(a, b); }
  for (int i = 0; i < 5000; ++i) { const auto [a, b] = random_pair(g, -10, 30, -10, 30); check(a, b); }
  // One factor below 1 (one 64-bit word), the other above: the product's
  // short paths (two partial products, or one) against the oracle.
  for (int i = 0; i < 5000; ++i) { const auto [a, b] = random_pair(g, -60, -1, 0, 40); check(a, b); }
  for (int i = 0; i < 5000; ++i) { const auto [a, b] = random_pair(g, -60, -1, -60, -1); check(a, b); }
  for (Fixed a : edge_values())
    for (Fixed b : edge_values()) check(a, b);
  CHECK(exact_count > 20000);
  CHECK(overflowed > 1000);
  CHECK(ties > 10);
}

TEST_CASE("Fixed: multiplication edge cases", "[fixed]") {
  const Fixed r = Fixed::resolution();
  const Fixed half_one = Fixed::from_raw(Raw{1} << 63);  // 0.5
  CHECK((r * half_one).raw() == 1);                       // 0.5 ulp tie -> away from 0
  CHECK((-r * half_one).raw() == -1);
  CHECK((r * Fixed::from_raw((Raw{1} << 63) - 1)).raw() == 0);  // just below the tie
  CHECK((r * r).raw() == 0);
  CHECK(Fixed::max() * Fixed(1) == Fixed::max());
  CHECK(Fixed::lowest() * Fixed(1) == Fixed::lowest());
  CHECK(Fixed::max() * Fixed(-1) == Fixed::lowest() + r);
  CHECK(Fixed(-3) * Fixed(-5) == Fixed(15));
  CHECK(Fixed::from_double(1.5) * Fixed::from_double(-2.25) == Fixed::from_double(-3.375));
}

TEST_CASE("Fixed: division is correctly rounded (ties away from zero)", "[fixed]") {
  SplitMix64 g{3};
  int exact_count = 0, overflowed = 0, short_divisor = 0;
  auto check = [&](Fixed a, Fixed b) {
    if (b == Fixed()) return;
    const cpp_int num = to_big(a.raw()) * kTwo64, den = to_big(b.raw());
    const cpp_int expected = div_round_away(num, den);
    if (!fits(expected)) {
      REQUIRE_THROWS_AS(a / b, FixedPointOverflow);
      ++overflowed;
      return;
    }
    const Fixed got = a / b;
    // |got - exact| <= 1/2 ulp  <=>  |got*den - num| * 2 <= |den|
    const cpp_int err2 = 2 * abs(to_big(got.raw()) * den - num);
    if (to_big(got.raw()) != expected || err2 > abs(den))
      FAIL("div wrong: " << hex(a.raw()) << " / " << hex(b.raw()) << " = " << hex(got.raw())
                         << ", expected " << hex(from_big(expected)));
    Fixed acc = a;
    acc /= b;
    if (acc != got) FAIL("/= differs from /");
    if (abs(den) < kTwo64) ++short_divisor;
    ++exact_count;
  };
  for (int i = 0; i < 60000; ++i) { const auto [a, b] = random_pair(g); check(a, b); }
  for (int i = 0; i < 5000; ++i) { const auto [a, b] = random_pair(g, -60, 62, -60, -1); check(a, b); }  // short divisors
  for (int i = 0; i < 5000; ++i) { const auto [a, b] = random_pair(g, -20, 20, -20, 20); check(a, b); }
  for (Fixed a : edge_values())
    for (Fixed b : edge_values()) check(a, b);
  CHECK(exact_count > 20000);
  CHECK(short_divisor > 3000);
  CHECK(overflowed > 1000);
}

TEST_CASE("Fixed: division edge cases", "[fixed]") {
  const Fixed r = Fixed::resolution();
  CHECK_THROWS_AS(Fixed(1) / Fixed(), std::domain_error);
  CHECK_THROWS_AS(Fixed() / Fixed(), std::domain_error);
  CHECK((r / Fixed(2)).raw() == 1);   // 0.5 ulp tie -> away from zero
  CHECK((-r / Fixed(2)).raw() == -1);
  CHECK((r / Fixed(-2)).raw() == -1);
  CHECK((Fixed::from_raw(3) / Fixed(2)).raw() == 2);
  CHECK((r / Fixed(3)).raw() == 0);
  CHECK((Fixed::from_raw(2) / Fixed(3)).raw() == 1);
  CHECK(Fixed(1) / Fixed(3) == Fixed::from_raw(Raw{0x5555555555555555}));
  CHECK(Fixed(-2) / Fixed(3) == Fixed::from_raw(-Raw{0xAAAAAAAAAAAAAAABull}));  // .666 rounds up
  CHECK(Fixed::lowest() / Fixed(1) == Fixed::lowest());
  CHECK(Fixed::lowest() / Fixed(-2) == Fixed::from_raw(Raw{1} << 126));
  CHECK(Fixed::max() / Fixed::max() == Fixed(1));
  CHECK(Fixed::lowest() / Fixed::lowest() == Fixed(1));
  CHECK(Fixed() / Fixed::lowest() == Fixed());
  CHECK_THROWS_AS(Fixed::lowest() / Fixed(-1), FixedPointOverflow);
  CHECK_THROWS_AS(Fixed::max() / r, FixedPointOverflow);
  CHECK_THROWS_AS(Fixed(1) / r, FixedPointOverflow);  // 2^64 > max
  CHECK_THROWS_AS(Fixed::max() / Fixed::from_raw((Raw{1} << 64) - 1), FixedPointOverflow);
  CHECK(Fixed(-1) / Fixed::from_raw((Raw{1} << 64) * 4) == Fixed::from_raw(-(Raw{1} << 62)));
}

TEST_CASE("Fixed: sqrt is correctly rounded", "[fixed]") {
  SplitMix64 g{4};
  int count = 0;
  auto check = [&](Fixed a) {
    const cpp_int n = to_big(a.raw()) * kTwo64;  // sqrt(value) * 2^64 = sqrt(n)
    const cpp_int s = boost::multiprecision::sqrt(n);
    REQUIRE(s * s <= n);  // the oracle itself
    REQUIRE((s + 1) * (s + 1) > n);
    const cpp_int expected = (n - s * s > s) ? cpp_int(s + 1) : s;  // no ties possible
    const Fixed got = sqrt(a);
    const cpp_int g2 = to_big(got.raw());
    // |g - sqrt(n)| <= 1/2  <=>  (g - 1/2)^2 <= n <= (g + 1/2)^2  <=>  4g^2-4g+1 <= 4n <= 4g^2+4g+1
    if (g2 != expected || (g2 > 0 && 4 * g2 * g2 - 4 * g2 + 1 > 4 * n) ||
        4 * n > 4 * g2 * g2 + 4 * g2 + 1)
      FAIL("sqrt wrong: sqrt(" << hex(a.raw()) << ") = " << hex(got.raw()) << ", expected "
                               << hex(from_big(expected)));
    ++count;
  };
  for (int i = 0; i < 60000; ++i) check(random_fixed(g, -64, 62, false));
  // Every power of two (both exponent parities) and its neighbours.
  for (int k = 0; k < 127; ++k) {
    const Raw p = Raw{1} << k;
    check(Fixed::from_raw(p));
    check(Fixed::from_raw(p + 1));
    if (k > 0) check(Fixed::from_raw(p - 1));
  }
  // Exact squares of raw roots and their neighbours: s^2 * 2^-64 is the
  // square of s * 2^-64 when s is a multiple of 2^32.
  for (int i = 0; i < 3000; ++i) {
    const URaw root = URaw{g.next() >> g.range(1, 63)} << 32;  // < 2^96
    const cpp_int sq = (cpp_int(static_cast<std::uint64_t>(root >> 32)) << 32);
    const cpp_int raw_sq = sq * sq / kTwo64;
    if (!fits(raw_sq)) continue;
    const Raw rs = from_big(raw_sq);
    CHECK(sqrt(Fixed::from_raw(rs)).raw() == static_cast<Raw>(root));
    check(Fixed::from_raw(rs));
    if (rs > 0) check(Fixed::from_raw(rs - 1));
    if (rs < Fixed::max().raw()) check(Fixed::from_raw(rs + 1));
  }
  check(Fixed::max());
  check(Fixed());
  CHECK(count > 33000);
  CHECK(sqrt(Fixed(4)) == Fixed(2));
  CHECK(sqrt(Fixed(1)) == Fixed(1));
  CHECK(sqrt(Fixed()) == Fixed());
  CHECK(sqrt(Fixed::resolution()).raw() == Raw{1} << 32);  // sqrt(2^-64) = 2^-32
  CHECK(sqrt(Fixed::from_raw(Raw{1} << 126)) == Fixed::from_raw(Raw{1} << 95));  // sqrt(2^62) = 2^31
  CHECK_THROWS_AS(sqrt(-Fixed::resolution()), std::domain_error);
  CHECK_THROWS_AS(sqrt(Fixed::lowest()), std::domain_error);
}

TEST_CASE("Fixed: overflow is reported with the operation name, never wraps", "[fixed]") {
  const Fixed two62 = Fixed::from_double(0x1p62);
  const Fixed r = Fixed::resolution();
  CHECK_THROWS_AS(two62 * Fixed(4), FixedPointOverflow);
  CHECK_THROWS_AS(two62 * Fixed(-4), FixedPointOverflow);  // -2^64 < lowest
  CHECK(two62 * Fixed(-2) == Fixed::lowest());             // exactly -2^63: fits
  CHECK_THROWS_AS(two62 * Fixed(2), FixedPointOverflow);   // +2^63: does not
  CHECK_THROWS_AS(Fixed::max() + r, FixedPointOverflow);
  CHECK_THROWS_AS(Fixed::lowest() - r, FixedPointOverflow);
  CHECK_THROWS_AS(-Fixed::lowest(), FixedPointOverflow);
  CHECK_THROWS_AS(abs(Fixed::lowest()), FixedPointOverflow);
  CHECK_THROWS_AS(Fixed::lowest() * Fixed(-1), FixedPointOverflow);
  CHECK_THROWS_AS(Fixed::max() * Fixed::max(), FixedPointOverflow);
  CHECK_THROWS_AS(Fixed::lowest() * Fixed::lowest(), FixedPointOverflow);
  // Products whose 256-bit value exceeds 2^192 (would wrap in 128 bits).
  CHECK_THROWS_AS(Fixed::from_raw(Raw{1} << 100) * Fixed::from_raw(Raw{1} << 100), FixedPointOverflow);
  CHECK_THROWS_AS(Fixed::max() * Fixed::from_raw((Raw{1} << 64) + 1), FixedPointOverflow);
  // Only the rounding overflows: the exact product is 2^63 - 2^-65 (half an
  // ulp above max()), which rounds away from zero to 2^63. Negated, the same
  // rounding lands exactly on lowest().
  const Fixed almost = Fixed::from_raw(static_cast<Raw>(~std::uint64_t{0}) << 63);
  const Fixed one_plus = Fixed::from_raw((Raw{1} << 64) + 1);
  CHECK_THROWS_AS(almost * one_plus, FixedPointOverflow);
  CHECK(-almost * one_plus == Fixed::lowest());
  CHECK(almost * Fixed::from_raw(Raw{1} << 64) == almost);
  CHECK_THROWS_AS(Fixed::from_double(1e19), FixedPointOverflow);
  CHECK_THROWS_AS(Fixed::from_double(-1e19), FixedPointOverflow);
  CHECK_THROWS_AS(Fixed::from_double(std::numeric_limits<double>::quiet_NaN()), FixedPointOverflow);
  CHECK_THROWS_AS(Fixed::from_double(std::numeric_limits<double>::infinity()), FixedPointOverflow);
  CHECK_THROWS_AS(Fixed::from_double(-std::numeric_limits<double>::infinity()), FixedPointOverflow);
  CHECK_THROWS_AS(Fixed::from_double(0x1p63), FixedPointOverflow);
  CHECK_THROWS_AS(Fixed::from_double(-0x1p63), FixedPointOverflow);
  CHECK_THROWS_AS(Fixed::from_double(std::numeric_limits<double>::max()), FixedPointOverflow);
  Fixed acc = Fixed::max();
  CHECK_THROWS_AS(acc += r, FixedPointOverflow);
  CHECK(acc == Fixed::max());  // unchanged after the failed operation
  CHECK_THROWS_AS(acc *= Fixed(2), FixedPointOverflow);
  CHECK(acc == Fixed::max());

  CHECK_THROWS_WITH(two62 * Fixed(4), Catch::Contains("multiplication"));
  CHECK_THROWS_WITH(Fixed::max() + r, Catch::Contains("addition"));
  CHECK_THROWS_WITH(Fixed::lowest() - r, Catch::Contains("subtraction"));
  CHECK_THROWS_WITH(Fixed::max() / r, Catch::Contains("division"));
  CHECK_THROWS_WITH(-Fixed::lowest(), Catch::Contains("negation"));
  CHECK_THROWS_WITH(Fixed::from_double(1e19), Catch::Contains("double"));
  // FixedPointOverflow is a std::overflow_error.
  CHECK_THROWS_AS(two62 * Fixed(4), std::overflow_error);
}

TEST_CASE("Fixed: from_double is exact on multiples of 2^-64 and round-trips", "[fixed]") {
  SplitMix64 g{5};
  for (int i = 0; i < 20000; ++i) {
    const int nb = g.range(1, 53);                    // significant bits
    std::uint64_t mant = g.next() >> (64 - nb);
    mant |= std::uint64_t{1} << (nb - 1);
    const int e = g.range(-64, 63 - nb);              // lsb >= 2^-64, |d| < 2^63
    const bool neg = (g.next() & 1) != 0;
    const double d = std::ldexp(neg ? -static_cast<double>(mant) : static_cast<double>(mant), e);
    const Fixed f = Fixed::from_double(d);
    const cpp_int expected = double_scaled(d, 64);
    if (to_big(f.raw()) != expected) FAIL("from_double(" << d << ") not exact");
    if (std::bit_cast<std::uint64_t>(f.to_double()) != std::bit_cast<std::uint64_t>(d))
      FAIL("round trip failed for " << d);
  }
  CHECK(Fixed::from_double(0.0) == Fixed());
  CHECK(Fixed::from_double(-0.0) == Fixed());
  CHECK(Fixed().to_double() == 0.0);
  CHECK_FALSE(std::signbit(Fixed().to_double()));
  CHECK(Fixed::from_double(-0.5).raw() == -(Raw{1} << 63));
  CHECK(Fixed::from_double(-1.0) == Fixed(-1));
  CHECK(Fixed::from_double(-0x1p-64).raw() == -1);
  CHECK(Fixed::from_double(0x1p-64).to_double() == 0x1p-64);
  CHECK(Fixed::from_double(-0.25).to_double() == -0.25);
  CHECK(Fixed::from_double(-3.75).to_double() == -3.75);
  CHECK(Fixed::from_double(123456789.125) == Fixed(123456789) + Fixed::from_raw(Raw{1} << 61));
  const double below = std::nextafter(0x1p63, 0.0);  // 2^63 - 1024
  CHECK(Fixed::from_double(below).to_double() == below);
  CHECK(Fixed::from_double(-below).to_double() == -below);
  CHECK(Fixed(std::numeric_limits<int>::min()).to_double() == -2147483648.0);
  CHECK(Fixed::max().to_double() == 0x1p63);        // nearest double to 2^63 - 2^-64
  CHECK(Fixed::lowest().to_double() == -0x1p63);
  CHECK(Fixed::resolution().to_double() == 0x1p-64);
}

TEST_CASE("Fixed: from_double rounds to nearest, ties away from zero", "[fixed]") {
  CHECK(Fixed::from_double(0x1p-65).raw() == 1);     // exactly half an ulp
  CHECK(Fixed::from_double(-0x1p-65).raw() == -1);
  CHECK(Fixed::from_double(0x1.8p-65).raw() == 1);   // 0.75 ulp
  CHECK(Fixed::from_double(0x1.fffffffffffffp-66).raw() == 0);  // just under half
  CHECK(Fixed::from_double(0x1p-66).raw() == 0);
  CHECK(Fixed::from_double(0x1.8p-64).raw() == 2);   // 1.5 ulp -> 2
  CHECK(Fixed::from_double(-0x1.8p-64).raw() == -2);
  CHECK(Fixed::from_double(0x1.4p-64).raw() == 1);   // 1.25 ulp -> 1
  CHECK(Fixed::from_double(std::numeric_limits<double>::denorm_min()).raw() == 0);
  CHECK(Fixed::from_double(-std::numeric_limits<double>::min()).raw() == 0);
  SplitMix64 g{6};
  for (int i = 0; i < 20000; ++i) {
    std::uint64_t mant = (g.next() >> 11) | (std::uint64_t{1} << 52);
    const int e = g.range(-64 - 60, -65);  // lsb below 2^-64: rounding needed
    const bool neg = (g.next() & 1) != 0;
    const double d = std::ldexp(neg ? -static_cast<double>(mant) : static_cast<double>(mant), e);
    const cpp_int expected = div_round_away(double_scaled(d, 200), cpp_int(1) << 136);
    const Fixed f = Fixed::from_double(d);
    if (to_big(f.raw()) != expected) FAIL("from_double(" << d << ") rounding wrong");
  }
}

TEST_CASE("Fixed: to_double returns the nearest double (ties to even)", "[fixed]") {
  CHECK(Fixed::from_raw((Raw{1} << 53) + 1).to_double() == 0x1p-11);  // tie -> even (down)
  CHECK(Fixed::from_raw((Raw{1} << 53) + 3).to_double() == 0x1.0000000000002p-11);  // tie -> even (up)
  CHECK(Fixed::from_raw(-((Raw{1} << 53) + 3)).to_double() == -0x1.0000000000002p-11);
  CHECK(Fixed::from_raw((Raw{1} << 54) + 3).to_double() == 0x1.0000000000001p-10);  // above tie
  SplitMix64 g{7};
  std::vector<Fixed> values;
  for (int i = 0; i < 20000; ++i) values.push_back(random_fixed(g, -64, 62));
  for (Fixed e : edge_values()) values.push_back(e);
  int checked = 0;
  for (Fixed f : values) {
    if (f == Fixed()) continue;
    const double d = f.to_double();
    const cpp_int target = to_big(f.raw()) * (cpp_int(1) << 128);  // value * 2^192
    const cpp_int err = abs(double_scaled(d, 192) - target);
    const cpp_int err_up = abs(double_scaled(std::nextafter(d, HUGE_VAL), 192) - target);
    const cpp_int err_down = abs(double_scaled(std::nextafter(d, -HUGE_VAL), 192) - target);
    const bool even = (std::bit_cast<std::uint64_t>(d) & 1) == 0;
    if (err > err_up || err > err_down || ((err == err_up || err == err_down) && !even))
      FAIL("to_double not nearest for raw " << hex(f.raw()));
    ++checked;
  }
  CHECK(checked > 20000);
}

TEST_CASE("Fixed: abs, unary minus and half", "[fixed]") {
  STATIC_REQUIRE(Fixed::from_raw(3).half().raw() == 2);    // 1.5 ulp tie -> away from 0
  STATIC_REQUIRE(Fixed::from_raw(-3).half().raw() == -2);
  STATIC_REQUIRE(Fixed::from_raw(1).half().raw() == 1);
  STATIC_REQUIRE(Fixed::from_raw(-1).half().raw() == -1);
  STATIC_REQUIRE(Fixed(3).half() == Fixed::from_double(1.5));
  CHECK(Fixed::lowest().half().raw() == -(Raw{1} << 126));
  CHECK(Fixed::max().half().raw() == Raw{1} << 126);  // (2^127 - 1) / 2 rounded away
  CHECK(abs(Fixed(-5)) == Fixed(5));
  CHECK(abs(Fixed::max()) == Fixed::max());
  CHECK(-Fixed::max() == Fixed::lowest() + Fixed::resolution());
  SplitMix64 g{8};
  for (int i = 0; i < 10000; ++i) {
    const Fixed a = random_fixed(g, -64, 62);
    const cpp_int x = to_big(a.raw());
    if (to_big((-a).raw()) != -x || to_big(abs(a).raw()) != abs(x) ||
        to_big(a.half().raw()) != div_round_away(x, 2))
      FAIL("abs/neg/half wrong for " << hex(a.raw()));
  }
  CHECK(+Fixed(3) == Fixed(3));
}

TEST_CASE("Fixed: a small time-of-impact style expression is reproducible", "[fixed]") {
  // Solve t^2 * a - 2 b t + c = 0 for the smaller root with fixed-point ops
  // and compare with the exactly rounded step-by-step oracle: every step is
  // correctly rounded, so the whole chain is bit-for-bit determined.
  const Fixed a = Fixed::from_double(2.5), b = Fixed::from_double(3.25), c = Fixed::from_double(1.0625);
  const Fixed disc = b * b - a * c;            // 10.5625 - 2.65625 = 7.90625 (exact)
  CHECK(disc == Fixed::from_double(7.90625));
  const Fixed root = sqrt(disc);
  const Fixed t = (b - root) / a;
  // Oracle for the last two steps.
  const cpp_int n = to_big(disc.raw()) * kTwo64;
  cpp_int s = boost::multiprecision::sqrt(n);
  if (n - s * s > s) ++s;
  CHECK(to_big(root.raw()) == s);
  CHECK(to_big(t.raw()) == div_round_away((to_big(b.raw()) - s) * kTwo64, to_big(a.raw())));
  CHECK(std::abs(t.to_double() - (3.25 - std::sqrt(7.90625)) / 2.5) < 1e-15);
}
