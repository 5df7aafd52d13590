// What a run records at each record time (records.hpp's FrameRecord): every
// ball's state read from its own clock, the energy and a hash of the exact
// state, made whole or in slices; and the check of a frame for overlaps.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include "collide2d/geometry/nearby_pairs.hpp"
#include "collide2d/geometry/segment_distance.hpp"
#include "collide2d/numeric/fixed_words.hpp"
#include "collide2d/sim/records.hpp"
#include "collide2d/sim/world.hpp"

namespace collide2d {

// FNV-1a: hash h takes n more bytes.
inline void hash_bytes(std::uint64_t& h, const unsigned char* bytes, std::size_t n) {
  for (std::size_t k = 0; k < n; ++k) h = (h ^ bytes[k]) * 0x100000001b3ULL;
}

// FNV-1a over the bytes of each number's exact representation.
inline void hash_number(std::uint64_t& h, double x) {
  unsigned char bytes[sizeof x];
  std::memcpy(bytes, &x, sizeof x);
  hash_bytes(h, bytes, sizeof x);
}
inline void hash_number(std::uint64_t& h, const Fixed& x) {
  const Fixed::Raw raw = x.raw();
  unsigned char bytes[sizeof raw];
  std::memcpy(bytes, &raw, sizeof raw);
  hash_bytes(h, bytes, sizeof raw);
}

// Any other type (the high-precision reference of the studies): by its
// double, which is all a reference run's frames are compared by.
template <class Num>
void hash_number(std::uint64_t& h, const Num& x) {
  hash_number(h, NumberTraits<Num>::to_double(x));
}

// The exact words of a coordinate: only Fixed has more than its double shows.
inline void append_words(std::vector<std::int64_t>& out, const Fixed& x) {
  const FixedWords w = to_words(x);
  out.insert(out.end(), {w.hi, w.lo});
}

// Ball b's state at t as the frames and the tunnelling watch read it: its
// body where it is on its clock or static (a fixed or sleeping ball does not
// move), carried along its motion otherwise.
template <class B, class Num>
BallState<Num> state_as_read(const B& b, const Num& t) {
  if (b.time == t || b.is_static()) return {b.position, b.velocity, b.acceleration, b.radius};
  return state_at(b, t);
}

// Balls [first, last) of the frame at `time`, appended to `into`'s
// positions, velocities and (fixed point) raw words, each ball's state
// read from its own clock (a gas is not carried to its record times; under
// accelerations every ball is there already). The state hash and the energy
// (mechanical_energy, world.hpp, over the balls that are not fixed) take the
// balls in index order.
template <class W, class Num>
void append_frame_balls(const W& w, const Num& time, std::size_t first, std::size_t last, FrameRecord& into,
                        std::uint64_t& hash, Num& energy) {
  using T = NumberTraits<Num>;
  for (std::size_t i = first; i < last; ++i) {
    const auto& b = w.balls[i];
    const BallState<Num> s = state_as_read(b, time);
    into.position.insert(into.position.end(), {T::to_double(s.position.x), T::to_double(s.position.y)});
    into.velocity.insert(into.velocity.end(), {T::to_double(s.velocity.x), T::to_double(s.velocity.y)});
    for (const Num* x : {&s.position.x, &s.position.y, &s.velocity.x, &s.velocity.y}) hash_number(hash, *x);
    if constexpr (std::is_same_v<Num, Fixed>) {
      for (const Num* x : {&s.position.x, &s.position.y}) append_words(into.position_raw, *x);
      for (const Num* x : {&s.velocity.x, &s.velocity.y}) append_words(into.velocity_raw, *x);
    }
    if (!b.fixed) energy = energy + mechanical_energy(b, s.position, s.velocity);
  }
}

inline constexpr std::uint64_t kFrameHashStart = 0xcbf29ce484222325ULL;  // FNV-1a's offset basis

// The frame at `time`, whole.
template <class W, class Num>
  requires requires(const W& w) { w.balls; }  // a World or a GasWorld
FrameRecord make_frame(const W& w, std::int64_t step, const Num& time) {
  FrameRecord f;
  f.step = step;
  f.time = NumberTraits<Num>::to_double(time);
  f.state_hash = kFrameHashStart;
  f.position.reserve(2 * w.balls.size());
  f.velocity.reserve(2 * w.balls.size());
  Num energy{};
  append_frame_balls(w, time, 0, w.balls.size(), f, f.state_hash, energy);
  f.energy = NumberTraits<Num>::to_double(energy);
  return f;
}

// The same frame handed on in slices as it is made, for a large scene (a
// million balls' whole frame is 32 MB of the run's peak, held only to be
// written): on_slice(slice) for balls [0, k), [k, 2k), ... in order, k =
// balls_per_slice ≥ 1 (the last slice may hold fewer). The record returned
// holds the step, time, energy and state hash, the same bits as
// make_frame's, and no positions or velocities.
template <class W, class Num, class OnSlice>
  requires requires(const W& w) { w.balls; }
FrameRecord make_frame_in_slices(const W& w, std::int64_t step, const Num& time, std::size_t balls_per_slice,
                                 OnSlice on_slice) {
  FrameRecord f, part;
  f.step = step;
  f.time = NumberTraits<Num>::to_double(time);
  f.state_hash = kFrameHashStart;
  Num energy{};
  const std::size_t n = w.balls.size(), k = std::max<std::size_t>(balls_per_slice, 1);
  for (std::size_t first = 0; first < n; first += k) {
    for (auto* v : {&part.position, &part.velocity}) v->clear();
    for (auto* v : {&part.position_raw, &part.velocity_raw}) v->clear();
    append_frame_balls(w, time, first, std::min(n, first + k), part, f.state_hash, energy);
    on_slice(FrameSlice{f.time, first, part.position, part.velocity, part.position_raw, part.velocity_raw});
  }
  f.energy = NumberTraits<Num>::to_double(energy);
  return f;
}

// Largest penetration of any ball into another ball or a wall, in doubles.
// Pairs are found through a grid (geometry/nearby_pairs.hpp): O(N log N) a
// frame, so that checking a frame of a million balls costs about a second.
// centre(i), radius(i): ball i's centre (a Vec2<double>) and radius, for
// the n balls of the frame; r_max the largest radius (a run's radii never
// change: it is found once). A run's check computes each centre from its
// ball (a million balls' bodies are 64 MB, read at the memory's speed), so
// the balls are read in as few passes as the grid allows: the walls and the
// grid's extent in one, the grid's two (counting and placing each ball),
// and the pairs, where each ball's own centre is read once for them all.
template <class Centre, class Radius>
double deepest_overlap_of(Centre centre, Radius radius, std::size_t n, double r_max,
                          const std::vector<std::array<double, 4>>& walls) {
  double deepest = 0;
  // A ball whose centre lies farther than r_max from a wall's bounding box
  // along either axis is farther than its radius from the wall: it cannot
  // deepen the overlap (which starts at 0), and most balls of a large
  // scene are such for every wall. The reach is widened far beyond the
  // rounding of the test.
  const double wall_reach = r_max * (1 + 0x1p-40) + 0x1p-1000;
  struct WallBox {
    Segment<double> segment;
    double lo_x, hi_x, lo_y, hi_y;
  };
  std::vector<WallBox> boxes;
  for (const auto& w : walls)
    boxes.push_back({{{w[0], w[1]}, {w[2], w[3]}}, std::min(w[0], w[2]) - wall_reach, std::max(w[0], w[2]) + wall_reach,
                     std::min(w[1], w[3]) - wall_reach, std::max(w[1], w[3]) + wall_reach});
  NearbyExtent extent;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2<double> c = centre(i);
    extent.include(c);
    for (const WallBox& b : boxes) {
      if (c.x < b.lo_x || b.hi_x < c.x || c.y < b.lo_y || b.hi_y < c.y) continue;
      deepest = std::max(deepest, radius(i) - distance_to_segment(c, b.segment));
    }
  }
  // A pair farther apart than the sum of its radii (by more than rounding:
  // squares compared with a margin of 2^-40) cannot deepen the overlap:
  // its square root, the cost of the check, is taken only for the rest.
  std::size_t last_i = n;
  Vec2<double> centre_i{};
  double radius_i = 0;
  for_each_nearby_pair_within(extent, n, r_max, centre, [&](std::size_t i, std::size_t j) {
    if (i != last_i) last_i = i, centre_i = centre(i), radius_i = radius(i);
    const double reach = radius_i + radius(j);
    const double d2 = length_squared(centre_i - centre(j));
    if (d2 > reach * reach * (1 + 0x1p-40)) return;
    deepest = std::max(deepest, reach - std::sqrt(d2));
  });
  return deepest;
}

// The same for a whole frame's positions.
template <class Radius>
double deepest_overlap_of(const FrameRecord& f, Radius radius, std::size_t n, double r_max,
                          const std::vector<std::array<double, 4>>& walls) {
  auto centre = [&](std::size_t i) { return Vec2<double>{f.position[2 * i], f.position[2 * i + 1]}; };
  return deepest_overlap_of(centre, radius, n, r_max, walls);
}
double deepest_overlap(const FrameRecord& f, const std::vector<double>& radius, const std::vector<std::array<double, 4>>& walls);


}  // namespace collide2d
