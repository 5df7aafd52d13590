// The run file: an H5MD 1.1 HDF5 file holding one simulation run. Plain data
// in (RunWriter), plain data out (read_run_file); no dependency on the engine.
//
// Layout (SPEC.md "Run file (HDF5)"; add, never rename). Every group, dataset
// and attribute with its type, shape, units and when it is present:
// docs/formats/run-file.md. In short (F frames, N balls, W walls):
//   /h5md                      attr version = [1, 1]
//     author                   attr name
//     creator                  attr name = "collide2d", version
//   /particles/balls           attr units: the scene's own (no H5MD unit attributes)
//     box                      attr dimension = 2, boundary = ["none", "none"]
//     position                 step [F] int64, time [F] float64, value [F][N][2] float64
//     velocity                 step, time (hard links to position's), value
//     mass, radius             [N] float64 (H5MD per-particle data)
//     position_raw             fixed-mode runs only (mode = "fixed"): step,
//     velocity_raw             time (links), value [F][N][2][2] int64, the
//                              exact Q63.64 values that position and velocity
//                              round: last axis [hi, lo], value =
//                              (hi * 2^64 + (uint64)lo) / 2^64; attr format
//   /observables/energy        step, time (links), value [F] float64
//   /observables/state_hash    step, time (links), value [F] uint64
//   /observables/summary       scalar string (JSON); present once finished
//   /events/{time,kind,a,b,impulse}   [events]: float64, int32 x3, float64,
//                              shuffled and deflated; attrs description, and
//                              on kind labels = ["ball-ball", "ball-wall"]
//   /parameters                scene_json, options_json (scalar strings),
//                              radius [N], mass [N], walls [W][4] (attr
//                              columns = ax ay bx by), wall_restitution [W]
//                              float64; attrs mode, compiler, units
//   /checkpoint                time, frames_written, events_written,
//                              engine_state_offset, engine_state_size [k]
//                              (one row per checkpoint, int64; the last
//                              complete row is the latest checkpoint);
//                              engine_state [bytes] uint8: the latest blob
//                              at [offset, offset + size), written beside the
//                              previous one, never over it
// mass, radius, wall_restitution and the descriptive attributes came later:
// older files lack them, and the reader takes files without them.
// Strings are fixed-length, null-terminated, UTF-8 (every H5MD reader takes
// them). All time series are chunked and extendible along their first axis.
//
// Crash safety: the file is written with SWMR (H5F_ACC_SWMR_WRITE, HDF5 1.10
// format). checkpoint() writes everything buffered, the engine state, then the
// checkpoint record, flushing the file between the two, so after kill -9 the
// file opens (read-only with SWMR_READ) and the last complete checkpoint
// record names counts of frames and events that are all on disk.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "collide2d/sim/records.hpp"

namespace collide2d {

// A run file that cannot be created, written, read or resumed. The message
// names the file and says what is wrong.
struct RunFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct RunHeader {
  std::string scene_json;
  std::string options_json;
  std::string mode;  // "strict" | "fixed"
  std::vector<double> radius, mass;  // one per ball: N = radius.size()
  std::vector<std::array<double, 4>> walls;  // ax, ay, bx, by
  // One per wall, or empty: then /parameters/wall_restitution is not written
  // (and files written before it was stored read back without it).
  std::vector<double> wall_restitution;
  std::string creator_version, compiler, author;
};

// The engine's own state at a checkpoint, opaque to this module.
struct Checkpoint {
  double time = 0;
  std::int64_t frames_written = 0;  // set by RunWriter::checkpoint
  std::int64_t events_written = 0;  // set by RunWriter::checkpoint
  std::vector<std::uint8_t> engine_state;
};

// Whether a run with this header stores the exact raw values (fixed mode).
bool stores_raw_values(const RunHeader& header);

// Where a run that will end up at `path` is written meanwhile.
std::string partial_run_path(const std::string& path);

struct ResumedRun;

// Writes `partial_run_path(path)`; finish() renames it to `path` atomically.
// Destroyed without finish(): the partial file is removed, unless a checkpoint
// was written (then it stays for resume_run_file).
class RunWriter {
 public:
  // Throws RunFileError naming the file if it cannot be created, or if the
  // header is inconsistent (no balls, radius and mass of different lengths).
  // A header with mode "fixed" gives the file the *_raw series.
  RunWriter(const std::string& path, const RunHeader& header);

