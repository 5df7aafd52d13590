// The run file's reader. Layout and crash-safety design: see run_file.hpp.
#include <algorithm>
#include <filesystem>
#include <new>

#include "collide2d/io/run_file.hpp"
#include "collide2d/io/run_file_hdf5.hpp"
#include "collide2d/io/run_file_raw.hpp"

namespace collide2d {

using namespace h5;

namespace {

namespace fs = std::filesystem;

// HDF5 1.10 refuses a file whose superblock still says a writer has it open
// (the writer died) with this message, suggesting h5clear.
bool says_status_flag(const std::string& message) { return message.find("already open for write") != std::string::npos; }

// Opens a run file read-only, including one whose writer was killed.
// - A file killed in SWMR mode (any kill after the writer's constructor) keeps
//   the SWMR-write flag: plain read-only is refused, SWMR_READ is accepted and
//   never writes to the file.
// - A file killed outside SWMR mode (inside finish(), which reopens the file
//   without SWMR) keeps the plain write flag. That only clearing fixes: open it
//   read-write with the private file-access property "clear_status_flags",
//   exactly what `h5clear -s` does in 1.10 (HDF5 has no public call for it).
//   HDF5's file lock makes that open fail while a live writer holds the file.
Hid open_for_reading(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Failure("no such file");
  if (!fs::is_regular_file(path, ec)) throw Failure("not a regular file");
  if (fs::file_size(path, ec) == 0) throw Failure("empty file, not a run file");
  if (H5Fis_hdf5(path.c_str()) <= 0) fail("not an HDF5 file (or its superblock is damaged)");
  hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id >= 0) return Hid(id, "");
  const std::string first = describe_failure("cannot open the run file");
  if (!says_status_flag(first)) throw Failure(first);
  id = H5Fopen(path.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT);
  if (id >= 0) return Hid(id, "");
  H5Eclear2(H5E_DEFAULT);
  Hid fapl(H5Pcreate(H5P_FILE_ACCESS), "fapl");
  hbool_t clear = true;
  if (H5Pset(fapl, "clear_status_flags", &clear) >= 0) {
    const hid_t rw = H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl);
    if (rw >= 0) H5Fclose(rw);
  }
  H5Eclear2(H5E_DEFAULT);
  return Hid(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), first + "; clearing the status flag did not help");
}

// Extents needing more bytes than the file holds are corrupt (an extent says
// nothing of what was written: unwritten chunks read as zeros). They are
// refused before they turn into huge allocations or loops over billions of
// fill values. collide2d stores everything but the events as it is; the
// events may be deflated, which shrinks data at most 1032-fold.
void check_extent_fits(long double bytes_stored, long double file_bytes, const std::string& what) {
  if (bytes_stored > file_bytes) fail(what + ": dataset extents exceed the file size (corrupt file)");
}

template <class T>
std::vector<T> read_all(hid_t loc, const char* path, hid_t mtype, const std::vector<hsize_t>& tail,
                        long double file_bytes) {
  Hid d = dataset(loc, path);
  const auto dims = shape(d);
  if (dims.size() != tail.size() + 1 || !std::equal(tail.begin(), tail.end(), dims.begin() + 1))
    fail(std::string("unexpected shape of ") + path);
  hsize_t n = 1;
  long double bytes = sizeof(T);
  for (auto x : dims) n *= x, bytes *= static_cast<long double>(x);
  check_extent_fits(bytes, file_bytes, path);
  std::vector<T> out(n);
  if (n > 0) check_ok(H5Dread(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), std::string("read ") + path);
  return out;
}

