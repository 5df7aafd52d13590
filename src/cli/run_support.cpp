#include "cli/run_support.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <span>
#include <sstream>
#include <stdexcept>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "cli/build_info.hpp"
#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "cli/progress.hpp"

namespace collide2d::cli {

namespace {

// The scene of scene_json must be the one the file's datasets describe: replay
// compares frame k of the file with frame k of the scene, ball by ball, and
// resume appends the scene's frames to the file's. A file whose two disagree
// (edited, or written by something else) is refused here. Every value is
// compared exactly: run_header took them from this very scene.
void check_scene_matches_header(const Scene& scene, const RunHeader& h) {
  const std::size_t n = h.radius.size();
  if (scene.balls.size() != n)
    throw std::runtime_error("scene_json holds " + std::to_string(scene.balls.size()) + " balls, /parameters/radius " +
                             std::to_string(n));
  for (std::size_t i = 0; i < n; ++i)
    if (!(scene.balls[i].radius == h.radius[i]) || !(scene.balls[i].mass == h.mass[i]))
      throw std::runtime_error("balls[" + std::to_string(i) +
                               "] of scene_json has another radius or mass than /parameters/radius and mass");
  if (scene.walls.size() != h.walls.size())
    throw std::runtime_error("scene_json holds " + std::to_string(scene.walls.size()) + " walls, /parameters/walls " +
                             std::to_string(h.walls.size()));
  for (std::size_t w = 0; w < h.walls.size(); ++w) {
    const WallSpec& s = scene.walls[w];
    if (!(std::array<double, 4>{s.a[0], s.a[1], s.b[0], s.b[1]} == h.walls[w]) ||
        (!h.wall_restitution.empty() && !(s.restitution == h.wall_restitution[w])))
      throw std::runtime_error("walls[" + std::to_string(w) +
                               "] of scene_json differs from /parameters/walls or wall_restitution");
  }
}

}  // namespace

bool read_back_parameters(const RunHeader& header, const std::string& file, Scene& scene, RunOptions& options) {
  try {
    options = RunOptions::from_json(nlohmann::json::parse(header.options_json));
    scene = scene_from_text(header.scene_json);
    check_scene_matches_header(scene, header);
    return true;
  } catch (const std::exception& e) {
    std::cerr << file << ": /parameters cannot be read back: " << e.what() << "\n";
    return false;
  }
}

RunHeader run_header(const Scene& scene, std::string scene_text, const RunOptions& options) {
  RunHeader h;
  h.scene_json = std::move(scene_text);
  h.options_json = options.to_json().dump();
  h.mode = options.mode;
  h.radius.reserve(scene.balls.size());
  h.mass.reserve(scene.balls.size());
  for (const BallSpec& b : scene.balls) {
    h.radius.push_back(b.radius);
    h.mass.push_back(b.mass);
  }
  for (const WallSpec& w : scene.walls) {
    h.walls.push_back({w.a[0], w.a[1], w.b[0], w.b[1]});
    h.wall_restitution.push_back(w.restitution);
  }
  h.creator_version = COLLIDE2D_VERSION;
  h.compiler = compiler_description();
  h.author = "collide2d user";
  return h;
}

std::string first_field_outside_fixed_range(const Scene& s) {
  auto outside = [](double x) { return !fixed_range_holds(x); };
  auto point = [&](const Point& p, const std::string& path) -> std::string {
    for (int k = 0; k < 2; ++k)
      if (outside(p[k])) return path + "[" + std::to_string(k) + "]";
    return "";
  };
  std::string field;
  if (!(field = point(s.gravity, "gravity")).empty()) return field;
  if (outside(s.duration)) return "duration";
  for (std::size_t i = 0; i < s.balls.size(); ++i) {
    const BallSpec& b = s.balls[i];
    const std::string at = "balls[" + std::to_string(i) + "]";
    for (const auto& [p, name] : {std::pair{&b.position, ".position"}, {&b.velocity, ".velocity"}})
      if (!(field = point(*p, at + name)).empty()) return field;
    if (b.acceleration && !(field = point(*b.acceleration, at + ".acceleration")).empty()) return field;
    if (outside(b.radius)) return at + ".radius";
    if (outside(b.mass)) return at + ".mass";
  }
  for (std::size_t i = 0; i < s.walls.size(); ++i) {
    const std::string at = "walls[" + std::to_string(i) + "]";
    if (!(field = point(s.walls[i].a, at + ".a")).empty()) return field;
    if (!(field = point(s.walls[i].b, at + ".b")).empty()) return field;
  }
  return "";
}

nlohmann::json summary_json(const SimulationSummary& s, std::int64_t events) {
  const RestCounters& r = s.counters.rest;
  return {{"events", events},
          {"ball_ball", s.counters.ball_ball},
          {"ball_wall", s.counters.ball_wall},
          {"left_wall", s.counters.leave_wall},
          {"ignored_contacts", s.counters.ignored},
          {"cell_crossings", s.counters.cell_crossings},
          {"stale_events", s.counters.stale},
          {"came_to_rest", r.came_to_rest},
          {"fell_asleep", r.fell_asleep},
          {"woken", r.woken},
          {"plastic_pairs", r.plastic_pairs},
          {"made_plastic_by_rest_rules", r.made_plastic()},
          {"left_pair", s.counters.leave_pair},
          {"creeping", r.creeping},
          {"held", r.held},
          {"renewed", r.renewed},
          {"island_impact_solves", s.counters.islands.impact_solves},
          {"island_force_solves", s.counters.islands.force_solves},
          {"island_rows", s.counters.islands.rows},
          {"island_rounds", s.counters.islands.rounds},
          {"island_largest", s.counters.islands.largest},
          {"frames", s.frames},
          {"energy_start", s.energy_start},
          {"energy_end", s.energy_end},
          {"energy_removed_by_rest", s.energy_removed_by_rest},
          {"at_rest_since", s.at_rest_since},
          {"events_last_tenth", s.events_last_tenth},
          {"events_per_second_last_tenth", s.last_tenth > 0 ? s.events_last_tenth / s.last_tenth : 0.0},
          {"deepest_overlap", s.deepest_overlap},
          {"wall_crossings", s.wall_crossings},
          {"final_hash", s.final_hash},
          {"gas_engine_until", std::isinf(s.gas_engine_until) ? nlohmann::json("end") : nlohmann::json(s.gas_engine_until)},
          {"wall_seconds", s.wall_seconds},
          {"rest_height", s.rest.height},
          {"rest_speed", s.rest.speed},
          {"rest_band", s.rest.band},
          {"creep_speed", s.rest.creep_speed}};
}

// The most this process has had resident (Linux: VmHWM of /proc/self/status,
// which counts from the program's own start; getrusage's ru_maxrss would
// include the memory of a parent that started it), −1 where unknown.
double peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    long long kilobytes = 0;
    if (std::sscanf(line.c_str(), "VmHWM: %lld kB", &kilobytes) == 1) return 1024.0 * static_cast<double>(kilobytes);
  }
  return -1;
}

