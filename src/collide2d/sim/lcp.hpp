// A linear complementarity problem (small, sparse), solved exactly.
//
//     w = A x + b,   x_r ≥ 0,  w_r ≥ 0,  x_r w_r = 0   (complementary rows)
//                    w_r = 0                           (equality rows)
//
// A is symmetric positive (semi)definite here (contact_graph.hpp). Principal
// pivoting: start with every row active (w = 0), solve A_SS x_S = −b_S, and
// flip the rows that break their sign condition (an active row pulling,
// x_r < 0, or an inactive one sinking, w_r < 0, each beyond its inputs'
// rounding, 2^-40 of `size`, and for fixed point never less than a few
// units of its resolution: resolution_floor). All breaching rows flip at once (Júdice and
// Pires' block pivoting: a pile's few dozen contacts settle in a handful of
// solves) while that lowers the number of breaches; when it stops doing so,
// one row at a time, the lowest-numbered (Murty's least-index rule). At
// most 4 k + 16 solves: a redundant pile can cycle on rows that rounding
// alone makes breach; projected Gauss–Seidel finishes from there. Equality
// rows never flip. Every step
// is a fixed sequence of +, −, ×, ÷ in the caller's number type: the same
// bits everywhere.
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "collide2d/numeric/number_traits.hpp"
#include "collide2d/sim/elimination_order.hpp"

namespace collide2d {

// A k × k matrix in one block, row by row (A[r][s]), whose entries are all
// zero between uses: its user zeroes what it wrote, and the storage only
// grows, so that a problem of k rows costs what its nonzero entries cost,
// not k² (a pile's contacts each touch a handful of others).
template <class Num>
struct SquareMatrix {
  std::size_t k = 0;
  std::vector<Num> entries;
  // Rows of n (every entry zero already).
  void reshape(std::size_t n) {
    k = n;
    if (entries.size() < n * n) entries.resize(n * n, Num{});
  }
  Num* operator[](std::size_t r) { return entries.data() + r * k; }
  const Num* operator[](std::size_t r) const { return entries.data() + r * k; }
};

template <class Num>
struct Lcp {
  std::vector<Num> b, size;  // size: the scale of row r's inputs (for the rounding tolerance)
  std::vector<char> equality, active;
  std::vector<Num> x;
  // The row solved last, an equation (a strike), or none.
  std::size_t forced;
  // Pivoting rounds so far (one elimination each): what the solves cost.
  std::size_t rounds = 0;

  explicit Lcp(std::size_t k = 0) { reset(k); }

  // A fresh problem of k rows, all zero (the storage is kept: an island's
  // solves reuse one Lcp).
  void reset(std::size_t k) {
    for (const auto& [r, s] : written_) A[r][s] = Num{};
    written_.clear();
    A.reshape(k);
    b.assign(k, Num{});
    size.assign(k, Num{});
    equality.assign(k, 0);
    active.assign(k, 1);
    x.assign(k, Num{});
    forced = k;
    rounds = 0;
  }

  // A_rs = value (A is symmetric: set both). Unset entries are zero.
  void set(std::size_t r, std::size_t s, const Num& value) {
    A[r][s] = value;
    written_.push_back({r, s});
  }
  const Num& a(std::size_t r, std::size_t s) const { return A[r][s]; }

  // Returns the forced row if it depends on the active rows (the others
  // answer it alone), else the number of rows.
  std::size_t solve() {
    const std::size_t k = b.size();
    // A stays fixed from here on; a pile's contacts each touch a handful of
    // others, so each row's products run over its nonzero entries only (a
    // zero entry adds nothing), in increasing column order.
    nonzero_start.assign(k + 1, 0);
    for (const auto& [r, s] : written_) ++nonzero_start[r + 1];
    for (std::size_t r = 0; r < k; ++r) nonzero_start[r + 1] += nonzero_start[r];
    nonzero_column.resize(written_.size());
    std::vector<std::size_t>& next = next_in_row_;
    next.assign(nonzero_start.begin(), nonzero_start.end() - 1);
    for (const auto& [r, s] : written_) nonzero_column[next[r]++] = s;
    std::size_t kept = 0;
    for (std::size_t r = 0; r < k; ++r) {
      const auto first = nonzero_column.begin() + static_cast<std::ptrdiff_t>(nonzero_start[r]);
      const auto last = nonzero_column.begin() + static_cast<std::ptrdiff_t>(nonzero_start[r + 1]);
      std::sort(first, last);
      nonzero_start[r] = kept;
      std::size_t previous = k;  // no column
      for (auto it = first; it != last; ++it) {
        const std::size_t column = *it;
        if (column != previous && !(A[r][column] == Num{})) nonzero_column[kept++] = column;
        previous = column;
      }
    }
    nonzero_start[k] = kept;
    nonzero_column.resize(kept);
    std::size_t fewest = k + 1, single_steps_after = 0;
    for (std::size_t iteration = 0; iteration < 4 * k + 16; ++iteration) {
      ++rounds;
      if (!solve_active()) return forced;
      std::vector<std::size_t>& breaching = breaching_;
      breaching.clear();
      for (std::size_t r = 0; r < k; ++r) {
        if (equality[r]) continue;
        const Num tolerance = num<Num>(0x1p-40) * size[r] + resolution_floor(r);
        if ((active[r] && x[r] * A[r][r] < -tolerance) || (!active[r] && residual(r) < -tolerance)) breaching.push_back(r);
      }
      if (breaching.empty()) break;
      // Block steps while they help (three chances), then Murty's.
      if (breaching.size() < fewest) fewest = breaching.size(), single_steps_after = iteration + 3;
      if (iteration < single_steps_after)
        for (std::size_t r : breaching) active[r] = !active[r];
      else
        active[breaching.front()] = !active[breaching.front()];
    }
    for (std::size_t r = 0; r < k; ++r)
      if (!equality[r] && x[r] < Num{}) x[r] = Num{};  // a push within rounding of none
    if (violation() > 0) polish();
    return k;
  }