RunHeader read_header(hid_t f, long double file_bytes) {
  if (!link_exists(f, "/h5md")) fail("not an H5MD file (no /h5md group)");
  RunHeader h;
  Hid h5md = group(f, "h5md", false);
  {
    Hid attr(H5Aopen(h5md, "version", H5P_DEFAULT), "missing /h5md version");
    Hid space(H5Aget_space(attr), "dataspace");
    int version[2] = {0, 0};
    if (H5Sget_simple_extent_npoints(space) != 2) fail("/h5md version is not two integers");
    check_ok(H5Aread(attr, H5T_NATIVE_INT, version), "read /h5md version");
    if (version[0] != 1) fail("H5MD version " + std::to_string(version[0]) + "." + std::to_string(version[1]) + " is not 1.x");
  }
  h.author = read_string(group(h5md, "author", false), "name", false);
  h.creator_version = read_string(group(h5md, "creator", false), "version", false);
  Hid parameters = group(f, "parameters", false);
  h.scene_json = read_string(parameters, "scene_json", true);
  h.options_json = read_string(parameters, "options_json", true);
  h.mode = read_string(parameters, "mode", false);
  h.compiler = read_string(parameters, "compiler", false);
  h.radius = read_all<double>(parameters, "radius", H5T_NATIVE_DOUBLE, {}, file_bytes);
  h.mass = read_all<double>(parameters, "mass", H5T_NATIVE_DOUBLE, {}, file_bytes);
  if (h.mass.size() != h.radius.size()) fail("/parameters/mass and radius have different lengths");
  const auto walls = read_all<double>(parameters, "walls", H5T_NATIVE_DOUBLE, {4}, file_bytes);
  for (std::size_t i = 0; i + 4 <= walls.size(); i += 4) h.walls.push_back({walls[i], walls[i + 1], walls[i + 2], walls[i + 3]});
  // Stored since the run file described its walls; older files lack it.
  if (link_exists(parameters, "wall_restitution")) {
    h.wall_restitution = read_all<double>(parameters, "wall_restitution", H5T_NATIVE_DOUBLE, {}, file_bytes);
    if (h.wall_restitution.size() != h.walls.size()) fail("/parameters/wall_restitution and walls have different lengths");
  }
  if (h.radius.empty()) fail("/parameters/radius is empty");
  return h;
}

// The common length of a group of series that grow together; a finished file
// must have them all equal, a killed one may have some a little longer.
hsize_t common_rows(std::initializer_list<hid_t> series, bool finished, const char* what) {
  hsize_t lo = ~hsize_t{0}, hi = 0;
  for (hid_t d : series) {
    const auto dims = shape(d);
    if (dims.empty()) fail(std::string("a ") + what + " dataset is scalar");
    lo = std::min(lo, dims[0]);
    hi = std::max(hi, dims[0]);
  }
  if (finished && lo != hi) fail(std::string("the ") + what + " datasets have different lengths");
  return lo;
}

void check_row_shape(hid_t d, const std::vector<hsize_t>& row_shape, const char* name) {
  const auto dims = shape(d);
  if (dims.size() != row_shape.size() + 1 || !std::equal(row_shape.begin(), row_shape.end(), dims.begin() + 1))
    fail(std::string("unexpected shape of ") + name);
}

template <class T>
T read_one(hid_t d, hid_t mtype, hsize_t row) {
  T value{};
  read_rows(d, mtype, row, 1, &value);
  return value;
}