void print_summary(const SimulationSummary& s, std::int64_t events) {
  using ull = unsigned long long;
  const RestCounters& r = s.counters.rest;
  const double rate = s.wall_seconds > 0 ? static_cast<double>(events) / s.wall_seconds : 0;
  const double change = s.energy_end - s.energy_start;
  std::printf("events      %lld (ball-ball %llu, ball-wall %llu)\n", static_cast<long long>(events),
              static_cast<ull>(s.counters.ball_ball), static_cast<ull>(s.counters.ball_wall));
  if (s.counters.ignored > 0)
    std::printf("ignored     %llu contacts the method reported for objects moving apart\n", static_cast<ull>(s.counters.ignored));
  std::printf("rest        %llu came to rest on a support, %llu plastic pairs, %llu fell asleep, %llu woken, %llu strikes on islands, "
              "%llu creeping, %llu contacts renewed\n",
              static_cast<ull>(r.came_to_rest), static_cast<ull>(r.plastic_pairs), static_cast<ull>(r.fell_asleep),
              static_cast<ull>(r.woken), static_cast<ull>(r.held), static_cast<ull>(r.creeping), static_cast<ull>(r.renewed));
  // The one place the rest rules set a collision's restitution aside
  // (issue 11: the share is reported, and over 1 % said loudly).
  const std::uint64_t collisions = s.counters.ball_ball + s.counters.ball_wall;
  const std::uint64_t plastic = r.made_plastic();
  const double plastic_percent = collisions > 0 ? 100.0 * static_cast<double>(plastic) / static_cast<double>(collisions) : 0.0;
  std::printf("restitution applied in %llu of %llu collisions; the rest rules made %llu plastic (%.3g %%)\n",
              static_cast<ull>(collisions - plastic), static_cast<ull>(collisions), static_cast<ull>(plastic), plastic_percent);
  if (plastic_percent > 1.0)
    std::printf("warning     over 1 %% of the collisions were made plastic by the rest rules: each ended a series of "
                "bounces rising less than rest.height (%.3g) in one impact; a smaller rest.height leaves more of them "
                "to the restitution, at the cost of more events\n",
                s.rest.height);
  if (const IslandSolveCounters& k = s.counters.islands; k.impact_solves + k.force_solves > 0) {
    const double solves = static_cast<double>(k.impact_solves + k.force_solves);
    std::printf("islands     %llu LCP solves (%llu impacts, %llu forces), %.3g rows and %.3g pivoting rounds per solve, "
                "largest %llu rows\n",
                static_cast<ull>(k.impact_solves + k.force_solves), static_cast<ull>(k.impact_solves),
                static_cast<ull>(k.force_solves), static_cast<double>(k.rows) / solves, static_cast<double>(k.rounds) / solves,
                static_cast<ull>(k.largest));
  }
  std::printf("energy      %.17g -> %.17g (change %.3g, %.3g relative); the rest rules took %.3g of it\n", s.energy_start,
              s.energy_end, change, s.energy_start != 0 ? change / std::fabs(s.energy_start) : 0.0, s.energy_removed_by_rest);
  if (s.at_rest_since >= 0)
    std::printf("at rest     every ball still from t = %.6g\n", s.at_rest_since);
  else
    std::printf("at rest     not by the end\n");
  std::printf("last tenth  %lld events in %.6g s (%.3g per simulated second)\n", static_cast<long long>(s.events_last_tenth),
              s.last_tenth, s.last_tenth > 0 ? s.events_last_tenth / s.last_tenth : 0.0);
  std::printf("overlap     deepest %.3g at any frame; %lld times a centre went through a wall%s\n", s.deepest_overlap,
              static_cast<long long>(s.wall_crossings), s.wall_crossings > 0 ? " (tunnelling: contacts were missed)" : "");
  if (std::isinf(s.gas_engine_until))
    std::printf("gas engine  the whole run (no ball accelerates: events without the rest rules' bookkeeping)\n");
  else if (s.gas_engine_until >= 0)
    std::printf("gas engine  until t = %.17g, where a ball was struck twice at one instant; the event engine from there\n",
                s.gas_engine_until);
  std::printf("time        %.3f s wall, %.0f events/s, %lld frames\n", s.wall_seconds, rate, static_cast<long long>(s.frames));
  if (const double peak = peak_resident_bytes(); peak > 0)
    std::printf("memory      peak %.1f MiB resident\n", peak / (1024.0 * 1024.0));
  std::printf("final hash  %016llx\n", static_cast<ull>(s.final_hash));
}

