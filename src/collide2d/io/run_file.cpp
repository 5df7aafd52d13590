// The run file's writer and resume over the HDF5 1.10 C API. Layout and
// crash-safety design: see run_file.hpp; the reader is run_file_read.cpp.
#include "collide2d/io/run_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <optional>
#include <utility>

#include "collide2d/io/run_file_hdf5.hpp"
#include "collide2d/io/run_file_raw.hpp"

namespace collide2d {

using namespace h5;

namespace {

namespace fs = std::filesystem;

constexpr hsize_t kEventChunk = 4096;  // 32 KiB per chunk of doubles
constexpr hsize_t kSeriesChunk = 512;  // 1-D per-frame series

// Frames per chunk of position/velocity (and their raw words): up to 64, at
// most ~512 KiB per chunk of the widest so one chunk fits HDF5's default
// 1 MiB chunk cache.
hsize_t frame_chunk_rows(std::size_t n_balls, bool raw) {
  const hsize_t bytes_per_frame = static_cast<hsize_t>(n_balls) * 2 * sizeof(double) * (raw ? 2 : 1);
  return std::clamp<hsize_t>((512 * 1024) / bytes_per_frame, 1, 64);
}

// rename() is atomic, but only durable once the data and the directory entry
// reach the disk; without these a power cut could leave an empty file.
void fsync_path(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? O_RDONLY | O_DIRECTORY : O_RDONLY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

std::string with_path(const std::string& path, const std::exception& e) { return path + ": " + e.what(); }

// Runs an HDF5 step with the library's own error printing off; a failure
// becomes a RunFileError naming the file.
template <class Step>
void naming_the_file(const std::string& path, Step step) {
  QuietErrors quiet;
  try {
    step();
  } catch (const Failure& e) {
    throw RunFileError(with_path(path, e));
  }
}

// A scene's numbers carry no units: collide2d takes whatever units the scene
// was written in. An H5MD `unit` attribute would claim more than is known, so
// there is none, and this says so instead.
constexpr const char* kUnits =
    "lengths, times and masses are in the scene's own units (collide2d fixes none; SI, m s kg, is customary); "
    "velocity is length/time, impulse mass*length/time, energy mass*length^2/time^2. Hence no H5MD unit attributes.";

// Attributes that make the file self-describing for someone opening it with
// h5py or HDFView: what the event columns and the wall rows mean.
void describe_layout(hid_t file) {
  write_string(group(file, "particles/balls", false), "units", kUnits, false);
  write_string(group(file, "parameters", false), "units", kUnits, false);
  write_string(group(file, "events", false), "description",
               "every collision, one row each, in the order the engine processed them", false);
  auto describe = [&](const char* path, const char* text) {
    write_string(dataset(file, path), "description", text, false);
  };
  describe("/events/time", "when the collision happened");
  describe("/events/kind", "what collided: 0 ball-ball, 1 ball-wall (attribute labels, indexed by kind)");
  write_string_list(dataset(file, "/events/kind"), "labels", {"ball-ball", "ball-wall"});
  describe("/events/a", "a ball (row of /particles/balls)");
  describe("/events/b", "kind 0: the other ball (row of /particles/balls); kind 1: the wall (row of /parameters/walls)");
  describe("/events/impulse", "magnitude of the normal impulse on ball a (mass x speed)");
  describe("/particles/balls/mass", "each ball's mass (the same values as /parameters/mass)");
  describe("/particles/balls/radius", "each ball's radius (the same values as /parameters/radius)");
  describe("/parameters/walls",
           "one row per wall: the segment from (ax, ay) to (bx, by), two-sided with round ends (a ball can strike "
           "either face or either end)");
  write_string_list(dataset(file, "/parameters/walls"), "columns", {"ax", "ay", "bx", "by"});
  if (link_exists(file, "/parameters/wall_restitution"))
    describe("/parameters/wall_restitution",
             "each wall's restitution; a contact's is the product of its two objects' values");
}

}  // namespace

std::string partial_run_path(const std::string& path) { return path + ".partial"; }

bool stores_raw_values(const RunHeader& header) { return header.mode == "fixed"; }

// ---------------------------------------------------------------- writing

struct RunWriter::Impl {
  std::string path, partial;
  std::size_t n_balls = 0;
  bool raw = false;  // the file has the *_raw series (fixed mode)
  hsize_t frame_chunk = 1;
  std::size_t slice_balls = 0;   // balls_per_frame_slice()
  std::size_t sliced_balls = 0;  // of the frame being written in slices
  double sliced_time = 0;        // that frame's time
  Hid file;
  Series ds;
  std::int64_t frames_on_disk = 0, events_on_disk = 0, checkpoints = 0;
  hsize_t state_offset = 0, state_size = 0;  // the committed engine state
  bool checkpointed = false, finished = false;
  bool scene_text_written = false;  // by with_scene_text: create() skips it
  bool header_written = false;
  // Appended but not yet written.
  std::vector<std::int64_t> f_step;
  std::vector<double> f_time, f_pos, f_vel, f_energy;
  std::vector<std::uint64_t> f_hash;
  std::vector<std::int64_t> f_pos_raw, f_vel_raw;
  std::vector<double> e_time, e_impulse;
  std::vector<int> e_kind, e_a, e_b;

