// The engines users would otherwise pick (Box2D 2.4, Chipmunk 7), run on a
// collide2d scene, and the measures every engine is judged by, taken the
// same way for all: sampled states → energy, deepest overlap, balls outside.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "collide2d/geometry/vec2.hpp"
#include "collide2d/scene/scene.hpp"

namespace collide2d {

// Positions and velocities of every ball at one time.
struct PeerSample {
  std::vector<Vec2<double>> position, velocity;
};

struct PeerRun {
  std::string engine;
  double simulated = 0;  // seconds
  double wall = 0;       // seconds, the stepping (or event loop) alone
  PeerSample first, last;
  double deepest_overlap = 0;  // over every sample: max (r_i + r_j − d) / min(r_i, r_j), walls: (r − d) / r
};

// Total energy, SPEC.md's definition: Σ ½ m v² − m a·p (a the ball's own
// acceleration: the scene's gravity unless it sets one).
double scene_energy(const Scene& scene, const PeerSample& s);

// The deepest overlap of a sample, relative to the smaller radius (0: none).
double deepest_relative_overlap(const Scene& scene, const PeerSample& s);

// Balls whose centre has left the box: the bounding box of the walls' ends.
int balls_outside(const Scene& scene, const PeerSample& s);

// Steps a peer engine (`step(dt)`) for `until` simulated seconds at
// dt = 1/60 s, timing the steps alone, and takes `sample()` at the start,
// every `sample_every` simulated seconds and at the end.
template <class Step, class Sample>
void step_and_sample(PeerRun& out, const Scene& scene, double until, double sample_every, Step step, Sample sample) {
  const double dt = 1.0 / 60.0;
  const long steps = std::lround(until / dt);
  const long steps_per_sample = std::max(1L, std::lround(sample_every / dt));
  out.first = sample();
  for (long k = 1; k <= steps; ++k) {
    const auto start = std::chrono::steady_clock::now();
    step(dt);
    out.wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (k % steps_per_sample == 0 || k == steps) {
      out.last = sample();
      out.deepest_overlap = std::max(out.deepest_overlap, deepest_relative_overlap(scene, out.last));
    }
  }
  out.simulated = static_cast<double>(steps) * dt;
}

// Box2D 2.4 with its documented settings for elastic balls: friction 0,
// fixed rotation, restitution from the scene, velocity threshold for
// restitution its default (1 m/s) or 0; step 1/60 s, 8 velocity and 3
// position iterations. Samples every `sample_every` simulated seconds.
PeerRun run_box2d(const Scene& scene, double until, double sample_every, bool zero_restitution_threshold);

// Chipmunk 7 likewise: elasticity from the scene, friction 0, infinite
// moment (no rotation), step 1/60 s, its default 10 iterations.
PeerRun run_chipmunk(const Scene& scene, double until, double sample_every);

// Once, before anything is printed: Chipmunk's banner goes to standard error.
void start_chipmunk();

}  // namespace collide2d