  // The same file made in two steps, for a scene too large to hold its text
  // beside its balls: with_scene_text creates the file holding only
  // /parameters/scene_json, so the text may go before the scene is parsed
  // again from its file; write_header then writes the rest (its scene_json
  // ignored). Nothing may be appended before write_header; a writer
  // destroyed before it removes its file, as any unfinished one does.
  static RunWriter with_scene_text(const std::string& path, const std::string& scene_json);
  void write_header(const RunHeader& header);
  ~RunWriter();
  RunWriter(RunWriter&&) noexcept;
  RunWriter& operator=(RunWriter&&) noexcept;
  RunWriter(const RunWriter&) = delete;
  RunWriter& operator=(const RunWriter&) = delete;

  // Buffered; written a chunk at a time. Throws RunFileError if position or
  // velocity is not N*2 long, if position_raw and velocity_raw are not N*2*2
  // long in a fixed-mode file or not empty in another, or on a write error.
  void append_frame(const FrameRecord& frame);
  // A large scene's frame in slices, as it is made (a million balls' whole
  // frame is 32 MB held only to be written). balls_per_frame_slice() > 0:
  // this file takes them (its frames are written a chunk of balls at a
  // time; 0: whole frames only, which are buffered). Slices come in ball
  // order, the next frame's balls [first, first + count), each a multiple of
  // balls_per_frame_slice() but the last (they are then whole chunks); then
  // append_frame() with the frame's step, time, energy and hash and no
  // positions, velocities or raw words ends it. Throws RunFileError on a
  // slice out of order, of the wrong sizes, or a frame ended early.
  std::size_t balls_per_frame_slice() const;
  void append_frame_slice(const FrameSlice& slice);
  void append_event(const EventRecord& event);

  // Makes everything so far durable and records the checkpoint; its counts are
  // replaced by the writer's own (frames_written(), events_written()).
  void checkpoint(const Checkpoint& checkpoint);

  // Writes /observables/summary, closes, and renames the file into place.
  void finish(const std::string& summary_json);

  std::int64_t frames_written() const;  // appended so far, buffered or not
  std::int64_t events_written() const;
  const std::string& path() const;          // the final name
  const std::string& partial_path() const;  // where it is written meanwhile

 private:
  struct Impl;
  explicit RunWriter(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  friend ResumedRun resume_run_file(const std::string& path);
};

struct RunContents {
  RunHeader header;
  std::vector<FrameRecord> frames;  // unfinished file: up to the last checkpoint
  std::vector<EventRecord> events;  // unfinished file: up to the last checkpoint
  std::optional<Checkpoint> last_checkpoint;
  std::vector<Checkpoint> checkpoints;  // every record, oldest first (older ones' engine state may be overwritten)
  bool finished = false;     // finish() completed (/observables/summary exists)
  std::string summary_json;  // empty unless finished
};

// Reads a whole run file. A missing, empty, truncated, corrupt or foreign file
// throws RunFileError. A file whose writer was killed opens too: read-only
// with SWMR_READ when it was killed in SWMR mode, else after clearing the
// superblock status flag as `h5clear -s` does. An unfinished file yields only
// what its last checkpoint made durable (nothing if it has none).
RunContents read_run_file(const std::string& path);

// A run to continue: the header, the last checkpoint (with the engine state to
// restore), and a writer that already holds every frame and event up to it.
struct ResumedRun {
  RunHeader header;
  Checkpoint checkpoint;
  RunWriter writer;
};

// Continues an interrupted run. `path` is the final name or its partial file.
// The checkpointed prefix is copied into a fresh file which then replaces the
// partial file atomically, so a crash during resume loses nothing. Throws
// RunFileError if there is no partial file, it has no checkpoint, or the run
// is already finished.
ResumedRun resume_run_file(const std::string& path);

}  // namespace collide2d
