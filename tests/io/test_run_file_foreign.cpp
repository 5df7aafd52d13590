// Run files written on x86-64 (datasets/determinism/run_x86_64_*.h5, by a gcc
// -O3 build), read on whatever machine runs this test: under qemu on aarch64,
// ppc64le and i686 (issue 15). The file declares its byte order (every number
// dataset little-endian, whatever the writer's), HDF5 converts on read, and
// the raw fixed-point words mean the same Fixed here as on x86-64: they
// round-trip through this machine's Fixed (two-word on i686) and round to the
// very doubles x86-64 stored beside them. `collide2d replay` of the same files
// (tests/cli/replay_stored.cmake) re-simulates them here, bit for bit.
#include <catch2/catch.hpp>

#include <hdf5.h>

#include <cstring>
#include <filesystem>
#include <string>

#include "collide2d/io/run_file.hpp"
#include "collide2d/numeric/fixed_words.hpp"

using namespace collide2d;

namespace {

const std::string kDir = COLLIDE2D_DETERMINISM_DIR;

bool same_bits(double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; }

// The byte order and width HDF5 records for a dataset's elements in the file.
struct StoredType {
  H5T_class_t type_class;
  H5T_order_t order;
  std::size_t size;
};

StoredType stored_type(const std::string& file, const char* path) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  const hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
  REQUIRE(d >= 0);
  const hid_t t = H5Dget_type(d);
  const StoredType s{H5Tget_class(t), H5Tget_order(t), H5Tget_size(t)};
  H5Tclose(t);
  H5Dclose(d);
  H5Fclose(f);
  return s;
}

}  // namespace

TEST_CASE("a run file from x86-64 declares little-endian numbers", "[io][cross]") {
  for (const char* mode : {"strict", "fixed"}) {
    const std::string file = kDir + "/run_x86_64_" + mode + ".h5";
    INFO(file);
    REQUIRE(std::filesystem::exists(file));
    for (const char* path : {"/particles/balls/position/value", "/particles/balls/velocity/value",
                             "/particles/balls/position/time", "/events/time", "/events/impulse"}) {
      INFO(path);
      const StoredType t = stored_type(file, path);
      CHECK(t.type_class == H5T_FLOAT);
      CHECK(t.order == H5T_ORDER_LE);
      CHECK(t.size == 8);
    }
    if (std::string(mode) == "fixed") {
      for (const char* path : {"/particles/balls/position_raw/value", "/particles/balls/velocity_raw/value"}) {
        INFO(path);
        const StoredType t = stored_type(file, path);
        CHECK(t.type_class == H5T_INTEGER);
        CHECK(t.order == H5T_ORDER_LE);
        CHECK(t.size == 8);
      }
    }
  }
}

TEST_CASE("raw fixed-point words from x86-64 are the same Fixed values here", "[io][cross]") {
  const RunContents run = read_run_file(kDir + "/run_x86_64_fixed.h5");
  REQUIRE(run.header.mode == "fixed");
  REQUIRE(run.finished);
  REQUIRE(run.frames.size() >= 2);
  const std::size_t coordinates = 2 * run.header.radius.size();
  std::size_t checked = 0, negative_hi = 0, high_lo = 0;
  for (const FrameRecord& f : run.frames) {
    REQUIRE(f.position_raw.size() == 2 * coordinates);
    REQUIRE(f.velocity_raw.size() == 2 * coordinates);
    for (std::size_t k = 0; k < coordinates; ++k) {
      for (const auto& [raw, doubles] : {std::pair{&f.position_raw, &f.position}, std::pair{&f.velocity_raw, &f.velocity}}) {
        const std::int64_t hi = (*raw)[2 * k], lo = (*raw)[2 * k + 1];
        INFO("frame " << f.step << ", coordinate " << k << ": hi " << hi << " lo " << lo);
        const Fixed x = from_words(hi, lo);
        const FixedWords back = to_words(x);
        REQUIRE(back.hi == hi);
        REQUIRE(back.lo == lo);
        // x86-64 rounded the exact value to this double; so must this machine.
        REQUIRE(same_bits(x.to_double(), (*doubles)[k]));
        ++checked;
        negative_hi += hi < 0;
        high_lo += lo < 0;  // low word with its top bit set: read as unsigned
      }
    }
  }
  // The words exercised both signs of the high word and the low word's top
  // bit, where a sign or width mistake would show.
  CHECK(checked > 100);
  CHECK(negative_hi > 0);
  CHECK(high_lo > 0);
}

TEST_CASE("a strict run file from x86-64 holds no raw words and reads whole", "[io][cross]") {
  const RunContents run = read_run_file(kDir + "/run_x86_64_strict.h5");
  REQUIRE(run.header.mode == "strict");
  REQUIRE(run.finished);
  REQUIRE(run.frames.size() >= 2);
  for (const FrameRecord& f : run.frames) {
    CHECK(f.position_raw.empty());
    CHECK(f.position.size() == 2 * run.header.radius.size());
  }
  CHECK_FALSE(run.events.empty());
}