  // How far x is from a solution: the largest breach of a row's condition
  // beyond its tolerance (0 when x solves the problem).
  double violation() const {
    double worst = 0;
    for (std::size_t r = 0; r < b.size(); ++r) {
      Num w{}, tolerance_num{};
      residual_and_tolerance(r, w, tolerance_num);
      const double tolerance = NumberTraits<Num>::to_double(tolerance_num);
      const double wd = NumberTraits<Num>::to_double(w);
      double breach = 0;
      if (equality[r] || x[r] > Num{}) breach = wd < 0 ? -wd : wd;
      else breach = -wd;
      if (breach - tolerance > worst) worst = breach - tolerance;
    }
    return worst;
  }

  // w_r = b_r + Σ_s A_rs x_s (after solve()).
  Num residual(std::size_t r) const {
    Num w = b[r];
    for (std::size_t e = nonzero_start[r]; e < nonzero_start[r + 1]; ++e) w = w + A[r][nonzero_column[e]] * x[nonzero_column[e]];
    return w;
  }

 private:
  // The columns of row r's nonzero entries: nonzero_column[nonzero_start[r] ..
  // nonzero_start[r + 1]).
  std::vector<std::size_t> nonzero_column, nonzero_start;
  SquareMatrix<Num> A;
  std::vector<std::pair<std::size_t, std::size_t>> written_;  // every (r, s) set since the last reset
  std::vector<std::size_t> breaching_;    // solve()'s rows that break their conditions, storage reused
  std::vector<std::size_t> next_in_row_;  // solve(): where each row's next written column goes

  // The residual w_r (as residual(r)) and the row's rounding tolerance:
  // 2^-40 of the scale of its terms (its inputs and each A_rs x_s) plus the
  // resolution floor below. One pass makes each product once.
  void residual_and_tolerance(std::size_t r, Num& w, Num& tolerance) const {
    auto magnitude = [](const Num& v) { return NumberTraits<Num>::abs(v); };
    w = b[r];
    Num scale = size[r] + magnitude(b[r]);
    for (std::size_t e = nonzero_start[r]; e < nonzero_start[r + 1]; ++e) {
      const Num term = A[r][nonzero_column[e]] * x[nonzero_column[e]];
      w = w + term;
      scale = scale + magnitude(term);
    }
    tolerance = num<Num>(0x1p-40) * scale + resolution_floor(r);
  }

  // A number type that rounds to an absolute step (fixed point: 2^-64)
  // cannot resolve a row's residual more finely than a few steps per term,
  // whatever the row's scale: a pile at rest has velocities of zero, so the
  // relative tolerance above is zero too, and the residual's last few units
  // (rounding, 1e-19) would count as a breach that no pivoting or sweep can
  // remove. Four units per term of the row (each product and sum rounds by
  // half a unit; the solution's own rounding comes through A) and four for
  // b. A floating-point type has no such floor (zero: the same bits as
  // before).
  Num resolution_floor(std::size_t r) const {
    if constexpr (NumberTraits<Num>::rounds_absolutely) {
      const std::size_t terms = nonzero_start[r + 1] - nonzero_start[r] + 1;
      return num<Num>(4.0 * static_cast<double>(terms)) * NumberTraits<Num>::resolution();
    } else {
      (void)r;
      return Num{};
    }
  }

