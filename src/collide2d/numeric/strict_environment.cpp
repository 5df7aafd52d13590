#include "collide2d/numeric/strict_environment.hpp"

#include <cfenv>
#include <cfloat>
#include <cstdint>
#include <cstring>
#include <cstdio>

#include "collide2d/numeric/fp_control_register.hpp"

// x87 extended precision would round intermediates differently from SSE2.
static_assert(FLT_EVAL_METHOD == 0, "strict mode needs double evaluated as double (no x87)");
#if defined(__FAST_MATH__)
#error "collide2d must not be compiled with -ffast-math: strict mode promises IEEE semantics"
#endif
#if defined(__FINITE_MATH_ONLY__) && __FINITE_MATH_ONLY__
#error "collide2d must not be compiled with -ffinite-math-only"
#endif

namespace collide2d {
namespace {

// Values read through volatile so the compiler cannot fold the checks away.
volatile double smallest_normal = DBL_MIN;
volatile double two = 2.0;
volatile double a_factor = 1.0 + 0x1p-30;  // a*a = 1 + 2^-29 + 2^-60 exactly
volatile double minus_square_rounded = -(1.0 + 0x1p-29);

}  // namespace

namespace {

std::string register_says(const FpControlState& s) {
  char buf[64];
  std::snprintf(buf, sizeof buf, " (%s = 0x%llx)", s.register_name, static_cast<unsigned long long>(s.raw));
  return buf;
}

}  // namespace

std::string strict_environment_problem() {
  // The control register first (MXCSR, FPCR or FPSCR): names the bit at fault.
  if (const FpControlState reg = read_fp_control(); reg.register_name != nullptr) {
    if (!reg.round_to_nearest) return "the rounding mode is not round-to-nearest" + register_says(reg);
    if (reg.flush_to_zero) return "subnormal results are flushed to zero (FTZ is on)" + register_says(reg);
    if (reg.denormals_are_zero) return "subnormal operands are read as zero (DAZ is on)" + register_says(reg);
  }
  // Then the arithmetic itself, on every architecture: what the bits promise.
  if (std::fegetround() != FE_TONEAREST) return "the rounding mode is not round-to-nearest";
  // Flush-to-zero: the halved smallest normal is a subnormal, never zero.
  // Its bits tell FTZ apart from DAZ, under which a comparison would read a
  // subnormal operand as zero too.
  const double subnormal = smallest_normal / two;
  std::uint64_t bits = 0;
  std::memcpy(&bits, &subnormal, sizeof bits);
  if (bits == 0) return "subnormal results are flushed to zero (FTZ is on)";
  // Denormals-are-zero: a subnormal operand must not read as zero.
  volatile double subnormal_in = subnormal;
  if (subnormal_in * two != smallest_normal) return "subnormal operands are read as zero (DAZ is on)";
  // Contraction: unfused, a*a rounds to 1 + 2^-29 and the sum is exactly 0;
  // a fused multiply-add would keep the 2^-60 term.
  const double a = a_factor;
  const double unfused = a * a + minus_square_rounded;
  if (unfused != 0.0) return "a*b+c is contracted into a fused multiply-add (-ffp-contract must be off)";
  return {};
}

}  // namespace collide2d
