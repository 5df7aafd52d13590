// collide2d bench peers: the same scenes in collide2d (strict, event engine,
// in this process, no run file), Box2D 2.4 (its default restitution threshold
// and 0) and Chipmunk 7, judged alike (peers/peer_run.hpp): CSV
// scene,engine,simulated_s,wall_s_per_simulated_s,energy_change,deepest_overlap,balls_outside.
// energy_change: (E_end − E_start) / |E_start|; deepest_overlap: over the
// smaller radius, at samples every 0.1 simulated seconds.
#include "cli/bench_peers.hpp"

#include <chrono>
#include <cstdio>
#include <iostream>

#include "cli/commands.hpp"
#include "cli/run_support.hpp"
#include "collide2d/scene/builtin_scene.hpp"
#include "collide2d/sim/simulate.hpp"
#include "lab/bench_scenes.hpp"
#include "peers/peer_run.hpp"

namespace collide2d::cli {
namespace {

constexpr double sample_every = 0.1;

PeerRun run_collide2d(const Scene& scene_in, double until) {
  Scene scene = scene_in;
  scene.record_interval = sample_every;
  PeerRun out;
  out.engine = "collide2d";
  auto to_sample = [](const FrameRecord& f) {
    PeerSample s;
    for (std::size_t k = 0; k + 1 < f.position.size(); k += 2) {
      s.position.push_back({f.position[k], f.position[k + 1]});
      s.velocity.push_back({f.velocity[k], f.velocity[k + 1]});
    }
    return s;
  };
  bool first = true;
  double measuring = 0;  // wall time spent on the measures, taken off
  const auto start = std::chrono::steady_clock::now();
  simulate<double>(
      scene, until,
      [&](const FrameRecord& f) {
        const auto t0 = std::chrono::steady_clock::now();
        out.last = to_sample(f);
        if (first) out.first = out.last, first = false;
        out.deepest_overlap = std::max(out.deepest_overlap, deepest_relative_overlap(scene, out.last));
        measuring += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      },
      [](const EventRecord&) {}, EngineChoice{});
  out.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - measuring;
  out.simulated = until;
  return out;
}

// Balls at 10^5 per second in a unit box: 20 balls of radius 0.02 on a
// lattice, directions spread evenly.
Scene tunnelling_trap() {
  Scene s;
  s.name = "tunnelling_trap";
  s.duration = 0.1;
  s.walls = {{{0, 0}, {1, 0}, 1}, {{1, 0}, {1, 1}, 1}, {{1, 1}, {0, 1}, 1}, {{0, 1}, {0, 0}, 1}};
  for (int k = 0; k < 20; ++k) {
    BallSpec b;
    b.radius = 0.02;
    b.position = {0.1 + 0.2 * (k % 5), 0.125 + 0.25 * (k / 5)};
    const double phi = 0.1 + 2 * 3.14159265358979 * k / 20.0;
    b.velocity = {1e5 * std::cos(phi), 1e5 * std::sin(phi)};
    s.balls.push_back(b);
  }
  return s;
}

}  // namespace

int run_bench_peers(const BenchPeersOptions& o) {
  struct Case {
    Scene scene;
    double until;
  };
  std::vector<Case> cases;
  for (double speed : {1.0, 10.0}) {
    Scene gas = hard_disk_gas(2000, 0.45, speed, o.gas_seconds, 1);
    gas.name = "dense_gas_2000_speed" + std::to_string(static_cast<int>(speed));
    cases.push_back({gas, o.gas_seconds});
  }
  cases.push_back({tunnelling_trap(), 0.1});
  cases.push_back({scene_from_text(builtin_pile_scene_json()), o.pile_seconds});

  start_chipmunk();
  std::printf("scene,engine,simulated_s,wall_s_per_simulated_s,energy_change,deepest_overlap,balls_outside\n");
  std::fflush(stdout);
  for (const Case& c : cases) {
    std::vector<PeerRun> runs;
    std::cerr << "bench peers: " << c.scene.name << ": collide2d\n";
    runs.push_back(run_collide2d(c.scene, c.until));
    std::cerr << "bench peers: " << c.scene.name << ": box2d, chipmunk\n";
    runs.push_back(run_box2d(c.scene, c.until, sample_every, false));
    runs.push_back(run_box2d(c.scene, c.until, sample_every, true));
    runs.push_back(run_chipmunk(c.scene, c.until, sample_every));
    for (const PeerRun& r : runs) {
      const double e0 = scene_energy(c.scene, r.first), e1 = scene_energy(c.scene, r.last);
      std::printf("%s,%s,%.4g,%.4g,%.3g,%.3g,%d\n", c.scene.name.c_str(), r.engine.c_str(), r.simulated,
                  r.wall / r.simulated, (e1 - e0) / std::abs(e0), r.deepest_overlap, balls_outside(c.scene, r.last));
      std::fflush(stdout);
    }
  }
  return exit_ok;
}

}  // namespace collide2d::cli
