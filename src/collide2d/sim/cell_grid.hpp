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
// Walls likewise: a ball touches a wall only with its centre within r_max of
// it, and its centre stays in its cell until its next crossing, so each cell
// keeps the walls that come within 2 r_max + band of it (a generous margin,
// in doubles) and a ball is predicted against those alone; at a crossing,
// against the walls its new cell has and its old one had not. A scene
// without walls near most balls (a large gas in a box) does no work for them.
//
// The grid only decides *which* pairs are predicted, never what a prediction
// gives (see EventEngine::predict_pair): runs are bit-identical with or
// without it (tested).
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "collide2d/sim/prefetch.hpp"
#include "collide2d/sim/state_bytes.hpp"
#include "collide2d/sim/world.hpp"
#include "collide2d/toi/quadratic.hpp"

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
  // within it is a neighbour) and at least sqrt(area / 4N) (at most about
  // four cells per ball, so a sparse scene does not pay for empty cells).
  // Why so small: a collision predicts both balls against the 9 cells
  // around them (cost ∝ side²), while crossings come at a rate ∝ 1/side; in
  // a dense gas (η = 0.45) the smallest side predicts about half as many
  // pairs as cells of one ball's share of the area (sqrt(area / N)), and in a
  // dilute one (η = 0.1) the two are about even. Lines are placed in
  // doubles, then converted: the same scene gives the same grid in every
  // mode and build.
  // `one_cell`: a single cell, every pair predicted (to test the grid).
  // (A World, or a gas's GasWorld: balls with positions and radii, walls.)
  template <class W>
  explicit CellGrid(const W& world, bool one_cell = false, double band = 0) {
    using T = NumberTraits<Num>;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, r_max = 0;
    auto include = [&](double x, double y) {
      lo[0] = std::min(lo[0], x), hi[0] = std::max(hi[0], x);
      lo[1] = std::min(lo[1], y), hi[1] = std::max(hi[1], y);
    };
    for (const auto& b : world.balls) {
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
                                 std::sqrt(extent[0] * extent[1] / (4 * n)));
    std::vector<Num>* lines[2] = {&x_lines_, &y_lines_};
    for (int axis = 0; axis < 2; ++axis) {
      // floor(extent / side) cells of width extent / count ≥ side; at most 2N + 1,
      // and at most max_cells_per_axis (wider cells are as right, only slower).
      // One cell when that is not a number of at least 1: a world with
      // nothing in it (extent −inf), or one whose extent overflows a double
      // (balls at ±1e308: inf / inf). One cell predicts every pair, which is
      // always right; converting NaN to int is not (fuzz_scene found it).
      const double ratio = extent[axis] / side;
      const double count = one_cell || !(side > 0) || !(ratio >= 1)
                               ? 1.0
                               : std::min({std::floor(ratio), 2 * n + 1, static_cast<double>(max_cells_per_axis)});
      const int cells = static_cast<int>(count);
      for (int k = 1; k < cells; ++k) lines[axis]->push_back(num<Num>(lo[axis] + extent[axis] * k / cells));
    }
    columns_ = static_cast<int>(x_lines_.size()) + 1;
    rows_ = static_cast<int>(y_lines_.size()) + 1;
    cells_.assign(static_cast<std::size_t>(columns_) * rows_, Cell{});
    cell_of_.assign(world.balls.size(), {});
    list_walls_near_cells(world, 2 * r_max + band + 1e-9 * std::max(extent[0], extent[1]));
  }

  int columns() const { return columns_; }
  int rows() const { return rows_; }

  // Puts every ball in the cell its centre is in at time t, read from its
  // own clock (when the prediction starts afresh).
  template <class W>
  void assign(const W& world, const Num& t) {
    std::fill(cells_.begin(), cells_.end(), Cell{});
    overflow_.clear();
    for (int i = 0; i < static_cast<int>(world.balls.size()); ++i) {
      const auto& b = world.balls[i];
      const Vec2<Num> p = b.time == t ? b.position : state_at(b, t).position;
      const int cx = static_cast<int>(std::upper_bound(x_lines_.begin(), x_lines_.end(), p.x) - x_lines_.begin());
      const int cy = static_cast<int>(std::upper_bound(y_lines_.begin(), y_lines_.end(), p.y) - y_lines_.begin());
      cell_of_[i] = {cx, cy};
      insert(cy * columns_ + cx, i);
    }
  }

  // Checkpoints: each ball's cell (the grid at a record time is the one the
  // crossings made, which the positions alone need not give at a line), then
  // every cell's members in their order, cell by cell. The order is kept
  // because predictions visit a cell's members in it: it decides which
  // predictions are pushed and so the queue's push count, which a resumed
  // run must continue exactly (a grid refilled in ball order gave the same
  // trajectory but other push numbers, and other checkpoint bytes).
  void save(ByteWriter& out) const {
    for (const CellXY& c : cell_of_) out.put(static_cast<std::int32_t>(c.x)), out.put(static_cast<std::int32_t>(c.y));
    auto put_member = [&](int i) { out.put(static_cast<std::int32_t>(i)); };
    for (int c = 0; c < static_cast<int>(cells_.size()); ++c) visit_members(c, put_member);
  }
  void load(ByteReader& in) {
    std::fill(cells_.begin(), cells_.end(), Cell{});
    overflow_.clear();
    const int n = static_cast<int>(cell_of_.size());
    for (int i = 0; i < n; ++i) {
      std::int32_t x = 0, y = 0;
      in.get(x);
      in.get(y);
      if (x < 0 || y < 0 || x >= columns_ || y >= rows_) throw std::runtime_error("checkpoint holds a ball outside the grid");
      cell_of_[i] = {x, y};
    }
    // Each ball once, in increasing cell order: then inserting them in turn
    // rebuilds every cell with its members in the saved order.
    std::vector<bool> seen(static_cast<std::size_t>(n), false);
    int previous_cell = 0;
    for (int k = 0; k < n; ++k) {
      std::int32_t i = 0;
      in.get(i);
      if (i < 0 || i >= n || seen[static_cast<std::size_t>(i)])
        throw std::runtime_error("checkpoint holds a cell listing that is not each ball once");
      seen[static_cast<std::size_t>(i)] = true;
      const int c = cell_of_[i].y * columns_ + cell_of_[i].x;
      if (c < previous_cell) throw std::runtime_error("checkpoint holds a cell listing out of cell order");
      previous_cell = c;
      insert(c, i);
    }
  }

  // Whether a crossing of ball i along `step` (0 to 3) stays on the grid,
  // as every crossing the grid predicts does (a loaded checkpoint's are
  // checked: one off the grid would move the ball into no cell).
  bool step_stays_inside(int i, int step) const {
    const auto [cx, cy] = cell_of_[static_cast<std::size_t>(i)];
    switch (static_cast<CellStep>(step)) {
      case CellStep::right: return cx + 1 < columns_;
      case CellStep::left: return cx > 0;
      case CellStep::up: return cy + 1 < rows_;
      case CellStep::down: return cy > 0;
    }
    return false;
  }

  // Asks the memory for which cell ball i is in (prefetch.hpp).
  [[gnu::always_inline]] void prefetch_cell_of(int i) const { prefetch_element(cell_of_, i); }

  // Asks the memory for the cells around ball i's (three short rows).
  [[gnu::always_inline]] void prefetch_neighbourhood(int i) const {
    const auto [cx, cy] = cell_of_[static_cast<std::size_t>(i)];
    const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, columns_ - 1);
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, rows_ - 1); ++y) {
      __builtin_prefetch(&cells_[static_cast<std::size_t>(y * columns_ + x0)]);
      __builtin_prefetch(&cells_[static_cast<std::size_t>(y * columns_ + x1)]);
    }
  }

  // Calls visit(j) for every ball in the cells around ball i's (its own too).
  template <class Visit>
  void for_each_neighbour(int i, Visit visit) const {
    const auto [cx, cy] = cell_of_[i];
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, rows_ - 1); ++y)
      for (int x = std::max(cx - 1, 0); x <= std::min(cx + 1, columns_ - 1); ++x) visit_members(y * columns_ + x, visit);
  }

  // Moves ball i one cell along `step`, then calls visit(j) for every ball in
  // the cells that have just become its neighbours (the far row or column).
  template <class Visit>
  void cross(int i, CellStep step, Visit visit) {
    auto [cx, cy] = cell_of_[i];
    erase(cy * columns_ + cx, i);
    const int dx = step == CellStep::right ? 1 : step == CellStep::left ? -1 : 0;
    const int dy = step == CellStep::up ? 1 : step == CellStep::down ? -1 : 0;
    cx += dx, cy += dy;
    cell_of_[i] = {cx, cy};
    insert(cy * columns_ + cx, i);
    auto visit_cell = [&](int x, int y) {
      if (x < 0 || x >= columns_ || y < 0 || y >= rows_) return;
      visit_members(y * columns_ + x, visit);
    };
    if (dx != 0)
      for (int y = cy - 1; y <= cy + 1; ++y) visit_cell(cx + dx, y);
    else
      for (int x = cx - 1; x <= cx + 1; ++x) visit_cell(x, cy + dy);
  }

  // The walls that come near ball i's cell (and so the only ones it can
  // touch before it leaves the cell), in increasing order.
  std::span<const int> walls_near(int i) const {
    const auto c = static_cast<std::size_t>(cell_of_[i].y * columns_ + cell_of_[i].x);
    if (!((has_walls_[c / 64] >> (c % 64)) & 1)) return {};
    const std::size_t r = walled_rank(c);
    return {wall_index_.data() + wall_start_[r], wall_index_.data() + wall_start_[r + 1]};
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
  // state's time `clock`) or goes out less deep than a position can tell
  // (b² / A == 0): it stays. (Otherwise a ball resting on a line, its
  // velocity a rounding error out and its acceleration in, would cross and
  // cross back for ever at one instant. Fixed point needs the depth: its
  // clock rounds to the same absolute 2^-64 as its positions, so a ball 2^-64
  // a second out, turning back at 2.2, has t_back = 2^-64 / 1.1, one unit of
  // the clock, and went out 2^-128 / 2.2 deep, nothing.)
  Crossing next_crossing(int i, const BallState<Num>& s, const Num& horizon, const Num& clock = Num{}) const {
    using T = NumberTraits<Num>;
    const auto [cx, cy] = cell_of_[i];
    Crossing first;
    auto consider = [&](const Num& C, const Num& b, const Num& A, CellStep step) {
      const Num zero{};
      RootSearch<Num> r;
      // (|b| < 1 and b² < A first: the quotient then cannot overflow fixed point.)
      auto too_shallow = [&] {
        if (!(-b < num<Num>(1.0))) return false;
        const Num b2 = b * b;
        return b2 < A && b2 / A == zero;
      };
      if (C == zero && b < zero && zero < A && (clock + -(b + b) / A == clock || too_shallow())) return;
      // Inside (C > 0) and not moving out (b ≥ 0), w(t) ≥ C + A t²: the line
      // is no nearer than t = sqrt(C / −A), beyond the horizon H when
      // 2 (−A) H² < C (formed as 2 (−A) H < C / H for H ≥ 1, so that fixed
      // point cannot overflow). Fixed point needs this said: for a ball
      // resting with a residual 2^-64 towards a line 0.18 away, A·C rounds
      // to zero in the discriminant, which reports a root at once, and the
      // ball would be moved cell after cell at one instant, away from its
      // neighbours.
      if (zero < C && !(b < zero)) {
        if (!(A < zero)) return;
        const Num one = num<Num>(1.0), reach = num<Num>(2.0) * -A * horizon;
        if (horizon < one ? reach * horizon < C : reach < C / horizon) return;
      }
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

  // next_crossing for a ball that does not accelerate (a gas): each line's
  // distance C inside the cell falls at the speed u towards it, and is
  // crossed at C / u (at once if already out and moving out). The
  // crossing's time changes the cost of a run, never its bits, and this one
  // rounds no later than the quadratic's root by more than the cells'
  // margin. Within the horizon H when u H ≥ C, formed as u ≥ C / H for
  // H ≥ 1 so that fixed point cannot overflow.
  Crossing next_crossing_linear(int i, const Vec2<Num>& p, const Vec2<Num>& v, const Num& horizon) const {
    const auto [cx, cy] = cell_of_[i];
    const Num zero{}, one = num<Num>(1.0);
    Crossing first;
    auto consider = [&](const Num& C, const Num& u, CellStep step) {
      if (!(zero < u)) return;
      if (!(zero < C)) {
        if (!first.found || zero < first.time) first = {true, zero, step};
        return;
      }
      if (horizon < one ? horizon * u < C : u < C / horizon) return;
      const Num t = C / u;
      if (!first.found || t < first.time) first = {true, t, step};
    };
    if (cx + 1 < columns_) consider(x_lines_[cx] - p.x, v.x, CellStep::right);
    if (cx > 0) consider(p.x - x_lines_[cx - 1], -v.x, CellStep::left);
    if (cy + 1 < rows_) consider(y_lines_[cy] - p.y, v.y, CellStep::up);
    if (cy > 0) consider(p.y - y_lines_[cy - 1], -v.y, CellStep::down);
    return first;
  }

 private:
  std::vector<Num> x_lines_, y_lines_;  // interior lines, increasing
  int columns_ = 1, rows_ = 1;
  // The balls of a cell, in the order they came: the first few in the cell
  // itself (16 bytes: a dense gas's cells hold 0 to 4 discs, and the nine
  // cells a prediction reads are three short runs of memory, not nine
  // vectors elsewhere on the heap), the rest in `overflow_`.
  static constexpr int inline_members = 3;
  static constexpr int max_cells_per_axis = 65535;  // CellXY's 16 bits
  struct Cell {
    std::int32_t count = 0;
    std::int32_t member[inline_members] = {};
  };
  // A ball's cell, 4 bytes (a million balls' are 4 MB): at most
  // max_cells_per_axis columns and rows.
  struct CellXY {
    std::uint16_t x = 0, y = 0;
    CellXY() = default;
    CellXY(int cx, int cy) : x(static_cast<std::uint16_t>(cx)), y(static_cast<std::uint16_t>(cy)) {}
  };
  std::vector<Cell> cells_;                                  // row-major
  std::unordered_map<int, std::vector<int>> overflow_;      // a cell's members past the inline ones
  std::vector<CellXY> cell_of_;                              // each ball's cell

  template <class Visit>
  void visit_members(int c, Visit& visit) const {
    const Cell& cell = cells_[static_cast<std::size_t>(c)];
    const int n = cell.count < inline_members ? cell.count : inline_members;
    for (int k = 0; k < n; ++k) visit(static_cast<int>(cell.member[k]));
    if (cell.count > inline_members)
      for (int j : overflow_.at(c)) visit(j);
  }
  void insert(int c, int i) {
    Cell& cell = cells_[static_cast<std::size_t>(c)];
    if (cell.count < inline_members) cell.member[cell.count] = i;
    else overflow_[c].push_back(i);
    ++cell.count;
  }
  // Removes ball i from cell c, keeping the others' order.
  void erase(int c, int i) {
    Cell& cell = cells_[static_cast<std::size_t>(c)];
    const int n = cell.count < inline_members ? cell.count : inline_members;
    int k = 0;
    while (k < n && cell.member[k] != i) ++k;
    if (k < n) {
      for (; k + 1 < n; ++k) cell.member[k] = cell.member[k + 1];
      if (cell.count > inline_members) {  // the first of the rest moves in
        std::vector<int>& rest = overflow_.at(c);
        cell.member[inline_members - 1] = rest.front();
        rest.erase(rest.begin());
      }
    } else {
      std::vector<int>& rest = overflow_.at(c);
      rest.erase(std::find(rest.begin(), rest.end(), i));
    }
    if (--cell.count <= inline_members) overflow_.erase(c);
  }
  // The walls near each cell, all cells' lists in one array. Whether a cell
  // has any is a bit of `has_walls_`, read first: in a large gas almost no
  // cell has walls, and a bit a cell stays in the cache. Only the cells
  // with walls have starts: the one of rank r among them (walled_rank) has
  // wall_index_[wall_start_[r] .. wall_start_[r + 1]). (Starts for every
  // cell took 4 bytes a cell, 7 bytes a ball of a dense gas; the rank takes
  // 4 bytes a 64 cells and one popcount.)
  std::vector<int> wall_start_, wall_index_;
  std::vector<std::uint64_t> has_walls_;
  std::vector<std::uint32_t> walled_before_;  // per word of has_walls_: the cells with walls before it

  // Cell c's rank among the cells with walls (c has walls).
  std::size_t walled_rank(std::size_t c) const {
    const std::uint64_t below = has_walls_[c / 64] & ((std::uint64_t{1} << (c % 64)) - 1);
    return walled_before_[c / 64] + static_cast<std::size_t>(std::popcount(below));
  }

  // The cells whose rectangles (unbounded at the outer rows and columns),
  // widened by `margin`, meet wall w: the segment a + s (b − a), 0 ≤ s ≤ 1,
  // clipped to the rectangle axis by axis (Liang and Barsky) leaves a piece.
  // Only the cells over the wall's widened bounding box are tried.
  template <class W>
  void list_walls_near_cells(const W& world, double margin) {
    using T = NumberTraits<Num>;
    std::vector<double> lines[2];
    for (const Num& x : x_lines_) lines[0].push_back(T::to_double(x));
    for (const Num& y : y_lines_) lines[1].push_back(T::to_double(y));
    const int count[2] = {columns_, rows_};
    std::vector<std::pair<int, int>> near;  // (cell, wall), walls in increasing order
    for (int w = 0; w < static_cast<int>(world.walls.size()); ++w) {
      const Segment<Num>& seg = world.walls[static_cast<std::size_t>(w)].segment;
      const double a[2] = {T::to_double(seg.a.x), T::to_double(seg.a.y)};
      const double b[2] = {T::to_double(seg.b.x), T::to_double(seg.b.y)};
      const double d[2] = {b[0] - a[0], b[1] - a[1]};
      int first[2], last[2];  // the cells over the widened bounding box, per axis
      for (int axis = 0; axis < 2; ++axis) {
        const std::vector<double>& l = lines[axis];
        const double box_lo = std::min(a[axis], b[axis]) - margin, box_hi = std::max(a[axis], b[axis]) + margin;
        first[axis] = static_cast<int>(std::upper_bound(l.begin(), l.end(), box_lo) - l.begin());
        last[axis] = std::min(static_cast<int>(std::upper_bound(l.begin(), l.end(), box_hi) - l.begin()), count[axis] - 1);
      }
      for (int cy = first[1]; cy <= last[1]; ++cy)
        for (int cx = first[0]; cx <= last[0]; ++cx) {
          const int c[2] = {cx, cy};
          double s_lo = 0, s_hi = 1;
          for (int axis = 0; axis < 2; ++axis) {
            const std::vector<double>& l = lines[axis];
            const double lo = c[axis] > 0 ? l[static_cast<std::size_t>(c[axis] - 1)] - margin : -INFINITY;
            const double hi = c[axis] + 1 < count[axis] ? l[static_cast<std::size_t>(c[axis])] + margin : INFINITY;
            if (d[axis] == 0) {
              if (a[axis] < lo || hi < a[axis]) s_lo = 2;
              continue;
            }
            const double s1 = (lo - a[axis]) / d[axis], s2 = (hi - a[axis]) / d[axis];
            s_lo = std::max(s_lo, std::min(s1, s2));
            s_hi = std::min(s_hi, std::max(s1, s2));
          }
          if (s_lo <= s_hi) near.emplace_back(cy * columns_ + cx, w);
        }
    }
    // The cells with walls, and their ranks.
    has_walls_.assign((static_cast<std::size_t>(columns_) * rows_ + 63) / 64, 0);
    for (const auto& [cell, w] : near) has_walls_[static_cast<std::size_t>(cell) / 64] |= std::uint64_t{1} << (cell % 64);
    walled_before_.assign(has_walls_.size(), 0);
    std::uint32_t walled = 0;
    for (std::size_t k = 0; k < has_walls_.size(); ++k) {
      walled_before_[k] = walled;
      walled += static_cast<std::uint32_t>(std::popcount(has_walls_[k]));
    }
    // Counting sort by cell rank (stable: each cell's walls stay in increasing order).
    wall_start_.assign(static_cast<std::size_t>(walled) + 1, 0);
    for (const auto& [cell, w] : near) ++wall_start_[walled_rank(static_cast<std::size_t>(cell)) + 1];
    for (std::size_t r = 1; r < wall_start_.size(); ++r) wall_start_[r] += wall_start_[r - 1];
    wall_index_.assign(near.size(), 0);
    std::vector<int> fill(wall_start_.begin(), wall_start_.end() - 1);
    for (const auto& [cell, w] : near)
      wall_index_[static_cast<std::size_t>(fill[walled_rank(static_cast<std::size_t>(cell))]++)] = w;
  }
};

}  // namespace collide2d