  // Redundant contacts can leave the pivoting with a dependent row that
  // sinks (its conditions cannot be met by the rows before it). Projected
  // Gauss–Seidel then finishes the job from there: each row in turn takes
  // the x that zeroes its w, clamped at 0 for a complementary row; sweeps
  // repeat until no row breaches its tolerance, or 64 sweeps have not
  // halved the breach (what is left is the rounding of a dependent row,
  // which more sweeps only shuffle), or 4 k + 256 sweeps have run. It
  // converges for any positive semidefinite A with a positive diagonal, and
  // every step is in a fixed order.
  void polish() {
    const std::size_t k = b.size();
    double last = violation();
    for (std::size_t sweep = 0; sweep < 4 * k + 256; ++sweep) {
      for (std::size_t r = 0; r < k; ++r) {
        if (!(Num{} < A[r][r])) continue;
        Num next = x[r] - residual(r) / A[r][r];
        if (!equality[r] && next < Num{}) next = Num{};
        x[r] = next;
      }
      if ((sweep & 7) != 7) continue;
      const double now = violation();
      if (!(now > 0)) break;
      if ((sweep & 63) != 63) continue;
      if (!(now < 0.5 * last)) break;
      last = now;
    }
    for (std::size_t r = 0; r < k; ++r) {
      Num w{}, tolerance{};
      residual_and_tolerance(r, w, tolerance);
      active[r] = equality[r] || x[r] > Num{} || !(tolerance < w);
    }
  }

  // x on the active rows solves A_SS x_S = −b_S, zero elsewhere, by
  // symmetric Gaussian elimination in minimum-degree order, the forced row
  // last (A is symmetric positive semidefinite, for which this is stable
  // without pivoting). Contacts of a pile are often redundant (more contacts than
  // the balls have degrees of freedom): a row whose pivot has fallen to
  // rounding, 2^-36 of its diagonal, depends on the rows before it; its
  // unknown is set to zero and the others carry it (the forces of a
  // redundant pile are not unique, any admissible choice is as good; this
  // one is fixed by the elimination order). If the forced row is the one that
  // depends on the others, there is no answer in impulses (false).
  bool solve_active() {
    const Num zero{};
    const std::size_t k = b.size();
    Scratch& w = scratch_;
    w.clear_touched();
    // The free rows in an order of little fill-in (elimination_order.hpp).
    w.free_rows.clear();
    for (std::size_t r = 0; r < k; ++r)
      if (active[r] && r != forced) w.free_rows.push_back(r);
    w.place.assign(k, k);  // row → its place in free_rows (k: not free)
    for (std::size_t a = 0; a < w.free_rows.size(); ++a) w.place[w.free_rows[a]] = a;
    const auto for_each_neighbour = [&](std::size_t a, auto visit) {
      const std::size_t r = w.free_rows[a];
      for (std::size_t e = nonzero_start[r]; e < nonzero_start[r + 1]; ++e)
        if (w.place[nonzero_column[e]] < k) visit(w.place[nonzero_column[e]]);
    };
    minimum_degree_order(w.free_rows.size(), for_each_neighbour, w.ordering, w.order);
    std::vector<std::size_t>& S = w.S;
    S.clear();
    for (std::size_t a : w.order) S.push_back(w.free_rows[a]);
    if (forced < k) S.push_back(forced);
    const std::size_t m = S.size();
    w.m = m;
    if (w.M.size() < m * (m + 1)) w.M.resize(m * (m + 1), zero);  // row r at r (m + 1): A_SS, then −b_S (all zero now)
    auto at = [&](std::size_t r, std::size_t s) -> Num& { return w.M[r * (m + 1) + s]; };
    // Only entries that may be nonzero are visited: those of A's own
    // pattern and the fill-in as it appears, listed both ways: below[s],
    // the rows r > s that may hold (r, s) (the rows a pivot changes), and
    // above[r], the columns s > r of row r that may (the pivot row's
    // entries). Every entry ever written is listed; the rest stay zero.
    w.in_s.assign(k, m);  // row of A → its place in S (m: not in S)
    for (std::size_t r = 0; r < m; ++r) w.in_s[S[r]] = r;
    w.below.reset(m);
    w.above.reset(m);
    if (w.listed.size() < m * m) w.listed.resize(m * m, 0);
    auto list = [&](std::size_t r, std::size_t s) {  // (r, s) may be nonzero from now on
      if (s == r || w.listed[r * m + s]) return;
      w.listed[r * m + s] = 1;
      if (s < r) w.below.add(s, r);
      else w.above.add(r, s);
    };
    for (std::size_t r = 0; r < m; ++r) {
      const std::size_t row_of_a = S[r];
      for (std::size_t e = nonzero_start[row_of_a]; e < nonzero_start[row_of_a + 1]; ++e) {
        const std::size_t s = w.in_s[nonzero_column[e]];
        if (s == m) continue;
        at(r, s) = A[row_of_a][nonzero_column[e]];
        list(r, s);
      }
      at(r, m) = -b[row_of_a];
    }
    w.dependent.assign(m, 0);
    // The nonzero columns right of each pivot, in increasing order (the
    // back substitution sums over them in that order):
    // upper[upper_start[col] .. upper_start[col + 1]), the last may be m (−b).
    std::vector<std::size_t>&upper = w.upper, &upper_start = w.upper_start;
    upper.clear();
    upper_start.assign(m + 1, 0);
    const Num small = num<Num>(0x1p-36);
    for (std::size_t col = 0; col < m; ++col) {
      const Num pivot = at(col, col);
      upper_start[col] = upper.size();
      if (!(small * A[S[col]][S[col]] < pivot)) {
        if (S[col] == forced) return false;
        w.dependent[col] = 1;
        continue;
      }
      // Row col is final now. Only its nonzero entries change the rows
      // below (fill-in stays near the contact graph's own pattern).
      w.above.for_each(col, [&](std::size_t s) { upper.push_back(s); });
      std::sort(upper.begin() + static_cast<std::ptrdiff_t>(upper_start[col]), upper.end());
      upper.erase(std::remove_if(upper.begin() + static_cast<std::ptrdiff_t>(upper_start[col]), upper.end(),
                                 [&](std::size_t s) { return at(col, s) == zero; }),
                  upper.end());
      if (!(at(col, m) == zero)) upper.push_back(m);
      w.below.for_each(col, [&](std::size_t r) {
        if (at(r, col) == zero) return;
        const Num f = at(r, col) / pivot;
        if (f == zero) return;
        for (std::size_t e = upper_start[col]; e < upper.size(); ++e) {
          const std::size_t s = upper[e];
          at(r, s) = at(r, s) - f * at(col, s);
          if (s < m) list(r, s);
        }
      });
    }
    upper_start[m] = upper.size();
    std::vector<Num>& xs = w.xs;
    xs.assign(m, zero);
    for (std::size_t col = m; col-- > 0;) {
      if (w.dependent[col]) continue;
      Num sum = at(col, m);
      for (std::size_t e = upper_start[col]; e < upper_start[col + 1]; ++e)
        if (upper[e] < m) sum = sum - at(col, upper[e]) * xs[upper[e]];
      xs[col] = sum / at(col, col);
    }
    x.assign(k, zero);
    for (std::size_t r = 0; r < m; ++r) x[S[r]] = xs[r];
    return true;
  }

