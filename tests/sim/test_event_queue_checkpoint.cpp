// EventQueue checkpoints: a queue saved and loaded pops exactly the events
// the saved one would have, in the same order; a checkpoint whose events
// name no ball of the scene, an unknown kind, or that ends early is refused
// with an error, never loaded into a queue that would index past its balls.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "collide2d/sim/event_queue.hpp"
#include "collide2d/sim/state_bytes.hpp"

namespace {

using namespace collide2d;

constexpr int kBalls = 4;
constexpr int kWalls = 3;  // the wall contact names wall 2

// A queue of four balls holding collisions, a wall contact and a tie in time
// (told apart by kind, then indices).
EventQueue<double> filled_queue(bool earliest_contact_only) {
  EventQueue<double> q;
  q.keep_earliest_contact_only(earliest_contact_only);
  q.reserve(kBalls);
  auto event = [](double t, EventKind kind, int a, int b) {
    Event<double> e;
    e.time = t, e.kind = kind, e.a = a, e.b = b;
    return e;
  };
  q.push(event(0.50, EventKind::ball_ball, 0, 1), 0, 0);
  q.push(event(0.25, EventKind::ball_wall, 1, 2), 1, 0);
  q.push(event(0.75, EventKind::ball_ball, 2, 3), 2, 0);
  q.push(event(0.25, EventKind::ball_ball, 3, 2), 3, 0);
  return q;
}

std::vector<std::uint8_t> saved(const EventQueue<double>& q) {
  ByteWriter out;
  q.save(out);
  return out.bytes();
}

// The bytes of the first event of the first ball that has one: after the
// push count (8), the number of lists (8), that list's version (8) and count (8).
constexpr std::size_t kFirstEvent = 32;
constexpr std::size_t kKindOffset = kFirstEvent + sizeof(double);
constexpr std::size_t kBallOffset = kKindOffset + 1;       // int32 a
constexpr std::size_t kPartnerOffset = kBallOffset + 4;    // int32 b

void write_int32(std::vector<std::uint8_t>& bytes, std::size_t at, std::int32_t value) {
  for (int k = 0; k < 4; ++k) bytes[at + k] = static_cast<std::uint8_t>(static_cast<std::uint32_t>(value) >> (8 * k));
}

}  // namespace

TEST_CASE("a loaded queue pops what the saved one would have", "[sim][event_queue][checkpoint]") {
  for (bool earliest_only : {false, true}) {
    EventQueue<double> original = filled_queue(earliest_only);
    const std::vector<std::uint8_t> bytes = saved(original);
    EventQueue<double> loaded;
    loaded.keep_earliest_contact_only(earliest_only);
    ByteReader in(bytes);
    loaded.load(in, kBalls, kWalls);
    REQUIRE(in.done());
    int popped = 0;
    while (!original.empty()) {
      REQUIRE_FALSE(loaded.empty());
      const PoppedEvent<double> x = original.pop(), y = loaded.pop();
      CHECK(x.event.time == y.event.time);
      CHECK(x.event.kind == y.event.kind);
      CHECK(x.event.a == y.event.a);
      CHECK(x.event.b == y.event.b);
      CHECK(x.event.pushed == y.event.pushed);
      ++popped;
    }
    CHECK(loaded.empty());
    CHECK(popped == 4);
  }
}

TEST_CASE("a checkpoint whose events name no ball or wall of the scene is refused", "[sim][event_queue][checkpoint]") {
  const std::vector<std::uint8_t> good = saved(filled_queue(false));
  // The first stored event is ball 0's collision with ball 1 (a = 0, b = 1).
  std::int32_t a = 0, b = 0;
  std::memcpy(&a, good.data() + kBallOffset, 4);
  std::memcpy(&b, good.data() + kPartnerOffset, 4);
  REQUIRE(a == 0);
  REQUIRE(b == 1);
  const auto load = [](const std::vector<std::uint8_t>& bytes, int balls = kBalls, int walls = kWalls) {
    EventQueue<double> q;
    ByteReader in(bytes);
    q.load(in, balls, walls);
  };
  REQUIRE_NOTHROW(load(good));
  // Another scene: one ball more, or too few walls for the wall contact.
  CHECK_THROWS_AS(load(good, kBalls + 1), std::runtime_error);
  CHECK_THROWS_AS(load(good, kBalls, 2), std::runtime_error);
  for (std::int32_t bad : {-1, kBalls, 1 << 30}) {
    std::vector<std::uint8_t> bytes = good;
    write_int32(bytes, kBallOffset, bad);
    CHECK_THROWS_AS(load(bytes), std::runtime_error);
    bytes = good;
    write_int32(bytes, kPartnerOffset, bad);
    CHECK_THROWS_AS(load(bytes), std::runtime_error);
  }
  std::vector<std::uint8_t> unknown_kind = good;
  unknown_kind[kKindOffset] = static_cast<std::uint8_t>(EventKind::leave_pair) + 1;
  CHECK_THROWS_AS(load(unknown_kind), std::runtime_error);
  std::vector<std::uint8_t> truncated(good.begin(), good.end() - 1);
  CHECK_THROWS_AS(load(truncated), std::runtime_error);
}
