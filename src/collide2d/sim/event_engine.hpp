// The event-driven engine: exact event order, deterministic ties.
//
// Time advances from event to event; nothing is stepped. Between record
// times T_k = k Δ every ball moves on its exact parabola, each pair's next
// contact is predicted by the analytic time of impact, and the earliest
// event is processed first, in (time, kind, a, b) order (event_queue.hpp).
// How record times meet the motion depends on the scene (simulate.hpp):
//  - Without accelerations (a gas), record times do not touch the motion:
//    run_to carries nothing and keeps every prediction (made once, to the
//    end of the run), a frame reads each ball's state at T_k from its own
//    clock, and a checkpoint holds the queue itself, so a resumed
//    run goes on with the very predictions the uninterrupted one had. The
//    record interval changes what is written, never the run.
//  - Under accelerations, advance_to carries every ball to T_k and the
//    prediction starts afresh for [T_k, T_k+1]: a horizon of one record
//    interval. A parabola's time of impact over a long horizon is costly in
//    fixed point, and a settling pile's predictions rarely live long
//    (README, "Frames that keep predictions"). The step engine's steps are
//    runs of their own the same way.
//
// Only neighbours are predicted against each other (cell_grid.hpp); a pair
// is always predicted from the later of the two balls' clocks, so the grid
// changes the cost of a run, never its bits.
//
// What a contact does, and the rules that bring balls to rest (persistent
// contacts, sleep) and wake them, are in contact_rules.hpp, contact_graph.hpp
// and rest.hpp. This file decides when: after each contact it solves the
// forces of the islands involved, lets their balls fall asleep if they can,
// wakes what a strike wakes, and predicts again for every ball whose motion
// changed. A sleeping ball is static, like a fixed one: it makes no events of
// its own and is predicted against as an obstacle.
//
// This file holds the class, its public interface and the event loop (which
// event is next, what it does, the islands it touches). The members of each
// other concept are defined in a file of their own, included at the end:
// event_engine_prediction.hpp (when the next events come),
// event_engine_rest.hpp (sleep and wake: how the engine applies rest.hpp's
// rules 2 and 3), event_engine_gas.hpp (a strike in a gas, without the rest
// rules' bookkeeping) and event_engine_checkpoint.hpp (the state as bytes).
#pragma once

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "collide2d/sim/cell_grid.hpp"
#include "collide2d/sim/contact_graph.hpp"
#include "collide2d/sim/contact_rules.hpp"
#include "collide2d/sim/event_queue.hpp"
#include "collide2d/sim/prefetch.hpp"
#include "collide2d/sim/state_bytes.hpp"
#include "collide2d/sim/world.hpp"
#include "collide2d/toi/article_methods.hpp"

