// Strict mode refuses an environment that flushes subnormals to zero.
#include <catch2/catch.hpp>

#include "collide2d/numeric/strict_environment.hpp"

#if defined(__x86_64__) || defined(__SSE2__)
#include <xmmintrin.h>
#endif

TEST_CASE("the test environment is strict", "[numeric][strict]") {
  CHECK(collide2d::strict_environment_problem().empty());
}

#if defined(__x86_64__) || defined(__SSE2__)
TEST_CASE("flush-to-zero is detected and refused", "[numeric][strict]") {
  const unsigned saved = _mm_getcsr();
  _mm_setcsr(saved | 0x8000u);  // FTZ
  const std::string ftz = collide2d::strict_environment_problem();
  _mm_setcsr(saved | 0x0040u);  // DAZ
  const std::string daz = collide2d::strict_environment_problem();
  _mm_setcsr(saved);
  CHECK(ftz.find("flushed to zero") != std::string::npos);
  CHECK(daz.find("read as zero") != std::string::npos);
  CHECK(collide2d::strict_environment_problem().empty());
}
#endif
