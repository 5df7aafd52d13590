// The pairs of balls close enough to overlap, found through a grid.
//
// Two balls overlap only if their centres are less than r_i + r_j ≤ 2 r_max
// apart, so with square cells 2 r_max wide (a hair more, for rounding) a
// ball can only overlap balls in its own cell and the eight around it. The
// checks of a scene (overlap at t = 0) and of a run (the deepest overlap at
// each frame) visit those pairs alone: O(N log N) for N balls, not N²/2.
// Plain doubles: these are checks on the results, never part of a run.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "collide2d/geometry/vec2.hpp"

namespace collide2d {

// Calls visit(i, k) once for every pair i < k of the n balls whose cells
// touch (a superset of the pairs that can overlap). centre(i) gives ball i's
// centre as a Vec2<double>; r_max is the largest radius.
template <class Centre, class Visit>
void for_each_nearby_pair(std::size_t n, double r_max, Centre centre, Visit visit) {
  // Balls with a non-finite centre (a run gone wrong) have no cell: they are
  // not visited, and cannot spoil the sort.
  std::vector<std::size_t> finite;
  for (std::size_t i = 0; i < n; ++i)
    if (std::isfinite(centre(i).x) && std::isfinite(centre(i).y)) finite.push_back(i);
  if (finite.size() < 2) return;
  double lo_x = centre(finite[0]).x, lo_y = centre(finite[0]).y;
  for (std::size_t i : finite) lo_x = std::min(lo_x, centre(i).x), lo_y = std::min(lo_y, centre(i).y);
  // Cell indices are kept as whole doubles: no integer conversion can
  // overflow, however far apart a scene's balls are.
  const double cell = r_max > 0 ? 2 * r_max * (1 + 1e-9) : 1.0;
  using Cell = std::pair<double, double>;
  std::vector<std::pair<Cell, std::size_t>> sorted;
  std::vector<Cell> cell_of(n);
  for (std::size_t i : finite) {
    const Vec2<double> c = centre(i);
    cell_of[i] = {std::floor((c.x - lo_x) / cell), std::floor((c.y - lo_y) / cell)};
    sorted.push_back({cell_of[i], i});
  }
  // In (column, row) order the three cells of a neighbouring column, rows
  // cy − 1 to cy + 1, are one run of the sorted array.
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i : finite) {
    const auto [cx, cy] = cell_of[i];
    for (double dx = -1; dx <= 1; ++dx) {
      const Cell last{cx + dx, cy + 1};
      auto it = std::lower_bound(sorted.begin(), sorted.end(), std::pair{Cell{cx + dx, cy - 1}, std::size_t{0}});
      for (; it != sorted.end() && !(last < it->first); ++it)
        if (it->second > i) visit(i, it->second);
    }
  }
}

}  // namespace collide2d