  Impl(std::string final_path, std::string work_path) : path(std::move(final_path)), partial(std::move(work_path)) {}

  // Without finish(): the partial file goes, unless a checkpoint made it
  // resumable. Errors cannot be reported from here and are ignored.
  ~Impl() {
    if (finished) return;
    QuietErrors quiet;
    ds = Series{};
    file.reset();
    std::error_code ec;
    if (!checkpointed) fs::remove(partial, ec);
  }

  void create_with_scene_text(const std::string& scene_json);
  void create(const RunHeader& h);
  void require_header() const {
    if (!header_written) throw RunFileError(partial + ": nothing can be written before the run's header");
  }
  void require_no_unfinished_frame() const {
    if (sliced_balls > 0)
      throw RunFileError(partial + ": a frame given in slices is unfinished (" + std::to_string(sliced_balls) + " of " +
                         std::to_string(n_balls) + " balls)");
  }
  void write_frames();
  void write_frame_series(hsize_t n, const std::int64_t* step, const double* time, const double* energy,
                          const std::uint64_t* hash);
  void write_frame_rows(hsize_t n, const std::int64_t* step, const double* time, const double* pos, const double* vel,
                        const double* energy, const std::uint64_t* hash, const std::int64_t* pos_raw,
                        const std::int64_t* vel_raw);
  void write_events();
  void checkpoint(const Checkpoint& cp);
  void finish(const std::string& summary);
};

// Builds the whole layout, then switches to SWMR: after that no object may be
// created, so everything (checkpoint datasets included) exists from the start.
void RunWriter::Impl::create(const RunHeader& h) {
  n_balls = h.radius.size();
  if (n_balls == 0) throw Failure("a run needs at least one ball");
  if (h.mass.size() != n_balls) throw Failure("radius and mass have different lengths");
  if (!h.wall_restitution.empty() && h.wall_restitution.size() != h.walls.size())
    throw Failure("wall_restitution and walls have different lengths");
  raw = stores_raw_values(h);
  frame_chunk = frame_chunk_rows(n_balls, raw);
  if (!scene_text_written) {
    Hid fapl = latest_format_fapl();
    file = Hid(H5Fcreate(partial.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), "cannot create the run file");
  }

  // Attributes are closed as soon as written: SWMR cannot start while any is open.
  const hsize_t two = 2;
  Hid space2(H5Screate_simple(1, &two, nullptr), "dataspace"), scalar(H5Screate(H5S_SCALAR), "dataspace");
  auto attribute = [](hid_t loc, const char* name, hid_t ftype, hid_t mtype, hid_t space, const void* value) {
    Hid a(H5Acreate2(loc, name, ftype, space, H5P_DEFAULT, H5P_DEFAULT), std::string("create ") + name);
    check_ok(H5Awrite(a, mtype, value), std::string("write ") + name);
  };
  Hid h5md = group(file, "h5md", true);
  const int version[2] = {1, 1};
  attribute(h5md, "version", H5T_STD_I32LE, H5T_NATIVE_INT, space2, version);
  write_string(group(h5md, "author", true), "name", h.author, false);
  Hid creator = group(h5md, "creator", true);
  write_string(creator, "name", "collide2d", false);
  write_string(creator, "version", h.creator_version, false);

  Hid particles = group(file, "particles", true);
  Hid balls = group(particles, "balls", true);
  Hid box = group(balls, "box", true);
  const int two_d = 2;
  attribute(box, "dimension", H5T_STD_I32LE, H5T_NATIVE_INT, scalar, &two_d);
  Hid str4 = string_type(4);
  attribute(box, "boundary", str4, str4, space2, "none\0none");  // two 5-byte strings
  // H5MD's time-independent per-particle data: a plain [N] dataset each.
  write_array(balls, "mass", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {n_balls}, h.mass.data());
  write_array(balls, "radius", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {n_balls}, h.radius.data());

  // One step and one time axis for every per-frame element: H5MD lets
  // elements share them by hard links, and then they can never disagree.
  Hid position = group(balls, "position", true);
  create_series(position, "step", H5T_STD_I64LE, {}, kSeriesChunk);
  create_series(position, "time", H5T_IEEE_F64LE, {}, kSeriesChunk);
  create_series(position, "value", H5T_IEEE_F64LE, {n_balls, 2}, frame_chunk);
  create_element(balls, "velocity", position, H5T_IEEE_F64LE, {n_balls, 2}, frame_chunk);
  if (raw) create_raw_series(balls, position, n_balls, frame_chunk);
  Hid observables = group(file, "observables", true);
  create_element(observables, "energy", position, H5T_IEEE_F64LE, {}, kSeriesChunk);
  create_element(observables, "state_hash", position, H5T_STD_U64LE, {}, kSeriesChunk);

  // Events are most of a run file's bytes. Indices and times compress
  // (a, b to 45 %, kind to 3 %, time to 64 % in a gas); an impulse is a
  // double of full entropy (91 %), and deflating it cost 7 % of a gas's
  // whole run for 5 % of the file: it is stored as it is. Chunks of 4 Ki
  // rows: with 1 Ki, setting up deflate for each small chunk cost another
  // 6 % (a 4,000-disc gas, paired whole-process runs, 2026-11-28); 16 Ki gained nothing
  // more, and each checkpoint leaves its partial chunk behind (below).
  Hid events = group(file, "events", true);
  create_series(events, "time", H5T_IEEE_F64LE, {}, kEventChunk, true);
  for (const char* name : {"kind", "a", "b"}) create_series(events, name, H5T_STD_I32LE, {}, kEventChunk, true);
  create_series(events, "impulse", H5T_IEEE_F64LE, {}, kEventChunk, false);

  Hid parameters = group(file, "parameters", !scene_text_written);
  if (!scene_text_written) write_string(parameters, "scene_json", h.scene_json, true);
  write_string(parameters, "options_json", h.options_json, true);
  write_string(parameters, "mode", h.mode, false);
  write_string(parameters, "compiler", h.compiler, false);
  write_array(parameters, "radius", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {n_balls}, h.radius.data());
  write_array(parameters, "mass", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {n_balls}, h.mass.data());
  write_array(parameters, "walls", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {h.walls.size(), 4}, h.walls.data());
  if (h.wall_restitution.size() == h.walls.size())
    write_array(parameters, "wall_restitution", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {h.walls.size()},
                h.wall_restitution.data());

  Hid cp = group(file, "checkpoint", true);
  create_series(cp, "time", H5T_IEEE_F64LE, {}, 64);
  for (const char* name : {"frames_written", "events_written", "engine_state_offset", "engine_state_size"})
    create_series(cp, name, H5T_STD_I64LE, {}, 64);
  create_series(cp, "engine_state", H5T_STD_U8LE, {}, 64 * 1024);

  describe_layout(file);
  ds = open_series(file);
  // A frame that is a chunk by itself along time may come in slices of
  // whole chunks of balls (of both series, where the raw words' are
  // narrower).
  if (frame_chunk == 1) {
    slice_balls = static_cast<std::size_t>(chunk_extent(ds.position, 1));
    if (raw) slice_balls = std::lcm(slice_balls, static_cast<std::size_t>(chunk_extent(ds.position_raw, 1)));
  }
  check_ok(H5Fstart_swmr_write(file), "cannot start SWMR writing");
  header_written = true;
}

void RunWriter::Impl::create_with_scene_text(const std::string& scene_json) {
  Hid fapl = latest_format_fapl();
  file = Hid(H5Fcreate(partial.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), "cannot create the run file");
  write_string(group(file, "parameters", true), "scene_json", scene_json, true);
  scene_text_written = true;
}

void RunWriter::Impl::write_frames() {
  write_frame_rows(f_step.size(), f_step.data(), f_time.data(), f_pos.data(), f_vel.data(), f_energy.data(),
                   f_hash.data(), f_pos_raw.data(), f_vel_raw.data());
  f_step.clear(), f_time.clear(), f_pos.clear(), f_vel.clear(), f_energy.clear(), f_hash.clear();
  f_pos_raw.clear(), f_vel_raw.clear();
}

// n frames' rows, from the appended ones or straight from one frame.
void RunWriter::Impl::write_frame_rows(hsize_t n, const std::int64_t* step, const double* time, const double* pos,
                                       const double* vel, const double* energy, const std::uint64_t* hash,
                                       const std::int64_t* pos_raw, const std::int64_t* vel_raw) {
  const hsize_t at = static_cast<hsize_t>(frames_on_disk);
  write_rows(ds.position, H5T_NATIVE_DOUBLE, at, n, pos);
  write_rows(ds.velocity, H5T_NATIVE_DOUBLE, at, n, vel);
  if (raw) {
    write_rows(ds.position_raw, H5T_NATIVE_INT64, at, n, pos_raw);
    write_rows(ds.velocity_raw, H5T_NATIVE_INT64, at, n, vel_raw);
  }
  write_frame_series(n, step, time, energy, hash);
}

// The per-frame series of n frames (their balls' rows written already);
// they end the frames.
void RunWriter::Impl::write_frame_series(hsize_t n, const std::int64_t* step, const double* time,
                                         const double* energy, const std::uint64_t* hash) {
  const hsize_t at = static_cast<hsize_t>(frames_on_disk);
  write_rows(ds.step, H5T_NATIVE_INT64, at, n, step);
  write_rows(ds.time, H5T_NATIVE_DOUBLE, at, n, time);
  write_rows(ds.energy, H5T_NATIVE_DOUBLE, at, n, energy);
  write_rows(ds.hash, H5T_NATIVE_UINT64, at, n, hash);
  frames_on_disk += static_cast<std::int64_t>(n);
}

void RunWriter::Impl::write_events() {
  const hsize_t n = e_time.size(), at = static_cast<hsize_t>(events_on_disk);
  write_rows(ds.ev_time, H5T_NATIVE_DOUBLE, at, n, e_time.data());
  write_rows(ds.ev_kind, H5T_NATIVE_INT, at, n, e_kind.data());
  write_rows(ds.ev_a, H5T_NATIVE_INT, at, n, e_a.data());
  write_rows(ds.ev_b, H5T_NATIVE_INT, at, n, e_b.data());
  write_rows(ds.ev_impulse, H5T_NATIVE_DOUBLE, at, n, e_impulse.data());
  events_on_disk += static_cast<std::int64_t>(n);
  e_time.clear(), e_kind.clear(), e_a.clear(), e_b.clear(), e_impulse.clear();
}

// Order matters for kill -9 at any instant. (1) Frames, events and the new
// engine state go to a region of /checkpoint/engine_state disjoint from the
// committed one, then a flush puts them in the file. (2) The record (five
// one-row appends) follows, then a second flush. A reader takes the last row
// present in all five record datasets, so a torn record falls back to the
// previous one, whose data and blob are untouched. Only appends and in-place
// raw writes are used: what SWMR permits and keeps consistent for readers.
void RunWriter::Impl::checkpoint(const Checkpoint& cp) {
  write_frames();
  write_events();
  const hsize_t size = cp.engine_state.size();
  const hsize_t offset = size <= state_offset ? 0 : state_offset + state_size;
  write_rows(ds.cp_state, H5T_NATIVE_UINT8, offset, size, cp.engine_state.data());
  check_ok(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush");
  const hsize_t row = static_cast<hsize_t>(checkpoints);
  const std::int64_t offset64 = static_cast<std::int64_t>(offset), size64 = static_cast<std::int64_t>(size);
  write_rows(ds.cp_time, H5T_NATIVE_DOUBLE, row, 1, &cp.time);
  write_rows(ds.cp_frames, H5T_NATIVE_INT64, row, 1, &frames_on_disk);
  write_rows(ds.cp_events, H5T_NATIVE_INT64, row, 1, &events_on_disk);
  write_rows(ds.cp_offset, H5T_NATIVE_INT64, row, 1, &offset64);
  write_rows(ds.cp_size, H5T_NATIVE_INT64, row, 1, &size64);
  check_ok(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush");
  ++checkpoints;
  state_offset = offset;
  state_size = size;
  checkpointed = true;
}

// SWMR mode forbids creating objects, so the summary is written after closing
// and reopening the file without SWMR; only then is the file renamed.
void RunWriter::Impl::finish(const std::string& summary) {
  write_frames();
  write_events();
  ds = Series{};
  check_ok(H5Fclose(file.release()), "close");
  Hid fapl = latest_format_fapl();
  file = Hid(H5Fopen(partial.c_str(), H5F_ACC_RDWR, fapl), "reopen to finish");
  write_string(group(file, "observables", false), "summary", summary, true);
  check_ok(H5Fclose(file.release()), "close");
  fsync_path(partial, false);
  std::error_code ec;
  fs::rename(partial, path, ec);
  if (ec) throw Failure("cannot rename " + partial + " to " + path + ": " + ec.message());
  finished = true;
  fsync_path(fs::absolute(path).parent_path().string(), true);
}

RunWriter::RunWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

RunWriter::RunWriter(const std::string& path, const RunHeader& header)
    : impl_(std::make_unique<Impl>(path, partial_run_path(path))) {
  naming_the_file(impl_->partial, [&] { impl_->create(header); });
}

RunWriter RunWriter::with_scene_text(const std::string& path, const std::string& scene_json) {
  auto impl = std::make_unique<Impl>(path, partial_run_path(path));
  naming_the_file(impl->partial, [&] { impl->create_with_scene_text(scene_json); });
  return RunWriter(std::move(impl));
}

void RunWriter::write_header(const RunHeader& header) {
  if (impl_->header_written) throw RunFileError(impl_->partial + ": the run's header is written already");
  naming_the_file(impl_->partial, [&] { impl_->create(header); });
}

RunWriter::~RunWriter() = default;
RunWriter::RunWriter(RunWriter&&) noexcept = default;
RunWriter& RunWriter::operator=(RunWriter&&) noexcept = default;

void RunWriter::append_frame(const FrameRecord& f) {
  Impl& w = *impl_;
  w.require_header();
  // The end of a frame given in slices: its record, without balls.
  if (w.sliced_balls > 0) {
    const bool no_balls = f.position.empty() && f.velocity.empty() && f.position_raw.empty() && f.velocity_raw.empty();
    auto refuse = [&](const std::string& why) {
      throw RunFileError(w.partial + ": frame at step " + std::to_string(f.step) + " ending its slices: " + why);
    };
    if (!no_balls) refuse("it holds balls of its own");
    if (w.sliced_balls != w.n_balls)
      refuse("its slices hold " + std::to_string(w.sliced_balls) + " of " + std::to_string(w.n_balls) + " balls");
    if (std::memcmp(&f.time, &w.sliced_time, sizeof f.time) != 0)
      refuse("its time is not its slices' (" + std::to_string(w.sliced_time) + ")");
    naming_the_file(w.partial, [&] { w.write_frame_series(1, &f.step, &f.time, &f.energy, &f.state_hash); });
    w.sliced_balls = 0;
    return;
  }
  if (f.position.size() != 2 * w.n_balls || f.velocity.size() != 2 * w.n_balls)
    throw RunFileError(w.partial + ": frame at step " + std::to_string(f.step) + " does not hold 2*" +
                       std::to_string(w.n_balls) + " coordinates");
  // A fixed-mode file without its exact values, or raw values dropped
  // silently from another file, would lose what the caller meant to keep.
  const std::size_t raw_size = w.raw ? raw_words_per_frame(w.n_balls) : 0;
  if (f.position_raw.size() != raw_size || f.velocity_raw.size() != raw_size)
    throw RunFileError(w.partial + ": frame at step " + std::to_string(f.step) +
                       (w.raw ? " lacks the raw values of a fixed-mode run (2*2*" + std::to_string(w.n_balls) +
                                    " words each)"
                              : " has raw values, which only a fixed-mode run stores"));
  // A frame that is a chunk by itself (a large scene: frame_chunk_rows) is
  // written from the caller's record, not copied first: a million balls'
  // copy would be 32 MB more of the run's peak, and a second pass over it.
  if (w.frame_chunk == 1 && w.f_step.empty()) {
    naming_the_file(w.partial, [&] {
      w.write_frame_rows(1, &f.step, &f.time, f.position.data(), f.velocity.data(), &f.energy, &f.state_hash,
                         f.position_raw.data(), f.velocity_raw.data());
    });
    return;
  }
  w.f_step.push_back(f.step);
  w.f_time.push_back(f.time);
  w.f_pos.insert(w.f_pos.end(), f.position.begin(), f.position.end());
  w.f_vel.insert(w.f_vel.end(), f.velocity.begin(), f.velocity.end());
  w.f_energy.push_back(f.energy);
  w.f_hash.push_back(f.state_hash);
  w.f_pos_raw.insert(w.f_pos_raw.end(), f.position_raw.begin(), f.position_raw.end());
  w.f_vel_raw.insert(w.f_vel_raw.end(), f.velocity_raw.begin(), f.velocity_raw.end());
  // Written when the rows end on a chunk boundary: whole chunks, few calls.
  if ((static_cast<hsize_t>(frames_written()) % w.frame_chunk) != 0) return;
  naming_the_file(w.partial, [&] { w.write_frames(); });
}

std::size_t RunWriter::balls_per_frame_slice() const { return impl_->slice_balls; }

void RunWriter::append_frame_slice(const FrameSlice& s) {
  Impl& w = *impl_;
  w.require_header();
  const std::size_t count = s.position.size() / 2;
  auto refuse = [&](const std::string& why) {
    throw RunFileError(w.partial + ": slice of balls from " + std::to_string(s.first) + ": " + why);
  };
  if (w.slice_balls == 0) refuse("this file takes whole frames only (balls_per_frame_slice() is 0)");
  if (s.first != w.sliced_balls) refuse("the frame's next slice starts at ball " + std::to_string(w.sliced_balls));
  if (s.first > 0 && std::memcmp(&s.time, &w.sliced_time, sizeof s.time) != 0)
    refuse("its time is not the frame's (" + std::to_string(w.sliced_time) + ")");
  if (count == 0 || s.position.size() != 2 * count || s.velocity.size() != 2 * count)
    refuse("positions and velocities must hold 2 coordinates for each of at least one ball");
  if (s.first + count > w.n_balls) refuse("it ends past the last of " + std::to_string(w.n_balls) + " balls");
  if (s.first + count < w.n_balls && count % w.slice_balls != 0)
    refuse("a slice before the last holds a multiple of " + std::to_string(w.slice_balls) + " balls");
  const std::size_t raw_size = w.raw ? 2 * 2 * count : 0;
  if (s.position_raw.size() != raw_size || s.velocity_raw.size() != raw_size)
    refuse(w.raw ? "a fixed-mode run's slice holds 2*2 raw words a ball" : "only a fixed-mode run stores raw values");
  // Written at once: the row's first chunks may stay in the file without
  // its step and time (a kill, or a later slice refused), one row past
  // them, which readers take as the frames all series hold.
  naming_the_file(w.partial, [&] {
    const hsize_t at = static_cast<hsize_t>(w.frames_on_disk);
    write_row_part(w.ds.position, H5T_NATIVE_DOUBLE, at, s.first, count, s.position.data());
    write_row_part(w.ds.velocity, H5T_NATIVE_DOUBLE, at, s.first, count, s.velocity.data());
    if (w.raw) {
      write_row_part(w.ds.position_raw, H5T_NATIVE_INT64, at, s.first, count, s.position_raw.data());
      write_row_part(w.ds.velocity_raw, H5T_NATIVE_INT64, at, s.first, count, s.velocity_raw.data());
    }
  });
  w.sliced_balls += count;
  w.sliced_time = s.time;
}

void RunWriter::append_event(const EventRecord& e) {
  Impl& w = *impl_;
  w.require_header();
  w.e_time.push_back(e.time);
  w.e_kind.push_back(e.kind);
  w.e_a.push_back(e.a);
  w.e_b.push_back(e.b);
  w.e_impulse.push_back(e.impulse);
  if ((static_cast<hsize_t>(events_written()) % kEventChunk) != 0) return;
  naming_the_file(w.partial, [&] { w.write_events(); });
}

void RunWriter::checkpoint(const Checkpoint& cp) {
  impl_->require_header();
  impl_->require_no_unfinished_frame();
  naming_the_file(impl_->partial, [&] { impl_->checkpoint(cp); });
}

void RunWriter::finish(const std::string& summary_json) {
  if (impl_->finished) throw RunFileError(impl_->path + ": the run is already finished");
  impl_->require_header();
  impl_->require_no_unfinished_frame();
  naming_the_file(impl_->partial, [&] { impl_->finish(summary_json); });
}

std::int64_t RunWriter::frames_written() const {
  return impl_->frames_on_disk + static_cast<std::int64_t>(impl_->f_step.size());
}
std::int64_t RunWriter::events_written() const {
  return impl_->events_on_disk + static_cast<std::int64_t>(impl_->e_time.size());
}
const std::string& RunWriter::path() const { return impl_->path; }
const std::string& RunWriter::partial_path() const { return impl_->partial; }

// ---------------------------------------------------------------- resuming

// Continues from a copy rather than in place: past its last checkpoint the
// killed file holds whatever the kill left (extents, half-written chunks), and
// shrinking it would need a read-write open of a file we cannot trust. The
// copy holds exactly the checkpointed prefix and replaces the partial file by
// rename, so at every instant one complete resumable file exists.
ResumedRun resume_run_file(const std::string& path) {
  const std::string suffix = ".partial";
  const bool is_partial = path.size() > suffix.size() && path.ends_with(suffix);
  const std::string final_path = is_partial ? path.substr(0, path.size() - suffix.size()) : path;
  const std::string partial = partial_run_path(final_path);
  std::error_code ec;
  if (!fs::exists(partial, ec)) throw RunFileError(partial + ": no interrupted run to resume (no such file)");
  RunContents old = read_run_file(partial);
  if (old.finished) throw RunFileError(partial + ": the run is already finished");
  if (!old.last_checkpoint) throw RunFileError(partial + ": no checkpoint to resume from");

  const std::string scratch = partial + ".resume";
  std::optional<RunWriter> writer;
  try {
    QuietErrors quiet;
    auto impl = std::make_unique<RunWriter::Impl>(final_path, scratch);
    impl->create(old.header);
    writer.emplace(RunWriter(std::move(impl)));
    // The same sequence of writes as the interrupted run made, checkpoint by
    // checkpoint, so that the finished file equals an uninterrupted run's.
    std::size_t frame = 0, event = 0;
    for (const Checkpoint& cp : old.checkpoints) {
      for (; frame < static_cast<std::size_t>(cp.frames_written); ++frame) writer->append_frame(old.frames[frame]);
      for (; event < static_cast<std::size_t>(cp.events_written); ++event) writer->append_event(old.events[event]);
      writer->checkpoint(cp);
    }
    fs::rename(scratch, partial, ec);
    if (ec) throw Failure("cannot replace it with " + scratch + ": " + ec.message());
    writer->impl_->partial = partial;
  } catch (const Failure& e) {
    writer.reset();
    fs::remove(scratch, ec);
    throw RunFileError(with_path(partial, e));
  } catch (...) {
    writer.reset();
    fs::remove(scratch, ec);
    throw;
  }
  return ResumedRun{std::move(old.header), std::move(*old.last_checkpoint), std::move(*writer)};
}

}  // namespace collide2d
