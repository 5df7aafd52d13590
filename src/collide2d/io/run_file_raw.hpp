// The exact fixed-point series of a run file, /particles/balls/position_raw
// and velocity_raw (layout: run_file.hpp). Present in fixed-mode files only:
// a double holds 53 significant bits, a Q63.64 value up to 127. Internal to
// the run file, like run_file_hdf5.hpp.
#pragma once

#include <vector>

#include "collide2d/io/run_file.hpp"
#include "collide2d/io/run_file_hdf5.hpp"

namespace collide2d::h5 {

// The `format` attribute of both groups: how to get the number back.
inline constexpr const char* kRawFormat =
    "Q63.64 fixed point as two int64 words, last axis [hi, lo]: value = (hi * 2^64 + (uint64)lo) / 2^64 exactly "
    "(hi signed; lo holds the unsigned low 64 bits, so add 2^64 to it when negative)";

// Words per frame of one raw series: N balls x 2 coordinates x [hi, lo].
inline std::size_t raw_words_per_frame(std::size_t n_balls) { return n_balls * 2 * 2; }

// Creates both series beside position (whose step and time they link to).
void create_raw_series(hid_t balls, hid_t position, std::size_t n_balls, hsize_t chunk_rows);

// Checks the raw series' shapes against N balls; their row count.
hsize_t raw_rows(const Series& s, std::size_t n_balls);

// Fills position_raw and velocity_raw of frames [0, frames.size()).
void read_raw_frames(const Series& s, std::size_t n_balls, std::vector<FrameRecord>& frames);

}  // namespace collide2d::h5
