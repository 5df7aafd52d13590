// The two-word 128-bit integers (numeric/portable_int128.hpp, fixed mode's
// arithmetic on i686) against the compiler's __int128 on the same operands:
// every operation fixed.hpp uses, bit for bit. Exhaustive over a set of edge
// values (word boundaries, carries and borrows between the words, the sign
// bit, the extremes) and every shift count, then over a million random pairs
// from a fixed-seed generator. Only where __int128 exists (x86-64, aarch64,
// ppc64le): it is the reference.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "collide2d/numeric/portable_int128.hpp"

#if defined(__SIZEOF_INT128__)

namespace {

using collide2d::portable::Int128;
using collide2d::portable::UInt128;
__extension__ using NU = unsigned __int128;
__extension__ using NS = __int128;

NU native(UInt128 v) { return (NU{v.hi()} << 64) | v.lo(); }
NS native(Int128 v) { return static_cast<NS>(native(v.bits())); }
UInt128 portable_u(NU v) { return UInt128::from_words(static_cast<std::uint64_t>(v >> 64), static_cast<std::uint64_t>(v)); }
Int128 portable_s(NS v) { return Int128(portable_u(static_cast<NU>(v))); }

struct SplitMix64 {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
};

// Word boundaries and their neighbours, with both signs: where carries,
// borrows, sign extension and overflow happen.
std::vector<NU> edge_values() {
  std::vector<NU> base;
  for (int k : {0, 1, 31, 32, 33, 62, 63, 64, 65, 95, 96, 126, 127}) {
    const NU p = NU{1} << k;
    base.push_back(p);
    base.push_back(p - 1);
    base.push_back(p + 1);
  }
  base.push_back(0);
  base.push_back(NU{0xFFFFFFFFFFFFFFFFull});                          // low word full: +1 carries
  base.push_back(NU{0xFFFFFFFFFFFFFFFFull} << 64);                    // high word full, low empty
  base.push_back((NU{0x8000000000000000ull} << 64) | 0xFFFFFFFFFFFFFFFFull);
  base.push_back((NU{0x0123456789ABCDEFull} << 64) | 0xFEDCBA9876543210ull);
  std::vector<NU> all = base;
  for (NU v : base) all.push_back(NU{0} - v);  // negations: -1, -2^127, ...
  return all;
}

// One pair through every binary operation, both ways.
void check_pair(NU a, NU b) {
  const UInt128 pa = portable_u(a), pb = portable_u(b);
  const NS sa = static_cast<NS>(a), sb = static_cast<NS>(b);
  const Int128 qa = portable_s(sa), qb = portable_s(sb);
  REQUIRE(native(pa + pb) == a + b);
  REQUIRE(native(pa - pb) == a - b);
  REQUIRE(native(pa * pb) == a * b);
  REQUIRE(native(pa & pb) == (a & b));
  REQUIRE(native(pa | pb) == (a | b));
  REQUIRE(native(pa ^ pb) == (a ^ b));
  REQUIRE((pa == pb) == (a == b));
  REQUIRE((pa < pb) == (a < b));
  REQUIRE((pa > pb) == (a > b));
  REQUIRE((pa <= pb) == (a <= b));
  REQUIRE((qa < qb) == (sa < sb));
  REQUIRE((qa > qb) == (sa > sb));
  REQUIRE((qa >= qb) == (sa >= sb));
  REQUIRE((qa == qb) == (sa == sb));
  REQUIRE(native(qa * qb) == static_cast<NS>(a * b));
  // Overflow detection as the built-ins report it, and the wrapped results.
  NS nr = 0;
  Int128 pr;
  REQUIRE(collide2d::portable::add_overflows(qa, qb, pr) == __builtin_add_overflow(sa, sb, &nr));
  REQUIRE(native(pr) == nr);
  REQUIRE(collide2d::portable::sub_overflows(qa, qb, pr) == __builtin_sub_overflow(sa, sb, &nr));
  REQUIRE(native(pr) == nr);
}

void check_one(NU a) {
  const UInt128 pa = portable_u(a);
  const NS sa = static_cast<NS>(a);
  const Int128 qa = portable_s(sa);
  REQUIRE(native(~pa) == ~a);
  REQUIRE(native(-pa) == NU{0} - a);
  REQUIRE(native(-qa) == static_cast<NS>(NU{0} - a));
  REQUIRE(native(~qa) == ~sa);
  for (int s = 0; s < 128; ++s) {
    REQUIRE(native(pa << s) == a << s);
    REQUIRE(native(pa >> s) == a >> s);
    REQUIRE(native(qa << s) == static_cast<NS>(a << s));
    REQUIRE(native(qa >> s) == sa >> s);  // arithmetic (gcc, and C++20)
  }
  REQUIRE(static_cast<std::uint64_t>(pa) == static_cast<std::uint64_t>(a));
  REQUIRE(static_cast<std::int64_t>(qa) == static_cast<std::int64_t>(sa));
  REQUIRE(static_cast<std::int32_t>(qa) == static_cast<std::int32_t>(sa));
  REQUIRE(static_cast<std::uint8_t>(pa) == static_cast<std::uint8_t>(a));
  REQUIRE(static_cast<bool>(pa) == (a != 0));
  REQUIRE(native(UInt128(qa)) == a);  // the signed <-> unsigned casts keep the bits
  REQUIRE(native(Int128(pa)) == sa);
  UInt128 inc = pa, dec = pa;
  REQUIRE(native(++inc) == a + 1);
  REQUIRE(native(--dec) == a - 1);
  // The bytes in memory are the built-in type's (hashes and checkpoints).
  unsigned char pb[16], nb[16];
  std::memcpy(pb, &qa, 16);
  std::memcpy(nb, &sa, 16);
  REQUIRE(std::memcmp(pb, nb, 16) == 0);
}

// floor((hi:lo) / d) for hi < d, against the 128-bit division.
void check_division(std::uint64_t hi, std::uint64_t lo, std::uint64_t d) {
  std::uint64_t rem = 0;
  const std::uint64_t q = collide2d::portable::div_128_64(hi, lo, d, rem);
  const NU n = (NU{hi} << 64) | lo;
  REQUIRE(q == static_cast<std::uint64_t>(n / d));
  REQUIRE(rem == static_cast<std::uint64_t>(n % d));
}

}  // namespace