namespace {

// The run went non-finite (an overflow the scene check could not foresee):
// a verification failure, exit 1, rather than a summary full of inf and NaN.
struct NonFiniteRun : std::runtime_error {
  using std::runtime_error::runtime_error;
};

bool all_finite(std::span<const double> values) {
  return std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); });
}
bool frame_is_finite(const FrameRecord& f) {
  return std::isfinite(f.time) && std::isfinite(f.energy) && all_finite(f.position) && all_finite(f.velocity);
}
NonFiniteRun non_finite_by(double time) {
  char text[128];
  std::snprintf(text, sizeof text, "the run went non-finite by t = %.9g (a position, velocity or the energy is inf or NaN)", time);
  return NonFiniteRun(text);
}

// The frames of a run as they go to its file: a large scene's in slices of
// whole chunks as they are made (simulate.hpp's FrameSink), so that no whole
// frame is held; `on_frame` then has the frame's record (no balls in it).
template <class OnFrame>
struct FramesToFile {
  RunWriter& writer;
  OnFrame on_frame;
  std::size_t balls_per_slice() const { return writer.balls_per_frame_slice(); }
  void slice(const FrameSlice& s) {
    if (!all_finite(s.position) || !all_finite(s.velocity)) throw non_finite_by(s.time);
    writer.append_frame_slice(s);
  }
  void operator()(const FrameRecord& f) { on_frame(f); }
};
template <class OnFrame>
FramesToFile(RunWriter&, OnFrame) -> FramesToFile<OnFrame>;
// A sink that stopped matching the concept would be taken as a plain
// callable, and large frames would quietly go whole again.
static_assert(FrameSink<FramesToFile<void (*)(const FrameRecord&)>>);

}  // namespace

