// A uniform grid of cells, so that a ball is predicted only against its
// neighbours: an event costs O(1) instead of O(N).
//
// Why it is exact: every cell is at least as wide and as tall as the largest
// diameter (plus a margin far above rounding). Two balls whose cells are not
// neighbours (sharing neither an edge nor a corner) have a whole cell between
// their centres, so they are more than r_i + r_j apart and cannot touch. Each
// ball belongs to one cell and changes cell at a crossing event, the exact time
// its parabola crosses a cell line; at that moment it is predicted against the
// balls of the cells that have just become its neighbours. The outer rows and
// columns reach to infinity, so a ball that leaves the scene's box still has a
// cell.
//
// The grid only decides *which* pairs are predicted, never what a prediction
// gives (see EventEngine::predict_pair): runs are bit-identical with or
// without it (tested).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "sim/world.hpp"
#include "toi/quadratic.hpp"

namespace collide2d {

// Which way a crossing takes a ball: +x, −x, +y, −y.
enum class CellStep : int { right = 0, left = 1, up = 2, down = 3 };

template <class Num>
class CellGrid {
 public:
  CellGrid() = default;

  // Cells span the box of the walls' ends and the balls' starting centres,
  // `columns` × `rows` of them, each at least 2 r_max + 1e-9·extent + `band`
  // across (`band`: the rest rules' contact band, so that every support
  // within it is a neighbour) and
  // about one ball's share of the area (sqrt(area / N)), so a cell holds about
  // one ball. Lines are placed in doubles, then converted: the same scene
  // gives the same grid in every mode and build.
  // `one_cell`: a single cell, every pair predicted (to test the grid).
  explicit CellGrid(const World<Num>& world, bool one_cell = false, double band = 0) {
    using T = NumberTraits<Num>;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, r_max = 0;
    auto include = [&](double x, double y) {
      lo[0] = std::min(lo[0], x), hi[0] = std::max(hi[0], x);
      lo[1] = std::min(lo[1], y), hi[1] = std::max(hi[1], y);
    };
    for (const Body<Num>& b : world.balls) {
      include(T::to_double(b.position.x), T::to_double(b.position.y));
      r_max = std::max(r_max, T::to_double(b.radius));
    }
    for (const WallGeometry<Num>& w : world.walls) {
      include(T::to_double(w.segment.a.x), T::to_double(w.segment.a.y));
      include(T::to_double(w.segment.b.x), T::to_double(w.segment.b.y));
    }
    const double extent[2] = {hi[0] - lo[0], hi[1] - lo[1]};
    const double n = static_cast<double>(std::max<std::size_t>(world.balls.size(), 1));
    const double side = std::max(2 * r_max + 1e-9 * std::max(extent[0], extent[1]) + band,
                                 std::sqrt(extent[0] * extent[1] / n));
    std::vector<Num>* lines[2] = {&x_lines_, &y_lines_};
    for (int axis = 0; axis < 2; ++axis) {
      // floor(extent / side) cells of width extent / count ≥ side; at most 2N + 1.
      const double count = one_cell ? 1.0 : side > 0 ? std::min(std::floor(extent[axis] / side), 2 * n + 1) : 1.0;
      const int cells = std::max(1, static_cast<int>(count));
      for (int k = 1; k < cells; ++k) lines[axis]->push_back(num<Num>(lo[axis] + extent[axis] * k / cells));
    }
    columns_ = static_cast<int>(x_lines_.size()) + 1;
    rows_ = static_cast<int>(y_lines_.size()) + 1;
    members_.assign(static_cast<std::size_t>(columns_) * rows_, {});
    cell_of_.assign(world.balls.size(), 0);
  }

  int columns() const { return columns_; }
  int rows() const { return rows_; }

  // Puts every ball in the cell its centre is in now (at a record time, when
  // the prediction starts afresh).
  void assign(const World<Num>& world) {
    for (std::vector<int>& m : members_) m.clear();
    for (int i = 0; i < static_cast<int>(world.balls.size()); ++i) {
      const Vec2<Num>& p = world.balls[i].position;
      const int cx = static_cast<int>(std::upper_bound(x_lines_.begin(), x_lines_.end(), p.x) - x_lines_.begin());
      const int cy = static_cast<int>(std::upper_bound(y_lines_.begin(), y_lines_.end(), p.y) - y_lines_.begin());
      cell_of_[i] = cy * columns_ + cx;
      members_[cell_of_[i]].push_back(i);
    }
  }

