// The pairs of balls close enough to overlap, found through a grid.
//
// Two balls overlap only if their centres are less than r_i + r_j ≤ 2 r_max
// apart, so with square cells 2 r_max wide (a hair more, for rounding) a
// ball can only overlap balls in its own cell and the eight around it. The
// checks of a scene (overlap at t = 0) and of a run (the deepest overlap at
// each frame) visit those pairs alone: O(N log N) for N balls, not N²/2.
// Plain doubles: these are checks on the results, never part of a run.
//
// The hair more, derived. Coordinates are halved first, so that c/2 − lo/2
// cannot overflow however far apart the balls are (halving is exact but for
// subnormals, off by at most 2^-1075 each). Ball i's cell along an axis is
// floor(q_i), q_i = fl(fl(c_i/2 − lo/2) / w) with w the halved cell width.
// With u = 2^-53 and E the largest c/2 − lo/2,
//     |q_i − q_k| w ≤ |c_i − c_k| / 2 + 4·2^-1075 + 4.0001 u E.
// Two balls that overlap have |c_i − c_k| < 2 r_max (1 + 3u) along each axis,
// so for w = r_max (1 + 1e-9) + 2^-48 E + 2^-1060 the difference is below 1
// and their cells are neighbours. Without the E term (the cell was 2 r_max
// (1 + 1e-9) alone) balls far from the lowest one, whose offsets carry
// rounding errors larger than a cell, could land two or more cells apart
// while overlapping: check accepted such a scene (balls of radius 6.7e-7 at
// x = 1.14e8, 6.4e-7 apart, and one at x = -2.6e11; fuzz/README.md). The E
// term is 2^-48 ≈ 3.6e-15 of the extent: no more pairs for any usual scene.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include "collide2d/geometry/vec2.hpp"

