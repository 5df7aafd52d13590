// The event engine's queue: events in exact (time, kind, a, b) order.
//
// Ties (the same time to the last bit) go by kind, then by the indices a, b:
// the order never depends on memory layout or on when an event was pushed.
// Each event carries the versions of its balls when it was predicted; an
// event whose ball has changed its motion since is stale and skipped.
#pragma once

#include <cstdint>
#include <algorithm>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "collide2d/numeric/number_traits.hpp"
#include "collide2d/toi/toi_result.hpp"

namespace collide2d {

enum class EventKind : std::uint8_t { ball_ball = 0, ball_wall = 1, leave_wall = 2, cell_crossing = 3, leave_pair = 4 };

// Events between two balls: they are stale when either ball's motion changed.
inline bool between_two_balls(EventKind k) { return k == EventKind::ball_ball || k == EventKind::leave_pair; }

// 48 bytes in strict mode (a queue holds a few per ball).
template <class Num>
struct Event {
  Num time{};
  EventKind kind = EventKind::ball_ball;
  int a = 0;  // a ball
  int b = 0;  // a ball (ball_ball, leave_pair), a wall (ball_wall, leave_wall: −1 for a ball's tangent) or a CellStep
  ContactFeature feature = ContactFeature::none;
  std::uint64_t version_a = 0, version_b = 0;  // set by the engine's push
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

// The pending events, one list per ball and a heap over the balls.
//
// Every event belongs to the ball whose prediction found it (its owner). A
// ball's list holds what was predicted for it since its motion last changed:
// an event pushed with a newer version of its owner than the list's replaces
// the whole list (every event there involves the owner, whose motion has
// changed since: they are stale, and nothing reads them again). The
// heap holds each ball with a list, keyed by its list's earliest event, so
// that it is only as large as the number of balls, whatever the number of
// predictions, and an event costs O(log N) plus a scan of one short list.
// The earliest event overall comes out first, in (time, kind, a, b) order;
// events equal in all four go in the order they were pushed. Whether an
// event is still current (the versions of both balls) is for the engine to
// judge as before.
template <class Num>
class EventQueue {
 public:
  void clear() {
    for (const Node& n : heap_) lists_[static_cast<std::size_t>(n.ball)].events.clear();
    heap_.clear();
    std::fill(place_.begin(), place_.end(), -1);
    popped_any_ = false;
  }
  bool empty() const { return heap_.empty(); }
  const Event<Num>& top() const { return earliest_of(heap_[0].ball); }
  void push(Event<Num> e, int owner, std::uint64_t owner_version) {
    e.pushed = pushes_++;
    const auto ball = static_cast<std::size_t>(owner);
    if (ball >= lists_.size()) {
      lists_.resize(ball + 1);
      place_.resize(ball + 1, -1);
    }
    List& list = lists_[ball];
    if (list.events.empty() || list.version != owner_version) {
      list.events.assign(1, e);
      list.version = owner_version;
      list.earliest = 0;
      if (place_[ball] < 0) {
        heap_.push_back(node_of(owner));
        place_[ball] = static_cast<int>(heap_.size() - 1);
        sift_up(heap_.size() - 1);
      } else {
        const auto at = static_cast<std::size_t>(place_[ball]);
        heap_[at] = node_of(owner);
        sift_down(sift_up(at));
      }
      return;
    }
    list.events.push_back(e);
    if (earlier(e, list.events[list.earliest])) {
      list.earliest = list.events.size() - 1;
      const auto at = static_cast<std::size_t>(place_[ball]);
      heap_[at] = node_of(owner);
      sift_up(at);
    }
  }
  // Checkpoints: every pending event with its place in the order (push
  // count) and each list's version; a loaded queue pops exactly what the
  // saved one would have (the heap's order is total: time, kind, a, b, push).
  template <class Writer>
  void save(Writer& out) const {
    out.put(pushes_);
    out.put(static_cast<std::uint64_t>(lists_.size()));
    for (const List& list : lists_) {
      out.put(list.version);
      out.put(static_cast<std::uint64_t>(list.events.size()));
      for (const Event<Num>& e : list.events) {
        out.put(e.time);
        out.put(static_cast<std::uint8_t>(e.kind));
        out.put(static_cast<std::int32_t>(e.a));
        out.put(static_cast<std::int32_t>(e.b));
        out.put(static_cast<std::uint8_t>(e.feature));
        out.put(e.version_a);
        out.put(e.version_b);
        out.put(e.pushed);
      }
    }
  }
  template <class Reader>
  void load(Reader& in) {
    heap_.clear();
    popped_any_ = false;
    in.get(pushes_);
    pushes_at_last_pop_ = pushes_;
    std::uint64_t n = 0;
    in.get(n);
    lists_.assign(n, {});
    place_.assign(n, -1);
    for (std::size_t ball = 0; ball < n; ++ball) {
      List& list = lists_[ball];
      in.get(list.version);
      std::uint64_t count = 0;
      in.get(count);
      list.events.resize(count);
      for (Event<Num>& e : list.events) {
        std::uint8_t kind = 0, feature = 0;
        std::int32_t a = 0, b = 0;
        in.get(e.time);
        in.get(kind);
        in.get(a);
        in.get(b);
        in.get(feature);
        in.get(e.version_a);
        in.get(e.version_b);
        in.get(e.pushed);
        e.kind = static_cast<EventKind>(kind), e.a = a, e.b = b, e.feature = static_cast<ContactFeature>(feature);
      }
      if (list.events.empty()) continue;
      find_earliest(list);
      heap_.push_back(node_of(static_cast<int>(ball)));
      place_[ball] = static_cast<int>(heap_.size() - 1);
      sift_up(heap_.size() - 1);
    }
  }

