// fuzz_run_file: run files through the reader of `collide2d replay` and
// `collide2d resume`. The input is decoded into a well-formed HDF5 file whose
// content it chooses (run_file_recipe.hpp), written as RUN.h5.partial in a
// scratch folder; then
//   1. read_run_file, the reader both commands start with; a file it accepts
//      must keep the reader's contract (below);
//   2. the scene and options read back from /parameters as both commands do
//      (read_back_parameters);
//   3. the command itself, as the program runs it: `resume RUN.h5` for an
//      unfinished file, `replay RUN.h5` for a finished one (renamed so). Both
//      simulate the scene, so they run only when that is cheap: the event
//      engine (or steps no shorter than a thousandth of the run), a run of at
//      most 1 s of simulated time in at most 1000 frames, at most 8 balls.
//      Other files stop after step 2; the counts are printed at exit.
//
// Outcomes the commands handle: RunFileError (exit 2 naming the file), a
// refused /parameters (exit 2), exit codes 0, 1 and 2 of the commands. Any
// other exception out of the reader or a command, a sanitizer report, a hang
// (libFuzzer's -timeout) or a broken contract is a finding.
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <streambuf>
#include <string>

#include <hdf5.h>

#include "cli/commands.hpp"
#include "cli/run_support.hpp"
#include "collide2d/io/run_file.hpp"
#include "run_file_recipe.hpp"

namespace {

using namespace collide2d;
namespace fs = std::filesystem;

fs::path scratch;  // this process's folder for RUN.h5 and its partial file
std::size_t inputs = 0, read_ok = 0, parameters_ok = 0, replayed = 0, resumed = 0;

// Swallows what the commands print.
struct NullBuffer : std::streambuf {
  int overflow(int c) override { return c; }
};

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_run_file: %s\n", what.c_str());
  std::abort();
}

void report() {
  std::fprintf(stderr,
               "fuzz_run_file: %zu inputs: %zu files read, %zu with readable parameters, %zu replayed, %zu resumed\n",
               inputs, read_ok, parameters_ok, replayed, resumed);
  std::error_code ec;
  fs::remove_all(scratch, ec);
}

// What read_run_file promises (run_file.hpp) and what replay and resume rely
// on when they index frames and events by it.
void check_contract(const RunContents& run) {
  const std::size_t n = run.header.radius.size();
  if (n == 0 || run.header.mass.size() != n) finding("header: no balls, or mass and radius differ in length");
  if (!run.header.wall_restitution.empty() && run.header.wall_restitution.size() != run.header.walls.size())
    finding("header: wall_restitution and walls differ in length");
  for (const FrameRecord& f : run.frames) {
    if (f.position.size() != 2 * n || f.velocity.size() != 2 * n) finding("a frame does not hold 2N coordinates");
    if (f.position_raw.size() != f.velocity_raw.size() || (!f.position_raw.empty() && f.position_raw.size() != 4 * n))
      finding("a frame's raw words are neither absent nor 2*2*N");
  }
  for (const Checkpoint& cp : run.checkpoints)
    if (cp.frames_written < 0 || static_cast<std::size_t>(cp.frames_written) > run.frames.size() ||
        cp.events_written < 0 || static_cast<std::size_t>(cp.events_written) > run.events.size())
      finding("a checkpoint counts frames or events that were not read");
  if (!run.finished && run.frames.size() != (run.last_checkpoint ? std::size_t(run.last_checkpoint->frames_written) : 0))
    finding("an unfinished file yields other frames than its last checkpoint made durable");
}

// Whether re-simulating this scene with these options costs little (see the
// header comment): only then are replay and resume run.
bool cheap(const Scene& scene, const cli::RunOptions& o) {
  const double until = o.until < 0 ? scene.duration : o.until;
  return scene.balls.size() <= 8 && until <= 1 && until / scene.record_interval <= 1000 &&
         (o.engine == "event" || o.dt >= until / 1000);
}

// `collide2d COMMAND path` as main() runs it: the command's own handling, and
// main's last resort turned into a finding.
int run_command(cli::Runner (*add)(CLI::App&), const char* name, const std::string& path) {
  CLI::App app;
  const cli::Runner runner = add(app);
  const char* argv[] = {"collide2d", name, path.c_str()};
  app.parse(3, argv);
  try {
    return runner();
  } catch (const std::exception& e) {
    finding(std::string("collide2d ") + name + " let an exception out: " + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  char folder[] = "/dev/shm/collide2d-fuzz-XXXXXX";
  char fallback[] = "/tmp/collide2d-fuzz-XXXXXX";
  const char* made = ::mkdtemp(folder);
  if (made == nullptr) made = ::mkdtemp(fallback);
  if (made == nullptr) finding("cannot make a scratch folder");
  scratch = made;
  std::atexit(report);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // the recipe's own refusals are checked, not printed
  // The commands' messages (one line per refused file) would drown
  // libFuzzer's; findings are printed with fprintf, which stays.
  static NullBuffer sink;
  std::cout.rdbuf(&sink);
  std::cerr.rdbuf(&sink);
  if (std::freopen("/dev/null", "w", stdout) == nullptr) finding("cannot silence stdout");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ++inputs;
  const std::string final_path = (scratch / "run.h5").string();
  const std::string partial = partial_run_path(final_path);
  std::error_code ec;
  for (const std::string& p : {final_path, partial, partial + ".resume"}) fs::remove(p, ec);

  FuzzedDataProvider in(data, size);
  fuzz::write_run_file_recipe(in, partial);

  RunContents run;
  try {
    run = read_run_file(partial);
  } catch (const RunFileError&) {
    return 0;  // exit 2: "RUN.h5.partial: ..."
  }
  ++read_ok;
  check_contract(run);

  Scene scene;
  cli::RunOptions options;
  if (!cli::read_back_parameters(run.header, partial, scene, options)) return 0;  // exit 2
  ++parameters_ok;
  // What replay's frame comparison and resume's appends rely on: the scene
  // is the one /parameters describes, ball for ball.
  if (scene.balls.size() != run.header.radius.size() || scene.walls.size() != run.header.walls.size())
    finding("the parameters read back describe another scene than /parameters/radius and walls");
  if (!cheap(scene, options)) return 0;

  if (run.finished) {
    fs::rename(partial, final_path, ec);
    if (ec) finding("cannot rename the scratch file");
    const int code = run_command(cli::add_replay_command, "replay", final_path);
    if (code < 0 || code > 2) finding("replay exit code " + std::to_string(code));
    ++replayed;
  } else {
    const int code = run_command(cli::add_resume_command, "resume", final_path);
    if (code < 0 || code > 2) finding("resume exit code " + std::to_string(code));
    ++resumed;
  }
  return 0;
}
