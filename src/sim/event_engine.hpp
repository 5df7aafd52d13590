// The event-driven engine: exact event order, deterministic ties.
//
// Time advances from event to event; nothing is stepped. Between record
// times T_k = k Δ every ball moves on its exact parabola, each pair's next
// contact is predicted by the analytic time of impact, and the earliest
// event is processed first. Ties (the same time to the last bit) go by kind,
// then by the indices a, b: the order never depends on memory layout. At every
// record time all balls are carried to T_k and the prediction starts afresh
// for [T_k, T_k+1], so a frame, a checkpoint and a resumed run all start from
// the same exact state.
//
// Only neighbours are predicted against each other (cell_grid.hpp); a pair
// is always predicted from the later of the two balls' clocks, so the grid
// changes the cost of a run, never its bits.
//
// Inelastic collapse (infinitely many bounces in finite time) and resting
// contact, all documented in the README:
//  - a ball bouncing on a wall face it is pressed against (its acceleration
//    has a component into the wall, g_n > 0) switches to resting contact
//    when its rebound would rise less than h_rest = 1e-6 r_min: it then slides
//    along the wall under the tangential part of its acceleration, and leaves
//    it at an end or when struck;
//  - between balls, the TC model (Luding & McNamara 1998): a collision within
//    t_c of either ball's previous collision (but not at the very same time:
//    that is a simultaneous chain) is made elastic. t_c = 1e-3 of the time to
//    fall one smallest radius, sqrt(r_min / g_max);
//  - balls pressed together (n·Δa < 0, a ball lying on another) or a ball
//    pressed on a wall's end leave a contact at no less than the hop speed
//    sqrt(2 |n·Δa| h_rest): a pile stands on hops of height h_rest instead of
//    sinking into itself. A pair left a hair inside contact by rounding is
//    given its contact when its separating speed has fallen to zero.
//  - a contact nothing presses together, closing slower than the creep speed
//    h_rest / duration, is not processed: the two creep together at that
//    speed at most, less than h_rest over the whole run (a row of balls
//    jammed between walls would otherwise ring without end at one instant).
// The run summary counts each (TC elastic, came to rest, hops, creep).
// Known limit: a row of touching balls jammed between two walls, ringing at
// tiny speeds, can make very many events in little time (the funnel scene).
#pragma once

#include <algorithm>
#include <cstdint>
#include <queue>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "response/response.hpp"
#include "sim/cell_grid.hpp"
#include "sim/held_contact.hpp"
#include "sim/state_bytes.hpp"
#include "sim/world.hpp"
#include "toi/article_methods.hpp"

namespace collide2d {

enum class EventKind : int { ball_ball = 0, ball_wall = 1, leave_wall = 2, cell_crossing = 3 };

template <class Num>
struct Event {
  Num time{};
  EventKind kind = EventKind::ball_ball;
  int a = 0;  // a ball
  int b = 0;  // a ball (ball_ball), a wall (ball_wall, leave_wall) or a CellStep
  std::uint64_t version_a = 0, version_b = 0;
  ContactFeature feature = ContactFeature::none;
  std::uint64_t pushed = 0;  // the queue's push count when it went in (order check)
};

// Later events compare greater: the priority queue's top is the earliest.
template <class Num>
struct LaterEvent {
  bool operator()(const Event<Num>& x, const Event<Num>& y) const {
    if (x.time != y.time) return y.time < x.time;
    if (x.kind != y.kind) return static_cast<int>(y.kind) < static_cast<int>(x.kind);
    if (x.a != y.a) return y.a < x.a;
    return y.b < x.b;
  }
};

// A processed collision, as the run file records it.
template <class Num>
struct Collision {
  Num time{};
  EventKind kind = EventKind::ball_ball;
  int a = 0, b = 0;
  Num impulse{};  // magnitude of the normal impulse on ball a
};

// The scales of the collapse and resting-contact rules (see above; derived
// from the scene in simulate.cpp).
template <class Num>
struct ContactThresholds {
  Num tc;           // the TC model's window
  Num rest_height;  // h_rest: lower rebounds come to rest (walls) or hop (balls, wall ends)
  Num creep_speed;  // unpressed contacts closing slower than this are let creep
};

struct EngineStall : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct EngineCounters {
  std::uint64_t ball_ball = 0, ball_wall = 0, leave_wall = 0, stale = 0;
  std::uint64_t cell_crossings = 0;
  std::uint64_t hops = 0;
  std::uint64_t ignored = 0;       // contacts a method reported for objects moving apart
  std::uint64_t creeping = 0;      // unpressed contacts too slow to process (creep)          // ball–ball contacts given the resting-contact hop
  std::uint64_t tc_elastic = 0;    // ball–ball collisions made elastic by the TC model
  std::uint64_t came_to_rest = 0;  // switches to resting contact
  std::uint64_t held = 0;          // ball–ball collisions of a ball held on its wall (held_contact.hpp)
};

template <class Num>
class EventEngine {
 public:
  // `method`: how contacts are predicted. analytic is exact; bisection and
  // seed (the article's, tolerance `eps`) are for the step engine, which is
  // this engine advanced one step at a time (see simulate.hpp).
  // `one_cell`: predict every pair (no grid); the results are the same bits.
  EventEngine(World<Num> world, const ContactThresholds<Num>& thresholds, ToiMethod method = ToiMethod::analytic,
              const Num& eps = Num{}, bool one_cell = false)
      : world_(std::move(world)), tc_(thresholds.tc), rest_height_(thresholds.rest_height),
        sqrt_rest_height_(NumberTraits<Num>::sqrt(thresholds.rest_height)),
        creep_speed_(thresholds.creep_speed), method_(method), eps_(eps), grid_(world_, one_cell) {}

