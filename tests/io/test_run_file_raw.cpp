// The exact fixed-point values in the run file (/particles/balls/*_raw):
// they round-trip, the documented formula gives back the Fixed value, strict
// files have none, resume keeps them, and h5py reads them exactly.
#include <catch2/catch.hpp>

#include "collide2d/sim/simulate.hpp"
#include "run_file_fixtures.hpp"

using namespace collide2d;
using namespace collide2d::test_io;

namespace {

// The formula of run_file.hpp, as written there: hi * 2^64 + (uint64)lo is
// the raw Q63.64 integer (value * 2^64). No overflow for any pair of words.
Fixed::Raw raw_by_formula(std::int64_t hi, std::int64_t lo) {
  return Fixed::Raw{hi} * (Fixed::Raw{1} << 64) + Fixed::Raw{static_cast<std::uint64_t>(lo)};
}

BallSpec ball(double x, double y, double vx, double vy, bool fixed = false) {
  BallSpec b;
  b.position = {x, y};
  b.velocity = {vx, vy};
  b.radius = 0.5;
  b.fixed = fixed;
  return b;
}

// Values whose two words a sign or width mistake would change. Ball 0 is
// fixed, so the extremes do not enter the energy (which would overflow).
// Every ball on its clock at `frame_time` (recorded there as it is).
World<Fixed> world_of_tricky_values(const Scene& scene, Fixed frame_time) {
  World<Fixed> w = make_world<Fixed>(scene);
  const Fixed res = Fixed::resolution();
  w.balls[0].position = {Fixed::lowest(), Fixed::max()};
  w.balls[0].velocity = {Fixed::max(), Fixed::lowest()};
  w.balls[1].position = {-res, Fixed(1) / Fixed(3)};
  w.balls[1].velocity = {Fixed::from_double(-1.5) - res, Fixed::from_double(2147483648.0) + res};
  w.balls[2].position = {Fixed{}, Fixed(-7) / Fixed(3)};
  w.balls[2].velocity = {res, Fixed::from_double(-0.1)};
  for (Body<Fixed>& b : w.balls) b.time = frame_time;
  return w;
}

// Every coordinate's words against the body's exact value: by the formula,
// by from_words, and the double beside them is that value rounded.
void require_words_are_state(const FrameRecord& f, const World<Fixed>& w) {
  for (std::size_t i = 0; i < w.balls.size(); ++i) {
    const Body<Fixed>& b = w.balls[i];
    const Fixed position[2] = {b.position.x, b.position.y}, velocity[2] = {b.velocity.x, b.velocity.y};
    for (std::size_t c = 0; c < 2; ++c) {
      INFO("ball " << i << ", coordinate " << c);
      const std::size_t k = 2 * i + c, hi = 2 * k, lo = 2 * k + 1;
      REQUIRE(raw_by_formula(f.position_raw[hi], f.position_raw[lo]) == position[c].raw());
      REQUIRE(raw_by_formula(f.velocity_raw[hi], f.velocity_raw[lo]) == velocity[c].raw());
      REQUIRE(from_words(f.position_raw[hi], f.position_raw[lo]) == position[c]);
      REQUIRE(same_bits(f.position[k], position[c].to_double()));
      REQUIRE(same_bits(f.velocity[k], velocity[c].to_double()));
    }
  }
}

std::vector<std::int64_t> read_words(hid_t file, const char* path) {
  const hid_t d = H5Dopen2(file, path, H5P_DEFAULT);
  REQUIRE(d >= 0);
  const hid_t space = H5Dget_space(d);
  std::vector<std::int64_t> words(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  REQUIRE(H5Dread(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, words.data()) >= 0);
  H5Sclose(space);
  H5Dclose(d);
  return words;
}

}  // namespace

TEST_CASE("run file raw: fixed-mode raw values round-trip exactly, in the documented layout", "[io][raw]") {
  TempDir tmp;
  const std::string path = tmp / "fixed.h5";
  const std::size_t n = 3;
  {
    RunWriter w(path, make_header(n, "fixed"));
    append(w, n, 0, 150, 0, 20, true);  // past several frame chunks
    w.checkpoint(make_checkpoint(1.0, 10, 1));
    append(w, n, 150, 170, 20, 30, true);
    w.finish("{}");
  }
  require_content(read_run_file(path), n, 170, 30, true);

  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  for (const char* name : {"/particles/balls/position_raw", "/particles/balls/velocity_raw"}) {
    INFO(name);
    CHECK(read_string_attr(f, name, "format").find("(hi * 2^64 + (uint64)lo) / 2^64") != std::string::npos);
    const hid_t d = H5Dopen2(f, (std::string(name) + "/value").c_str(), H5P_DEFAULT);
    REQUIRE(d >= 0);
    const hid_t space = H5Dget_space(d), type = H5Dget_type(d);
    std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    CHECK(dims == std::vector<hsize_t>{170, n, 2, 2});
    CHECK(H5Tget_class(type) == H5T_INTEGER);
    CHECK(H5Tget_size(type) == 8);
    CHECK(H5Tget_sign(type) == H5T_SGN_2);
    H5Tclose(type), H5Sclose(space), H5Dclose(d);
    for (const char* axis : {"/step", "/time"})
      CHECK(H5Lexists(f, (std::string(name) + axis).c_str(), H5P_DEFAULT) > 0);
  }
  // [frame][ball][coordinate][hi, lo], frame 2, ball 1, y, lo.
  const std::vector<std::int64_t> words = read_words(f, "/particles/balls/position_raw/value");
  CHECK(words[((2 * n + 1) * 2 + 1) * 2 + 1] == make_frame(2, n, true).position_raw[(2 * 1 + 1) * 2 + 1]);
  H5Fclose(f);
}

TEST_CASE("run file raw: a fixed-mode frame's raw words are its Fixed values exactly", "[io][raw]") {
  Scene scene;
  scene.balls = {ball(0, 0, 0, 0, true), ball(3, 0, 1, 0), ball(0, 3, 0, 1)};
  const World<Fixed> w = world_of_tricky_values(scene, Fixed(2));
  const FrameRecord record = make_frame(w, 4, Fixed(2));
  REQUIRE(record.position_raw.size() == 3 * 2 * 2);
  REQUIRE(record.velocity_raw.size() == 3 * 2 * 2);
  require_words_are_state(record, w);

  // And the same after the file.
  TempDir tmp;
  const std::string path = tmp / "fixed.h5";
  {
    RunWriter writer(path, make_header(3, "fixed"));
    writer.append_frame(record);
    writer.finish("{}");
  }
  const RunContents run = read_run_file(path);
  REQUIRE(run.frames.size() == 1);
  require_words_are_state(run.frames[0], w);
}

TEST_CASE("run file raw: a simulated fixed run's raw words are the state its hash covers", "[io][raw]") {
  Scene scene;
  scene.gravity = {0, -9.81};
  scene.record_interval = 0.1;
  scene.walls = {WallSpec{{-5, 0}, {5, 0}}};
  scene.balls = {ball(0, 2, 0.3, 0), ball(1.2, 3, -0.7, 1)};
  std::vector<FrameRecord> frames;
  simulate<Fixed>(scene, 2.0, [&](const FrameRecord& f) { frames.push_back(f); }, [](const EventRecord&) {});
  REQUIRE(frames.size() == 21);
  for (const FrameRecord& f : frames) {
    INFO("frame " << f.step);
    // FNV-1a over x, y, vx, vy of each ball, rebuilt from the words alone.
    std::uint64_t hash = 0xcbf29ce484222325ULL;
    for (std::size_t i = 0; i < 2; ++i) {
      for (std::size_t c = 0; c < 2; ++c) {
        const std::size_t hi = 4 * i + 2 * c;
        hash_number(hash, from_words(f.position_raw[hi], f.position_raw[hi + 1]));
        CHECK(same_bits(f.position[2 * i + c], from_words(f.position_raw[hi], f.position_raw[hi + 1]).to_double()));
      }
      for (std::size_t c = 0; c < 2; ++c) {
        const std::size_t hi = 4 * i + 2 * c;
        hash_number(hash, from_words(f.velocity_raw[hi], f.velocity_raw[hi + 1]));
        CHECK(same_bits(f.velocity[2 * i + c], from_words(f.velocity_raw[hi], f.velocity_raw[hi + 1]).to_double()));
      }
    }
    CHECK(hash == f.state_hash);
  }
  std::vector<FrameRecord> strict;
  simulate<double>(scene, 0.5, [&](const FrameRecord& f) { strict.push_back(f); }, [](const EventRecord&) {});
  for (const FrameRecord& f : strict) CHECK((f.position_raw.empty() && f.velocity_raw.empty()));
}

TEST_CASE("run file raw: strict files have no raw datasets, and the reader takes files with and without", "[io][raw]") {
  TempDir tmp;
  const std::string strict = tmp / "strict.h5";
  {
    RunWriter w(strict, make_header(2));
    append(w, 2, 0, 70, 0, 5);
    CHECK(error_of([&] { w.append_frame(make_frame(70, 2, true)); }).find("only a fixed-mode run") !=
          std::string::npos);
    w.finish("{}");
  }
  const hid_t f = H5Fopen(strict.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  CHECK(H5Lexists(f, "/particles/balls/position_raw", H5P_DEFAULT) == 0);
  CHECK(H5Lexists(f, "/particles/balls/velocity_raw", H5P_DEFAULT) == 0);
  H5Fclose(f);
  require_content(read_run_file(strict), 2, 70, 5, false);

  RunWriter fixed(tmp / "fixed.h5", make_header(2, "fixed"));
  CHECK(error_of([&] { fixed.append_frame(make_frame(0, 2, false)); }).find("lacks the raw values") !=
        std::string::npos);
  FrameRecord short_raw = make_frame(0, 2, true);
  short_raw.velocity_raw.pop_back();
  CHECK_FALSE(error_of([&] { fixed.append_frame(short_raw); }).empty());

  // A fixed-mode file from before raw values were stored: read, without them.
  // One raw series alone is a damaged file.
  const std::string old = tmp / "old_fixed.h5", half = tmp / "half.h5";
  for (const std::string& path : {old, half}) {
    RunWriter w(path, make_header(2, "fixed"));
    append(w, 2, 0, 10, 0, 3, true);
    w.finish("{}");
    const hid_t rw = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    REQUIRE(rw >= 0);
    REQUIRE(H5Ldelete(rw, "/particles/balls/velocity_raw", H5P_DEFAULT) >= 0);
    if (path == old) REQUIRE(H5Ldelete(rw, "/particles/balls/position_raw", H5P_DEFAULT) >= 0);
    H5Fclose(rw);
  }
  const RunContents run = read_run_file(old);
  CHECK(run.header.mode == "fixed");
  require_content(run, 2, 10, 3, false);
  const std::string message = error_of([&] { read_run_file(half); });
  CHECK(message.find(half) != std::string::npos);
  CHECK(message.find("velocity_raw") != std::string::npos);
}

TEST_CASE("run file raw: kill -9 and resume keep the raw datasets identical to an uninterrupted run",
          "[io][raw][crash]") {
  TempDir tmp;
  const std::size_t n = 300;  // 54 frames per chunk: partial chunks in flight at the kill
  const std::int64_t total_frames = 260, total_events = 3000;
  const std::string reference = tmp / "reference.h5", path = tmp / "run.h5";
  {
    RunWriter w(reference, make_header(n, "fixed"));
    append(w, n, 0, total_frames, 0, total_events, true);
    w.finish("{}");
  }
  run_and_kill([&] {
    RunWriter w(path, make_header(n, "fixed"));
    append(w, n, 0, 40, 0, 500, true);
    w.checkpoint(make_checkpoint(1.0, 200, 1));
    append(w, n, 40, 121, 500, 1300, true);
    w.checkpoint(make_checkpoint(2.0, 300, 2));
    append(w, n, 121, 200, 1300, 2000, true);  // lost by the kill
    die();
  });
  require_content(read_run_file(path + ".partial"), n, 121, 1300, true);
  {
    ResumedRun resumed = resume_run_file(path);
    CHECK(resumed.writer.frames_written() == 121);
    append(resumed.writer, n, 121, total_frames, 1300, total_events, true);
    resumed.writer.finish("{}");
  }
  require_content(read_run_file(path), n, total_frames, total_events, true);
  const hid_t a = H5Fopen(reference.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t b = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(a >= 0);
  REQUIRE(b >= 0);
  for (const char* name : {"/particles/balls/position_raw/value", "/particles/balls/velocity_raw/value",
                           "/particles/balls/position_raw/step", "/particles/balls/velocity_raw/step"}) {
    INFO(name);
    CHECK(read_words(a, name) == read_words(b, name));
  }
  CHECK(read_string_attr(b, "/particles/balls/position_raw", "format") ==
        read_string_attr(a, "/particles/balls/position_raw", "format"));
  H5Fclose(a);
  H5Fclose(b);
}

TEST_CASE("run file raw: h5py reads the exact values by the README's formula", "[io][raw][h5py]") {
  if (std::system("/usr/bin/python3 -c 'import h5py' >/dev/null 2>&1") != 0) {
    WARN("python3 with h5py is not installed: skipped");
    return;
  }
  Scene scene;
  scene.balls = {ball(0, 0, 0, 0, true), ball(3, 0, 1, 0), ball(0, 3, 0, 1)};
  const World<Fixed> w = world_of_tricky_values(scene, Fixed{});
  TempDir tmp;
  const std::string path = tmp / "fixed.h5";
  {
    RunWriter writer(path, make_header(3, "fixed"));
    writer.append_frame(make_frame(w, 0, Fixed{}));
    writer.finish("{}");
  }
  // The README's snippet, then the values world_of_tricky_values set.
  const std::string script = R"(import sys
from fractions import Fraction
import h5py
with h5py.File(sys.argv[1], "r") as f:
    words = f["/particles/balls/position_raw/value"][:]   # frames x N x 2 x [hi, lo], int64
    vwords = f["/particles/balls/velocity_raw/value"][:]
    doubles = f["/particles/balls/position/value"][:]
    fmt = f["/particles/balls/position_raw"].attrs["format"]
    linked = f["/particles/balls/position_raw/step"] == f["/particles/balls/position/step"]
def exact(hi, lo):
    return Fraction(int(hi) * 2**64 + int(lo) % 2**64, 2**64)
x = [[exact(*words[0, i, c]) for c in range(2)] for i in range(3)]
v = [[exact(*vwords[0, i, c]) for c in range(2)] for i in range(3)]
r = Fraction(1, 2**64)
assert x[0] == [-2**63, 2**63 - r], x[0]
assert v[0] == [2**63 - r, -2**63], v[0]
assert x[1][0] == -r, x[1]
assert x[1][1] == Fraction(round(Fraction(2**64, 3)), 2**64), x[1]
assert v[1] == [Fraction(-3, 2) - r, 2**31 + r], v[1]
assert x[2][0] == 0 and x[2][1] == Fraction(round(Fraction(-7 * 2**64, 3)), 2**64), x[2]
assert v[2][0] == r, v[2]
assert "(hi * 2^64 + (uint64)lo) / 2^64" in (fmt.decode() if isinstance(fmt, bytes) else fmt), fmt
assert linked
# The doubles are the exact values rounded to nearest (Python's int / int rounds so too).
assert all(float(x[i][c]) == doubles[0, i, c] for i in range(3) for c in range(2))
)";
  const std::string script_path = tmp / "check.py";
  std::ofstream(script_path) << script;
  CHECK(std::system(("/usr/bin/python3 " + script_path + " " + path).c_str()) == 0);
}
