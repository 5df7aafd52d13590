// fuzz_run_file_bytes: raw bytes as a run file, through read_run_file. Not run
// by run_fuzzers.sh or CI: what it finds is inside libhdf5 (a leak on the
// error path of a corrupted object header, within seconds), which we cannot
// fix; run it with ASAN_OPTIONS=detect_leaks=0 to get past that. Kept to
// measure HDF5 (fuzz/README.md, "Raw bytes") and to try again with a later
// one. Seed: a real run file (datasets/fuzz/run_file_bytes/).
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include <hdf5.h>

#include "collide2d/io/run_file.hpp"

namespace {
std::string path;
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  path = "/dev/shm/collide2d-fuzz-bytes-" + std::to_string(::getpid()) + ".h5";
  if (!std::ofstream(path)) path = "/tmp/collide2d-fuzz-bytes-" + std::to_string(::getpid()) + ".h5";
  std::atexit([] { std::remove(path.c_str()); });
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                 static_cast<std::streamsize>(size));
  try {
    collide2d::read_run_file(path);
  } catch (const collide2d::RunFileError&) {
  }
  return 0;
}