  const World<Num>& world() const { return world_; }
  World<Num>& world() { return world_; }
  const EngineCounters& counters() const { return counters_; }
  const Num& now() const { return now_; }

  // Processes every event up to `until` (inclusive) and carries all balls
  // there. `on_collision(const Collision<Num>&)` sees each collision in order.
  template <class OnCollision>
  void advance_to(const Num& until, OnCollision on_collision) {
    queue_ = {};
    popped_any_ = false;
    grid_.assign(world_);
    for (int i = 0; i < static_cast<int>(world_.balls.size()); ++i) predict(i, until, -1, true);
    while (!queue_.empty() && !(until < queue_.top().time)) {
      const Event<Num> e = queue_.top();
      queue_.pop();
      check_order(e);
      if (!current(e)) {
        ++counters_.stale;
        continue;
      }
      // A run of events that never lets time advance is a stall (a contact the
      // model cannot resolve): report it rather than loop forever.
      same_time_events_ = e.time == now_ ? same_time_events_ + 1 : 0;
      if (same_time_events_ > max_events_at_one_time)
        throw EngineStall("engine stalled: more than " + std::to_string(max_events_at_one_time) +
                          " events at one time, last between ball " + std::to_string(e.a) + " and " +
                          (e.kind == EventKind::ball_ball ? "ball " : "wall ") + std::to_string(e.b));
      now_ = e.time;
      process(e, until, on_collision);
    }
    for (Body<Num>& b : world_.balls) advance_to_time(b, until);
    now_ = until;
  }

  // The whole mutable state at a record time (checkpoints): the clock, the
  // counters and every body. Walls never change and are not stored.
  // The layout's version leads, so that a checkpoint of another layout is
  // refused by name instead of misread (2: the `held` counter).
  static constexpr std::uint32_t checkpoint_layout = 2;

