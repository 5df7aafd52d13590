#include "cli/run_support.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <stdexcept>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "cli/build_info.hpp"

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

RunHeader run_header(const Scene& scene, const std::string& scene_text, const RunOptions& options) {
  RunHeader h;
  h.scene_json = scene_text;
  h.options_json = options.to_json().dump();
  h.mode = options.mode;
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

nlohmann::json summary_json(const SimulationSummary& s, std::int64_t events) {
  const RestCounters& r = s.counters.rest;
  return {{"events", events},
          {"ball_ball", s.counters.ball_ball},
          {"ball_wall", s.counters.ball_wall},
          {"left_wall", s.counters.leave_wall},
          {"ignored_contacts", s.counters.ignored},
          {"cell_crossings", s.counters.cell_crossings},
          {"came_to_rest", r.came_to_rest},
          {"fell_asleep", r.fell_asleep},
          {"woken", r.woken},
          {"plastic_pairs", r.plastic_pairs},
          {"left_pair", s.counters.leave_pair},
          {"creeping", r.creeping},
          {"held", r.held},
          {"renewed", r.renewed},
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
          {"wall_seconds", s.wall_seconds},
          {"rest_height", s.rest.height},
          {"rest_speed", s.rest.speed},
          {"rest_band", s.rest.band},
          {"creep_speed", s.rest.creep_speed}};
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
  std::printf("time        %.3f s wall, %.0f events/s, %lld frames\n", s.wall_seconds, rate, static_cast<long long>(s.frames));
  std::printf("final hash  %016llx\n", static_cast<ull>(s.final_hash));
}

int run_into(RunWriter& writer, const Scene& scene, const std::string& scene_name, const RunOptions& o,
             const std::vector<std::uint8_t>* resume_from) {
#ifdef __GLIBC__
  // The run file deflates each chunk of events, and zlib takes ~256 KiB of
  // tables for it and frees them at once. glibc would give that memory back
  // to the kernel every time: a brk and a TLB flush each, which made a gas
  // run 15% slower, and twice as slow with a checkpoint every 5 s (measured
  // on a virtual machine). Keeping up to 64 MiB free avoids it.
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
#endif
  try {
    const double until = o.until < 0 ? scene.duration : o.until;
    auto last_report = std::chrono::steady_clock::now();
    const auto start = last_report;
    CheckpointControl checkpoints;
    if (o.checkpoint_every > 0) {
      checkpoints.every_frames = std::max<std::int64_t>(1, std::llround(o.checkpoint_every / scene.record_interval));
      checkpoints.on_checkpoint = [&](double time, std::vector<std::uint8_t> state) {
        writer.checkpoint(Checkpoint{time, 0, 0, std::move(state)});
      };
    }
    checkpoints.resume_from = resume_from;
    const SimulationSummary summary = simulate_in_mode(
        scene, o,
        [&](const FrameRecord& f) {
          writer.append_frame(f);
          const auto now = std::chrono::steady_clock::now();
          if (now - last_report > std::chrono::seconds(1) && now - start > std::chrono::seconds(2)) {
            std::cerr << "run: t = " << f.time << " of " << until << ", " << writer.events_written() << " events\n";
            last_report = now;
          }
        },
        [&](const EventRecord& e) { writer.append_event(e); },
        checkpoints);
    const std::int64_t events = writer.events_written();
    writer.finish(summary_json(summary, events).dump());
    std::cout << "run " << scene.name << " (" << o.mode << ", " << o.engine << " engine, " << o.method << ") -> "
              << writer.path() << "\n";
    print_summary(summary, events);
  } catch (const RunFileError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const FixedPointOverflow& e) {
    std::cerr << scene_name << ": " << e.what() << " (" << fixed_range_note << ")\n";
    return 2;
  } catch (const StrictOverflow& e) {
    std::cerr << scene_name << ": " << e.what() << " (" << strict_range_note << ")\n";
    return 2;
  } catch (const EngineStall& e) {
    std::cerr << scene_name << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace collide2d::cli
