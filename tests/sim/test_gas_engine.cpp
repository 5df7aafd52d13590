// The gas engine (gas_engine.hpp) gives EventEngine's bits: the same frames,
// events and counts on a gas, through a jam (where it hands the run over)
// and through a checkpoint and resume on either side of the jam.
#include <catch2/catch.hpp>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "collide2d/numeric/fixed.hpp"
#include "collide2d/sim/simulate.hpp"
#include "engine_runs.hpp"
#include "lab/random_queries.hpp"

using namespace collide2d;
using collide2d::test::ball;
using collide2d::test::Recorded;

namespace {

// A box of side L with n balls on a lattice, random velocities (SplitMix),
// two sizes and masses, restitution e (walls too), no gravity.
Scene box_gas(int n, double L, double e, std::uint64_t seed) {
  Scene s;
  s.gravity = {0, 0};
  s.restitution = e;
  s.record_interval = 0.5;
  s.walls = {{{0, 0}, {L, 0}, e}, {{L, 0}, {L, L}, e}, {{L, L}, {0, L}, e}, {{0, L}, {0, 0}, e}};
  s.walls.push_back({{0.3 * L, 0.6 * L}, {0.5 * L, 0.45 * L}, e});  // a slanted wall inside, with two round ends
  SplitMix64 rng(seed);
  auto uniform = [&] { return rng.uniform(-1, 1); };
  const int side = 1 + static_cast<int>(std::sqrt(static_cast<double>(n)));
  for (int k = 0; k < n; ++k) {
    const double x = (k % side + 0.5) * L / side, y = (k / side + 0.5) * L / side;
    if (std::fabs(y - 0.6 * L + (x - 0.3 * L) * 0.75) < 0.6 && x > 0.2 * L && x < 0.6 * L) continue;  // near the inner wall
    s.balls.push_back(ball(x, y, 2 * uniform(), 2 * uniform(), k % 3 == 0 ? 0.2 : 0.12, k % 3 == 0 ? 2.0 : 1.0, e));
  }
  return s;
}

// Three balls in a row, the last two touching exactly (centres 2r apart in
// doubles), the first coming at them: at t = 1 the middle ball is struck,
// and at that instant it strikes the third: a jam, in the middle of a gas.
Scene gas_with_a_jam(double e) {
  Scene s = box_gas(250, 14, e, 99);
  std::vector<BallSpec> kept;
  for (const BallSpec& b : s.balls)
    if (b.position[1] > 5) kept.push_back(b);  // nothing reaches the row before t = 1
  s.balls = kept;
  s.balls.push_back(ball(1.5, 1.5, 1, 0, 0.25));
  s.balls.push_back(ball(3.0, 1.5, 0, 0, 0.25));
  s.balls.push_back(ball(3.5, 1.5, 0, 0, 0.25));
  return s;
}

template <class Num>
bool same_bits(const Num& x, const Num& y) {
  return std::memcmp(&x, &y, sizeof x) == 0;
}

void require_same_run(const Recorded& gas, const Recorded& event) {
  REQUIRE(gas.events.size() == event.events.size());
  for (std::size_t k = 0; k < gas.events.size(); ++k) {
    INFO("event " << k);
    REQUIRE(same_bits(gas.events[k].time, event.events[k].time));
    REQUIRE(gas.events[k].a == event.events[k].a);
    REQUIRE(gas.events[k].b == event.events[k].b);
    REQUIRE(same_bits(gas.events[k].impulse, event.events[k].impulse));
  }
  REQUIRE(gas.frames.size() == event.frames.size());
  for (std::size_t k = 0; k < gas.frames.size(); ++k) REQUIRE(gas.frames[k].state_hash == event.frames[k].state_hash);
  CHECK(gas.summary.counters.ball_ball == event.summary.counters.ball_ball);
  CHECK(gas.summary.counters.ball_wall == event.summary.counters.ball_wall);
  CHECK(gas.summary.counters.rest.creeping == event.summary.counters.rest.creeping);
  CHECK(gas.summary.counters.rest.came_to_rest == event.summary.counters.rest.came_to_rest);
  CHECK(gas.summary.counters.rest.plastic_pairs == event.summary.counters.rest.plastic_pairs);
  CHECK(gas.summary.final_hash == event.summary.final_hash);
}

template <class Num>
void check_gas_against_event_engine(const Scene& s, double until, bool jam) {
  EngineChoice event_engine;
  event_engine.gas_engine = false;
  const Recorded gas = test::run<Num>(s, until), event = test::run<Num>(s, until, event_engine);
  CHECK(event.summary.gas_engine_until == -1);
  if (jam) {
    CHECK(gas.summary.gas_engine_until == 1.0);  // the jam's instant, where the run was handed over
  } else {
    CHECK(std::isinf(gas.summary.gas_engine_until));
    CHECK(gas.summary.counters.cell_crossings == event.summary.counters.cell_crossings);
  }
  REQUIRE(gas.events.size() > 500);  // a run with something in it
  require_same_run(gas, event);
}

// The run resumed from each of its checkpoints ends as the uninterrupted one,
// and makes the same checkpoints on the way.
template <class Num>
void check_resume(const Scene& s, double until) {
  std::vector<std::vector<std::uint8_t>> states;
  CheckpointControl every;
  every.every_frames = 3;
  every.on_checkpoint = [&](double, std::vector<std::uint8_t> state) { states.push_back(std::move(state)); };
  Recorded whole;
  whole.summary = simulate<Num>(s, until, [&](const FrameRecord& f) { whole.frames.push_back(f); },
                                [&](const EventRecord& e) { whole.events.push_back(e); }, {}, every);
  REQUIRE(states.size() >= 3);
  for (std::size_t k = 0; k < states.size(); ++k) {
    INFO("resumed from checkpoint " << k);
    CheckpointControl from;
    from.resume_from = &states[k];
    from.every_frames = 3;
    std::vector<std::vector<std::uint8_t>> later;
    from.on_checkpoint = [&](double, std::vector<std::uint8_t> state) { later.push_back(std::move(state)); };
    std::vector<EventRecord> events;
    const SimulationSummary resumed = simulate<Num>(s, until, [](const FrameRecord&) {},
                                                    [&](const EventRecord& e) { events.push_back(e); }, {}, from);
    CHECK(resumed.final_hash == whole.summary.final_hash);
    CHECK(resumed.counters.ball_ball == whole.summary.counters.ball_ball);
    CHECK(resumed.counters.stale == whole.summary.counters.stale);
    CHECK(resumed.counters.cell_crossings == whole.summary.counters.cell_crossings);
    CHECK(resumed.gas_engine_until == whole.summary.gas_engine_until);
    REQUIRE(events.size() <= whole.events.size());
    const std::size_t skipped = whole.events.size() - events.size();
    for (std::size_t m = 0; m < events.size(); ++m) REQUIRE(same_bits(events[m].time, whole.events[skipped + m].time));
    // Its checkpoints are the uninterrupted run's, byte for byte.
    REQUIRE(later.size() == states.size() - k - 1);
    for (std::size_t m = 0; m < later.size(); ++m) CHECK(later[m] == states[k + 1 + m]);
  }
}

// A run whose tunnelling watch is shown one wall more than the engine: a
// line across the box that the balls fly through, each pass a crossing. The
// gas engine's watch checks each piece from where the engine says it began
// and keeps no starts; EventEngine's keeps them (and so does the gas
// engine's after a jam): both must count the same crossings, resumed or not.
template <class Engine>
SimulationSummary run_with_a_wall_only_the_watch_sees(const Scene& s, double until, const CheckpointControl& checkpoints) {
  const RestScales scales = rest_scales(s);
  std::vector<std::array<double, 4>> walls;
  for (const WallSpec& w : s.walls) walls.push_back({w.a[0], w.a[1], w.b[0], w.b[1]});
  walls.push_back({7.0, 0.5, 7.0, 13.5});
  World<double> world = make_world<double>(s);
  const RestThresholds<double> thresholds = scales.in<double>();
  Engine engine = [&] {
    if constexpr (std::is_same_v<Engine, GasEngine<double>>) return Engine(std::move(world), thresholds);
    else return Engine(std::move(world), thresholds, ToiMethod::analytic, 1e-9);
  }();
  auto on_frame = [](const FrameRecord&) {};
  auto on_event = [](const EventRecord&) {};
  return simulate_detail::drive<double>(engine, s, scales, walls, until, on_frame, on_event, EngineChoice{},
                                        checkpoints, std::chrono::steady_clock::now());
}

void check_watch_counts(const Scene& s, double until) {
  std::vector<std::vector<std::uint8_t>> states;
  CheckpointControl every;
  every.every_frames = 3;
  every.on_checkpoint = [&](double, std::vector<std::uint8_t> state) { states.push_back(std::move(state)); };
  const SimulationSummary gas = run_with_a_wall_only_the_watch_sees<GasEngine<double>>(s, until, every);
  const SimulationSummary event = run_with_a_wall_only_the_watch_sees<EventEngine<double>>(s, until, {});
  // Each ball of this gas flies a few of its own diameters between strikes
  // and the box is 14 wide: over the run, many pieces cross the line.
  CHECK(gas.wall_crossings > 20);
  CHECK(gas.wall_crossings == event.wall_crossings);
  CHECK(gas.final_hash == event.final_hash);
  REQUIRE(states.size() >= 2);
  for (std::size_t k = 0; k < states.size(); ++k) {
    INFO("resumed from checkpoint " << k);
    CheckpointControl from;
    from.resume_from = &states[k];
    CHECK(run_with_a_wall_only_the_watch_sees<GasEngine<double>>(s, until, from).wall_crossings == gas.wall_crossings);
  }
}

}  // namespace

