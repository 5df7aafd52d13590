// What a run produces, as plain doubles: a frame at each record time and a
// record of each collision. The simulator hands these on (simulate.hpp) and
// the run file stores and reads back the same types (io/run_file.hpp), so a
// value is never copied field by field from one type into another.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace collide2d {

// The state of every ball at one record time.
struct FrameRecord {
  std::int64_t step = 0;
  double time = 0;
  std::vector<double> position;  // N*2: x0, y0, x1, y1, ...
  std::vector<double> velocity;  // N*2
  double energy = 0;
  std::uint64_t state_hash = 0;  // of the exact state in the run's number type
  // Fixed mode only (empty otherwise, and when read from a fixed-mode file
  // written without them): the exact Q63.64 values, which the doubles above
  // round. Per coordinate the two words of numeric/fixed_words.hpp, hi then
  // lo: x0.hi, x0.lo, y0.hi, y0.lo, x1.hi, ... (N*2*2).
  std::vector<std::int64_t> position_raw;
  std::vector<std::int64_t> velocity_raw;
};

// Balls [first, first + position.size() / 2) of a frame, laid out as in
// FrameRecord: what a consumer that takes a large frame in pieces is handed
// (simulate.hpp's FrameSink), valid only during the call.
struct FrameSlice {
  double time = 0;  // the frame's
  std::size_t first = 0;
  std::span<const double> position, velocity;
  std::span<const std::int64_t> position_raw, velocity_raw;  // fixed mode only
};

// One collision, in the order the engine processed it.
struct EventRecord {
  double time = 0;
  int kind = 0;  // 0 ball–ball, 1 ball–wall
  int a = 0;     // a ball
  int b = 0;     // a ball (kind 0) or a wall (kind 1)
  double impulse = 0;  // magnitude of the normal impulse on ball a (mass × speed)
};

}  // namespace collide2d
