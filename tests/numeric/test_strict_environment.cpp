// Strict mode refuses an environment that flushes subnormals to zero or does
// not round to nearest, read from the control register of each architecture
// (MXCSR on x86, FPCR on aarch64, FPSCR on POWER) and from the arithmetic.
#include <catch2/catch.hpp>

#include <cfenv>
#include <cfloat>
#include <string>

#include "collide2d/numeric/fp_control_register.hpp"
#include "collide2d/numeric/strict_environment.hpp"

#if defined(__x86_64__) || defined(__SSE2__)
#include <xmmintrin.h>
#endif

using collide2d::fp_control_flush_bit;
using collide2d::read_fp_control;
using collide2d::strict_environment_problem;
using collide2d::write_fp_control_raw;

namespace {
bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }
volatile double smallest_normal = DBL_MIN;
}  // namespace

TEST_CASE("the test environment is strict", "[numeric][strict]") {
  CHECK(strict_environment_problem().empty());
}

#if defined(__x86_64__) || defined(__SSE2__)
TEST_CASE("flush-to-zero is detected and refused", "[numeric][strict]") {
  const unsigned saved = _mm_getcsr();
  _mm_setcsr(saved | 0x8000u);  // FTZ
  const std::string ftz = strict_environment_problem();
  _mm_setcsr(saved | 0x0040u);  // DAZ
  const std::string daz = strict_environment_problem();
  _mm_setcsr(saved);
  CHECK(ftz.find("flushed to zero") != std::string::npos);
  CHECK(daz.find("read as zero") != std::string::npos);
  CHECK(strict_environment_problem().empty());
}
#endif

#if defined(__x86_64__) || defined(__SSE2__) || defined(__aarch64__) || defined(__powerpc64__)
TEST_CASE("the control register is read: MXCSR, FPCR or FPSCR", "[numeric][strict]") {
  const collide2d::FpControlState now = read_fp_control();
  REQUIRE(now.register_name != nullptr);
#if defined(__aarch64__)
  CHECK(std::string(now.register_name) == "FPCR");
#elif defined(__powerpc64__)
  CHECK(std::string(now.register_name) == "FPSCR");
#else
  CHECK(std::string(now.register_name) == "MXCSR");
#endif
  CHECK(now.round_to_nearest);
  CHECK_FALSE(now.flush_to_zero);
  CHECK_FALSE(now.denormals_are_zero);
}

TEST_CASE("the flush bit of the control register is refused by name", "[numeric][strict]") {
  const collide2d::FpControlState before = read_fp_control();
  REQUIRE(fp_control_flush_bit() != 0);
  write_fp_control_raw(before.raw | fp_control_flush_bit());
  const collide2d::FpControlState during = read_fp_control();
  const std::string problem = strict_environment_problem();
#if !defined(__powerpc64__)
  // What the bit does (POWER leaves flushing under NI to the implementation).
  const double halved = smallest_normal / 2;
#endif
  write_fp_control_raw(before.raw);
  CHECK(during.flush_to_zero);
  CHECK(contains(problem, "flushed to zero"));
  CHECK(contains(problem, before.register_name));
#if !defined(__powerpc64__)
  CHECK(halved == 0.0);
#endif
  CHECK(strict_environment_problem().empty());
}

TEST_CASE("a rounding mode other than nearest is refused by name", "[numeric][strict]") {
  const char* name = read_fp_control().register_name;
  for (int mode : {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
    REQUIRE(std::fesetround(mode) == 0);
    const collide2d::FpControlState during = read_fp_control();
    const std::string problem = strict_environment_problem();
    std::fesetround(FE_TONEAREST);
    CHECK_FALSE(during.round_to_nearest);
    CHECK(contains(problem, "round-to-nearest"));
    CHECK(contains(problem, name));
  }
  CHECK(strict_environment_problem().empty());
}
#endif