TEST_CASE("gas engine: a gas of 300 balls gives the event engine's bits, in both modes") {
  const Scene s = box_gas(300, 14, 0.9, 7);
  check_gas_against_event_engine<double>(s, 8, false);
  check_gas_against_event_engine<Fixed>(s, 8, false);
  const Scene elastic = box_gas(300, 14, 1.0, 11);
  check_gas_against_event_engine<double>(elastic, 8, false);
}

TEST_CASE("gas engine: at a jam it hands the run over, and the bits stay the event engine's") {
  for (double e : {1.0, 0.6}) {
    INFO("restitution " << e);
    check_gas_against_event_engine<double>(gas_with_a_jam(e), 10, true);
    check_gas_against_event_engine<Fixed>(gas_with_a_jam(e), 10, true);
  }
}

TEST_CASE("gas engine: resumed from any checkpoint, before or after a jam, it ends as the whole run") {
  check_resume<double>(box_gas(200, 12, 0.9, 3), 6);
  check_resume<double>(gas_with_a_jam(0.6), 6);
  check_resume<Fixed>(gas_with_a_jam(1.0), 6);
}

TEST_CASE("gas engine: it runs only where the scene is a gas") {
  Scene with_gravity = box_gas(50, 10, 0.9, 5);
  with_gravity.gravity = {0, -1};
  CHECK(test::run<double>(with_gravity, 1).summary.gas_engine_until == -1);
  Scene with_a_fixed_ball = box_gas(50, 10, 0.9, 5);
  with_a_fixed_ball.balls[3].fixed = true;
  with_a_fixed_ball.balls[3].velocity = {0, 0};
  CHECK(test::run<double>(with_a_fixed_ball, 1).summary.gas_engine_until == -1);
  CHECK(std::isinf(test::run<double>(box_gas(50, 10, 0.9, 5), 1).summary.gas_engine_until));
}

