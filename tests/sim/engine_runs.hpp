// What the engine tests share: a ball of a scene, and a run kept whole
// (every frame, every event, the summary).
#pragma once

#include <vector>

#include "collide2d/sim/simulate.hpp"

namespace collide2d::test {

inline BallSpec ball(double x, double y, double vx, double vy, double r, double m = 1, double e = 1) {
  BallSpec b;
  b.position = {x, y};
  b.velocity = {vx, vy};
  b.radius = r;
  b.mass = m;
  b.restitution = e;
  return b;
}

struct Recorded {
  std::vector<FrameRecord> frames;
  std::vector<EventRecord> events;
  SimulationSummary summary;
};

template <class Num = double>
Recorded run(const Scene& s, double until, const EngineChoice& choice = {}) {
  Recorded r;
  r.summary = simulate<Num>(s, until, [&](const FrameRecord& f) { r.frames.push_back(f); },
                            [&](const EventRecord& e) { r.events.push_back(e); }, choice);
  return r;
}

}  // namespace collide2d::test
