// A large scene's frames given to the run file in slices of balls
// (RunWriter::append_frame_slice), as `collide2d run` gives them so that no
// whole frame is held: the file reads back frame for frame and bit for bit
// as the one written from whole frames; slices out of order, of the wrong
// sizes or a frame left unfinished are refused.
#include <catch2/catch.hpp>

#include <span>
#include <string>

#include "run_file_fixtures.hpp"

using namespace collide2d;
using namespace collide2d::test_io;

namespace {

// Over 2^15 balls: a frame is a chunk by itself along time and is cut into
// chunks of 2^15 balls (512 KiB of positions), so it takes two slices, the
// second a short one.
constexpr std::size_t kBalls = 40000;

FrameSlice slice_of(const FrameRecord& f, std::size_t first, std::size_t count) {
  auto doubles = [&](const std::vector<double>& v) { return std::span(v).subspan(2 * first, 2 * count); };
  auto words = [&](const std::vector<std::int64_t>& v) {
    return v.empty() ? std::span<const std::int64_t>{} : std::span(v).subspan(4 * first, 4 * count);
  };
  return FrameSlice{f.time, first, doubles(f.position), doubles(f.velocity), words(f.position_raw), words(f.velocity_raw)};
}

// The frame's record without its balls: what ends a frame given in slices.
FrameRecord record_of(FrameRecord f) {
  f.position.clear(), f.velocity.clear(), f.position_raw.clear(), f.velocity_raw.clear();
  return f;
}

}  // namespace

TEST_CASE("run file: a frame in slices reads back as the whole frame", "[io]") {
  TempDir tmp;
  for (const std::string mode : {"strict", "fixed"}) {
    INFO(mode);
    const bool raw = mode == "fixed";
    const std::string path = tmp / ("sliced_" + mode + ".h5");
    {
      RunWriter w(path, make_header(kBalls, mode));
      const std::size_t k = w.balls_per_frame_slice();
      REQUIRE(k == 32768);  // 512 KiB of positions, two chunks of raw words
      for (std::int64_t i = 0; i < 3; ++i) {
        const FrameRecord f = make_frame(i, kBalls, raw);
        for (std::size_t first = 0; first < kBalls; first += k)
          w.append_frame_slice(slice_of(f, first, std::min(k, kBalls - first)));
        w.append_frame(record_of(f));
        append(w, kBalls, 0, 0, 3 * i, 3 * i + 3);
      }
      // Whole frames may still come between sliced ones.
      w.append_frame(make_frame(3, kBalls, raw));
      append(w, kBalls, 0, 0, 9, 12);
      w.checkpoint(make_checkpoint(0.06, 50, 3));
      w.finish(R"({"events": 12})");
    }
    const RunContents run = read_run_file(path);
    require_same_header(run.header, make_header(kBalls, mode));
    require_content(run, kBalls, 4, 12, raw);
  }
}

