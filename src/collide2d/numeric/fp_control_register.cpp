#include "collide2d/numeric/fp_control_register.hpp"

#if defined(__SSE2__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace collide2d {

// Bit layouts, from the architecture manuals:
//
// MXCSR (Intel SDM vol. 1, 10.2.3): bit 6 DAZ, bits 13-14 RC (00 = nearest),
// bit 15 FTZ.
//
// FPCR (Arm ARM, AArch64 FPCR): bits 22-23 RMode (00 = RN, to nearest), bit 24
// FZ (flush subnormal inputs and outputs to zero; with FEAT_AFP and FPCR.AH=1
// inputs and outputs are controlled apart, but either way FZ=1 is refused),
// bit 19 FZ16 (half precision only: not ours).
//
// FPSCR (Power ISA v3.1, 4.2.2), in the low word as mffs returns it: bits 0-1
// RN (00 = round to nearest), bit 2 NI (non-IEEE mode: an implementation may
// then flush subnormal results to zero, the ISA leaves it open).
#if defined(__SSE2__) || defined(__x86_64__)
namespace {
constexpr std::uint64_t kDaz = 1u << 6, kRoundingField = 3u << 13, kFtz = 1u << 15;
}
FpControlState read_fp_control() {
  FpControlState s;
  s.register_name = "MXCSR";
  s.raw = _mm_getcsr();
  s.round_to_nearest = (s.raw & kRoundingField) == 0;
  s.flush_to_zero = (s.raw & kFtz) != 0;
  s.denormals_are_zero = (s.raw & kDaz) != 0;
  return s;
}
void write_fp_control_raw(std::uint64_t raw) { _mm_setcsr(static_cast<unsigned>(raw)); }
std::uint64_t fp_control_flush_bit() { return kFtz; }

#elif defined(__aarch64__)
namespace {
constexpr std::uint64_t kRoundingField = 3u << 22, kFz = 1u << 24;
}
FpControlState read_fp_control() {
  FpControlState s;
  s.register_name = "FPCR";
  std::uint64_t fpcr;
  asm volatile("mrs %0, fpcr" : "=r"(fpcr));
  s.raw = fpcr;
  s.round_to_nearest = (fpcr & kRoundingField) == 0;
  s.flush_to_zero = (fpcr & kFz) != 0;
  s.denormals_are_zero = s.flush_to_zero;  // FZ flushes subnormal inputs too
  return s;
}
void write_fp_control_raw(std::uint64_t raw) { asm volatile("msr fpcr, %0" : : "r"(raw)); }
std::uint64_t fp_control_flush_bit() { return kFz; }

#elif defined(__powerpc64__) || defined(__powerpc__)
namespace {
constexpr std::uint64_t kRoundingField = 3u, kNonIeee = 1u << 2;
}
FpControlState read_fp_control() {
  FpControlState s;
  s.register_name = "FPSCR";
  // mffs copies the FPSCR into a floating-point register; its bits are read
  // back through memory. __builtin_mffs is gcc's and clang's spelling of it.
  const double image = __builtin_mffs();
  std::uint64_t bits;
  __builtin_memcpy(&bits, &image, sizeof bits);
  s.raw = bits & 0xffffffffu;
  s.round_to_nearest = (s.raw & kRoundingField) == 0;
  s.flush_to_zero = (s.raw & kNonIeee) != 0;
  s.denormals_are_zero = false;
  return s;
}
void write_fp_control_raw(std::uint64_t raw) {
  double image;
  __builtin_memcpy(&image, &raw, sizeof image);
  __builtin_mtfsf(0xff, image);  // all eight 4-bit fields of the low word
}
std::uint64_t fp_control_flush_bit() { return kNonIeee; }

#else
// No reader: the arithmetic checks of strict_environment_problem() still run.
FpControlState read_fp_control() { return {}; }
void write_fp_control_raw(std::uint64_t) {}
std::uint64_t fp_control_flush_bit() { return 0; }
#endif

}  // namespace collide2d