void check_run_size(const Scene& scene, const RunOptions& o, const RunLimits& limits) {
  const double until = o.until < 0 ? scene.duration : o.until;
  const double frames = std::floor(until / scene.record_interval) + 1;
  char text[256];
  if (!(frames <= limits.max_frames)) {
    std::snprintf(text, sizeof text, "%.3g frames in %.6g s of simulated time; the limit is %.3g (--max-frames raises it)",
                  frames, until, limits.max_frames);
    throw SceneError("record.interval", text);
  }
  if (o.engine == "step") {
    const double steps = std::ceil(until / o.dt);
    if (!(steps <= limits.max_steps)) {
      std::snprintf(text, sizeof text, "--dt %.6g makes %.3g steps in %.6g s of simulated time; the limit is %.3g (--max-steps raises it)",
                    o.dt, steps, until, limits.max_steps);
      throw std::invalid_argument(text);
    }
  }
}

int run_into(RunWriter& writer, Scene& scene, const std::string& scene_name, const RunOptions& o,
             const std::vector<std::uint8_t>* resume_from) {
#ifdef __GLIBC__
  // The run file deflates each chunk of events, and zlib takes ~256 KiB of
  // tables for it and frees them at once. glibc would give that memory back
  // to the kernel every time: a brk and a TLB flush each, which made a gas
  // run 15% slower, and twice as slow with a checkpoint every 5 s (measured
  // on a virtual machine). Keeping up to 64 MiB free avoids it.
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
#endif
  install_interrupt_handlers();
  double last_checkpoint = -1;  // simulated time of the last checkpoint this process wrote
  double now_time = 0;
  ProgressLine progress("run " + writer.path());
  try {
    const double until = o.until < 0 ? scene.duration : o.until;
    CheckpointControl checkpoints;
    if (o.checkpoint_every > 0) {
      checkpoints.every_frames = std::max<std::int64_t>(1, std::llround(o.checkpoint_every / scene.record_interval));
      checkpoints.on_checkpoint = [&](double time, std::vector<std::uint8_t> state) {
        writer.checkpoint(Checkpoint{time, 0, 0, std::move(state)});
        last_checkpoint = time;
      };
    }
    checkpoints.resume_from = resume_from;
    const SimulationSummary summary = simulate_in_mode_releasing_balls(
        scene, o,
        FramesToFile{writer,
                     [&](const FrameRecord& f) {
                       now_time = f.time;
                       if (!frame_is_finite(f)) throw non_finite_by(f.time);
                       writer.append_frame(f);
                       char detail[96];
                       std::snprintf(detail, sizeof detail, "t = %.6g of %.6g, %lld events", f.time, until,
                                     static_cast<long long>(writer.events_written()));
                       progress.update(f.time, until, detail);
                       throw_if_interrupted();
                     }},
        [&](const EventRecord& e) {
          writer.append_event(e);
          throw_if_interrupted();
        },
        checkpoints);
    progress.finish();
    const std::int64_t events = writer.events_written();
    writer.finish(summary_json(summary, events).dump());
    std::cout << "run " << scene.name << " (" << o.mode << ", " << o.engine << " engine, " << o.method << ") -> "
              << writer.path() << "\n";
    print_summary(summary, events);
  } catch (const Interrupted& e) {
    progress.finish();
    std::ostringstream checkpoint;
    if (last_checkpoint >= 0) checkpoint << " (t = " << last_checkpoint << ")";
    if (last_checkpoint >= 0 || resume_from)
      std::cerr << scene_name << ": " << e.what() << " at t = " << now_time << "; " << writer.partial_path()
                << " holds the run up to its last checkpoint" << checkpoint.str() << ": `collide2d resume "
                << writer.path() << "` continues it\n";
    else
      std::cerr << scene_name << ": " << e.what() << " at t = " << now_time << "; nothing written (no checkpoint yet: "
                << "--checkpoint-every T makes a long run resumable)\n";
    return interrupted_exit_code(e.signal);
  } catch (const RunFileError& e) {
    progress.finish();
    std::cerr << e.what() << "\n";
    return exit_bad_input;
  } catch (const FixedPointOverflow& e) {
    progress.finish();
    std::cerr << scene_name << ": " << e.what() << " (" << fixed_range_note << ")\n";
    return exit_bad_input;
  } catch (const StrictOverflow& e) {
    progress.finish();
    std::cerr << scene_name << ": " << e.what() << " (" << strict_range_note << ")\n";
    return exit_bad_input;
  } catch (const NonFiniteRun& e) {
    progress.finish();
    std::cerr << scene_name << ": " << e.what() << "\n";
    return exit_verification_failed;
  } catch (const EngineStall& e) {
    progress.finish();
    std::cerr << scene_name << ": " << e.what() << "\n";
    return exit_verification_failed;
  }
  return exit_ok;
}

}  // namespace collide2d::cli
