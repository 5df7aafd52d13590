// The balls with pending events, ordered by the key of each one's earliest
// event: a calendar queue (Paul, J. Comput. Phys. 221, 615 (2007)), O(1) a
// change where a binary heap over N balls costs O(log N).
//
// Time is cut into buckets of width w from an origin. The balls whose key
// lies in the current bucket or before it are kept in a small binary heap
// (the front), ordered by the whole key; those in the next B − 1 buckets sit
// unordered in one linked list per bucket; later ones in an overflow list.
// When the front runs empty the next bucket's balls move into it; when the
// window of B buckets is used up, the calendar is laid out again from the
// overflow, with a width that puts a few balls in a bucket.
//
// Why the order is exact: a ball's bucket is floor((t − origin) · (1 / w))
// with t its key's time in doubles and 1 / w finite and positive (lay_out
// sees to it), a non-decreasing function of the time in any number mode
// (the conversion and the operations round monotonically). So
// every ball outside the front has a later time than every ball in it, and
// the front's heap orders the rest by the whole key: the first ball is the
// one a heap over all the balls would give, whatever the width or origin.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "collide2d/numeric/number_traits.hpp"
#include "collide2d/sim/prefetch.hpp"

namespace collide2d {

// Key: has `time` (a Num); Earlier: a strict total order on keys.
template <class Num, class Key, class Earlier>
class BallCalendar {
 public:
  bool empty() const { return count_ == 0; }
  // The ball whose key comes first (the calendar is not empty).
  int first() const { return front_[0]; }
  const Key& key(int ball) const { return of(ball).key; }
  // The balls that come next unless the first's new key comes before
  // them: the first's children in the front's heap (at most two; -1 none).
  std::array<int, 2> runners_up() const {
    return {front_.size() > 1 ? front_[1] : -1, front_.size() > 2 ? front_[2] : -1};
  }
  // Asks the memory for ball `ball`'s entry, which a set() will soon read.
  [[gnu::always_inline]] void prefetch(int ball) const { prefetch_element(at_, ball); }
  // Balls in the front's heap (the rest wait unordered in buckets).
  std::size_t front_size() const { return front_.size(); }
  void reserve(std::size_t balls) {
    if (at_.size() < balls) grow(balls);
  }

  void clear() {
    for (int b : front_) of(b).state = nowhere;
    for (int b : overflow_) of(b).state = nowhere;
    for (int& head : heads_) {
      for (int b = head; b >= 0;) {
        const int after = of(b).link;
        of(b).state = nowhere;
        b = after;
      }
      head = -1;
    }
    front_.clear();
    overflow_.clear();
    count_ = in_buckets_ = laid_out_for_ = changes_ = 0;
  }

  // Gives ball `ball` the key `k`, whether it was in the calendar or not.
  void set(int ball, const Key& k) {
    if (static_cast<std::size_t>(ball) >= at_.size()) grow(static_cast<std::size_t>(ball) + 1);
    Entry& e = of(ball);
    if (e.state == in_front) {
      // Still in the front: the heap is mended in place.
      const bool sooner = Earlier{}(k, e.key);
      e.key = k;
      if (!(bucket_of(k.time) >= static_cast<double>(current_ + 1))) {  // as put_in judges
        if (sooner) sift_up(static_cast<std::size_t>(e.link));
        else sift_down(static_cast<std::size_t>(e.link));
        return;
      }
      take_out(ball);
    } else if (e.state != nowhere) {
      take_out(ball);
      e.key = k;
    } else {
      e.key = k;
      ++count_;
    }
    put_in(ball);
    fill_front();
    keep_sized();
  }

  void remove(int ball) {
    if (of(ball).state == nowhere) return;
    take_out(ball);
    --count_;
    fill_front();
    keep_sized();
  }

