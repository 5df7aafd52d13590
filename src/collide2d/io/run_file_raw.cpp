// The exact fixed-point series of a run file; see run_file_raw.hpp.
#include "collide2d/io/run_file_raw.hpp"

#include <algorithm>

namespace collide2d::h5 {

void create_raw_series(hid_t balls, hid_t position, std::size_t n_balls, hsize_t chunk_rows) {
  const std::vector<hsize_t> row{n_balls, 2, 2};
  for (const char* name : {"position_raw", "velocity_raw"}) {
    Hid g = create_element(balls, name, position, H5T_STD_I64LE, row, chunk_rows);
    write_string(g, "format", kRawFormat, false);
  }
}

hsize_t raw_rows(const Series& s, std::size_t n_balls) {
  const std::vector<hsize_t> row{n_balls, 2, 2};
  hsize_t rows = ~hsize_t{0};
  for (hid_t d : {hid_t{s.position_raw}, hid_t{s.velocity_raw}}) {
    const auto dims = shape(d);
    if (dims.size() != 4 || !std::equal(row.begin(), row.end(), dims.begin() + 1))
      fail("unexpected shape of a *_raw dataset (want frames x N x 2 x 2)");
    rows = std::min(rows, dims[0]);
  }
  return rows;
}

void read_raw_frames(const Series& s, std::size_t n_balls, std::vector<FrameRecord>& frames) {
  const std::size_t per_frame = raw_words_per_frame(n_balls);
  const hsize_t n = frames.size();
  std::vector<std::int64_t> pos(n * per_frame), vel(n * per_frame);
  read_rows(s.position_raw, H5T_NATIVE_INT64, 0, n, pos.data());
  read_rows(s.velocity_raw, H5T_NATIVE_INT64, 0, n, vel.data());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    frames[i].position_raw.assign(pos.begin() + i * per_frame, pos.begin() + (i + 1) * per_frame);
    frames[i].velocity_raw.assign(vel.begin() + i * per_frame, vel.begin() + (i + 1) * per_frame);
  }
}

}  // namespace collide2d::h5