TEST_CASE("gas engine: the tunnelling watch counts from the engine's piece starts what it counts from its own") {
  check_watch_counts(box_gas(200, 14, 1.0, 5), 6);
  // After the jam at t = 1 the general engine runs and the watch keeps its starts.
  check_watch_counts(gas_with_a_jam(0.6), 6);
}

TEST_CASE("gas world: bodies go to one-line bodies and back bit for bit, and only those that fit") {
  Scene s = box_gas(40, 10, 0.9, 21);
  s.balls[5].restitution = 0.25;  // one differs: each ball's restitution is kept
  World<double> w = make_world<double>(s);
  for (std::size_t i = 0; i < w.balls.size(); ++i) {
    Body<double>& b = w.balls[i];
    REQUIRE(fits_a_gas_body(b));
    if (i % 3 == 0) {  // struck once: its clock is its last strike's time
      b.time = 0.125 * static_cast<double>(i);
      b.struck_at = b.time;
      b.version = 2 * i + 2;
    }
  }
  const GasWorld<double> g = gas_world_of(w);
  CHECK(g.restitution.size() == w.balls.size());
  const World<double> back = world_of(g);
  REQUIRE(back.balls.size() == w.balls.size());
  for (std::size_t i = 0; i < w.balls.size(); ++i) {
    INFO("ball " << i);
    const Body<double>&x = w.balls[i], &y = back.balls[i];
    for (const auto& [p, q] : {std::pair{&x.position, &y.position}, {&x.velocity, &y.velocity},
                               {&x.acceleration, &y.acceleration}, {&x.free_acceleration, &y.free_acceleration}}) {
      CHECK(same_bits(p->x, q->x));
      CHECK(same_bits(p->y, q->y));
    }
    for (const auto& [p, q] : {std::pair{&x.time, &y.time}, {&x.radius, &y.radius}, {&x.mass, &y.mass},
                               {&x.restitution, &y.restitution}, {&x.struck_at, &y.struck_at}})
      CHECK(same_bits(*p, *q));
    CHECK(x.version == y.version);
    CHECK(!y.fixed);
    CHECK(!y.asleep);
  }
  // One restitution for all: kept once.
  CHECK(gas_world_of(make_world<double>(box_gas(40, 10, 0.9, 21))).restitution.empty());
  // What a one-line body cannot hold.
  Body<double> b = w.balls[1];
  b.free_acceleration.x = -0.0;  // −0: the arithmetic on it would differ in its zeros
  CHECK(!fits_a_gas_body(b));
  b = w.balls[1];
  b.asleep = true;
  CHECK(!fits_a_gas_body(b));
  b = w.balls[1];
  b.fixed = true;
  CHECK(!fits_a_gas_body(b));
  b = w.balls[0];  // struck: its struck_at must be its clock
  b.struck_at = b.time + 1;
  CHECK(!fits_a_gas_body(b));
}