namespace collide2d {

struct EngineStall : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A run of events that never lets time advance is a stall (a contact the
// model cannot resolve): reported rather than looped on for ever. Both
// engines count the events at one time this way.
inline constexpr int max_events_at_one_time = 100000;

// The count of events at one time once an event at `time` is taken (time
// advanced: 0); throws EngineStall past max_events_at_one_time.
template <typename Num>
int count_events_at_one_time(int count, const Num& time, const Num& now, EventKind kind, int a, int b) {
  count = time == now ? count + 1 : 0;
  if (count > max_events_at_one_time) {
    char at[32];  // the instant, in the shortest text that reads back as it
    char* at_end = std::to_chars(at, at + sizeof at, NumberTraits<Num>::to_double(time)).ptr;
    throw EngineStall("engine stalled: more than " + std::to_string(max_events_at_one_time) +
                      " events at one time, t = " + std::string(at, static_cast<std::size_t>(at_end - at)) +
                      ", last between ball " + std::to_string(a) + " and " +
                      (kind == EventKind::ball_ball ? "ball " : "wall ") + std::to_string(b));
  }
  return count;
}

// What changed a ball's motion, as the engine tells its observer (below).
enum class MotionChange {
  response,  // the response to a collision (contact_rules.hpp): velocities of an island
  renewed,   // a contact renewed where it slid off a round partner (ContactRules::renew): velocities of an island
  forces,    // the ball's island's contact forces solved again (its acceleration; after a hold, its velocity)
  sleep,     // it fell asleep (rest.hpp, rule 2): velocity and acceleration zero
  wake,      // it woke (rule 3)
};

// The engine's observer: told of every change of a ball's motion, right
// after the change, with the ball carried to the engine's present time and
// its version (Body::version) one higher than before. Every change is told,
// wherever the engine makes it: in a collision's response and outside any
// collision callback (a contact left or renewed, forces solved again, sleep,
// wake), so that a trace of the motion (properties/engine_trace.hpp) sees
// every piece of every ball's path. The default observer does nothing and
// costs nothing: simulate() and the command line use it.
// An observer may also have ball_ball_asked(BallState a, BallState b, Num
// horizon) and ball_wall_asked(BallState a, int wall, Num horizon): then it
// is told of every time-of-impact query the engine asks (lab/engine_queries
// gathers the engine's own query mix with them).
struct NoMotionObserver {
  template <class Num>
  void motion_changed(const World<Num>&, int, MotionChange) {}
};

struct EngineCounters {
  std::uint64_t ball_ball = 0, ball_wall = 0, leave_wall = 0, leave_pair = 0, stale = 0;
  std::uint64_t cell_crossings = 0;
  std::uint64_t ignored = 0;  // contacts a method reported for objects moving apart
  RestCounters rest;          // what the rest rules did (rest.hpp)
  IslandSolveCounters islands;  // what their island solves cost (contact_graph.hpp)
};

template <class Num, class Observer = NoMotionObserver>
class EventEngine {
 public:
  // `method`: how contacts are predicted. analytic is exact; bisection and
  // seed (the article's, tolerance `eps`) are for the step engine, which is
  // this engine advanced one step at a time (see simulate.hpp).
  // `one_cell`: predict every pair (no grid); the results are the same bits.
  // `observer`: told of every change of a ball's motion (NoMotionObserver).
  EventEngine(World<Num> world, const RestThresholds<Num>& thresholds, ToiMethod method = ToiMethod::analytic,
              const Num& eps = Num{}, bool one_cell = false, Observer observer = {})
      : world_(std::move(world)), rules_(thresholds), method_(method), eps_(eps),
        grid_(world_, one_cell, NumberTraits<Num>::to_double(thresholds.band)), observer_(std::move(observer)) {
    graph_.reset(world_.balls.size());
    queue_.reserve(world_.balls.size());
    queue_.keep_earliest_contact_only(keeps_predictions_);
  }

  const World<Num>& world() const { return world_; }
  World<Num>& world() { return world_; }
  EngineCounters counters() const {
    EngineCounters c = counters_;
    c.rest = rules_.counters;
    c.islands = graph_.solve_counters;
    return c;
  }
  const Num& now() const { return now_; }
  // Whether a plain strike in a gas takes collide_in_gas (the default) or
  // the general collide() and settle(): the same bits either way.
  void use_plain_gas_path(bool on) { plain_gas_path_ = on && plain_gas_scene(); }
  // Whether a gas's queue keeps each ball's earliest contact only (the
  // default) or every prediction, as under accelerations (event_queue.hpp):
  // the same bits either way. Before the first event.
  void keep_earliest_contact_only(bool on) { queue_.keep_earliest_contact_only(on && keeps_predictions_); }
  const Num& energy_removed_by_rest() const { return rules_.energy_removed; }
  // No ball accelerates (a gas: straight paths, no rest rules): run_to keeps
  // the predictions across record times.
  bool keeps_predictions() const { return keeps_predictions_; }
  bool all_at_rest() const {
    return std::all_of(world_.balls.begin(), world_.balls.end(), [](const Body<Num>& b) { return b.is_static(); });
  }

  // Processes every event up to `until` (inclusive) and carries all balls
  // there, predicting afresh within [now, until] (record times under
  // accelerations; each step of the step engine). `on_collision(const
  // Collision<Num>&)` sees each collision in order.
  template <class OnCollision>
  void advance_to(const Num& until, OnCollision on_collision) {
    predict_all(until);
    process_until(until, until, on_collision);
    for (Body<Num>& b : world_.balls) advance_to_time(b, until);
    now_ = until;
    primed_ = false;
  }

  // The event engine from one record time to the next: every event up to
  // `until` (inclusive). A gas (keeps_predictions) predicts to `end`, the
  // run's end, the same at every call, and leaves every ball on its own
  // clock: the predictions stay good and are kept; the first call predicts
  // every ball. Under accelerations this is advance_to(until).
  template <class OnCollision>
  void run_to(const Num& until, const Num& end, OnCollision on_collision) {
    if (!keeps_predictions_) return advance_to(until, on_collision);
    if (!primed_ || !(end == end_)) predict_all(end);
    primed_ = true;
    end_ = end;
    process_until(until, end, on_collision);
    now_ = until;
  }

 private:
  void predict_all(const Num& end) {
    queue_.clear();
    grid_.assign(world_, now_);
    for (int i = 0; i < static_cast<int>(world_.balls.size()); ++i)
      predict(i, end, [&](int j) { return j < i && !world_.balls[j].is_static(); });
  }

  // Events up to `until`, each predicted again within `end`.
  template <class OnCollision>
  void process_until(const Num& until, const Num& end, OnCollision& on_collision) {
    while (!queue_.empty() && !(until < queue_.next_time())) {
      const PoppedEvent<Num> popped = queue_.pop();
      const Event<Num>& e = popped.event;
      queue_.prefetch_next([&](int k) __attribute__((always_inline)) {
        prefetch_object(&world_.balls[static_cast<std::size_t>(k)]);
        grid_.prefetch_cell_of(k);
      });
      // The look-ahead of the event before asked for these balls' cell
      // numbers; now the cells around them, which predict() reads.
      grid_.prefetch_neighbourhood(e.a);
      if (between_two_balls(e.kind)) grid_.prefetch_neighbourhood(e.b);
      // The owner's earliest contact, out of the queue with its owner's
      // motion as predicted: its next contact is asked for again after it.
      auto owner_as_predicted = [&] {
        return popped.contact && world_.balls[static_cast<std::size_t>(popped.owner)].version == popped.owner_version;
      };
      if (!current(e)) {
        ++counters_.stale;
        if (owner_as_predicted()) predict_contacts_after(popped.owner, e, end, true);
        continue;
      }
      same_time_events_ = count_events_at_one_time(same_time_events_, e.time, now_, e.kind, e.a, e.b);
      now_ = e.time;
      const bool as_predicted = owner_as_predicted();
      process(e, end, on_collision);
      if (as_predicted && owner_as_predicted()) predict_contacts_after(popped.owner, e, end, false);
    }
  }

 public:
  // A gas run handed over by GasEngine (gas_engine.hpp) at a jam: `next`,
  // the first event it did not process, is at `now`; the counts so far go
  // on. Every current contact is predicted afresh from the balls' clocks,
  // those before `next` (processed, changing nothing) left out, `next`'s
  // own place kept: the queue an uninterrupted run of this engine holds.
  // `grid`: the gas's own, laid out from the balls' starting centres, as a
  // resumed run lays it out again (a grid made from the centres at the jam
  // would give a resumed run other cells, and other checkpoints).
  void take_over_gas(const Num& now, const Num& end, const Event<Num>& next, const EngineCounters& so_far,
                     int same_time_events, CellGrid<Num> grid) {
    adopt_grid(std::move(grid));
    now_ = now;
    counters_ = so_far;
    rules_.counters = so_far.rest;
    counters_.rest = {};
    same_time_events_ = same_time_events;
    contacts_after_ = &next;
    contacts_from_stale_ = true;
    predict_all(end);
    contacts_after_ = nullptr;
    primed_ = true;
    end_ = end;
  }

  // The grid of a gas handed over (take_over_gas), before its checkpoint is loaded.
  void adopt_grid(CellGrid<Num> grid) { grid_ = std::move(grid); }

  // The whole mutable state at a record time (checkpoints): the clock, the
  // counters, the rest rules' energy tallies, every body on its own clock,
  // the contact graph, and (from run_to) the pending events and each ball's
  // cell. Walls never change and are not stored. The layout's version leads,
  // so that a checkpoint of another layout is refused by name instead of
  // misread (4: wall contacts in the contact graph, no faces; 6: the island
  // solves' counters; 7: the queue and the cells, from run_to; 8: a ball's
  // earliest contact, crossing and contact ends in the queue, not a list; 9:
  // each cell's members in order, the count of events at one time, and
  // which islands' forces are still good).
  static constexpr std::uint32_t checkpoint_layout = 9;

  // Field by field (event_engine_checkpoint.hpp).
  void save(ByteWriter& out) const;
  void load(ByteReader& in);

 private:
  World<Num> world_;
  ContactRules<Num> rules_;
  ToiMethod method_;
  Num eps_;
  CellGrid<Num> grid_;
  ContactGraph<Num> graph_;
  Num now_{};
  EngineCounters counters_;
  int same_time_events_ = 0;
  EventQueue<Num> queue_;
  bool keeps_predictions_ = no_ball_accelerates(world_);  // fixed by the scene
  bool primed_ = false;  // run_to: the queue holds every prediction to end_
  Num end_{};
  // Scratch lists of an event, kept so that their storage is reused.
  std::vector<int> changed_, island_, neighbours_;
  std::vector<std::uint64_t> judged_;  // settle(): the judgement in which a ball's island was found unable to sleep
  std::uint64_t judgement_ = 0;
  Collision<Num> gas_collision_;  // collide_in_gas's answer, its vectors reused
  const Event<Num>* contacts_after_ = nullptr;  // predict_contacts_after: only contacts from this one on are pushed
  bool contacts_from_stale_ = false;            // ... this one's key included (it was stale)
  bool plain_gas_path_ = plain_gas_scene();  // fixed by the scene and the method (plain_gas_strike)
  [[no_unique_address]] Observer observer_;

  // Ball x's motion has just changed (it is carried to now): a new version,
  // so that every prediction made from its old motion is stale, and the
  // observer is told. Every change of motion goes through here.
  void motion_changed(int x, MotionChange why) {
    ++world_.balls[x].version;
    observer_.motion_changed(world_, x, why);
  }

  static std::vector<std::uint64_t*> counter_fields(EngineCounters& c, RestCounters& r, IslandSolveCounters& s) {
    return {&c.ball_ball,     &c.ball_wall,     &c.leave_wall,    &c.leave_pair,    &c.stale,         &c.cell_crossings,
            &c.ignored,       &r.came_to_rest,  &r.fell_asleep,   &r.woken,         &r.plastic_pairs,
            &r.creeping,      &r.held,          &r.renewed,       &s.impact_solves, &s.force_solves,
            &s.rows,          &s.rounds,        &s.largest};
  }

  static void advance_to_time(Body<Num>& b, const Num& t) {
    if (!b.is_static()) collide2d::advance_to(b, t);
    b.time = t;
  }

  bool current(const Event<Num>& e) const {
    if (world_.balls[e.a].version != e.version_a) return false;
    return !between_two_balls(e.kind) || world_.balls[e.b].version == e.version_b;
  }

  // When the next events come (event_engine_prediction.hpp): every future
  // event of a moving ball (predict), a pair's next contact from the later
  // of its clocks (predict_pair), a wall's (predict_wall), a pair left a hair
  // inside contact while pressed together (pressed_contact_due), the end of
  // a persistent contact's range (predict_contact_ending), leaving a cell
  // (predict_crossing). Each pushes what it finds (push).
  void push(Event<Num> e, int owner);
  template <class Skip>
  void predict(int i, const Num& until, Skip skip);
  void predict_wall(int i, int w, const Num& until);
  void predict(int i, const Num& until);
  template <class Skip>
  const std::vector<int>& neighbours_of(int i, Skip skip);
  void predict_contacts_after(int i, const Event<Num>& e, const Num& until, bool stale);
  void predict_pair(int i, int j, const Num& until);
  bool certainly_apart_until(const Body<Num>& bi, const Body<Num>& bj, const Num& until) const;
  bool within_reach(const Vec2<Num>& offset, const Num& R) const;
  template <class StillTouching>
  RootSearch<Num> pressed_contact_due(const Vec2<Num>& dp, const Vec2<Num>& dv, const Vec2<Num>& da, const Num& R,
                                      const Num& scale, const Num& horizon, StillTouching still_touching) const;
  void predict_pressed_on_wall(int i, const BallState<Num>& s, int w, const Num& horizon, ContactFeature resting_on);
  void predict_crossing(int i, const BallState<Num>& s, const Num& horizon);
  RootSearch<Num> bisection_contact(const BallState<Num>& si, const BallState<Num>& sj, const Num& horizon) const;
  ToiResult<Num> wall_contact(const BallState<Num>& s, int w, const Num& horizon) const;
  RootSearch<Num> first_exit(const Vec2<Num>& tangent, const Vec2<Num>& p, const Vec2<Num>& v, const Vec2<Num>& a,
                             const Vec2<Num>& origin, const Num& lo, const Num& hi, const Num& horizon) const;
  void predict_contact_ending(const PersistentContact<Num>& c, const Num& horizon, int owner);

  // The contact forces of the islands holding `seeds` are found again where
  // a contact came or went or a ball's mobility changed (ContactGraph::forces
  // keeps them otherwise): every ball of them is carried to now and takes its
  // acceleration.
  void solve_islands(const std::vector<int>& seeds, std::vector<int>& changed) {
    std::vector<int>& balls = island_;
    graph_.island(world_, seeds, balls);
    if (balls.empty()) return;
    for (int x : balls) advance_to_time(world_.balls[x], now_);
    graph_.forces(world_, balls, rules_.thresholds().least_press);
    for (int x : balls) {
      motion_changed(x, MotionChange::forces);
      changed.push_back(x);
    }
  }

  // Rest in the engine (event_engine_rest.hpp): after every event, the
  // balls whose motion changed are offered sleep (settle: rest.hpp, rule 2)
  // and predicted again; a strike fast enough wakes a sleeper (wake: rule 3).
  std::vector<int> moving_partners(int i) const;
  void settle(std::vector<int>& changed, const Num& until);
  void wake_uncarried(std::vector<int>& changed);
  void fall_asleep(const std::vector<int>& balls, std::vector<int>& changed);
  void wake(int first, std::vector<int>& changed);

  // Ball e.a meets its partner (n towards e.a): the balls of the islands
  // involved are carried to now, the collision is resolved (contact_rules.hpp)
  // and their forces are solved again, with those of every ball in `changed`
  // (balls woken by the strike).
  template <class OnCollision>
  void collide(const Event<Num>& e, const Vec2<Num>& n, std::vector<int>& changed, OnCollision& on_collision) {
    const int seeds[2] = {e.a, e.b};
    graph_.island(world_, std::span<const int>(seeds, e.kind == EventKind::ball_ball ? 2 : 1), island_);
    for (int x : island_) advance_to_time(world_.balls[x], now_);
    const Collision<Num>& c = rules_.collide(world_, graph_, grid_, e, rules_.contact_for(world_, e, n), island_, changed);
    for (int x : rules_.moved_balls()) motion_changed(x, MotionChange::response);
    on_collision(c);
    solve_islands(changed, changed);  // the collision's islands, and any woken ball's
  }

  template <class OnCollision>
  void process(const Event<Num>& e, const Num& until, OnCollision& on_collision) {
    graph_.parted().clear();  // what this event's contacts do, for wake_uncarried
    if (e.kind == EventKind::cell_crossing) {
      // The motion goes on unchanged (no new clock, no new version): only
      // the balls it may meet change.
      ++counters_.cell_crossings;
      const std::span<const int> walls_before = grid_.walls_near(e.a);
      grid_.cross(e.a, static_cast<CellStep>(e.b), [&](int j) {
        if (j != e.a) predict_pair(e.a, j, until);
      });
      for (int w : grid_.walls_near(e.a))
        if (!std::binary_search(walls_before.begin(), walls_before.end(), w)) predict_wall(e.a, w, until);
      predict_crossing(e.a, state_at(world_.balls[e.a], now_), until - now_);
      return;
    }
    // An event that changes nothing (a contact that ended already, a
    // creeping one, one the article's methods report for objects moving
    // apart) leaves its balls on their clocks: it is judged on copies
    // carried to its time, and only an event that acts carries the balls
    // themselves. A ball's clock moves with its motion or not at all, so
    // that a pair asked for again later is predicted from the same clocks,
    // to the same bits (predict_pair), whenever it is asked.
    Body<Num>& a = world_.balls[e.a];
    std::vector<int>& changed = changed_;
    changed.assign(1, e.a);
    if (e.kind == EventKind::leave_wall || e.kind == EventKind::leave_pair) {
      // A contact slid out of its range: it ends, and its island is solved
      // again without it. Past the end of a wall's face the ball goes on
      // along the tangent at that end (the same line), until it has risen
      // off it.
      const PersistentContact<Num>* c =
          e.kind == EventKind::leave_wall ? graph_.with_wall(e.a, e.b) : graph_.find_pair(e.a, e.b);
      if (!c) return;  // it ended already
      advance_to_time(a, e.time);
      if (e.kind == EventKind::leave_pair) {
        advance_to_time(world_.balls[e.b], e.time);
        changed.push_back(e.b);
        ++counters_.leave_pair;
      } else {
        ++counters_.leave_wall;
      }
      const PersistentContact<Num> gone = *c;
      graph_.remove(gone);
      if (gone.feature == ContactFeature::wall_face) graph_.add(rules_.onto_the_end(world_, gone));
      solve_islands(changed, changed);
      if (method_ == ToiMethod::analytic && rules_.renew(world_, graph_, gone, changed)) {
        for (int x : rules_.moved_balls()) motion_changed(x, MotionChange::renewed);
        solve_islands(changed, changed);
      }
      settle(changed, until);
      return;
    }
    Body<Num> a_then = a;
    advance_to_time(a_then, e.time);
    if (e.kind == EventKind::ball_wall) {
      const Vec2<Num> n = wall_normal(a_then, e);
      // The article's methods can report a contact with a ball that is
      // leaving the wall (the seed method's textbook root, bisection's
      // overlap test); acting on it would ring forever at one instant. The
      // step engine drops it and counts it; the next step predicts afresh.
      if (method_ != ToiMethod::analytic && !approaching(a_then, n)) {
        ++counters_.ignored;
        return;
      }
      if (rules_.creeping(n, a_then.velocity, a_then.acceleration)) return;
      a = a_then;
      ++counters_.ball_wall;
      if (plain_gas_strike(e)) return collide_in_gas(e, n, on_collision, until);
      collide(e, n, changed, on_collision);
      settle(changed, until);
      return;
    }
    Body<Num>& b = world_.balls[e.b];
    Body<Num> b_then = b;
    advance_to_time(b_then, e.time);
    const Vec2<Num> n = normalized(a_then.position - b_then.position);  // from b to a
    if (method_ != ToiMethod::analytic && !(dot(n, a_then.velocity - b_then.velocity) < Num{})) {
      ++counters_.ignored;  // likewise for two balls moving apart
      return;
    }
    if (rules_.creeping(n, a_then.velocity - b_then.velocity, a_then.acceleration - b_then.acceleration)) return;
    a = a_then, b = b_then;
    // A strike fast enough wakes a sleeping ball (rest.hpp, rule 3).
    changed.push_back(e.b);
    if (rules_.wakes(-dot(n, a.velocity - b.velocity)))
      for (int x : {e.a, e.b})
        if (world_.balls[x].asleep) wake(x, changed);
    ++counters_.ball_ball;
    if (plain_gas_strike(e)) return collide_in_gas(e, n, on_collision, until);
    collide(e, n, changed, on_collision);
    settle(changed, until);
  }

  // A strike in a gas, where every rest rule is idle, without their
  // bookkeeping (event_engine_gas.hpp): the same calls, the same bits.
  bool plain_gas_strike(const Event<Num>& e) const;
  bool plain_gas_scene() const;
  template <class OnCollision>
  void collide_in_gas(const Event<Num>& e, const Vec2<Num>& n, OnCollision& on_collision, const Num& until);

  // The ball's velocity has a component into the wall (or it is pressed on it).
  static bool approaching(const Body<Num>& a, const Vec2<Num>& n) {
    const Num zero{};
    const Num vn = dot(a.velocity, n);
    return vn < zero || (vn == zero && dot(a.free_acceleration, n) < zero);
  }

  // The wall's unit normal at the contact, towards the ball.
  Vec2<Num> wall_normal(const Body<Num>& a, const Event<Num>& e) const {
    return wall_contact_normal(world_.walls[e.b], e.feature, a.position);
  }
};

}  // namespace collide2d

// The definitions of the members declared above, one concept a file.
#include "collide2d/sim/event_engine_checkpoint.hpp"
#include "collide2d/sim/event_engine_gas.hpp"
#include "collide2d/sim/event_engine_prediction.hpp"
#include "collide2d/sim/event_engine_rest.hpp"
