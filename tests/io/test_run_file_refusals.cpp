// Damaged run files the reader refuses with RunFileError, each once a memory
// error, undefined behaviour or a read without end (fuzz_run_file and the
// review around its findings; fuzz/README.md), and strings in the other
// character set, once refused. Each test writes a good file with RunWriter,
// then replaces one dataset through HDF5's C API.
#include <catch2/catch.hpp>

#include <cstdint>
#include <limits>
#include <vector>

#include "run_file_fixtures.hpp"

using namespace collide2d;
using namespace collide2d::test_io;

namespace {

// An unfinished run of 2 balls with two checkpoints, at 10 and 20 frames.
std::string partial_with_two_checkpoints(const TempDir& tmp) {
  const std::string path = tmp / "run.h5";
  RunWriter w(path, make_header(2));
  append(w, 2, 0, 10, 0, 30);
  w.checkpoint(make_checkpoint(0.2, 16, 1));
  append(w, 2, 10, 20, 30, 60);
  w.checkpoint(make_checkpoint(0.4, 16, 2));
  return w.partial_path();  // the writer is dropped: the partial file stays
}

// Replaces the dataset at `path` by one of `dims` (chunked, extendible along
// the first axis, as the writer's series are) holding `values` (int64, row
// major; fewer than the extent: the rest is never written).
void replace_int64(const std::string& file_path, const char* path, std::vector<hsize_t> dims,
                   const std::vector<std::int64_t>& values) {
  const hid_t f = H5Fopen(file_path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  REQUIRE(f >= 0);
  REQUIRE(H5Ldelete(f, path, H5P_DEFAULT) >= 0);
  std::vector<hsize_t> maxdims = dims, chunk = dims;
  maxdims[0] = H5S_UNLIMITED;
  chunk[0] = 64;
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims.data());
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  REQUIRE(H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data()) >= 0);
  const hid_t d = H5Dcreate2(f, path, H5T_STD_I64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  REQUIRE(d >= 0);
  if (!values.empty()) {
    const hsize_t count = values.size();
    const hid_t mspace = H5Screate_simple(1, &count, nullptr);
    const hid_t fspace = H5Dget_space(d);
    std::vector<hsize_t> start(dims.size(), 0), block = dims;
    block[0] = count;
    for (std::size_t i = 1; i < dims.size(); ++i) block[0] /= dims[i];
    REQUIRE(H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start.data(), nullptr, block.data(), nullptr) >= 0);
    REQUIRE(H5Dwrite(d, H5T_NATIVE_INT64, mspace, fspace, H5P_DEFAULT, values.data()) >= 0);
    H5Sclose(fspace);
    H5Sclose(mspace);
  }
  H5Dclose(d);
  H5Pclose(dcpl);
  H5Sclose(space);
  H5Fclose(f);
}

}  // namespace

TEST_CASE("run file refused: checkpoint records with two numbers a row", "[io][refusals]") {
  // Each record was read into one int64 on the stack, a row of two written
  // past it (AddressSanitizer: stack-buffer-overflow, fuzz_run_file).
  TempDir tmp;
  const std::string path = partial_with_two_checkpoints(tmp);
  replace_int64(path, "/checkpoint/frames_written", {2, 2}, {10, 10, 20, 20});
  CHECK(error_of([&] { read_run_file(path); }).find("unexpected shape of a /checkpoint dataset") != std::string::npos);
}

TEST_CASE("run file refused: a checkpoint whose offset and size add past int64", "[io][refusals]") {
  // offset + size was formed in int64: undefined for these (UBSan).
  TempDir tmp;
  const std::string path = partial_with_two_checkpoints(tmp);
  replace_int64(path, "/checkpoint/engine_state_offset", {2}, {0, std::numeric_limits<std::int64_t>::max()});
  CHECK(error_of([&] { read_run_file(path); }).find("a checkpoint record does not match") != std::string::npos);
}

TEST_CASE("run file refused: checkpoint counts that go back", "[io][refusals]") {
  // Records of 20 then 10 frames: the reader kept 10 frames (the last
  // record's), and resume copied frames 10 to 19 of those 10 (a read past
  // the end of a vector).
  TempDir tmp;
  const std::string path = partial_with_two_checkpoints(tmp);
  REQUIRE(read_run_file(path).frames.size() == 20);  // untouched, it reads
  replace_int64(path, "/checkpoint/frames_written", {2}, {20, 10});
  CHECK(error_of([&] { read_run_file(path); }).find("a checkpoint record does not match") != std::string::npos);
  CHECK(error_of([&] { resume_run_file(path); }).find("a checkpoint record does not match") != std::string::npos);
}

TEST_CASE("run file refused: an extent of 2^40 rows with nothing written", "[io][refusals]") {
  // Unwritten chunks read as zeros: a few bytes of metadata could claim a
  // trillion checkpoint records or engine-state bytes, read one by one.
  TempDir tmp;
  const std::string path = partial_with_two_checkpoints(tmp);
  for (const char* name : {"/checkpoint/time", "/checkpoint/frames_written", "/checkpoint/events_written",
                           "/checkpoint/engine_state_offset", "/checkpoint/engine_state_size"})
    replace_int64(path, name, {hsize_t{1} << 40}, {});
  CHECK(error_of([&] { read_run_file(path); }).find("/checkpoint: dataset extents exceed the file size") !=
        std::string::npos);
}

TEST_CASE("run file: strings in ASCII, as h5py writes them by default, are read", "[io][refusals]") {
  // HDF5 converts strings within one character set only: the reader asked
  // for UTF-8 and refused ASCII ("no appropriate function for conversion
  // path"). Fixed and variable length.
  TempDir tmp;
  const std::string path = tmp / "run.h5";
  {
    RunWriter w(path, make_header(2));
    w.finish("{}");
  }
  const std::string scene = make_header(2).scene_json;
  for (const bool variable : {false, true}) {
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    REQUIRE(f >= 0);
    REQUIRE(H5Ldelete(f, "/parameters/scene_json", H5P_DEFAULT) >= 0);
    const hid_t type = H5Tcopy(H5T_C_S1);
    REQUIRE(H5Tset_size(type, variable ? H5T_VARIABLE : scene.size() + 1) >= 0);
    REQUIRE(H5Tset_cset(type, H5T_CSET_ASCII) >= 0);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t d = H5Dcreate2(f, "/parameters/scene_json", type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    REQUIRE(d >= 0);
    const char* text = scene.c_str();
    REQUIRE(H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, variable ? static_cast<const void*>(&text) : text) >= 0);
    H5Dclose(d);
    H5Sclose(space);
    H5Tclose(type);
    H5Fclose(f);
    INFO((variable ? "variable length" : "fixed length"));
    CHECK(read_run_file(path).header.scene_json == scene);
  }
}