  void save(ByteWriter& out) const {
    out.put(checkpoint_layout);
    out.put(now_);
    for (std::uint64_t c : {counters_.ball_ball, counters_.ball_wall, counters_.leave_wall, counters_.stale,
                            counters_.cell_crossings, counters_.hops, counters_.ignored, counters_.creeping, counters_.tc_elastic,
                            counters_.came_to_rest, counters_.held})
      out.put(c);
    out.put(static_cast<std::uint64_t>(world_.balls.size()));
    for (const Body<Num>& b : world_.balls) {
      out.put(b.position);
      out.put(b.velocity);
      out.put(b.acceleration);
      out.put(b.free_acceleration);
      for (const Num* x : {&b.time, &b.radius, &b.mass, &b.restitution, &b.last_collision}) out.put(*x);
      out.put(static_cast<std::uint8_t>(b.fixed));
      out.put(static_cast<std::uint8_t>(b.has_collided));
      out.put(static_cast<std::int32_t>(b.resting_wall));
      out.put(b.version);
    }
  }
  void load(ByteReader& in) {
    std::uint32_t layout = 0;
    in.get(layout);
    if (layout != checkpoint_layout)
      throw std::runtime_error("checkpoint of layout " + std::to_string(layout) + ", this build reads layout " +
                               std::to_string(checkpoint_layout) + ": resume it with the collide2d that wrote it");
    in.get(now_);
    for (std::uint64_t* c : {&counters_.ball_ball, &counters_.ball_wall, &counters_.leave_wall, &counters_.stale,
                             &counters_.cell_crossings, &counters_.hops, &counters_.ignored, &counters_.creeping,
                             &counters_.tc_elastic, &counters_.came_to_rest, &counters_.held})
      in.get(*c);
    std::uint64_t n = 0;
    in.get(n);
    if (n != world_.balls.size()) throw std::runtime_error("checkpoint holds a different number of balls");
    for (Body<Num>& b : world_.balls) {
      in.get(b.position);
      in.get(b.velocity);
      in.get(b.acceleration);
      in.get(b.free_acceleration);
      for (Num* x : {&b.time, &b.radius, &b.mass, &b.restitution, &b.last_collision}) in.get(*x);
      std::uint8_t fixed = 0, collided = 0;
      std::int32_t resting = -1;
      in.get(fixed);
      in.get(collided);
      in.get(resting);
      in.get(b.version);
      b.fixed = fixed != 0;
      b.has_collided = collided != 0;
      b.resting_wall = resting;
    }
  }

 private:
  World<Num> world_;
  Num tc_, rest_height_, sqrt_rest_height_, creep_speed_;
  ToiMethod method_;
  Num eps_;
  CellGrid<Num> grid_;
  Num now_{};
  EngineCounters counters_;
  int same_time_events_ = 0;
  static constexpr int max_events_at_one_time = 100000;
  std::priority_queue<Event<Num>, std::vector<Event<Num>>, LaterEvent<Num>> queue_;
  std::uint64_t pushes_ = 0, pushes_at_last_pop_ = 0;
  Event<Num> last_popped_;
  bool popped_any_ = false;

  static void advance_to_time(Body<Num>& b, const Num& t) {
    if (!b.fixed) collide2d::advance_to(b, t);
    b.time = t;
  }

  bool current(const Event<Num>& e) const {
    if (world_.balls[e.a].version != e.version_a) return false;
    return e.kind != EventKind::ball_ball || world_.balls[e.b].version == e.version_b;
  }

  // Every future event of ball i within [now, until], against its
  // neighbours (`skip`: the partner just processed, which predicts this pair
  // itself; `lower_done`: moving balls of lower index already predicted this
  // pair), every wall, leaving the wall it rests on, and leaving its cell.
  void predict(int i, const Num& until, int skip, bool lower_done = false) {
    const Body<Num>& bi = world_.balls[i];
    if (bi.fixed) return;
    grid_.for_each_neighbour(i, [&](int j) {
      if (j == i || j == skip || (lower_done && j < i && !world_.balls[j].fixed)) return;
      predict_pair(i, j, until);
    });
    const Num horizon = until - now_;
    const BallState<Num> si = state_at(bi, now_);
    for (int w = 0; w < static_cast<int>(world_.walls.size()); ++w) {
      if (w == bi.resting_wall) continue;
      const ToiResult<Num> r = wall_contact(si, w, horizon);
      if (r.hit())
        push({now_ + r.time, EventKind::ball_wall, i, w, 0, 0, r.feature});
      else if (method_ == ToiMethod::analytic)
        predict_pressed_on_wall(i, si, w, horizon);
    }
    if (bi.resting_wall >= 0) predict_leaving(i, si, horizon);
    predict_crossing(i, si, horizon);
  }

  // The next contact of balls i and j, predicted from the later of their
  // clocks (the last change of either's motion): the answer depends only on
  // the two motions, never on when, or whether, the grid asks for it.
  void predict_pair(int i, int j, const Num& until) {
    const Body<Num>& bi = world_.balls[i];
    const Body<Num>& bj = world_.balls[j];
    const Num t0 = bj.fixed || bj.time < bi.time ? bi.time : bj.time;
    const BallState<Num> si = state_at(bi, t0), sj = state_at(bj, t0);
    const Num horizon = until - t0;
    const ToiResult<Num> r = method_ == ToiMethod::analytic ? time_of_impact_ball_ball(si, sj, horizon)
                                                            : bisection_ball_ball(si, sj, horizon, eps_);
    if (r.hit()) {
      push({t0 + r.time, EventKind::ball_ball, std::min(i, j), std::max(i, j), 0, 0, r.feature});
      return;
    }
    const RootSearch<Num> pressed = pressed_contact_due(si.position - sj.position, si.velocity - sj.velocity,
                                                        si.acceleration - sj.acceleration, si.radius + sj.radius, horizon);
    if (pressed.found)
      push({t0 + pressed.t, EventKind::ball_ball, std::min(i, j), std::max(i, j), 0, 0, ContactFeature::ball});
  }

