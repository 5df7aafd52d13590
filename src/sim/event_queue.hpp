// The event engine's queue: events in exact (time, kind, a, b) order.
//
// Ties (the same time to the last bit) go by kind, then by the indices a, b:
// the order never depends on memory layout or on when an event was pushed.
// Each event carries the versions of its balls when it was predicted; an
// event whose ball has changed its motion since is stale and skipped.
#pragma once

#include <cstdint>
#include <queue>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "numeric/number_traits.hpp"
#include "toi/toi_result.hpp"

namespace collide2d {

enum class EventKind : int { ball_ball = 0, ball_wall = 1, leave_wall = 2, cell_crossing = 3, leave_pair = 4 };

// Events between two balls: they are stale when either ball's motion changed.
inline bool between_two_balls(EventKind k) { return k == EventKind::ball_ball || k == EventKind::leave_pair; }

template <class Num>
struct Event {
  Num time{};
  EventKind kind = EventKind::ball_ball;
  int a = 0;  // a ball
  int b = 0;  // a ball (ball_ball, leave_pair), a wall (ball_wall, leave_wall: −1 for a ball's tangent) or a CellStep
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

// A processed collision: what the run file records.
template <class Num>
struct Collision {
  Num time{};
  EventKind kind = EventKind::ball_ball;
  int a = 0, b = 0;
  Num impulse{};  // magnitude of the normal impulse on ball a
  // Every moving ball the response could move (the island of a and b, or
  // the two alone: a and b among them unless static), in index order, and
  // its velocity just before.
  std::vector<int> island;
  std::vector<Vec2<Num>> island_velocity_before;
};

template <class Num>
class EventQueue {
 public:
  void clear() {
    queue_ = {};
    popped_any_ = false;
  }
  bool empty() const { return queue_.empty(); }
  const Event<Num>& top() const { return queue_.top(); }
  void push(Event<Num> e) {
    e.pushed = pushes_++;
    queue_.push(e);
  }
  Event<Num> pop() {
    Event<Num> e = queue_.top();
    queue_.pop();
    check_order(e);
    return e;
  }

 private:
  std::priority_queue<Event<Num>, std::vector<Event<Num>>, LaterEvent<Num>> queue_;
  std::uint64_t pushes_ = 0, pushes_at_last_pop_ = 0;
  Event<Num> last_popped_;
  bool popped_any_ = false;

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
};

}  // namespace collide2d
