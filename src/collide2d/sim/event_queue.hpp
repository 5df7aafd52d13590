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
#include <memory>
#include <vector>

#include "collide2d/numeric/number_traits.hpp"
#include "collide2d/sim/ball_calendar.hpp"
#include "collide2d/sim/prefetch.hpp"
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
  // Where the paths of a and b that end here began: each body as it was
  // just before, on its own clock (straight lines: only a gas's engine
  // gives them, gas_engine.hpp). The tunnelling watch then checks those
  // pieces from them and keeps no copy of its own.
  struct PieceStart {
    Vec2<Num> position, velocity;
    Num time{};
  };
  bool has_piece_starts = false;
  PieceStart piece_start_a, piece_start_b;
};

// Whether an event is a contact (a time of impact or a pressed contact): it
// is predicted from the clocks of the balls involved, never from when it is
// asked, so that asking again gives the same bits. A cell crossing and the
// end of a persistent contact are predicted from the present, and are not.
inline bool is_contact(EventKind k) { return k == EventKind::ball_ball || k == EventKind::ball_wall; }

// (time, kind, a, b): x comes after y in the processing order.
template <class Num>
bool after_in_order(const Event<Num>& x, const Event<Num>& y) {
  return LaterEvent<Num>{}(x, y);
}

// An event out of the queue, with the ball whose prediction it was.
template <class Num>
struct PoppedEvent {
  Event<Num> event;
  int owner = 0;
  std::uint64_t owner_version = 0;  // the owner's version when it was predicted
  bool contact = false;             // the owner's earliest contact (is_contact)
};

