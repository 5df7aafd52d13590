// Internals of the run file shared by its writer (run_file.cpp) and reader
// (run_file_read.cpp): owning HDF5 identifiers, error capture, strings, and
// the chunked time series. Not part of the public interface.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace collide2d::h5 {

// An HDF5 call failed; the public functions rethrow it as a RunFileError that
// names the file.
struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `what` and the innermost message on HDF5's error stack, which it clears.
std::string describe_failure(const std::string& what);
// Throws Failure(describe_failure(what)).
[[noreturn]] void fail(const std::string& what);
hid_t check_id(hid_t id, const std::string& what);
void check_ok(herr_t status, const std::string& what);

// HDF5 prints its error stack on stderr by default. We report errors as
// exceptions instead, so it is silenced while one of our functions runs.
class QuietErrors {
 public:
  QuietErrors() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

void close_any(hid_t id);

// Owns one HDF5 identifier of any kind.
class Hid {
 public:
  Hid() = default;
  Hid(hid_t id, const std::string& what) : id_(check_id(id, what)) {}
  ~Hid() { reset(); }
  Hid(Hid&& o) noexcept : id_(std::exchange(o.id_, -1)) {}
  Hid& operator=(Hid&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, -1);
    }
    return *this;
  }
  operator hid_t() const { return id_; }
  hid_t release() { return std::exchange(id_, -1); }
  void reset() {
    if (id_ >= 0) close_any(std::exchange(id_, -1));
  }

 private:
  hid_t id_ = -1;
};

Hid group(hid_t loc, const char* name, bool create);
Hid dataset(hid_t loc, const char* path);
bool link_exists(hid_t file, const std::string& path);

// H5MD strings: fixed-length, null-terminated, UTF-8; `length` excludes the NUL.
Hid string_type(std::size_t length);
void write_string(hid_t loc, const char* name, const std::string& value, bool as_dataset);
std::string read_string(hid_t loc, const char* name, bool as_dataset);
// A 1-D attribute of strings, each padded to the longest (labels, column names).
void write_string_list(hid_t loc, const char* name, const std::vector<std::string>& values);

// An int32 attribute: a scalar for one value, 1-D for several.
void write_int_attribute(hid_t loc, const char* name, const std::vector<int>& values);

// A contiguous dataset written once (the parameters); zero-sized dims allowed.
void write_array(hid_t loc, const char* name, hid_t ftype, hid_t mtype, std::vector<hsize_t> dims, const void* data);
std::vector<hsize_t> shape(hid_t dataset);

// A time series: chunked and unlimited along its first axis only; with
// `compressed`, each chunk is shuffled and deflated (lossless).
Hid create_series(hid_t loc, const char* name, hid_t ftype, std::vector<hsize_t> row_shape, hsize_t chunk_rows,
                  bool compressed = false);
void write_rows(hid_t dataset, hid_t mtype, hsize_t at, hsize_t n, const void* data);
void read_rows(hid_t dataset, hid_t mtype, hsize_t at, hsize_t n, void* out);
// Entries [first, first + n) along the second axis of row `at` (a slice of a
// frame's balls), growing the extent to hold the row first.
void write_row_part(hid_t dataset, hid_t mtype, hsize_t at, hsize_t first, hsize_t n, const void* data);
// A chunked dataset's chunk extent along `axis`.
hsize_t chunk_extent(hid_t dataset, int axis);

// A further H5MD element `name` in `parent`: a group whose step and time are
// hard links to those of `axes` (so they can never disagree) and a `value`
// series. Returns the group.
Hid create_element(hid_t parent, const char* name, hid_t axes, hid_t ftype, std::vector<hsize_t> row_shape,
                   hsize_t chunk_rows);

// A file access property list for the HDF5 1.10 format.
Hid latest_format_fapl();

// The datasets of a run file that grow as it is written.
// position_raw and velocity_raw exist in fixed-mode files only (else -1).
struct Series {
  Hid step, time, position, velocity, energy, hash;
  Hid position_raw, velocity_raw;
  Hid ev_time, ev_kind, ev_a, ev_b, ev_impulse;
  Hid cp_time, cp_frames, cp_events, cp_offset, cp_size, cp_state;
};
Series open_series(hid_t file);

// Where the raw series live (run_file_raw.cpp writes and reads them).
inline constexpr const char* kPositionRawPath = "/particles/balls/position_raw/value";
inline constexpr const char* kVelocityRawPath = "/particles/balls/velocity_raw/value";

}  // namespace collide2d::h5
