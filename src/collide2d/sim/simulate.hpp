// Runs a scene with the event engine in a number mode and hands every frame
// and collision, as doubles, to the caller (who writes the run file).
#pragma once

#include <array>
#include <chrono>
#include <concepts>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <optional>
#include <type_traits>
#include <vector>

#include "collide2d/sim/event_engine.hpp"
#include "collide2d/sim/frames.hpp"
#include "collide2d/sim/gas_engine.hpp"
#include "collide2d/sim/records.hpp"
#include "collide2d/sim/tunnelling_watch.hpp"

namespace collide2d {

// The rest rules' scales (rest.hpp), from the scene's own (r_min the
// smallest radius, g_max the largest acceleration, T the duration) unless
// the scene sets them in its "rest" object:
//   h_rest = 1e-6 r_min           a rise this low is no bounce
//   v_rest = sqrt(2 g_max h_rest) the speed that rises h_rest
//   δ      = h_rest               a support this close is touching
//   creep  = h_rest / T           creeping for the whole run sinks by h_rest
//   press  = 2^-30 g_max          a smaller push is rounding, not a press
struct RestScales {
  double height = 0, speed = 0, band = 0, creep_speed = 0, least_press = 0;
  template <class Num>
  RestThresholds<Num> in() const {
    return {num<Num>(height), num<Num>(speed), num<Num>(band), num<Num>(creep_speed), num<Num>(least_press)};
  }
};
RestScales rest_scales(const Scene& scene);

struct SimulationSummary {
  EngineCounters counters;
  std::int64_t frames = 0;
  double energy_start = 0, energy_end = 0;
  double deepest_overlap = 0;  // largest penetration seen at any frame (0: none)
  std::int64_t wall_crossings = 0;  // times a centre went through a wall (tunnelling; tunnelling_watch.hpp)
  std::uint64_t final_hash = 0;
  double wall_seconds = 0;
  RestScales rest;
  double energy_removed_by_rest = 0;  // kinetic energy taken by rest on a face, plastic pairs and sleep
  double at_rest_since = -1;          // the first frame time from which every ball is static (−1: not at rest)
  std::int64_t events = 0;            // collisions
  std::int64_t events_last_tenth = 0; // collisions in the last tenth of the run, [0.9 until, until]
  double last_tenth = 0;              // that tenth's length
  // Which engine ran: −1 EventEngine; the time at which the gas engine
  // (gas_engine.hpp) handed the run over to EventEngine (a jam); +inf: the
  // gas engine ran the whole run.
  double gas_engine_until = -1;
};

// Ball i's state as the tunnelling watch sees it.
template <class B, class Num>
PathPoint path_point(const B& b, const Num& t) {
  using T = NumberTraits<Num>;
  // Every ball of a collision is on its clock just after it: no carrying
  // (in fixed point, six products).
  const BallState<Num> s = state_as_read(b, t);
  auto d = [](const Vec2<Num>& v) { return Vec2<double>{T::to_double(v.x), T::to_double(v.y)}; };
  return {d(s.position), d(s.velocity), d(s.acceleration), T::to_double(t)};
}
template <class W, class Num>
  requires requires(const W& w) { w.balls; }
std::vector<PathPoint> path_points(const W& w, const Num& t) {
  std::vector<PathPoint> points;
  points.reserve(w.balls.size());
  for (const auto& b : w.balls) points.push_back(path_point(b, t));
  return points;
}
// A gas's pieces as the watch's check reads them, in doubles. Fixed point
// converts them by screen_double (within 3 · 2^-53 of each, a few times
// cheaper than the nearest double, and eight of them an event): the watch's
// tolerances are 1e-9 of the coordinates, and a centre that went through a
// wall lies a radius beyond it.
template <class Num>
double watch_double(const Num& x) {
  if constexpr (screens_in_double<Num>) return NumberTraits<Num>::screen_double(x);
  else return NumberTraits<Num>::to_double(x);
}
// Where a piece ends, as TunnellingWatch::check reads it: the position and
// the time alone.
template <class B, class Num>
PathPoint piece_end(const B& b, const Num& t) {
  const BallState<Num> s = state_as_read(b, t);
  return {{watch_double(s.position.x), watch_double(s.position.y)}, {}, {}, watch_double(t)};
}
// Each ball where its present piece began (its body, on its own clock).
template <class Num>
std::vector<PathPoint> path_points_on_own_clocks(const World<Num>& w) {
  std::vector<PathPoint> points;
  points.reserve(w.balls.size());
  for (const Body<Num>& b : w.balls) points.push_back(path_point(b, b.time));
  return points;
}
template <class Num>
PathPoint path_point(const typename Collision<Num>::PieceStart& s) {
  auto d = [](const Vec2<Num>& v) { return Vec2<double>{watch_double(v.x), watch_double(v.y)}; };
  return {d(s.position), d(s.velocity), Vec2<double>{}, watch_double(s.time)};
}

// How to advance: the event engine (exact; frames at record times), or the
// step engine (the article's loop: each step of length dt finds the earliest
// contact inside it with `method`, moves there, responds and goes on with the
// rest of the step; steps end at record times too).
struct EngineChoice {
  bool step = false;
  double dt = 0;
  ToiMethod method = ToiMethod::analytic;
  double eps = 1e-9;
  // false: every strike in a gas takes the general path too, not the plain
  // gas path (EventEngine::collide_in_gas); the same bits, which a property
  // checks (properties/determinism_checks.cpp).
  bool plain_gas_path = true;
  // false: a gas's queue keeps every prediction, as under accelerations,
  // not each ball's earliest contact only (event_queue.hpp); the same bits,
  // which the same property checks.
  bool earliest_contact_only = true;
  // false: a gas runs in EventEngine, not in GasEngine (gas_engine.hpp);
  // the same bits, which the property gas-engine checks.
  bool gas_engine = true;
};

// Who is handed the frames: a callable on_frame(const FrameRecord&) takes
// them whole. A FrameSink takes a large one in slices as it is made (a
// million balls' whole frame is 32 MB of the run's peak, held only to be
// written): sink.balls_per_slice() balls at a time (0: whole frames, as a
// frame no larger than one slice always is), each to sink.slice(), then
// sink(record) with the frame's step, time, energy and hash, and its
// positions and velocities empty.
template <class S>
concept FrameSink = requires(S& s, const FrameSlice& slice, const FrameRecord& f) {
  { s.balls_per_slice() } -> std::convertible_to<std::size_t>;
  s.slice(slice);
  s(f);
};

// Checkpoints: every `every_frames` record times the whole state (engine and
// this driver's running summary) goes to `on_checkpoint` as bytes. A run
// given `resume_from` (such bytes) continues after that record time and
// produces exactly what the uninterrupted run would: a gas's state holds the
// engine's pending events and each ball's cell as well as the bodies, and
// under accelerations prediction starts afresh at every record time anyway,
// so a checkpoint changes nothing in the run.
struct CheckpointControl {
  std::int64_t every_frames = 0;  // 0: no checkpoints
  std::function<void(double time, std::vector<std::uint8_t> state)> on_checkpoint;
  const std::vector<std::uint8_t>* resume_from = nullptr;
};

namespace simulate_detail {
template <class Num, class Engine, class OnFrame, class OnEvent>
SimulationSummary drive(Engine& engine, const Scene& scene, const RestScales& scales,
                        const std::vector<std::array<double, 4>>& walls, double until, OnFrame& on_frame,
                        OnEvent& on_event, const EngineChoice& choice, const CheckpointControl& checkpoints,
                        std::chrono::steady_clock::time_point started);

// `owned`: the scene itself, whose balls are let go once the world is made.
template <class Num, class OnFrame, class OnEvent>
SimulationSummary simulate(const Scene& scene, Scene* owned, double until, OnFrame on_frame, OnEvent on_event,
                           const EngineChoice& choice, const CheckpointControl& checkpoints) {
  const auto started = std::chrono::steady_clock::now();
  const RestScales scales = rest_scales(scene);
  const RestThresholds<Num> thresholds = scales.in<Num>();
  std::vector<std::array<double, 4>> walls;
  for (const WallSpec& w : scene.walls) walls.push_back({w.a[0], w.a[1], w.b[0], w.b[1]});
  // A gas's world is made from the scene's balls directly: no World of
  // Bodies is held beside them (the same bodies either way).
  if (choice.gas_engine && choice.plain_gas_path && choice.earliest_contact_only && !choice.step)
    if (std::optional<GasWorld<Num>> gas = gas_world_of_scene<Num>(scene);
        gas && GasEngine<Num>::applies(*gas, choice.method, thresholds)) {
      if (owned) std::vector<BallSpec>().swap(owned->balls);
      GasEngine<Num> engine(std::move(*gas), thresholds);
      return drive<Num>(engine, scene, scales, walls, until, on_frame, on_event, choice, checkpoints, started);
    }
  World<Num> world = make_world<Num>(scene);
  if (owned) std::vector<BallSpec>().swap(owned->balls);
  EventEngine<Num> engine(std::move(world), thresholds, choice.method, num<Num>(choice.eps));
  engine.use_plain_gas_path(choice.plain_gas_path);
  engine.keep_earliest_contact_only(choice.earliest_contact_only);
  return drive<Num>(engine, scene, scales, walls, until, on_frame, on_event, choice, checkpoints, started);
}

// The run itself, in either engine: record times, frames, checkpoints.
template <class Num, class Engine, class OnFrame, class OnEvent>
SimulationSummary drive(Engine& engine, const Scene& scene, const RestScales& scales,
                        const std::vector<std::array<double, 4>>& walls, double until, OnFrame& on_frame,
                        OnEvent& on_event, const EngineChoice& choice, const CheckpointControl& checkpoints,
                        std::chrono::steady_clock::time_point started) {
  using T = NumberTraits<Num>;
  SimulationSummary summary;
  summary.rest = scales;
  summary.last_tenth = until / 10;
  const double last_tenth_from = until - summary.last_tenth;
  TunnellingWatch watch(walls);
  // The watch checks each ball's path piece by piece. Where a record time
  // carries the balls (accelerations, the step engine) a piece ends there;
  // in a gas nothing happens to a ball at a record time, so its piece runs on
  // to its next event, and is cut only where the run stops or may be resumed
  // (the last frame, a checkpoint: a resumed run starts its pieces there).
  // The gas engine says where each piece began (a body changes only at its
  // own strikes), and the watch then keeps no starts of its own (40 bytes a
  // ball) and cuts no piece but at the run's end, until a jam hands the run
  // to the general engine, whose pieces it keeps from there.
  const bool frames_end_pieces = choice.step || !engine.keeps_predictions();
  bool watch_keeps_starts = true;
  // f(the engine's world), whichever type it is (gas_world.hpp).
  auto with_world = [&](auto f) {
    if constexpr (std::is_same_v<Engine, GasEngine<Num>>) engine.with_world(f);
    else f(engine.world());
  };
  if constexpr (std::is_same_v<Engine, GasEngine<Num>>) {
    watch_keeps_starts = engine.handed_over();
    engine.on_hand_over([&](const World<Num>& w) {
      watch.restart(path_points_on_own_clocks(w));
      watch_keeps_starts = true;
    });
  }
  if (watch_keeps_starts) with_world([&](const auto& w) { watch.restart(path_points(w, Num{})); });
  std::size_t balls_per_slice = 0;
  if constexpr (FrameSink<OnFrame>) balls_per_slice = on_frame.balls_per_slice();
  // The frame check's largest radius, once: the radii never change.
  double largest_radius = 0;
  with_world([&](const auto& w) {
    for (const auto& b : w.balls) largest_radius = std::max(largest_radius, T::to_double(b.radius));
  });
  auto frame_of = [&](const auto& w, std::int64_t step, const Num& t) {
    if constexpr (FrameSink<OnFrame>)
      if (balls_per_slice > 0 && balls_per_slice < w.balls.size())
        return make_frame_in_slices(w, step, t, balls_per_slice, [&](const FrameSlice& s) { on_frame.slice(s); });
    return make_frame(w, step, t);
  };
  auto record = [&](std::int64_t step, const Num& t, bool pieces_end, bool last) {
    FrameRecord f;
    with_world([&](const auto& w) {
      f = frame_of(w, step, t);
      if (pieces_end || last)
        for (std::size_t i = 0; i < w.balls.size(); ++i) {
          const auto& b = w.balls[i];
          if (b.fixed) continue;
          if (watch_keeps_starts) watch.observe(i, path_point(b, t));
          else if (last) watch.check(path_point<Num>({b.position, b.velocity, b.time}), piece_end(b, t));
        }
    });
    summary.wall_crossings = watch.crossings();
    if (step == 0) summary.energy_start = f.energy;
    summary.energy_end = f.energy;
    summary.final_hash = f.state_hash;
    if (!engine.all_at_rest()) summary.at_rest_since = -1;
    else if (summary.at_rest_since < 0) summary.at_rest_since = f.time;
    ++summary.frames;
    on_frame(f);
    // The overlap check reads the positions alone: the velocities (16 bytes
    // a ball, and their raw words in fixed point) go first, and the check's
    // grid takes their room instead of adding to the frame's.
    std::vector<double>().swap(f.velocity);
    std::vector<std::int64_t>().swap(f.velocity_raw);
    // The radii are read from the bodies, not kept for the run (8 bytes a
    // ball): the scene's own (a double converts exactly, and back, into
    // fixed point's 64 fractional bits down to radii of 2^-12). A frame
    // handed on in slices holds no positions: each centre is read from its
    // body again, as the frame read it (the same doubles).
    with_world([&](const auto& w) {
      auto radius = [&](std::size_t i) { return T::to_double(w.balls[i].radius); };
      auto centre_of_body = [&](std::size_t i) {
        const Vec2<Num> p = state_as_read(w.balls[i], t).position;
        return Vec2<double>{T::to_double(p.x), T::to_double(p.y)};
      };
      const std::size_t n = w.balls.size();
      const double deepest = f.position.empty() ? deepest_overlap_of(centre_of_body, radius, n, largest_radius, walls)
                                                : deepest_overlap_of(f, radius, n, largest_radius, walls);
      summary.deepest_overlap = std::max(summary.deepest_overlap, deepest);
    });
  };
  const Num interval = num<Num>(scene.record_interval);
  const Num end = num<Num>(until);
  auto on_engine_collision = [&](const Collision<Num>& c) {
    const bool pair = c.kind == EventKind::ball_ball;
    with_world([&](const auto& w) {
      if (c.has_piece_starts) {
        watch.check(path_point<Num>(c.piece_start_a), piece_end(w.balls[c.a], c.time));
        if (pair) watch.check(path_point<Num>(c.piece_start_b), piece_end(w.balls[c.b], c.time));
      } else {
        if (!w.balls[c.a].fixed) watch.observe(c.a, path_point(w.balls[c.a], c.time));
        if (pair && !w.balls[c.b].fixed) watch.observe(c.b, path_point(w.balls[c.b], c.time));
      }
    });
    const EventRecord r{T::to_double(c.time), c.kind == EventKind::ball_ball ? 0 : 1, c.a, c.b, T::to_double(c.impulse)};
    ++summary.events;
    if (r.time >= last_tenth_from) ++summary.events_last_tenth;
    on_event(r);
  };
  auto advance = [&](const Num& t) { engine.advance_to(t, [&](const Collision<Num>& c) { on_engine_collision(c); }); };
  // A gas keeps its predictions across record times, to the run's end, and
  // the record interval changes only what is written; under accelerations
  // the engine starts afresh at each record time (EventEngine::run_to). The
  // step engine's steps are runs of their own.
  auto run_to = [&](const Num& t) {
    if (choice.step) return advance(t);
    engine.run_to(t, end, [&](const Collision<Num>& c) { on_engine_collision(c); });
  };
  const Num dt = num<Num>(choice.step ? choice.dt : 0.0);
  Num step_start{};
  std::int64_t first = 1;
  auto save = [&](std::int64_t k) {
    ByteWriter out;
    out.put(k);
    out.put(summary.frames);
    for (double x : {summary.energy_start, summary.energy_end, summary.deepest_overlap, summary.at_rest_since}) out.put(x);
    out.put(summary.wall_crossings);
    out.put(summary.events);
    out.put(summary.events_last_tenth);
    out.put(summary.final_hash);
    out.put(step_start);
    engine.save(out);
    return std::move(out.bytes());
  };
  if (checkpoints.resume_from) {
    ByteReader in(*checkpoints.resume_from);
    std::int64_t k = 0;
    in.get(k);
    in.get(summary.frames);
    for (double* x : {&summary.energy_start, &summary.energy_end, &summary.deepest_overlap, &summary.at_rest_since}) in.get(*x);
    in.get(summary.wall_crossings);
    in.get(summary.events);
    in.get(summary.events_last_tenth);
    in.get(summary.final_hash);
    in.get(step_start);
    engine.load(in);
    if (!in.done()) throw std::runtime_error("checkpoint state has trailing bytes");
    first = k + 1;
    if constexpr (std::is_same_v<Engine, GasEngine<Num>>) watch_keeps_starts = engine.handed_over();
    if (watch_keeps_starts) with_world([&](const auto& w) { watch.restart(path_points(w, engine.now())); });
    watch.set_crossings(summary.wall_crossings);
  } else {
    record(0, Num{}, false, false);  // the watch's pieces start here
  }
  for (std::int64_t k = first;; ++k) {
    Num t = interval * num<Num>(static_cast<double>(k));
    const bool last = !(t < end);
    if (last) t = end;
    if (choice.step) {
      // Steps of dt from the last step's end, cut at the record time.
      for (Num s = step_start + dt; s < t; s = s + dt) {
        advance(s);
        step_start = s;
      }
      step_start = t;
    }
    run_to(t);
    const bool checkpoint = checkpoints.every_frames > 0 && k % checkpoints.every_frames == 0 && checkpoints.on_checkpoint;
    record(k, t, frames_end_pieces || checkpoint, last);
    if (last) break;
    if (checkpoint) checkpoints.on_checkpoint(T::to_double(t), save(k));
  }
  summary.counters = engine.counters();
  if constexpr (std::is_same_v<Engine, GasEngine<Num>>) {
    engine.on_hand_over(nullptr);  // the watch goes with this frame
    summary.gas_engine_until = engine.handed_over() ? T::to_double(engine.handed_over_at()) : INFINITY;
  }
  summary.energy_removed_by_rest = T::to_double(engine.energy_removed_by_rest());
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return summary;
}
}  // namespace simulate_detail

template <class Num, class OnFrame, class OnEvent>
SimulationSummary simulate(const Scene& scene, double until, OnFrame on_frame, OnEvent on_event,
                           const EngineChoice& choice = {}, const CheckpointControl& checkpoints = {}) {
  return simulate_detail::simulate<Num>(scene, nullptr, until, on_frame, on_event, choice, checkpoints);
}

// The same, for a caller that gives the scene up: its balls are needed only
// to make the world, and go before the run starts (88 bytes a ball, 84 MiB
// of a million-ball run's peak). What else it holds stays.
template <class Num, class OnFrame, class OnEvent>
SimulationSummary simulate_releasing_balls(Scene& scene, double until, OnFrame on_frame, OnEvent on_event,
                                           const EngineChoice& choice = {}, const CheckpointControl& checkpoints = {}) {
  return simulate_detail::simulate<Num>(scene, &scene, until, on_frame, on_event, choice, checkpoints);
}

}  // namespace collide2d