TEST_CASE("run file: slices out of order, of the wrong size or unfinished are refused", "[io]") {
  TempDir tmp;
  const FrameRecord f = make_frame(0, kBalls);
  RunWriter w(tmp / "run.h5", make_header(kBalls));
  const std::size_t k = w.balls_per_frame_slice();
  CHECK(error_of([&] { w.append_frame_slice(slice_of(f, k, kBalls - k)); }).find("next slice starts at ball 0") !=
        std::string::npos);
  CHECK(error_of([&] { w.append_frame_slice(slice_of(f, 0, k - 1)); }).find("a multiple of 32768") != std::string::npos);
  FrameSlice uneven = slice_of(f, 0, k);
  uneven.velocity = uneven.velocity.first(2 * k - 2);
  CHECK(error_of([&] { w.append_frame_slice(uneven); }).find("2 coordinates") != std::string::npos);
  FrameSlice with_raw = slice_of(f, 0, k);
  const std::vector<std::int64_t> words(4 * k, 1);
  with_raw.position_raw = with_raw.velocity_raw = words;
  CHECK(error_of([&] { w.append_frame_slice(with_raw); }).find("only a fixed-mode run") != std::string::npos);
  // Nothing of the refused slices was taken: the frame starts at ball 0.
  w.append_frame_slice(slice_of(f, 0, k));
  CHECK(error_of([&] { w.append_frame(record_of(f)); }).find("32768 of 40000 balls") != std::string::npos);
  CHECK(error_of([&] { w.append_frame(f); }).find("holds balls of its own") != std::string::npos);
  FrameSlice late = slice_of(f, k, kBalls - k);
  late.time = std::nextafter(f.time, 1.0);
  CHECK(error_of([&] { w.append_frame_slice(late); }).find("its time is not the frame's") != std::string::npos);
  CHECK(error_of([&] { w.checkpoint(make_checkpoint(0.5, 10, 1)); }).find("unfinished") != std::string::npos);
  CHECK(error_of([&] { w.finish("{}"); }).find("unfinished") != std::string::npos);
  const FrameRecord longer = make_frame(0, 2 * kBalls);
  CHECK(error_of([&] { w.append_frame_slice(slice_of(longer, k, kBalls)); }).find("past the last") != std::string::npos);
  w.append_frame_slice(slice_of(f, k, kBalls - k));
  FrameRecord other_time = record_of(f);
  other_time.time = std::nextafter(f.time, 1.0);
  CHECK(error_of([&] { w.append_frame(other_time); }).find("its time is not its slices'") != std::string::npos);
  w.append_frame(record_of(f));
  // A record without balls and without slices before it is a short frame.
  CHECK(error_of([&] { w.append_frame(record_of(make_frame(1, kBalls))); }).find("does not hold 2*40000") !=
        std::string::npos);
  w.finish("{}");
  require_content(read_run_file(tmp / "run.h5"), kBalls, 1, 0);
}

TEST_CASE("run file: a small scene's frames are whole, never sliced", "[io]") {
  TempDir tmp;
  RunWriter w(tmp / "run.h5", make_header(3));
  CHECK(w.balls_per_frame_slice() == 0);  // several frames to a chunk, buffered
  const FrameRecord f = make_frame(0, 3);
  CHECK(error_of([&] { w.append_frame_slice(slice_of(f, 0, 3)); }).find("whole frames only") != std::string::npos);
  // A frame without balls is a short frame here, not the end of slices.
  CHECK(error_of([&] { w.append_frame(record_of(f)); }).find("does not hold 2*3") != std::string::npos);
}

TEST_CASE("run file: kill -9 between a frame's slices leaves the run resumable", "[io][crash]") {
  TempDir tmp;
  const std::string path = tmp / "run.h5";
  const FrameRecord f0 = make_frame(0, kBalls), f1 = make_frame(1, kBalls), f2 = make_frame(2, kBalls);
  auto sliced = [&](RunWriter& w, const FrameRecord& f) {
    const std::size_t k = w.balls_per_frame_slice();
    REQUIRE(k == 32768);
    for (std::size_t first = 0; first < kBalls; first += k) w.append_frame_slice(slice_of(f, first, std::min(k, kBalls - first)));
    w.append_frame(record_of(f));
  };
  run_and_kill([&] {
    RunWriter w(path, make_header(kBalls));
    sliced(w, f0);
    append(w, kBalls, 0, 0, 0, 3);
    w.checkpoint(make_checkpoint(0.0, 20, 5));
    w.append_frame_slice(slice_of(f1, 0, w.balls_per_frame_slice()));  // the row's first chunk, then the kill
    die();
  });
  REQUIRE(fs::exists(path + ".partial"));
  require_content(read_run_file(path + ".partial"), kBalls, 1, 3);
  {
    ResumedRun resumed = resume_run_file(path);
    CHECK(resumed.checkpoint.frames_written == 1);
    CHECK(resumed.checkpoint.events_written == 3);
    sliced(resumed.writer, f1);  // the resumed writer takes slices too
    resumed.writer.append_frame(f2);
    resumed.writer.finish("{}");
  }
  require_content(read_run_file(path), kBalls, 3, 3);
}