  // Pressed together while touching: resting contact (see the top of this
  // file). Rounding can leave a pair (Δp the offset between centres, or from
  // a wall's nearest point; R the contact distance) a hair inside contact,
  // where the gap never crosses zero again and no time of impact exists; the
  // contact is then due when their normal separating speed has fallen to
  // zero: t = (Δp·Δv) / −(Δp·Δa) for Δp·Δv ≥ 0, at once otherwise. Only while
  // the rise before that, s_n² / 2|a_n| = (Δp·Δv)² / (2 |Δp·Δa| |Δp|), stays
  // within h_rest (|Δp| ≈ R): a larger rise would take them apart, and the
  // time of impact would have seen them come back.
  RootSearch<Num> pressed_contact_due(const Vec2<Num>& dp, const Vec2<Num>& dv, const Vec2<Num>& da, const Num& R,
                                      const Num& horizon) const {
    const Num zero{};
    const Num pressing = dot(dp, da);
    if (!(pressing < zero) || R * R < length_squared(dp)) return {};
    const Num separating = dot(dp, dv);
    if (num<Num>(2.0) * -pressing * R * rest_height_ < separating * separating) return {};
    if (horizon * -pressing < separating) return {};  // not within the horizon (and no division that could overflow)
    return {true, separating < zero ? zero : separating / -pressing};
  }

  // The wall's counterpart of a pair left a hair inside contact (see
  // pressed_contact_due): the ball touches the wall's nearest point q, is
  // pressed towards it (Δp·a < 0 with Δp = p − q) and no time of impact
  // exists. The contact is due when it stops moving away from q.
  void predict_pressed_on_wall(int i, const BallState<Num>& s, int w, const Num& horizon) {
    const Num zero{};
    const WallGeometry<Num>& wall = world_.walls[w];
    const Num along = dot(wall.direction.hi, s.position - wall.segment.a);
    ContactFeature feature = ContactFeature::wall_face;
    Vec2<Num> q;
    if (!(zero < along)) {
      q = wall.segment.a, feature = ContactFeature::wall_end_a;
    } else if (!(along < wall.length_squared)) {
      q = wall.segment.b, feature = ContactFeature::wall_end_b;
    } else {
      // The foot of the perpendicular: only its normal part matters below.
      const Num side = cross(wall.direction.hi, s.position - wall.segment.a);
      const Vec2<Num> n = side < zero ? -wall.unit_normal : wall.unit_normal;
      q = s.position - dot(s.position - wall.segment.a, n) * n;
    }
    const RootSearch<Num> pressed = pressed_contact_due(s.position - q, s.velocity, s.acceleration, s.radius, horizon);
    if (pressed.found) push({now_ + pressed.t, EventKind::ball_wall, i, w, 0, 0, feature});
  }

  void predict_crossing(int i, const BallState<Num>& s, const Num& horizon) {
    const typename CellGrid<Num>::Crossing c = grid_.next_crossing(i, s, horizon);
    if (c.found) push({now_ + c.time, EventKind::cell_crossing, i, static_cast<int>(c.step), 0, 0, ContactFeature::none});
  }

  ToiResult<Num> wall_contact(const BallState<Num>& s, int w, const Num& horizon) const {
    switch (method_) {
      case ToiMethod::analytic: return time_of_impact_ball_wall(s, world_.walls[w], horizon);
      case ToiMethod::bisection: return bisection_ball_wall(s, world_.walls[w].segment, horizon, eps_);
      case ToiMethod::seed: return seed_ball_wall(s, world_.walls[w].segment, horizon);
    }
    return {};
  }

  // The queue must hand out events in (time, kind, a, b) order: an event that
  // was already queued when the previous one came out may not sort before it.
  // Checked with a plain lexicographic comparison, independent of LaterEvent,
  // so a broken tie-break cannot pass unnoticed (it would silently reorder
  // simultaneous events).
  void check_order(const Event<Num>& e) {
    auto key = [](const Event<Num>& x) { return std::tuple(x.time, static_cast<int>(x.kind), x.a, x.b); };
    if (popped_any_ && e.pushed < pushes_at_last_pop_ && key(e) < key(last_popped_))
      throw std::logic_error("event queue out of order at t = " + std::to_string(NumberTraits<Num>::to_double(e.time)));
    last_popped_ = e;
    pushes_at_last_pop_ = pushes_;
    popped_any_ = true;
  }