// The pending events: a few per ball, and a calendar over the balls.
//
// Every event belongs to the ball whose prediction found it (its owner).
// Where no ball accelerates (a gas: `earliest_contact_only`), a ball keeps,
// of what was predicted for it since its motion last changed:
//   - its earliest contact, one event however many neighbours and walls
//     were asked (Smallenburg's EDMD, after Paul: one event per particle);
//   - its next cell crossing;
//   - every other event (the end of a persistent contact).
// Only the earliest contact need be kept: the others can be asked again,
// to the same bits (is_contact), for a ball's clock moves only with its
// motion. When a ball's kept contact comes out and leaves its motion as it
// was (stale, its partner having changed; or a contact that changes
// nothing, such as a creeping one), the engine asks the owner's neighbours
// and walls again for its earliest contact from there on
// (EventEngine::predict_contacts_after). A later contact with a partner
// whose motion has changed since is that partner's prediction too, kept in
// its own place. So the queue gives what a list of every prediction would
// give next, with two events a ball instead of a dozen.
//
// Under accelerations a ball keeps every event predicted for it: a ball
// asleep there is carried to the present with its island without a change
// of motion, and a contact with it asked again could start from another
// clock (predict_pair), so its contacts are not asked again.
//
// An event pushed with a newer version of its owner than the ball's
// replaces all it holds (everything predicted before involves the owner,
// whose motion has changed since: stale). The calendar (ball_calendar.hpp) holds
// each ball with an event, keyed by its earliest. The earliest event
// overall comes out first, in (time, kind, a, b) order; events equal in all
// four go in the order they were pushed. Whether an event is still current
// (the versions of both balls) is for the engine to judge as before.
template <class Num>
class EventQueue {
 public:
  // Keep only each ball's earliest contact and crossing (a gas), or every
  // event (under accelerations); set before the first push.
  void keep_earliest_contact_only(bool on) { earliest_contact_only_ = on; }
  void clear() {
    for (List& list : lists_) list.has_contact = list.has_crossing = false, clear_others(list), list.placed = true;
    unplaced_.clear();
    calendar_.clear();
    popped_any_ = false;
  }
  // Room for `balls` balls at once (a queue grown one ball at a time would
  // double its storage past the need).
  void reserve(std::size_t balls) {
    if (lists_.size() < balls) lists_.resize(balls);
    calendar_.reserve(balls);
  }
  bool empty() {
    place_changed_lists();
    return calendar_.empty();
  }
  // The time of the earliest event (the queue is not empty): its key in the calendar.
  const Num& next_time() {
    place_changed_lists();
    return calendar_.key(calendar_.first()).time;
  }
  // Whether push(e, owner, owner_version) would keep e: not a contact no
  // earlier than the one the owner keeps. Asked first, it spares reading
  // the versions (the partner's memory) of the many contacts a prediction
  // finds and drops.
  bool would_keep(const Event<Num>& e, int owner, std::uint64_t owner_version) const {
    if (!earliest_contact_only_ || !is_contact(e.kind)) return true;
    const auto ball = static_cast<std::size_t>(owner);
    if (ball >= lists_.size()) return true;
    const List& list = lists_[ball];
    return list.version != owner_version || !list.has_contact || after_in_order(list.contact, e);
  }
  void push(Event<Num> e, int owner, std::uint64_t owner_version) {
    e.pushed = pushes_++;
    const auto ball = static_cast<std::size_t>(owner);
    if (ball >= lists_.size()) lists_.resize(ball + 1);
    List& list = lists_[ball];
    if (list.version != owner_version || !list.any()) {
      list.has_contact = list.has_crossing = false;
      clear_others(list);
      list.version = owner_version;
      mark_unplaced(owner);
    } else if (earlier_than_earliest(e, list, owner)) {
      mark_unplaced(owner);
    }
    if (!earliest_contact_only_) {
      add_other(list, e);
    } else if (is_contact(e.kind)) {
      if (!list.has_contact || earlier(e, list.contact)) list.contact = e, list.has_contact = true;
    } else if (e.kind == EventKind::cell_crossing) {
      if (!list.has_crossing || earlier_than_crossing(e, list, owner)) keep_crossing(list, e);
    } else {
      add_other(list, e);
    }
  }
  // Asks the memory for what the next event will read: its balls
  // (`prefetch_ball(k)` asks for what the engine keeps of ball k), its
  // owner's events, and for a collision the partner's events and place in
  // the calendar, which are written once the pair has been predicted again.
  // The calendar's key names them, and processing the present event takes
  // long enough for the misses of a large gas to be over by then. A hint
  // only: the order is untouched. `prefetch_ball` must be inlined as well
  // (prefetch.hpp: a call of prefetches alone is deleted).
  template <class PrefetchBall>
  [[gnu::always_inline]] void prefetch_next(PrefetchBall prefetch_ball) const {
    if (calendar_.empty()) return;
    const int ball = calendar_.first();
    const Node& next = calendar_.key(ball);
    prefetch_list(ball);
    prefetch_ball(next.a);
    if (next.kind != static_cast<int>(EventKind::ball_ball)) return;  // the rest are rare in a gas
    prefetch_ball(next.b);
    const int partner = next.a == ball ? next.b : next.a;
    prefetch_list(partner);
    calendar_.prefetch(partner);
  }
  // Checkpoints: every pending event with its place in the order (push
  // count) and each ball's version; a loaded queue pops exactly what the
  // saved one would have (the order is total: time, kind, a, b, push).
  template <class Writer>
  void save(Writer& out) const {
    out.put(pushes_);
    out.put(static_cast<std::uint64_t>(lists_.size()));
    for (const List& list : lists_) {
      out.put(list.version);
      std::uint64_t count = list.has_contact + list.has_crossing + (list.others ? list.others->events.size() : 0);
      out.put(count);
      auto put = [&](const Event<Num>& e) {
        out.put(e.time);
        out.put(static_cast<std::uint8_t>(e.kind));
        out.put(static_cast<std::int32_t>(e.a));
        out.put(static_cast<std::int32_t>(e.b));
        out.put(static_cast<std::uint8_t>(e.feature));
        out.put(e.version_a);
        out.put(e.version_b);
        out.put(e.pushed);
      };
      if (list.has_contact) put(list.contact);
      if (list.has_crossing) put(crossing_event(list, static_cast<int>(&list - lists_.data())));
      if (list.others)
        for (const Event<Num>& e : list.others->events) put(e);
    }
  }
  // A checkpoint is a file's bytes: the list count must be the scene's
  // `balls`, and every event must name balls and walls (`walls`) it has.
  template <class Reader>
  void load(Reader& in, std::size_t balls, std::size_t walls) {
    calendar_.clear();
    unplaced_.clear();
    popped_any_ = false;
    in.get(pushes_);
    pushes_at_last_pop_ = pushes_;
    std::uint64_t n = 0;
    in.get(n);
    if (n != balls) throw std::runtime_error("checkpoint holds the events of another number of balls");
    lists_.clear();
    lists_.resize(n);
    calendar_.reserve(n);
    for (std::size_t ball = 0; ball < n; ++ball) {
      List& list = lists_[ball];
      in.get(list.version);
      std::uint64_t count = 0;
      in.get(count);
      if (count > in.remaining() / 16) throw std::runtime_error("checkpoint holds more events than it has bytes for");
      for (std::uint64_t k = 0; k < count; ++k) {
        Event<Num> e;
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
        const auto names_a_ball = [&](std::int32_t k) { return k >= 0 && static_cast<std::uint64_t>(k) < n; };
        const bool with_wall = e.kind == EventKind::ball_wall || e.kind == EventKind::leave_wall;
        if (kind > static_cast<std::uint8_t>(EventKind::leave_pair) || !names_a_ball(a) ||
            (between_two_balls(e.kind) && !names_a_ball(b)) ||
            (with_wall && !(b >= 0 && static_cast<std::uint64_t>(b) < walls)) ||
            (e.kind == EventKind::cell_crossing && (a != static_cast<std::int32_t>(ball) || b < 0 || b > 3)) ||
            feature > static_cast<std::uint8_t>(ContactFeature::wall_end_b))
          throw std::runtime_error("checkpoint holds an event of no ball or wall of the scene");
        if (earliest_contact_only_ && is_contact(e.kind)) list.contact = e, list.has_contact = true;
        else if (earliest_contact_only_ && e.kind == EventKind::cell_crossing) {
          // Kept as its time, place and step: the rest is the ball's own
          // (that it names its own ball is checked above, for either mode).
          if (e.version_a != list.version || e.version_b != 0 ||
              e.feature != ContactFeature::none)
            throw std::runtime_error("checkpoint holds a cell crossing that is not its ball's own");
          keep_crossing(list, e);
        }
        else add_other(list, e);
      }
      if (list.any()) calendar_.set(static_cast<int>(ball), node_of(static_cast<int>(ball)));
    }
  }

