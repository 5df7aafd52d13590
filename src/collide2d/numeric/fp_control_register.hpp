// The floating-point control register of the machine strict mode runs on,
// read directly: MXCSR on x86 (x86-64, and i686 built with SSE2), FPCR on
// aarch64, FPSCR on POWER. strict_environment_problem() checks it before it
// checks the arithmetic itself, so that a wrong mode is named by its bit.
#pragma once

#include <cstdint>

namespace collide2d {

struct FpControlState {
  const char* register_name = nullptr;  // nullptr: no reader for this architecture
  std::uint64_t raw = 0;                // the register's bits as read
  bool round_to_nearest = true;         // rounding-mode field = to nearest, ties to even
  bool flush_to_zero = false;           // subnormal results become zero (MXCSR.FTZ, FPCR.FZ, FPSCR.NI)
  bool denormals_are_zero = false;      // subnormal operands read as zero (MXCSR.DAZ; FPCR.FZ does both)
};

FpControlState read_fp_control();

// Writes the register's raw bits (the value read_fp_control().raw returned,
// changed): for the tests that switch flush-to-zero on and expect a refusal.
// Does nothing where read_fp_control() has no reader.
void write_fp_control_raw(std::uint64_t raw);

// The flush-to-zero bit of this architecture's register (0 where unknown).
std::uint64_t fp_control_flush_bit();

}  // namespace collide2d