  void push(Event<Num> e) {
    e.pushed = pushes_++;
    e.version_a = world_.balls[e.a].version;
    if (e.kind == EventKind::ball_ball) e.version_b = world_.balls[e.b].version;
    queue_.push(e);
  }

  // A resting ball leaves its wall when its centre's projection passes an
  // end: along(t) = d·(p(t) − w_a) = C + 2 b t + A t² falls through 0, or
  // |d|² − along(t) does.
  void predict_leaving(int i, const BallState<Num>& s, const Num& horizon) {
    using T = NumberTraits<Num>;
    const WallGeometry<Num>& w = world_.walls[world_.balls[i].resting_wall];
    const Vec2<Num>& d = w.direction.hi;
    auto first_root = [&](Num A, Num b, Num C) {
      normalise_quadratic(A, b, C);
      return first_downward_root(A, b, C, [&] { return compensated_discriminant(A, b, C); }, horizon);
    };
    const Num A = T::half(dot(d, s.acceleration)), b = T::half(dot(d, s.velocity));
    const Num C = dot(d, s.position - w.segment.a);
    const RootSearch<Num> past_a = first_root(A, b, C);
    const RootSearch<Num> past_b = first_root(-A, -b, w.length_squared - C);
    RootSearch<Num> first = past_a;
    if (past_b.found && (!first.found || past_b.t < first.t)) first = past_b;
    if (first.found) push({now_ + first.t, EventKind::leave_wall, i, world_.balls[i].resting_wall, 0, 0, ContactFeature::none});
  }

  template <class OnCollision>
  void process(const Event<Num>& e, const Num& until, OnCollision& on_collision) {
    if (e.kind == EventKind::cell_crossing) {
      // The motion goes on unchanged (no new clock, no new version): only
      // the balls it may meet change.
      ++counters_.cell_crossings;
      grid_.cross(e.a, static_cast<CellStep>(e.b), [&](int j) {
        if (j != e.a) predict_pair(e.a, j, until);
      });
      predict_crossing(e.a, state_at(world_.balls[e.a], now_), until - now_);
      return;
    }
    Body<Num>& a = world_.balls[e.a];
    advance_to_time(a, e.time);
    if (e.kind == EventKind::leave_wall) {
      a.resting_wall = -1;
      a.acceleration = a.free_acceleration;
      ++a.version;
      ++counters_.leave_wall;
      predict(e.a, until, -1);
      return;
    }
    if (e.kind == EventKind::ball_wall) {
      // The article's methods can report a contact with a ball that is
      // leaving the wall (the seed method's textbook root, bisection's
      // overlap test); acting on it would ring forever at one instant. The
      // step engine drops it and counts it; the next step predicts afresh.
      if (method_ != ToiMethod::analytic && !approaching_wall(e)) {
        ++counters_.ignored;
        return;
      }
      if (creeping_into_wall(e)) {
        ++counters_.creeping;
        return;
      }
      on_collision(collide_with_wall(e));
      predict(e.a, until, -1);
      return;
    }
    Body<Num>& b = world_.balls[e.b];
    advance_to_time(b, e.time);
    if (method_ != ToiMethod::analytic && !(dot(a.position - b.position, a.velocity - b.velocity) < Num{})) {
      ++counters_.ignored;  // likewise for two balls moving apart
      return;
    }
    if (creeping_together(a, b)) {
      ++counters_.creeping;
      return;
    }
    on_collision(collide_balls(e));
    predict(e.a, until, e.b);
    predict(e.b, until, -1);
  }

  // Leaving resting contact: a struck ball moves freely again.
  static void free(Body<Num>& b) {
    b.resting_wall = -1;
    b.acceleration = b.free_acceleration;
  }

  // A fixed ball's motion never changes: its pending predictions stay valid.
  void mark_collided(Body<Num>& b, const Num& t) {
    if (!b.fixed) ++b.version;
    b.last_collision = t;
    b.has_collided = true;
  }