 private:
  static constexpr int nowhere = -2, in_front = -3, in_overflow = -4;  // Entry::state, else in a bucket
  // What the calendar knows of a ball, in one place: a change touches one
  // or two cache lines, not five. 24 bytes in doubles (a million balls'
  // calendar is 24 MB): a ball in a bucket's list has no place in the front
  // or the overflow, so one int is its place there or its next in the
  // list, and the other says where it is or, in a bucket, which ball is
  // before it (−1: it is the head; its bucket is found again from its key,
  // as put_in found it: the window has not moved since).
  struct Entry {
    Key key{};
    int link = 0;          // in front_ or overflow_: its place there; in a bucket: the next ball (−1: none)
    int state = nowhere;   // nowhere, in_front, in_overflow, or in a bucket: the ball before it (−1: none)
  };
  std::vector<Entry> at_;  // by ball
  std::vector<int> heads_;      // by slot: the first ball of the bucket (−1: empty); B = its size
  std::vector<int> front_;      // a binary min-heap of balls by key
  std::vector<int> overflow_;   // balls past the window, unordered
  std::vector<double> scratch_;
  double origin_ = 0, per_width_ = 1;  // the window's start, and 1 / its buckets' width
  std::int64_t current_ = 0, window_end_ = 0;  // buckets: the front's, and the first past the window
  std::size_t count_ = 0, in_buckets_ = 0;
  std::size_t laid_out_for_ = 0;  // balls in the calendar when it was last laid out
  std::size_t changes_ = 0;       // sets and removes since then

  void grow(std::size_t n) { at_.resize(n); }
  Entry& of(int ball) { return at_[static_cast<std::size_t>(ball)]; }
  const Entry& of(int ball) const { return at_[static_cast<std::size_t>(ball)]; }

  // A product, not a quotient (a third of the latency): rounding a product
  // by a positive constant is as monotone as a quotient, which is all the
  // order needs.
  double bucket_of(const Num& t) const { return (NumberTraits<Num>::to_double(t) - origin_) * per_width_; }
  // The list of bucket x (in the window), and of a key's time there.
  int slot_of_bucket(double x) const {
    return static_cast<int>(static_cast<std::int64_t>(x) & static_cast<std::int64_t>(heads_.size() - 1));
  }
  int slot_of(const Num& t) const { return slot_of_bucket(bucket_of(t)); }

  void put_in(int ball) {
    Entry& e = of(ball);
    const double x = bucket_of(e.key.time);
    if (!(x >= static_cast<double>(current_ + 1))) {  // the front's bucket or before (or not a number)
      push_front(ball);
    } else if (x < static_cast<double>(window_end_)) {
      int& head = heads_[static_cast<std::size_t>(slot_of_bucket(x))];
      e.state = -1;
      e.link = head;
      if (head >= 0) of(head).state = ball;
      head = ball;
      ++in_buckets_;
    } else {
      e.state = in_overflow;
      e.link = static_cast<int>(overflow_.size());
      overflow_.push_back(ball);
    }
  }

  // Removes the ball at `at` from `list` by moving the last one into its
  // place; true if one was moved there (the front's heap then mends it).
  bool swap_remove(std::vector<int>& list, std::size_t at) {
    const int last = list.back();
    list.pop_back();
    if (at == list.size()) return false;
    list[at] = last;
    of(last).link = static_cast<int>(at);
    return true;
  }

  void push_front(int ball) {
    Entry& e = of(ball);
    e.state = in_front;
    e.link = static_cast<int>(front_.size());
    front_.push_back(ball);
    sift_up(front_.size() - 1);
  }

  void take_out(int ball) {
    Entry& e = of(ball);
    const int state = e.state;
    e.state = nowhere;
    if (state == in_front) {
      const auto at = static_cast<std::size_t>(e.link);
      if (swap_remove(front_, at)) sift_down(sift_up(at));
    } else if (state == in_overflow) {
      swap_remove(overflow_, static_cast<std::size_t>(e.link));
    } else {
      const int prev = state, next = e.link;
      if (prev >= 0) of(prev).link = next;
      else heads_[static_cast<std::size_t>(slot_of(e.key.time))] = next;
      if (next >= 0) of(next).state = prev;
      --in_buckets_;
    }
  }

  // The front is never empty while any ball is in the calendar: the next
  // buckets move into it, and past the window the calendar is laid out again.
  void fill_front() {
    while (front_.empty() && count_ > 0) {
      if (in_buckets_ == 0) {
        lay_out();
        continue;
      }
      ++current_;
      int& head = heads_[static_cast<std::size_t>(current_ & static_cast<std::int64_t>(heads_.size() - 1))];
      for (int b = head; b >= 0;) {
        const int after = of(b).link;
        --in_buckets_;
        push_front(b);
        b = after;
      }
      head = -1;
    }
  }