// Every record present in all five checkpoint datasets (a kill inside
// checkpoint() can leave some one row longer), oldest first, each checked
// against the data. A record's engine state is what its region of
// /checkpoint/engine_state holds now: exact for the last one (the next
// checkpoint writes elsewhere), possibly overwritten for older ones.
// RunWriter::checkpoint records counts that never decrease, and resume copies
// the frames and events of each record in turn: a record counting more than
// a later one (or than the file holds) is refused.
std::vector<Checkpoint> checkpoints(const Series& s, hsize_t frames, hsize_t events, long double file_bytes) {
  // One number per row: a dataset with rows of more would be read past the
  // single value each row is read into (fuzz_run_file found a stack overflow).
  for (hid_t d : {hid_t{s.cp_time}, hid_t{s.cp_frames}, hid_t{s.cp_events}, hid_t{s.cp_offset}, hid_t{s.cp_size},
                  hid_t{s.cp_state}})
    check_row_shape(d, {}, "a /checkpoint dataset");
  const hsize_t k = common_rows({s.cp_time, s.cp_frames, s.cp_events, s.cp_offset, s.cp_size}, false, "checkpoint");
  check_extent_fits(static_cast<long double>(k) * 40, file_bytes, "/checkpoint");
  const hsize_t state_bytes = shape(s.cp_state).at(0);
  std::vector<Checkpoint> all;
  std::int64_t frames_before = 0, events_before = 0;
  for (hsize_t row = 0; row < k; ++row) {
    Checkpoint cp;
    cp.time = read_one<double>(s.cp_time, H5T_NATIVE_DOUBLE, row);
    cp.frames_written = read_one<std::int64_t>(s.cp_frames, H5T_NATIVE_INT64, row);
    cp.events_written = read_one<std::int64_t>(s.cp_events, H5T_NATIVE_INT64, row);
    const auto offset = read_one<std::int64_t>(s.cp_offset, H5T_NATIVE_INT64, row);
    const auto size = read_one<std::int64_t>(s.cp_size, H5T_NATIVE_INT64, row);
    // offset + size is not formed before both are known to be at most
    // state_bytes: two int64 near 2^63 would overflow.
    if (cp.frames_written < frames_before || static_cast<hsize_t>(cp.frames_written) > frames ||
        cp.events_written < events_before || static_cast<hsize_t>(cp.events_written) > events || offset < 0 ||
        size < 0 || static_cast<hsize_t>(offset) > state_bytes ||
        static_cast<hsize_t>(size) > state_bytes - static_cast<hsize_t>(offset))
      fail("a checkpoint record does not match the data in the file");
    check_extent_fits(static_cast<long double>(size), file_bytes, "/checkpoint/engine_state");
    frames_before = cp.frames_written;
    events_before = cp.events_written;
    cp.engine_state.resize(static_cast<std::size_t>(size));
    read_rows(s.cp_state, H5T_NATIVE_UINT8, static_cast<hsize_t>(offset), static_cast<hsize_t>(size),
              cp.engine_state.data());
    all.push_back(std::move(cp));
  }
  return all;
}

