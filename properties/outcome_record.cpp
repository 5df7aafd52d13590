// Property outcomes appended to an HDF5 file (COLLIDE2D_PROPERTY_RECORD), so
// that deep runs can be compared over time (analysis/summarise_properties.py).
//
// Layout (every string a variable-length UTF-8 string; h5py reads them as str):
//
//   /                       attribute  format = "collide2d property outcomes 1"
//   /runs/<n>               one group per process that recorded something,
//                           n = 000000, 000001, ... in the order the runs began;
//                           attributes, written once per run:
//                             compiler    e.g. "gcc 12.2.0" (cli/build_info.hpp)
//                             build_type  CMake build type, "Release"
//                             build_date  when this executable was compiled
//                             hostname, cores (int32: hardware threads)
//                             started     ISO-8601 UTC time of the first record
//                             pid         (int64)
//                             label       env COLLIDE2D_PROPERTY_RUN_LABEL, or ""
//                                         (one label for the processes of one ctest run)
//   /runs/<n>/<k>           one group per property run, k = 000000, 000001, ...;
//                           attributes:
//                             property, mode, counterexample (text; "" on success)
//                             seed (uint64), max_success, max_size, cases,
//                             failures, gave_up (int32; gave_up 0 or 1)
//                             judged (int32: = cases, the cases a check
//                               applied to and judged), discarded (int32:
//                               cases a check did not apply to, neither
//                               passed nor failed), rejected (int32: thrown
//                               away by a generator's precondition)
//                             seconds (float64), recorded (ISO-8601 UTC)
//                           datasets, parallel, one entry per tag (may be empty):
//                             distribution_tags    1-D strings, sorted
//                             distribution_counts  1-D int64
//                           and, parallel, one entry per reason for a discard:
//                             discard_reasons      1-D strings, sorted
//                             discard_counts       1-D int64
//                           (judged, discarded, rejected and the discard
//                           datasets are absent from records written before
//                           they were added: readers take cases as judged)
//
// Appending adds groups only, so earlier records are never rewritten. Each
// record opens, writes and closes the file (a crash loses at most the record
// being written), holding an exclusive flock on FILE.lock meanwhile: ctest -j
// runs several property processes at once against the same file.
#include "outcome_record.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <thread>
#include <vector>

#include "cli/build_info.hpp"
#include "collide2d/io/run_file_hdf5.hpp"

#ifndef COLLIDE2D_BUILD_TYPE
#define COLLIDE2D_BUILD_TYPE "unknown"
#endif

namespace collide2d::properties {

namespace {

using namespace collide2d::h5;

constexpr const char* kFormat = "collide2d property outcomes 1";

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string host_name() {
  char buf[256] = {};
  if (gethostname(buf, sizeof buf - 1) != 0) return "unknown";
  return buf;
}

Hid vlen_string_type() {
  Hid type(H5Tcopy(H5T_C_S1), "string type");
  check_ok(H5Tset_size(type, H5T_VARIABLE), "string type");
  check_ok(H5Tset_cset(type, H5T_CSET_UTF8), "string type");
  return type;
}

void write_text_attribute(hid_t loc, const char* name, const std::string& value) {
  Hid type = vlen_string_type();
  Hid space(H5Screate(H5S_SCALAR), "dataspace");
  Hid a(H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT), std::string("attribute ") + name);
  const char* p = value.c_str();
  check_ok(H5Awrite(a, type, &p), std::string("write attribute ") + name);
}

template <class T>
void write_number_attribute(hid_t loc, const char* name, hid_t type, T value) {
  Hid space(H5Screate(H5S_SCALAR), "dataspace");
  Hid a(H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT), std::string("attribute ") + name);
  check_ok(H5Awrite(a, type, &value), std::string("write attribute ") + name);
}

// Number of links in a group: the next record's index.
hsize_t link_count(hid_t g) {
  H5G_info_t info{};
  check_ok(H5Gget_info(g, &info), "group info");
  return info.nlinks;
}

std::string six_digits(hsize_t n) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%06llu", static_cast<unsigned long long>(n));
  return buf;
}

// Holds an exclusive flock on `path` while alive.
class FileLock {
 public:
  explicit FileLock(const std::string& path) : fd_(::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644)) {
    if (fd_ < 0) throw Failure("cannot open lock file " + path);
    while (::flock(fd_, LOCK_EX) != 0) {
    }
  }
  ~FileLock() { ::close(fd_); }  // closing releases the lock
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int fd_;
};