  // Every pending cell crossing as (ball, step, the ball's version it was
  // predicted for): a loaded checkpoint's are checked against the grid.
  template <class Visit>
  void for_each_crossing(Visit visit) const {
    for (std::size_t ball = 0; ball < lists_.size(); ++ball) {
      const List& list = lists_[ball];
      if (list.has_crossing) visit(static_cast<int>(ball), list.crossing.step, list.version);
      if (list.others)
        for (const Event<Num>& e : list.others->events)
          if (e.kind == EventKind::cell_crossing) visit(e.a, e.b, e.version_a);
    }
  }

  PoppedEvent<Num> pop() {
    place_changed_lists();
    const int ball = calendar_.first();
    List& list = lists_[static_cast<std::size_t>(ball)];
    const Slot first = earliest_slot(list, ball);
    PoppedEvent<Num> out{event_in(list, first, ball), ball, list.version, first == Slot::contact};
    if (first == Slot::contact) list.has_contact = false;
    else if (first == Slot::crossing) list.has_crossing = false;
    else remove_earliest_other(list);
    if (list.any()) calendar_.set(ball, node_of(ball));
    else calendar_.remove(ball);
    check_order(out.event);
    return out;
  }

 private:
  // What a push asks first (the version, the flags, the kept contact) comes first.
  // A ball's events other than its kept contact and crossing: contact
  // endings in a gas (rare: most balls never have one, and hold a null
  // pointer, not an empty vector's three words), every event under
  // accelerations. The earliest of them is marked.
  struct Others {
    std::vector<Event<Num>> events;
    std::size_t earliest = 0;
  };
  // A ball's next cell crossing, as little of it as is its own: the rest
  // of the event (kind, ball, versions) is the owner's (crossing_event), and
  // a million-ball gas keeps 24 bytes a ball less.
  struct Crossing {
    Num time{};
    std::uint64_t pushed = 0;
    int step = 0;
  };
  struct List {
    std::uint64_t version = 0;         // of the owner, when these were predicted
    bool has_contact = false, has_crossing = false;
    bool placed = true;                // the calendar holds the ball by its earliest event
    Event<Num> contact;                // the earliest contact (if has_contact)
    Crossing crossing;                 // the next cell crossing (if has_crossing)
    std::unique_ptr<Others> others;    // made at a ball's first other event, and kept
    bool any() const { return has_contact || has_crossing || (others && !others->events.empty()); }
  };
  // A ball's place in the order: the key of its earliest event, kept
  // beside it so that ordering the balls touches nothing else.
  struct Node {
    Num time{};
    int kind = 0, a = 0, b = 0, ball = 0;
    std::uint64_t pushed = 0;
  };
  // The same order as `earlier` on events.
  struct NodeEarlier {
    bool operator()(const Node& x, const Node& y) const {
      if (x.time != y.time) return x.time < y.time;
      if (x.kind != y.kind) return x.kind < y.kind;
      if (x.a != y.a) return x.a < y.a;
      if (x.b != y.b) return x.b < y.b;
      return x.pushed < y.pushed;
    }
  };
  std::vector<List> lists_;  // by ball
  std::vector<int> unplaced_;  // balls whose earliest event changed since the calendar last saw them
  BallCalendar<Num, Node, NodeEarlier> calendar_;  // the balls with events, by their earliest
  std::uint64_t pushes_ = 0, pushes_at_last_pop_ = 0;
  Event<Num> last_popped_;
  bool popped_any_ = false;
  bool earliest_contact_only_ = false;

  [[gnu::always_inline]] void prefetch_list(int ball) const { prefetch_element(lists_, ball); }