  // Lists of indices per row, as linked lists in one pool (order of
  // insertion reversed): what solve_active lists of a row's pattern.
  struct RowLists {
    static constexpr std::size_t none = static_cast<std::size_t>(-1);
    std::vector<std::size_t> first;
    std::vector<std::pair<std::size_t, std::size_t>> pool;  // (index, next)
    void reset(std::size_t rows) {
      first.assign(rows, none);
      pool.clear();
    }
    void add(std::size_t row, std::size_t index) {
      pool.push_back({index, first[row]});
      first[row] = pool.size() - 1;
    }
    template <class Visit>
    void for_each(std::size_t row, Visit visit) const {
      for (std::size_t node = first[row]; node != none; node = pool[node].second) visit(pool[node].first);
    }
  };
  // solve_active's working storage, kept from one round to the next. M and
  // listed are zero between rounds: a round's elimination writes only the
  // diagonal, the last column and the listed entries, and clear_touched
  // zeroes those (work of the order of the fill, not of m²).
  struct Scratch {
    std::vector<std::size_t> free_rows, place, order, S, in_s, upper, upper_start;
    MinimumDegreeScratch ordering;
    std::vector<Num> M, xs;
    RowLists below, above;
    std::vector<char> listed, dependent;
    std::size_t m = 0;  // the size of the last round's system
    void clear_touched() {
      if (m == 0) return;
      auto at = [&](std::size_t r, std::size_t s) -> Num& { return M[r * (m + 1) + s]; };
      for (std::size_t r = 0; r < m; ++r) {
        at(r, r) = Num{}, at(r, m) = Num{};
        below.for_each(r, [&](std::size_t below_r) { at(below_r, r) = Num{}, listed[below_r * m + r] = 0; });
        above.for_each(r, [&](std::size_t s) { at(r, s) = Num{}, listed[r * m + s] = 0; });
      }
      m = 0;
    }
  };
  Scratch scratch_;
};

}  // namespace collide2d