  // sqrt(2 g_n h_rest): the speed that rises h_rest against g_n. Formed as
  // sqrt(2 g_n) sqrt(h_rest) so that fixed point cannot round a tiny product
  // to zero (a zero hop would leave a pressed pair where it is, for ever).
  Num hop_speed(const Num& g_n) const { return NumberTraits<Num>::sqrt(num<Num>(2.0) * g_n) * sqrt_rest_height_; }

  // The TC model's window, (0, t_c) after the ball's last collision. A
  // collision at the very same time belongs to a simultaneous chain (a row
  // of touching balls jammed between walls): it keeps its restitution, so
  // the chain dissipates instead of ringing forever at one instant.
  bool within_tc(const Body<Num>& b, const Num& t) const {
    return b.has_collided && b.last_collision < t && t - b.last_collision < tc_;
  }

  Collision<Num> collide_balls(const Event<Num>& e) {
    Body<Num>& a = world_.balls[e.a];
    Body<Num>& b = world_.balls[e.b];
    ++counters_.ball_ball;
    const Vec2<Num> n = normalized(a.position - b.position);  // from b to a
    Num restitution = contact_restitution(a.restitution, b.restitution);
    if (within_tc(a, e.time) || within_tc(b, e.time)) {
      restitution = num<Num>(1.0);
      ++counters_.tc_elastic;
    }
    Num impulse{};
    // A ball resting on a wall that this contact pushes into it: both
    // contacts act at once (held_contact.hpp).
    bool a_held = pushed_into_its_wall(a, world_, n), b_held = pushed_into_its_wall(b, world_, -n);
    if ((a.resting_wall >= 0 && !a_held) || (b.resting_wall >= 0 && !b_held)) {
      // A resting ball the contact lifts off its wall slower than the hop
      // speed stays held (held_contact.hpp): the lift from the free impulse.
      const Num closing = dot(n, a.velocity - b.velocity);
      if (closing < Num{}) {
        const Num inv_a = a.fixed ? Num{} : num<Num>(1.0) / a.mass, inv_b = b.fixed ? Num{} : num<Num>(1.0) / b.mass;
        const Num J = -(num<Num>(1.0) + restitution) * closing / (inv_a + inv_b);
        auto low_lift = [&](const Body<Num>& x, const Vec2<Num>& n_x, const Num& inv) {
          const Num g_n = -dot(x.free_acceleration, face_normal_towards(world_.walls[x.resting_wall], x.position));
          return Num{} < g_n && lifted_less_than(x, world_, n_x, J * inv, hop_speed(g_n));
        };
        if (a.resting_wall >= 0 && !a_held) a_held = low_lift(a, n, inv_a);
        if (b.resting_wall >= 0 && !b_held) b_held = low_lift(b, -n, inv_b);
      }
    }
    if (a_held || b_held) {
      ++counters_.held;
      HeldOutcome outcome;
      impulse = collide_held(a, b, a_held, b_held, world_, n, restitution, [&](const Num& g) { return hop_speed(g); },
                             outcome);
      if (outcome.hopped) ++counters_.hops;
      if (!a_held) free(a);
      if (!b_held) free(b);
      mark_collided(a, e.time);
      mark_collided(b, e.time);
      return {e.time, EventKind::ball_ball, e.a, e.b, impulse};
    }
    // Pressed together (n·Δa < 0, with the accelerations they move with now):
    // they leave at no less than the hop speed sqrt(2 |n·Δa| h_rest).
    const Num pressing = dot(n, a.acceleration - b.acceleration);
    const Num hop = pressing < Num{} ? hop_speed(-pressing) : Num{};
    if (b.fixed || a.fixed) {
      Body<Num>& mover = b.fixed ? a : b;
      const Vec2<Num> normal = b.fixed ? n : -n;
      const Vec2<Num> before = mover.velocity;
      mover.velocity = reflect_velocity(before, normal, restitution);
      Vec2<Num> still{};
      if (separate_at_least(mover.velocity, still, mover.mass, mover.mass, true, normal, hop) != Num{}) ++counters_.hops;
      impulse = mover.mass * dot(mover.velocity - before, normal);
    } else {
      const TwoBallVelocities<Num> out = two_ball_impulse_response(a.velocity, b.velocity, a.mass, b.mass, n, restitution);
      a.velocity = out.v1;
      b.velocity = out.v2;
      const Num extra = separate_at_least(a.velocity, b.velocity, a.mass, b.mass, false, n, hop);
      if (extra != Num{}) ++counters_.hops;
      impulse = out.impulse + extra;
    }
    free(a);
    free(b);
    mark_collided(a, e.time);
    mark_collided(b, e.time);
    return {e.time, EventKind::ball_ball, e.a, e.b, impulse};
  }