Hid open_or_create(const std::string& path) {
  if (std::filesystem::exists(path)) return Hid(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open " + path);
  Hid file(H5Fcreate(path.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, H5P_DEFAULT), "create " + path);
  Hid root = group(file, "/", false);
  write_text_attribute(root, "format", kFormat);
  return file;
}

// The run group of this process in `file`: created with the build info at
// the process's first record into that file, remembered by path.
Hid run_group(hid_t file, const std::string& path) {
  static std::vector<std::pair<std::string, std::string>> known;  // path -> run group name
  Hid runs = link_exists(file, "/runs") ? group(file, "/runs", false) : group(file, "/runs", true);
  for (const auto& [p, name] : known)
    if (p == path && link_exists(file, "/runs/" + name)) return group(runs, name.c_str(), false);
  const std::string name = six_digits(link_count(runs));
  Hid run = group(runs, name.c_str(), true);
  write_text_attribute(run, "compiler", cli::compiler_description());
  write_text_attribute(run, "build_type", COLLIDE2D_BUILD_TYPE);
  write_text_attribute(run, "build_date", __DATE__ " " __TIME__);
  write_text_attribute(run, "hostname", host_name());
  write_number_attribute<std::int32_t>(run, "cores", H5T_NATIVE_INT32,
                                       static_cast<std::int32_t>(std::thread::hardware_concurrency()));
  write_text_attribute(run, "started", utc_now());
  write_number_attribute<std::int64_t>(run, "pid", H5T_NATIVE_INT64, static_cast<std::int64_t>(::getpid()));
  const char* label = std::getenv("COLLIDE2D_PROPERTY_RUN_LABEL");
  write_text_attribute(run, "label", label != nullptr ? label : "");
  std::erase_if(known, [&](const auto& entry) { return entry.first == path; });
  known.emplace_back(path, name);
  return run;
}

// Two parallel datasets: the keys (strings, sorted) and their counts.
void write_counts(hid_t g, const char* keys_name, const char* counts_name, const std::map<std::string, int>& counted) {
  std::vector<const char*> keys;
  std::vector<std::int64_t> counts;
  for (const auto& [key, count] : counted) keys.push_back(key.c_str()), counts.push_back(count);
  Hid type = vlen_string_type();
  write_array(g, keys_name, type, type, {keys.size()}, keys.data());
  write_array(g, counts_name, H5T_STD_I64LE, H5T_NATIVE_INT64, {counts.size()}, counts.data());
}

void append_outcome(const std::string& path, const PropertyOutcome& o) {
  QuietErrors quiet;
  FileLock lock(path + ".lock");
  Hid file = open_or_create(path);
  Hid run = run_group(file, path);
  Hid g = group(run, six_digits(link_count(run)).c_str(), true);
  write_text_attribute(g, "property", o.property);
  write_text_attribute(g, "mode", o.mode);
  write_number_attribute<std::uint64_t>(g, "seed", H5T_NATIVE_UINT64, o.seed);
  write_number_attribute<std::int32_t>(g, "max_success", H5T_NATIVE_INT32, o.max_success);
  write_number_attribute<std::int32_t>(g, "max_size", H5T_NATIVE_INT32, o.max_size);
  write_number_attribute<std::int32_t>(g, "cases", H5T_NATIVE_INT32, o.cases);
  write_number_attribute<std::int32_t>(g, "failures", H5T_NATIVE_INT32, o.failures);
  write_number_attribute<std::int32_t>(g, "gave_up", H5T_NATIVE_INT32, o.gave_up ? 1 : 0);
  write_number_attribute<std::int32_t>(g, "judged", H5T_NATIVE_INT32, o.cases);
  write_number_attribute<std::int32_t>(g, "discarded", H5T_NATIVE_INT32, o.discarded);
  write_number_attribute<std::int32_t>(g, "rejected", H5T_NATIVE_INT32, o.rejected);
  write_number_attribute<double>(g, "seconds", H5T_NATIVE_DOUBLE, o.seconds);
  write_text_attribute(g, "recorded", utc_now());
  write_text_attribute(g, "counterexample", o.counterexample);
  write_counts(g, "distribution_tags", "distribution_counts", o.distribution);
  write_counts(g, "discard_reasons", "discard_counts", o.discard_reasons);
  check_ok(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush " + path);
}

}  // namespace

// A record that cannot be written is reported on stderr, never thrown: the
// property's own verdict must not depend on the bookkeeping.
void record_property_outcome(const PropertyOutcome& outcome) {
  const char* path = std::getenv("COLLIDE2D_PROPERTY_RECORD");
  if (path == nullptr || *path == '\0') return;
  try {
    append_outcome(path, outcome);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "collide2d: cannot record property outcome in %s: %s\n", path, e.what());
  }
}

}  // namespace collide2d::properties