namespace collide2d {

// What the grid needs of the balls before it is laid out: how many have a
// finite centre (a run gone wrong may have others: they have no cell, are
// not visited and cannot spoil the sort) and the box of those centres,
// halved (c/2, below). Taken in one pass of include(); a caller that reads
// every centre anyway (a run's frame check) takes it on the way.
struct NearbyExtent {
  std::size_t finite_count = 0;
  double lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
  void include(const Vec2<double>& c) {
    if (!std::isfinite(c.x) || !std::isfinite(c.y)) return;
    ++finite_count;
    const double x = c.x * 0.5, y = c.y * 0.5;
    lo_x = std::min(lo_x, x), lo_y = std::min(lo_y, y), hi_x = std::max(hi_x, x), hi_y = std::max(hi_y, y);
  }
};

// Calls visit(i, k) once for every pair i < k of the n balls whose cells
// touch (a superset of the pairs that can overlap), in no particular order.
// centre(i) gives ball i's centre as a Vec2<double>; r_max is the largest
// radius; `e` is the balls' NearbyExtent.
// Ball and cell numbers are held in 32 bits (a run checks every frame with
// this, and its grid then takes about 16 bytes a ball instead of 40): at most
// 2^30 balls, so that the dense grid's 4 n + 64 cells fit too; a scene that
// large would not fit in memory anyway.
template <class Centre, class Visit>
void for_each_nearby_pair_within(const NearbyExtent& e, std::size_t n, double r_max, Centre centre, Visit visit) {
  if (n >= (std::size_t{1} << 30)) throw std::length_error("for_each_nearby_pair: more than 2^30 balls");
  // centre(i) is read once for each use (it may be computed: a run's check
  // reads each centre from its ball's motion).
  const std::size_t finite_count = e.finite_count;
  auto is_finite = [&](std::size_t i) {
    const Vec2<double> c = centre(i);
    return std::isfinite(c.x) && std::isfinite(c.y);
  };
  // The finite balls' indices are listed only when there are others: a
  // frame of a million balls is checked without 4 MB of indices 0, 1, 2, ...
  std::vector<std::uint32_t> finite;
  if (finite_count < n)
    for (std::size_t i = 0; i < n; ++i)
      if (is_finite(i)) finite.push_back(static_cast<std::uint32_t>(i));
  auto for_each_finite = [&](auto visit_ball) {
    if (finite_count == n)
      for (std::size_t i = 0; i < n; ++i) visit_ball(static_cast<std::uint32_t>(i));
    else
      for (std::uint32_t i : finite) visit_ball(i);
  };
  if (finite_count < 2) return;
  auto half = [&](std::size_t i) {
    const Vec2<double> c = centre(i);
    return Vec2<double>{c.x * 0.5, c.y * 0.5};
  };
  const double lo_x = e.lo_x, lo_y = e.lo_y, hi_x = e.hi_x, hi_y = e.hi_y;
  const double extent = std::max(hi_x - lo_x, hi_y - lo_y);
  const double cell = (r_max > 0 ? r_max * (1 + 1e-9) : 0.5) + 0x1p-48 * extent + 0x1p-1060;
  // Cell indices are whole doubles below 2^48: exact, and no integer
  // conversion can overflow.
  // A scene no wider than a few cells per ball (every run's frame, every
  // usual scene) gets a dense grid: balls counted into their cells, O(N).
  const double columns = std::floor((hi_x - lo_x) / cell) + 1, rows = std::floor((hi_y - lo_y) / cell) + 1;
  if (columns * rows <= 4.0 * static_cast<double>(finite_count) + 64) {
    const auto nx = static_cast<std::size_t>(columns), ny = static_cast<std::size_t>(rows);
    // A ball's cell is found twice, to count and to place it (the same
    // arithmetic, the same cell), rather than kept: 4 bytes a ball less.
    // A ball outside the extent it was given (a caller's NearbyExtent that
    // is not its centres') would be counted out of the grid: refused.
    auto cell_index = [&](std::uint32_t i) {
      const Vec2<double> c = half(i);
      const double fx = std::floor((c.x - lo_x) / cell), fy = std::floor((c.y - lo_y) / cell);
      if (!(fx >= 0 && fx < columns && fy >= 0 && fy < rows))
        throw std::logic_error("for_each_nearby_pair: a centre lies outside the extent given");
      return static_cast<std::size_t>(fy) * nx + static_cast<std::size_t>(fx);
    };
    std::vector<std::uint32_t> start(nx * ny + 1, 0), member(finite_count);
    for_each_finite([&](std::uint32_t i) { ++start[cell_index(i) + 1]; });
    for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
    // Counting sort in place: start[c] runs up to cell c's end as its
    // members go in, and is then moved back to its beginning (no second
    // array of cell starts: a frame of a million balls is checked with
    // 7 MB less).
    for_each_finite([&](std::uint32_t i) { member[start[cell_index(i)]++] = i; });
    for (std::size_t c = start.size() - 1; c > 0; --c) start[c] = start[c - 1];
    start[0] = 0;
    // Cell by cell, row by row: the cells around one are read from the
    // three rows the last one read too.
    for (std::size_t cy = 0; cy < ny; ++cy)
      for (std::size_t cx = 0; cx < nx; ++cx)
        for (std::size_t m = start[cy * nx + cx]; m < start[cy * nx + cx + 1]; ++m) {
          const std::uint32_t i = member[m];
          for (std::size_t y = cy > 0 ? cy - 1 : 0; y <= cy + 1 && y < ny; ++y)
            for (std::size_t x = cx > 0 ? cx - 1 : 0; x <= cx + 1 && x < nx; ++x)
              for (std::size_t e = start[y * nx + x]; e < start[y * nx + x + 1]; ++e)
                if (member[e] > i) visit(i, member[e]);
        }
    return;
  }
  using Cell = std::pair<double, double>;
  std::vector<std::pair<Cell, std::size_t>> sorted;
  std::vector<Cell> cell_of(n);
  for_each_finite([&](std::uint32_t i) {
    const Vec2<double> c = half(i);
    cell_of[i] = {std::floor((c.x - lo_x) / cell), std::floor((c.y - lo_y) / cell)};
    sorted.push_back({cell_of[i], i});
  });
  // In (column, row) order the three cells of a neighbouring column, rows
  // cy − 1 to cy + 1, are one run of the sorted array.
  std::sort(sorted.begin(), sorted.end());
  for_each_finite([&](std::size_t i) {
    const auto [cx, cy] = cell_of[i];
    for (double dx = -1; dx <= 1; ++dx) {
      const Cell last{cx + dx, cy + 1};
      auto it = std::lower_bound(sorted.begin(), sorted.end(), std::pair{Cell{cx + dx, cy - 1}, std::size_t{0}});
      for (; it != sorted.end() && !(last < it->first); ++it)
        if (it->second > i) visit(i, it->second);
    }
  });
}

// The same, taking the extent in a pass of its own.
template <class Centre, class Visit>
void for_each_nearby_pair(std::size_t n, double r_max, Centre centre, Visit visit) {
  NearbyExtent e;
  for (std::size_t i = 0; i < n; ++i) e.include(centre(i));
  for_each_nearby_pair_within(e, n, r_max, centre, visit);
}

}  // namespace collide2d
