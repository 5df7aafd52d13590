// EventEngine's checkpoints (part of event_engine.hpp, included at its end):
// the whole mutable state at a record time, field by field, so that the same
// state always gives the same bytes and a resumed run goes on to the same
// bits. The layout's version leads (EventEngine::checkpoint_layout).
#pragma once

#include "collide2d/sim/event_engine.hpp"

namespace collide2d {

template <class Num, class Observer>
inline void EventEngine<Num, Observer>::save(ByteWriter& out) const {
  out.put(checkpoint_layout);
  out.put(now_);
  out.put(static_cast<std::int32_t>(same_time_events_));
  for (const std::uint64_t* c : counter_fields(const_cast<EngineCounters&>(counters_), const_cast<RestCounters&>(rules_.counters),
                                               const_cast<IslandSolveCounters&>(graph_.solve_counters)))
    out.put(*c);
  out.put(rules_.energy_removed);
  out.put(static_cast<std::uint64_t>(world_.balls.size()));
  for (const Body<Num>& b : world_.balls) {
    for (const Vec2<Num>* v : {&b.position, &b.velocity, &b.acceleration, &b.free_acceleration}) out.put(*v);
    for (const Num* x : {&b.time, &b.radius, &b.mass, &b.restitution, &b.struck_at}) out.put(*x);
    out.put(static_cast<std::uint8_t>(b.fixed));
    out.put(static_cast<std::uint8_t>(b.asleep));
    out.put(b.version);
  }
  graph_.save(out);
  out.put(static_cast<std::uint8_t>(primed_));
  if (!primed_) return;
  out.put(end_);
  queue_.save(out);
  grid_.save(out);
}

template <class Num, class Observer>
inline void EventEngine<Num, Observer>::load(ByteReader& in) {
  std::uint32_t layout = 0;
  in.get(layout);
  if (layout != checkpoint_layout)
    throw std::runtime_error("checkpoint of layout " + std::to_string(layout) + ", this build reads layout " +
                             std::to_string(checkpoint_layout) + ": resume it with the collide2d that wrote it");
  in.get(now_);
  std::int32_t same_time_events = 0;
  in.get(same_time_events);
  if (same_time_events < 0 || same_time_events > max_events_at_one_time)
    throw std::runtime_error("checkpoint holds a count of events at one time out of range");
  same_time_events_ = same_time_events;
  for (std::uint64_t* c : counter_fields(counters_, rules_.counters, graph_.solve_counters)) in.get(*c);
  in.get(rules_.energy_removed);
  std::uint64_t n = 0;
  in.get(n);
  if (n != world_.balls.size()) throw std::runtime_error("checkpoint holds a different number of balls");
  for (Body<Num>& b : world_.balls) {
    for (Vec2<Num>* v : {&b.position, &b.velocity, &b.acceleration, &b.free_acceleration}) in.get(*v);
    for (Num* x : {&b.time, &b.radius, &b.mass, &b.restitution, &b.struck_at}) in.get(*x);
    std::uint8_t fixed = 0, asleep = 0;
    in.get(fixed);
    in.get(asleep);
    in.get(b.version);
    b.fixed = fixed != 0;
    b.asleep = asleep != 0;
  }
  graph_.load(in, world_.walls.size());
  std::uint8_t primed = 0;
  in.get(primed);
  primed_ = primed != 0;
  if (!primed_) return;
  in.get(end_);
  queue_.load(in, world_.balls.size(), world_.walls.size());
  grid_.load(in);
  queue_.for_each_crossing([&](int ball, int step, std::uint64_t version) {
    // A stale crossing is dropped when it comes out; a current one moves its ball.
    if (version == world_.balls[static_cast<std::size_t>(ball)].version && !grid_.step_stays_inside(ball, step))
      throw std::runtime_error("checkpoint holds a cell crossing off the grid");
  });
}

}  // namespace collide2d