  // Calls visit(j) for every ball in the cells around ball i's (its own too).
  template <class Visit>
  void for_each_neighbour(int i, Visit visit) const {
    const int cx = cell_of_[i] % columns_, cy = cell_of_[i] / columns_;
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, rows_ - 1); ++y)
      for (int x = std::max(cx - 1, 0); x <= std::min(cx + 1, columns_ - 1); ++x)
        for (int j : members_[y * columns_ + x]) visit(j);
  }

  // Moves ball i one cell along `step`, then calls visit(j) for every ball in
  // the cells that have just become its neighbours (the far row or column).
  template <class Visit>
  void cross(int i, CellStep step, Visit visit) {
    const int old_cell = cell_of_[i];
    std::vector<int>& from = members_[old_cell];
    from.erase(std::find(from.begin(), from.end(), i));
    int cx = old_cell % columns_, cy = old_cell / columns_;
    const int dx = step == CellStep::right ? 1 : step == CellStep::left ? -1 : 0;
    const int dy = step == CellStep::up ? 1 : step == CellStep::down ? -1 : 0;
    cx += dx, cy += dy;
    cell_of_[i] = cy * columns_ + cx;
    members_[cell_of_[i]].push_back(i);
    auto visit_cell = [&](int x, int y) {
      if (x < 0 || x >= columns_ || y < 0 || y >= rows_) return;
      for (int j : members_[y * columns_ + x]) visit(j);
    };
    if (dx != 0)
      for (int y = cy - 1; y <= cy + 1; ++y) visit_cell(cx + dx, y);
    else
      for (int x = cx - 1; x <= cx + 1; ++x) visit_cell(x, cy + dy);
  }

  struct Crossing {
    bool found = false;
    Num time{};  // from the state's time
    CellStep step = CellStep::right;
  };

  // When ball i, in state s, first leaves its cell within `horizon`. Each cell
  // line gives w(t) = A t² + 2 b t + C, the signed distance inside the cell;
  // the crossing is its first downward root. A centre a rounding error outside
  // its cell and still moving out crosses at once, unless it is on the line
  // and turns back in before the clock can tell (clock + t_back == clock, the
  // state's time `clock`): it stays. (Otherwise a ball resting on a line,
  // its velocity a rounding error out and its acceleration in, would cross
  // and cross back for ever at one instant.)
  Crossing next_crossing(int i, const BallState<Num>& s, const Num& horizon, const Num& clock = Num{}) const {
    using T = NumberTraits<Num>;
    const int cx = cell_of_[i] % columns_, cy = cell_of_[i] / columns_;
    Crossing first;
    auto consider = [&](const Num& C, const Num& b, const Num& A, CellStep step) {
      const Num zero{};
      RootSearch<Num> r;
      if (C == zero && b < zero && zero < A && clock + -(b + b) / A == clock) return;
      if (!(zero < C) && (b < zero || (b == zero && A < zero)))
        r = {true, zero};
      else
        r = first_downward_root(A, b, C, [&] { return compensated_discriminant(A, b, C); }, horizon);
      if (r.found && (!first.found || r.t < first.time)) first = {true, r.t, step};
    };
    const Num vx = T::half(s.velocity.x), vy = T::half(s.velocity.y);
    const Num ax = T::half(s.acceleration.x), ay = T::half(s.acceleration.y);
    if (cx + 1 < columns_) consider(x_lines_[cx] - s.position.x, -vx, -ax, CellStep::right);
    if (cx > 0) consider(s.position.x - x_lines_[cx - 1], vx, ax, CellStep::left);
    if (cy + 1 < rows_) consider(y_lines_[cy] - s.position.y, -vy, -ay, CellStep::up);
    if (cy > 0) consider(s.position.y - y_lines_[cy - 1], vy, ay, CellStep::down);
    return first;
  }

 private:
  std::vector<Num> x_lines_, y_lines_;  // interior lines, increasing
  int columns_ = 1, rows_ = 1;
  std::vector<std::vector<int>> members_;  // balls per cell, row-major
  std::vector<int> cell_of_;               // each ball's cell
};

}  // namespace collide2d