  // Creep (see the top of this file): a contact that nothing presses together
  // (n·Δa ≥ 0), closing slower than creep_speed, is let creep rather than
  // processed: in a row of balls jammed between walls every impulse would
  // at once cause another at the same instant, without end. Dropped, the
  // event leaves the motions as they are; the pair is predicted again when
  // either ball's motion next changes.
  bool creeping_together(const Body<Num>& a, const Body<Num>& b) const {
    const Vec2<Num> n = normalized(a.position - b.position);
    const Num closing = -dot(n, a.velocity - b.velocity);
    return !(dot(n, a.acceleration - b.acceleration) < Num{}) && closing < creep_speed_;
  }
  bool creeping_into_wall(const Event<Num>& e) const {
    const Body<Num>& a = world_.balls[e.a];
    const Vec2<Num> n = wall_normal(a, e);
    return !(dot(n, a.acceleration) < Num{}) && -dot(n, a.velocity) < creep_speed_;
  }

  // The ball's velocity has a component into the wall (or it is pressed on it).
  bool approaching_wall(const Event<Num>& e) const {
    const Body<Num>& a = world_.balls[e.a];
    const Num zero{};
    const Vec2<Num> n = wall_normal(a, e);
    const Num vn = dot(a.velocity, n);
    return vn < zero || (vn == zero && dot(a.free_acceleration, n) < zero);
  }

  // The wall's unit normal at the contact, towards the ball.
  Vec2<Num> wall_normal(const Body<Num>& a, const Event<Num>& e) const {
    const WallGeometry<Num>& w = world_.walls[e.b];
    if (e.feature == ContactFeature::wall_face) return face_normal_towards(w, a.position);
    return normalized(a.position - (e.feature == ContactFeature::wall_end_a ? w.segment.a : w.segment.b));
  }

  Collision<Num> collide_with_wall(const Event<Num>& e) {
    const Num zero{};
    Body<Num>& a = world_.balls[e.a];
    const WallGeometry<Num>& w = world_.walls[e.b];
    ++counters_.ball_wall;
    const Vec2<Num> n = wall_normal(a, e);
    const Vec2<Num> before = a.velocity;
    const Num restitution = contact_restitution(a.restitution, world_.wall_restitution[e.b]);
    // Resting on another wall that this one pushes it into (a wedge of two
    // walls): held, like a ball struck into its wall (held_contact.hpp).
    if (a.resting_wall != e.b && pushed_into_its_wall(a, world_, n)) {
      ++counters_.held;
      const Vec2<Num> t = wall_tangent(world_.walls[a.resting_wall]);
      HeldOutcome outcome;
      const Num impulse = bounce_along_wall(a, t, dot(n, t), restitution, [&](const Num& g) { return hop_speed(g); },
                                            outcome);
      if (outcome.hopped) ++counters_.hops;
      mark_collided(a, e.time);
      return {e.time, EventKind::ball_wall, e.a, e.b, impulse};
    }
    const Num pressing = -dot(a.free_acceleration, n);  // g_n
    a.velocity = reflect_velocity(before, n, restitution);
    mark_collided(a, e.time);
    // Pressed against the wall and rebounding less than h_rest: on a face,
    // between its ends, the ball comes to rest on it; anywhere else (an end,
    // or a face contact past an end) it hops, like balls pressed together.
    const Num rebound = dot(a.velocity, n);
    const Num along = dot(w.direction.hi, a.position - w.segment.a);
    const bool low = zero < pressing && rebound < hop_speed(pressing);
    if (low && e.feature == ContactFeature::wall_face && zero < along && along < w.length_squared) {
      a.velocity = a.velocity - rebound * n;
      a.acceleration = a.free_acceleration + pressing * n;  // the tangential part
      a.resting_wall = e.b;
      ++counters_.came_to_rest;
    } else {
      if (low) {
        a.velocity = a.velocity + (hop_speed(pressing) - rebound) * n;
        ++counters_.hops;
      }
      free(a);
    }
    const Num impulse = a.mass * dot(a.velocity - before, n);
    return {e.time, EventKind::ball_wall, e.a, e.b, impulse};
  }
};

}  // namespace collide2d
