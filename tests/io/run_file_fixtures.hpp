// Shared by the run-file tests: deterministic frames and events with values
// a lossy path would change, bitwise comparison, and a real kill -9.
#pragma once

#include <catch2/catch.hpp>

#include <hdf5.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>

#include "collide2d/io/run_file.hpp"

namespace collide2d::test_io {

namespace fs = std::filesystem;

// A fresh directory per test case, removed afterwards.
struct TempDir {
  fs::path dir;
  TempDir() {
    static int counter = 0;  // inline: one counter for every test file; the pid separates processes
    dir = fs::temp_directory_path() / ("collide2d_io_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
};

// Values that a decimal or lossy path would change: -0, subnormals, NaN with
// a payload, extremes, and long fractions.
inline double tricky(std::int64_t i, int k) {
  switch ((i + k) % 7) {
    case 0: return -0.0;
    case 1: return std::numeric_limits<double>::denorm_min() * static_cast<double>(i + 1);
    case 2: {
      std::uint64_t bits = 0x7ff8000000000000ull | static_cast<std::uint64_t>(i * 31 + k);
      double d;
      std::memcpy(&d, &bits, sizeof d);
      return d;
    }
    case 3: return std::numeric_limits<double>::max() / static_cast<double>(i + 2);
    default: return 0.1 * static_cast<double>(i) + 1.0 / (3.0 + k);
  }
}

// Raw Q63.64 words that a narrowing or sign mistake would change: the
// extremes of each word, -1, the top bit of the low word, long patterns.
inline std::int64_t tricky_word(std::int64_t i, int k) {
  switch ((i + k) % 6) {
    case 0: return std::numeric_limits<std::int64_t>::min();
    case 1: return std::numeric_limits<std::int64_t>::max();
    case 2: return -1;
    case 3: return static_cast<std::int64_t>(0x8000000000000000ull >> (i % 64));
    default: return static_cast<std::int64_t>(0x9e3779b97f4a7c15ull * static_cast<std::uint64_t>(i * 131 + k + 1));
  }
}

// mode "fixed" gives the file the raw series; make_frame(i, n, true) fills them.
inline RunHeader make_header(std::size_t n, const std::string& mode = "strict") {
  RunHeader h;
  h.scene_json = R"({"name": "tëst", "balls": [], "note": "ünïcode ✓"})";
  h.options_json = R"({"engine": "event", "mode": ")" + mode + R"("})";
  h.mode = mode;
  for (std::size_t i = 0; i < n; ++i) {
    h.radius.push_back(0.1 + 0.01 * static_cast<double>(i));
    h.mass.push_back(1.0 / (1.0 + static_cast<double>(i)));
  }
  h.walls = {{0, 0, 16, 0}, {-0.0, 1e-300, 3.5, std::nextafter(1.0, 2.0)}};
  h.wall_restitution = {0.9, std::nextafter(1.0, 0.0)};
  h.creator_version = "0.1.0";
  h.compiler = "gcc 12";
  h.author = "tester";
  return h;
}

inline FrameRecord make_frame(std::int64_t i, std::size_t n, bool raw = false) {
  FrameRecord f;
  f.step = i * 3 - 7;
  f.time = 0.02 * static_cast<double>(i);
  for (std::size_t k = 0; k < 2 * n; ++k) {
    f.position.push_back(tricky(i, static_cast<int>(k)));
    f.velocity.push_back(-tricky(i + 1, static_cast<int>(k)));
  }
  f.energy = tricky(i, 99);
  f.state_hash = 0xfedcba9876543210ull ^ static_cast<std::uint64_t>(i) * 0x9e3779b97f4a7c15ull;
  for (std::size_t k = 0; raw && k < 4 * n; ++k) {
    f.position_raw.push_back(tricky_word(i, static_cast<int>(k)));
    f.velocity_raw.push_back(tricky_word(i + 7, static_cast<int>(k) * 3));
  }
  return f;
}

inline EventRecord make_event(std::int64_t i) {
  return EventRecord{tricky(i, 3), static_cast<int>(i % 2), static_cast<int>(i % 5), static_cast<int>(i % 11) - 1,
                  tricky(i, 4)};
}

inline Checkpoint make_checkpoint(double time, std::size_t bytes, std::uint8_t seed) {
  Checkpoint cp;
  cp.time = time;
  for (std::size_t i = 0; i < bytes; ++i) cp.engine_state.push_back(static_cast<std::uint8_t>(seed + i * 7));
  return cp;
}

inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
inline bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

inline void require_same_header(const RunHeader& a, const RunHeader& b) {
  CHECK(a.scene_json == b.scene_json);
  CHECK(a.options_json == b.options_json);
  CHECK(a.mode == b.mode);
  CHECK(same_bits(a.radius, b.radius));
  CHECK(same_bits(a.mass, b.mass));
  REQUIRE(a.walls.size() == b.walls.size());
  for (std::size_t i = 0; i < a.walls.size(); ++i)
    CHECK(std::memcmp(a.walls[i].data(), b.walls[i].data(), sizeof(a.walls[i])) == 0);
  CHECK(same_bits(a.wall_restitution, b.wall_restitution));
  CHECK(a.creator_version == b.creator_version);
  CHECK(a.compiler == b.compiler);
  CHECK(a.author == b.author);
}

// Frames [0, frames) and events [0, events) as make_frame/make_event made them
// (with raw values if `raw`, else none).
inline void require_content(const RunContents& run, std::size_t n, std::int64_t frames, std::int64_t events,
                            bool raw = false) {
  REQUIRE(static_cast<std::int64_t>(run.frames.size()) == frames);
  REQUIRE(static_cast<std::int64_t>(run.events.size()) == events);
  for (std::int64_t i = 0; i < frames; ++i) {
    const FrameRecord want = make_frame(i, n, raw);
    const FrameRecord& got = run.frames[static_cast<std::size_t>(i)];
    INFO("frame " << i);
    REQUIRE(got.step == want.step);
    REQUIRE(same_bits(got.time, want.time));
    REQUIRE(same_bits(got.position, want.position));
    REQUIRE(same_bits(got.velocity, want.velocity));
    REQUIRE(same_bits(got.energy, want.energy));
    REQUIRE(got.state_hash == want.state_hash);
    REQUIRE(got.position_raw == want.position_raw);
    REQUIRE(got.velocity_raw == want.velocity_raw);
  }
  for (std::int64_t i = 0; i < events; ++i) {
    const EventRecord want = make_event(i);
    const EventRecord& got = run.events[static_cast<std::size_t>(i)];
    INFO("event " << i);
    REQUIRE(same_bits(got.time, want.time));
    REQUIRE(got.kind == want.kind);
    REQUIRE(got.a == want.a);
    REQUIRE(got.b == want.b);
    REQUIRE(same_bits(got.impulse, want.impulse));
  }
}

inline void append(RunWriter& w, std::size_t n, std::int64_t frames_from, std::int64_t frames_to, std::int64_t events_from,
            std::int64_t events_to, bool raw = false) {
  for (std::int64_t i = frames_from; i < frames_to; ++i) w.append_frame(make_frame(i, n, raw));
  for (std::int64_t i = events_from; i < events_to; ++i) w.append_event(make_event(i));
}

inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const RunFileError& e) {
    return e.what();
  }
  return "";
}

// A real kill -9, from inside: no destructor, no flush, no atexit runs.
inline void die() { ::raise(SIGKILL); }

// Runs `body` in a child process; the body must end by calling die() while
// its writer is still alive. Fails if the child ends any other way (an
// exception, returning).
inline void run_and_kill(const std::function<void()>& body) {
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    try {
      body();
    } catch (...) {
      ::_exit(3);
    }
    ::_exit(4);
  }
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  REQUIRE(WIFSIGNALED(status));
  REQUIRE(WTERMSIG(status) == SIGKILL);
}

inline std::string read_string_attr(hid_t loc, const char* obj, const char* name) {
  const hid_t attr = H5Aopen_by_name(loc, obj, name, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(attr >= 0);
  const hid_t type = H5Aget_type(attr);
  REQUIRE(H5Tget_class(type) == H5T_STRING);
  std::vector<char> buf(H5Tget_size(type) + 1, '\0');
  REQUIRE(H5Aread(attr, type, buf.data()) >= 0);
  H5Tclose(type);
  H5Aclose(attr);
  return std::string(buf.data());
}


}  // namespace collide2d::test_io
