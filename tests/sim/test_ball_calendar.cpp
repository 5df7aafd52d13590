// BallCalendar: the ball it names first is always the one with the least
// key, as a plain ordered set of all the keys would say, through any mix of
// new keys, changed keys and removals, with ties in time, times spread over
// many orders of magnitude, and in both number modes.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "collide2d/numeric/fixed.hpp"
#include "collide2d/sim/ball_calendar.hpp"

namespace {

using namespace collide2d;

template <class Num>
struct Key {
  Num time{};
  int kind = 0, a = 0, b = 0;
  std::uint64_t pushed = 0;
  auto tie() const { return std::tuple(time, kind, a, b, pushed); }
};
template <class Num>
struct KeyEarlier {
  bool operator()(const Key<Num>& x, const Key<Num>& y) const { return x.tie() < y.tie(); }
};

// `spread`: how far ahead of the present a new key's time may lie, as a
// power of ten drawn up to it (many keys crowd near the present, a few lie
// far out, as the earliest events of a gas's balls do). `coarse`: times on a
// grid of 1/8, so that many keys tie in time and are told apart by the rest.
template <class Num>
void check_against_a_set(std::uint32_t seed, int balls, int operations, double spread, bool coarse) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  BallCalendar<Num, Key<Num>, KeyEarlier<Num>> calendar;
  std::vector<Key<Num>> key(static_cast<std::size_t>(balls));
  std::vector<bool> in(static_cast<std::size_t>(balls), false);
  auto order = [&](int x, int y) {
    const auto kx = key[static_cast<std::size_t>(x)].tie(), ky = key[static_cast<std::size_t>(y)].tie();
    return kx < ky || (!(ky < kx) && x < y);
  };
  std::set<int, decltype(order)> reference(order);
  double now = 0;
  std::uint64_t pushes = 0;
  for (int op = 0; op < operations; ++op) {
    const int ball = static_cast<int>(rng() % static_cast<std::uint64_t>(balls));
    const auto i = static_cast<std::size_t>(ball);
    const double choice = unit(rng);
    if (choice < 0.15 && !reference.empty()) {
      // The first ball's event is taken: the present moves to it, and the
      // ball either has no more events or a later one.
      const int first = calendar.first();
      REQUIRE(first == *reference.begin());
      now = NumberTraits<Num>::to_double(key[static_cast<std::size_t>(first)].time);
      reference.erase(first);
      if (unit(rng) < 0.3) {
        calendar.remove(first);
        in[static_cast<std::size_t>(first)] = false;
        continue;
      }
      key[static_cast<std::size_t>(first)].time = num<Num>(now + std::pow(10.0, spread * unit(rng) - 3));
      key[static_cast<std::size_t>(first)].pushed = pushes++;
      reference.insert(first);
      calendar.set(first, key[static_cast<std::size_t>(first)]);
      continue;
    }
    if (choice < 0.2 && in[i]) {
      reference.erase(ball);
      calendar.remove(ball);
      in[i] = false;
      continue;
    }
    if (in[i]) reference.erase(ball);
    double t = now + std::pow(10.0, spread * unit(rng) - 3) * unit(rng);
    if (coarse) t = now + std::floor(8 * (t - now)) / 8;
    key[i] = {num<Num>(t), static_cast<int>(rng() % 4), static_cast<int>(rng() % 3), static_cast<int>(rng() % 3), pushes++};
    reference.insert(ball);
    in[i] = true;
    calendar.set(ball, key[i]);
    REQUIRE(calendar.empty() == reference.empty());
    if (!reference.empty()) REQUIRE(calendar.first() == *reference.begin());
  }
  // Draining it gives every ball in the set's order.
  while (!reference.empty()) {
    const int first = calendar.first();
    REQUIRE(first == *reference.begin());
    reference.erase(first);
    calendar.remove(first);
  }
  REQUIRE(calendar.empty());
}

}  // namespace

TEST_CASE("ball calendar: the first ball is the one of least key, as an ordered set says", "[sim][calendar]") {
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    check_against_a_set<double>(seed, 200, 40000, 3, false);
    check_against_a_set<double>(seed, 3000, 60000, 1, false);
    check_against_a_set<double>(seed, 50, 20000, 8, false);  // times from 1e-3 to 1e5 ahead: many layouts
  }
}

TEST_CASE("ball calendar: ties in time are ordered by the rest of the key", "[sim][calendar]") {
  for (std::uint32_t seed : {4u, 5u}) check_against_a_set<double>(seed, 300, 40000, 2, true);
}

TEST_CASE("ball calendar: fixed-point keys order the same way", "[sim][calendar]") {
  check_against_a_set<Fixed>(6, 300, 30000, 3, false);
  check_against_a_set<Fixed>(7, 300, 30000, 2, true);
}

TEST_CASE("ball calendar: clearing it empties it, and it fills again", "[sim][calendar]") {
  BallCalendar<double, Key<double>, KeyEarlier<double>> calendar;
  for (int b = 0; b < 100; ++b) calendar.set(b, {1.0 + b * 0.25, 0, b, 0, 0});
  REQUIRE(calendar.first() == 0);
  calendar.clear();
  REQUIRE(calendar.empty());
  for (int b = 99; b >= 50; --b) calendar.set(b, {2.0 - b * 0.01, 0, b, 0, 0});
  REQUIRE(calendar.first() == 99);
  calendar.remove(99);
  REQUIRE(calendar.first() == 98);
}

// The calendar's work is O(1) a change only while few balls share the front's
// heap: its width must suit the balls it holds. Before it laid itself out
// again as it filled, its one width came from the first ball alone (a width
// of 1 for a single time), and a run's whole calendar was one heap: every
// ball of a 10^6-disc gas in the front. Filled one ball at a time with times
// spread evenly over [0, 1), 10^4 balls leave a handful in the front (the
// width puts two to four balls to a bucket; 64 is far above that and far
// below the 10^4 of a calendar that never laid itself out again).
TEST_CASE("ball calendar: filled one ball at a time, it keeps few balls in its front", "[sim][calendar]") {
  BallCalendar<double, Key<double>, KeyEarlier<double>> calendar;
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> unit(0, 1);
  const int balls = 10000;
  for (int b = 0; b < balls; ++b) calendar.set(b, {unit(rng), 0, b, 0, static_cast<std::uint64_t>(b)});
  CHECK(calendar.front_size() <= 64);
  // Taking the events in order (each ball's next one a second later) keeps it so.
  double now = 0;
  for (int k = 0; k < 3 * balls; ++k) {
    const int first = calendar.first();
    const double t = calendar.key(first).time;
    REQUIRE(t >= now);
    now = t;
    calendar.set(first, {t + unit(rng), 0, first, 0, static_cast<std::uint64_t>(balls + k)});
    REQUIRE(calendar.front_size() <= 64);
  }
}