  Event<Num> pop() {
    const int ball = heap_[0].ball;
    List& list = lists_[static_cast<std::size_t>(ball)];
    const Event<Num> e = list.events[list.earliest];
    list.events[list.earliest] = list.events.back();
    list.events.pop_back();
    if (list.events.empty()) {
      place_[static_cast<std::size_t>(ball)] = -1;
      const Node last = heap_.back();
      heap_.pop_back();
      if (!heap_.empty()) {
        heap_[0] = last;
        place_[static_cast<std::size_t>(last.ball)] = 0;
        sift_down(0);
      }
    } else {
      find_earliest(list);
      heap_[0] = node_of(ball);
      sift_down(0);
    }
    check_order(e);
    return e;
  }

 private:
  struct List {
    std::vector<Event<Num>> events;
    std::uint64_t version = 0;  // of the owner, when these were predicted
    std::size_t earliest = 0;   // index of the earliest event
  };
  // A ball in the heap, with the order key of its earliest event kept in
  // place: the heap's comparisons touch nothing else.
  struct Node {
    Num time{};
    int kind = 0, a = 0, b = 0, ball = 0;
    std::uint64_t pushed = 0;
  };
  std::vector<List> lists_;  // by ball
  std::vector<Node> heap_;   // balls with events, a binary min-heap by their earliest event
  std::vector<int> place_;   // by ball: its index in heap_, or −1
  std::uint64_t pushes_ = 0, pushes_at_last_pop_ = 0;
  Event<Num> last_popped_;
  bool popped_any_ = false;

  static bool earlier(const Event<Num>& x, const Event<Num>& y) {
    if (LaterEvent<Num>{}(y, x)) return true;
    if (LaterEvent<Num>{}(x, y)) return false;
    return x.pushed < y.pushed;
  }
  // The same order as `earlier`, on nodes.
  static bool earlier(const Node& x, const Node& y) {
    if (x.time != y.time) return x.time < y.time;
    if (x.kind != y.kind) return x.kind < y.kind;
    if (x.a != y.a) return x.a < y.a;
    if (x.b != y.b) return x.b < y.b;
    return x.pushed < y.pushed;
  }
  static void find_earliest(List& list) {
    list.earliest = 0;
    for (std::size_t k = 1; k < list.events.size(); ++k)
      if (earlier(list.events[k], list.events[list.earliest])) list.earliest = k;
  }
  const Event<Num>& earliest_of(int ball) const {
    const List& list = lists_[static_cast<std::size_t>(ball)];
    return list.events[list.earliest];
  }
  Node node_of(int ball) const {
    const Event<Num>& e = earliest_of(ball);
    return {e.time, static_cast<int>(e.kind), e.a, e.b, ball, e.pushed};
  }
  void put(std::size_t i, const Node& n) {
    heap_[i] = n;
    place_[static_cast<std::size_t>(n.ball)] = static_cast<int>(i);
  }
  std::size_t sift_up(std::size_t i) {
    const Node n = heap_[i];
    while (i > 0 && earlier(n, heap_[(i - 1) / 2])) {
      put(i, heap_[(i - 1) / 2]);
      i = (i - 1) / 2;
    }
    put(i, n);
    return i;
  }
  void sift_down(std::size_t i) {
    const Node n = heap_[i];
    for (;;) {
      const std::size_t l = 2 * i + 1, r = l + 1;
      std::size_t least = l;
      if (l >= heap_.size()) break;
      if (r < heap_.size() && earlier(heap_[r], heap_[l])) least = r;
      if (!earlier(heap_[least], n)) break;
      put(i, heap_[least]);
      i = least;
    }
    put(i, n);
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
};

}  // namespace collide2d