  // A width suits the number of balls it was chosen for and the spread of
  // their times then. The calendar is laid out again from all its balls when
  // their number has doubled or halved since (the first balls of a run are
  // laid out when there are one, two, four, ... of them, not once for ever
  // with a width from the first ball alone), or when the front has grown
  // into a heap over a sixteenth of them (a width far too wide for the times
  // now). A lay-out costs O(count_), so each comes after O(count_) changes:
  // halving or doubling takes that many, and the front's growth is acted on
  // only `count_` changes after the last lay-out (equal times, say, which no
  // width can spread, must not lay it out at every change).
  void keep_sized() {
    ++changes_;
    if (count_ == 0) return;
    const bool resized = count_ >= 2 * laid_out_for_ || 2 * count_ <= laid_out_for_;
    const bool front_too_large = changes_ >= count_ && front_.size() > 64 && 16 * front_.size() > count_;
    if (resized || front_too_large) lay_out_all();
  }

  void lay_out_all() {
    auto to_overflow = [&](int b) {
      Entry& e = of(b);
      e.state = in_overflow;
      e.link = static_cast<int>(overflow_.size());
      overflow_.push_back(b);
    };
    for (int b : front_) to_overflow(b);
    front_.clear();
    for (int& head : heads_) {
      for (int b = head; b >= 0;) {
        const int after = of(b).link;
        to_overflow(b);
        b = after;
      }
      head = -1;
    }
    in_buckets_ = 0;
    lay_out();
    fill_front();
  }

  // Every ball is in the overflow: a new window from the earliest time, B
  // buckets (a power of two, at most the number of balls) of a width that
  // puts half the balls in its first quarter, two to four to a bucket there. The
  // median is that of an even sample of at most 1024 balls: the width only
  // sets the cost, never the order, and the sample keeps the memory small.
  // The overflow is sorted into the window in place.
  void lay_out() {
    const std::size_t n = overflow_.size();
    double t_min = INFINITY;
    for (int b : overflow_) t_min = std::fmin(t_min, NumberTraits<Num>::to_double(of(b).key.time));
    const std::size_t stride = std::max<std::size_t>(1, n / 1024);
    scratch_.clear();
    for (std::size_t k = 0; k < n; k += stride)
      scratch_.push_back(NumberTraits<Num>::to_double(of(overflow_[k]).key.time) - t_min);
    const std::size_t buckets = std::bit_floor(std::max<std::size_t>(16, n));
    auto middle = scratch_.begin() + static_cast<std::ptrdiff_t>(scratch_.size() / 2);
    std::nth_element(scratch_.begin(), middle, scratch_.end());
    const double median = *middle, largest = *std::max_element(scratch_.begin(), scratch_.end());
    double width = 4 * median / static_cast<double>(buckets);
    // (A subnormal width's reciprocal overflows to inf.)
    auto unusable = [](double w) { return !(w > 0) || !std::isfinite(w) || !std::isfinite(1 / w); };
    if (unusable(width)) width = largest / static_cast<double>(buckets);
    if (unusable(width)) width = 1;
    origin_ = std::isfinite(t_min) ? t_min : 0;
    per_width_ = 1 / width;
    current_ = 0;
    window_end_ = static_cast<std::int64_t>(buckets);
    heads_.assign(buckets, -1);
    std::size_t kept = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const int b = overflow_[k];
      if (bucket_of(of(b).key.time) >= static_cast<double>(window_end_)) {
        overflow_[kept] = b;
        of(b).link = static_cast<int>(kept++);
      } else {
        put_in(b);  // into the front or a bucket, never the overflow
      }
    }
    overflow_.resize(kept);
    laid_out_for_ = count_;
    changes_ = 0;
  }

  bool earlier(std::size_t x, std::size_t y) const { return Earlier{}(of(front_[x]).key, of(front_[y]).key); }
  void place(std::size_t at, int ball) {
    front_[at] = ball;
    of(ball).link = static_cast<int>(at);
  }
  std::size_t sift_up(std::size_t i) {
    const int ball = front_[i];
    const Key& k = of(ball).key;
    while (i > 0) {
      const std::size_t parent = (i - 1) / 2;
      if (!Earlier{}(k, of(front_[parent]).key)) break;
      place(i, front_[parent]);
      i = parent;
    }
    place(i, ball);
    return i;
  }
  void sift_down(std::size_t i) {
    const int ball = front_[i];
    const Key& k = of(ball).key;
    for (;;) {
      const std::size_t l = 2 * i + 1, r = l + 1;
      if (l >= front_.size()) break;
      const std::size_t least = r < front_.size() && earlier(r, l) ? r : l;
      if (!Earlier{}(of(front_[least]).key, k)) break;
      place(i, front_[least]);
      i = least;
    }
    place(i, ball);
  }
};

}  // namespace collide2d