RunContents read_contents(const std::string& path) {
  Hid file = open_for_reading(path);
  std::error_code ec;
  const auto file_bytes = static_cast<long double>(fs::file_size(path, ec));
  RunContents run;
  run.header = read_header(file, file_bytes);
  const hsize_t n = run.header.radius.size();
  run.finished = link_exists(file, "/observables/summary");
  if (run.finished) run.summary_json = read_string(file, "/observables/summary", true);

  const Series s = open_series(file);
  check_row_shape(s.position, {n, 2}, "/particles/balls/position/value");
  check_row_shape(s.velocity, {n, 2}, "/particles/balls/velocity/value");
  for (hid_t d : {hid_t{s.step}, hid_t{s.time}, hid_t{s.energy}, hid_t{s.hash}})
    check_row_shape(d, {}, "a per-frame series");
  for (hid_t d : {hid_t{s.ev_time}, hid_t{s.ev_kind}, hid_t{s.ev_a}, hid_t{s.ev_b}, hid_t{s.ev_impulse}})
    check_row_shape(d, {}, "an /events dataset");
  hsize_t frames_in_file =
      common_rows({s.step, s.time, s.position, s.velocity, s.energy, s.hash}, run.finished, "per-frame");
  const bool raw = s.position_raw >= 0;  // fixed mode; older fixed-mode files lack them too
  if (raw) {
    const hsize_t raw_frames = raw_rows(s, n);
    if (run.finished && raw_frames != frames_in_file) fail("the per-frame datasets have different lengths");
    frames_in_file = std::min(frames_in_file, raw_frames);
  }
  const hsize_t events_in_file =
      common_rows({s.ev_time, s.ev_kind, s.ev_a, s.ev_b, s.ev_impulse}, run.finished, "/events");
  run.checkpoints = checkpoints(s, frames_in_file, events_in_file, file_bytes);
  if (!run.checkpoints.empty()) run.last_checkpoint = run.checkpoints.back();

  // Past the last checkpoint an unfinished file holds whatever the kill left.
  hsize_t frames = frames_in_file, events = events_in_file;
  if (!run.finished) {
    frames = run.last_checkpoint ? static_cast<hsize_t>(run.last_checkpoint->frames_written) : 0;
    events = run.last_checkpoint ? static_cast<hsize_t>(run.last_checkpoint->events_written) : 0;
  }
  // The frames and events to be read must fit the file (check_extent_fits).
  const long double words_per_frame = 4.0L * n + 4 + (raw ? 8.0L * n : 0);
  check_extent_fits(
      static_cast<long double>(frames) * words_per_frame * 8 + static_cast<long double>(events) * 28 / 1032,
      file_bytes, "frames and events");

  std::vector<std::int64_t> step(frames);
  std::vector<double> time(frames), energy(frames), pos(frames * n * 2), vel(frames * n * 2);
  std::vector<std::uint64_t> hash(frames);
  read_rows(s.step, H5T_NATIVE_INT64, 0, frames, step.data());
  read_rows(s.time, H5T_NATIVE_DOUBLE, 0, frames, time.data());
  read_rows(s.position, H5T_NATIVE_DOUBLE, 0, frames, pos.data());
  read_rows(s.velocity, H5T_NATIVE_DOUBLE, 0, frames, vel.data());
  read_rows(s.energy, H5T_NATIVE_DOUBLE, 0, frames, energy.data());
  read_rows(s.hash, H5T_NATIVE_UINT64, 0, frames, hash.data());
  run.frames.resize(frames);
  for (hsize_t i = 0; i < frames; ++i) {
    FrameRecord& f = run.frames[i];
    f.step = step[i], f.time = time[i], f.energy = energy[i], f.state_hash = hash[i];
    f.position.assign(pos.begin() + i * n * 2, pos.begin() + (i + 1) * n * 2);
    f.velocity.assign(vel.begin() + i * n * 2, vel.begin() + (i + 1) * n * 2);
  }
  if (raw) read_raw_frames(s, n, run.frames);

  std::vector<double> ev_time(events), impulse(events);
  std::vector<int> kind(events), a(events), b(events);
  read_rows(s.ev_time, H5T_NATIVE_DOUBLE, 0, events, ev_time.data());
  read_rows(s.ev_kind, H5T_NATIVE_INT, 0, events, kind.data());
  read_rows(s.ev_a, H5T_NATIVE_INT, 0, events, a.data());
  read_rows(s.ev_b, H5T_NATIVE_INT, 0, events, b.data());
  read_rows(s.ev_impulse, H5T_NATIVE_DOUBLE, 0, events, impulse.data());
  run.events.resize(events);
  for (hsize_t i = 0; i < events; ++i) run.events[i] = EventRecord{ev_time[i], kind[i], a[i], b[i], impulse[i]};
  return run;
}

}  // namespace

RunContents read_run_file(const std::string& path) {
  QuietErrors quiet;
  try {
    return read_contents(path);
  } catch (const Failure& e) {
    throw RunFileError(path + ": " + e.what());
  } catch (const std::bad_alloc&) {
    throw RunFileError(path + ": too large to read into memory");
  } catch (const std::length_error&) {
    throw RunFileError(path + ": implausible dataset sizes (corrupt file)");
  } catch (const std::out_of_range&) {
    throw RunFileError(path + ": unexpected dataset shape (corrupt file)");
  }
}

}  // namespace collide2d