  // A prediction pushes several events for one ball, and the calendar needs
  // only the earliest: each ball whose earliest changed is placed once,
  // before the queue is next read (the order is the same, the work less).
  void mark_unplaced(int ball) {
    List& list = lists_[static_cast<std::size_t>(ball)];
    if (!list.placed) return;
    list.placed = false;
    unplaced_.push_back(ball);
  }
  void place_changed_lists() {
    for (int ball : unplaced_) {
      lists_[static_cast<std::size_t>(ball)].placed = true;
      calendar_.set(ball, node_of(ball));
    }
    unplaced_.clear();
  }

  static bool earlier(const Event<Num>& x, const Event<Num>& y) {
    if (LaterEvent<Num>{}(y, x)) return true;
    if (LaterEvent<Num>{}(x, y)) return false;
    return x.pushed < y.pushed;
  }
  // A ball's other events, with the earliest of them marked (under
  // accelerations they are all its events: a push is then O(1), a pop a
  // scan of one short list).
  static void add_other(List& list, const Event<Num>& e) {
    if (!list.others) list.others = std::make_unique<Others>();
    Others& o = *list.others;
    o.events.push_back(e);
    if (o.events.size() == 1 || earlier(e, o.events[o.earliest])) o.earliest = o.events.size() - 1;
  }
  static void remove_earliest_other(List& list) {
    Others& o = *list.others;
    o.events[o.earliest] = o.events.back();
    o.events.pop_back();
    o.earliest = 0;
    for (std::size_t k = 1; k < o.events.size(); ++k)
      if (earlier(o.events[k], o.events[o.earliest])) o.earliest = k;
  }
  static void clear_others(List& list) {
    if (list.others) list.others->events.clear();
  }
  // Ball `ball`'s crossing as the event it was pushed as: the ball's own
  // (a = the owner, its version then, which is the list's), no feature.
  static Event<Num> crossing_event(const List& list, int ball) {
    Event<Num> e{list.crossing.time, EventKind::cell_crossing, ball, list.crossing.step, ContactFeature::none};
    e.version_a = list.version;
    e.pushed = list.crossing.pushed;
    return e;
  }
  static void keep_crossing(List& list, const Event<Num>& e) {
    list.crossing = {e.time, e.pushed, e.b};
    list.has_crossing = true;
  }
  // The order of an event and a ball's crossing, `earlier` as if the
  // crossing were its event: decided by the times alone but at a tie, so
  // that the event is made only then.
  static bool earlier_than_crossing(const Event<Num>& e, const List& list, int ball) {
    if (e.time != list.crossing.time) return e.time < list.crossing.time;
    return earlier(e, crossing_event(list, ball));
  }
  static bool crossing_earlier_than(const List& list, int ball, const Event<Num>& e) {
    if (e.time != list.crossing.time) return list.crossing.time < e.time;
    return earlier(crossing_event(list, ball), e);
  }
  // Where a ball's earliest event is (it holds one at least).
  enum class Slot { contact, crossing, other };
  static Slot earliest_slot(const List& list, int ball) {
    Slot first = Slot::other;
    bool any = false;
    if (list.has_contact) first = Slot::contact, any = true;
    if (list.has_crossing && (!any || crossing_earlier_than(list, ball, list.contact))) first = Slot::crossing, any = true;
    if (list.others && !list.others->events.empty()) {
      const Event<Num>& other = list.others->events[list.others->earliest];
      if (!any || (first == Slot::contact ? earlier(other, list.contact) : earlier_than_crossing(other, list, ball)))
        first = Slot::other;
    }
    return first;
  }
  // Whether e comes before every event the ball holds (it holds one at least).
  static bool earlier_than_earliest(const Event<Num>& e, const List& list, int ball) {
    switch (earliest_slot(list, ball)) {
      case Slot::contact: return earlier(e, list.contact);
      case Slot::crossing: return earlier_than_crossing(e, list, ball);
      case Slot::other: break;
    }
    return earlier(e, list.others->events[list.others->earliest]);
  }
  static Event<Num> event_in(const List& list, Slot slot, int ball) {
    switch (slot) {
      case Slot::contact: return list.contact;
      case Slot::crossing: return crossing_event(list, ball);
      case Slot::other: break;
    }
    return list.others->events[list.others->earliest];
  }
  Node node_of(int ball) const {
    const List& list = lists_[static_cast<std::size_t>(ball)];
    const Slot first = earliest_slot(list, ball);
    if (first == Slot::crossing)
      return {list.crossing.time, static_cast<int>(EventKind::cell_crossing), ball, list.crossing.step, ball,
              list.crossing.pushed};
    const Event<Num>& e = first == Slot::contact ? list.contact : list.others->events[list.others->earliest];
    return {e.time, static_cast<int>(e.kind), e.a, e.b, ball, e.pushed};
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