TEST_CASE("portable 128-bit integers equal __int128 on every pair of edge values", "[numeric][int128]") {
  const std::vector<NU> edges = edge_values();
  for (NU a : edges) {
    check_one(a);
    for (NU b : edges) check_pair(a, b);
  }
}

TEST_CASE("portable 128-bit integers equal __int128 on random operands", "[numeric][int128]") {
  SplitMix64 g{20251125};
  for (int i = 0; i < 1000000; ++i) {
    // Mixed magnitudes: a random number of top bits cleared makes small
    // values, one-word values and full two-word values all common.
    NU a = (NU{g.next()} << 64) | g.next();
    NU b = (NU{g.next()} << 64) | g.next();
    a >>= g.next() % 128;
    b >>= g.next() % 128;
    if (g.next() & 1) a = NU{0} - a;
    if (g.next() & 1) b = NU{0} - b;
    check_pair(a, b);
    if (i % 64 == 0) check_one(a);
  }
}

TEST_CASE("conversions from built-in integers sign-extend like __int128", "[numeric][int128]") {
  REQUIRE(native(UInt128(-1)) == static_cast<NU>(-1));
  REQUIRE(native(Int128(-1)) == NS{-1});
  REQUIRE(native(Int128(std::numeric_limits<std::int64_t>::min())) == NS{std::numeric_limits<std::int64_t>::min()});
  REQUIRE(native(Int128(std::numeric_limits<std::uint64_t>::max())) == NS{std::numeric_limits<std::uint64_t>::max()});
  REQUIRE(native(UInt128(std::numeric_limits<std::int32_t>::min())) == static_cast<NU>(std::numeric_limits<std::int32_t>::min()));
  REQUIRE(native(Int128(std::numeric_limits<std::uint32_t>::max())) == NS{std::numeric_limits<std::uint32_t>::max()});
  REQUIRE(native(Int128(true)) == 1);
  REQUIRE(native(Int128(static_cast<signed char>(-128))) == -128);
}

TEST_CASE("portable 128 / 64 division equals the 128-bit division", "[numeric][int128]") {
  const std::uint64_t max = ~std::uint64_t{0};
  // Edge divisors: 1, powers of two (every normalising shift), all ones,
  // one top-half digit, and their neighbours; dividends at the extremes the
  // precondition hi < d allows, where the digit estimates need correcting.
  std::vector<std::uint64_t> divisors = {1, 2, 3, max, max - 1, 0xFFFFFFFFull, 0x100000000ull, 0x100000001ull,
                                         0x8000000000000000ull, 0x8000000000000001ull, 0x80000000FFFFFFFFull};
  for (int k = 0; k < 64; ++k) {
    divisors.push_back(std::uint64_t{1} << k);
    divisors.push_back((std::uint64_t{1} << k) | 1);
    divisors.push_back(max >> k);
  }
  for (std::uint64_t d : divisors) {
    for (std::uint64_t hi : std::vector<std::uint64_t>{0, d - 1, d / 2, (d - 1) >> 1}) {
      if (hi >= d) continue;  // outside the precondition: not a case
      for (std::uint64_t lo : std::vector<std::uint64_t>{0, 1, max, max - 1, 0xFFFFFFFFull, 0x100000000ull,
                                                         0x8000000000000000ull, d, d - 1})
        check_division(hi, lo, d);
    }
  }
  SplitMix64 g{64};
  for (int i = 0; i < 1000000; ++i) {
    const std::uint64_t d = g.next() >> (g.next() % 64);
    if (d == 0) continue;
    const std::uint64_t hi = g.next() % d;
    check_division(hi, g.next(), d);
  }
}

#endif  // __SIZEOF_INT128__
