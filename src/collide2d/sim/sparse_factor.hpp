// The linear systems of the complementarity solver (lcp.hpp): A_SS x_S =
// −b_S on the active rows S of a small sparse symmetric positive
// semidefinite A, by symmetric Gaussian elimination in the minimum-degree
// order of the whole of A (elimination_order.hpp; found once a matrix, every
// active set's rows taken in it), a chosen row last (stable without pivoting
// for such an A). The factor is kept apart from
// the right-hand side: the same rows of the same A come back often (a
// strike's refinement step, when it runs, solves its problem twice; an island struck again
// before any of its contacts changed asks the same again), and then only
// the substitutions are done again. A kept factor
// gives the same bits as a fresh one: elimination never reads the
// right-hand side, and the substitutions make the operations the fused
// elimination made, in the same order.
//
// Contacts of a pile are often redundant (more contacts than the balls have
// degrees of freedom): a row whose pivot has fallen to rounding, 2^-36 of
// its diagonal, depends on the rows before it; its unknown is set to zero
// and the others carry it (the forces of a redundant pile are not unique,
// any admissible choice is as good; this one is fixed by the elimination
// order). If the chosen last row (an equation: a strike) depends on the
// others, the factor says it cannot be solved.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "collide2d/numeric/number_traits.hpp"
#include "collide2d/sim/elimination_order.hpp"

namespace collide2d {

// A_SS = L D Lᵀ, kept as the elimination made it: for each place col of S,
// its pivot, the multipliers f = a_r,col / pivot of the places r below it
// (lower), and its row's entries right of the diagonal (upper, in
// increasing order), each nonzero only.
template <class Num>
struct SparseFactor {
  std::vector<char> active;      // the rows of the problem it covers (its key, with `last`)
  std::size_t last = 0;          // the row eliminated last (the number of rows: none)
  bool solvable = true;          // false: row `last` depends on the others
  std::vector<std::size_t> S;    // place → row, in elimination order
  std::vector<Num> pivot;        // per place
  std::vector<char> dependent;   // per place: the pivot fell to rounding
  std::vector<std::size_t> lower_start, upper_start;
  std::vector<std::pair<std::size_t, Num>> lower, upper;

  // x_S solving A_SS x_S = −b_S, zero on the other rows (a dependent row's
  // unknown too). `rhs` and `xs`: storage of the caller's, reused.
  void solve(const std::vector<Num>& b, std::vector<Num>& x, std::vector<Num>& rhs, std::vector<Num>& xs) const {
    const Num zero{};
    const std::size_t m = S.size();
    rhs.resize(m);
    for (std::size_t r = 0; r < m; ++r) rhs[r] = -b[S[r]];
    for (std::size_t col = 0; col < m; ++col) {
      const Num v = rhs[col];
      if (dependent[col] || v == zero) continue;
      for (std::size_t e = lower_start[col]; e < lower_start[col + 1]; ++e)
        rhs[lower[e].first] = rhs[lower[e].first] - lower[e].second * v;
    }
    xs.assign(m, zero);
    for (std::size_t col = m; col-- > 0;) {
      if (dependent[col]) continue;
      Num sum = rhs[col];
      for (std::size_t e = upper_start[col]; e < upper_start[col + 1]; ++e) sum = sum - upper[e].second * xs[upper[e].first];
      xs[col] = sum / pivot[col];
    }
    x.assign(b.size(), zero);
    for (std::size_t r = 0; r < m; ++r) x[S[r]] = xs[r];
  }
};

// The factors of one problem's matrix, the last few kept. `begin` names the
// matrix (its nonzero pattern and values, row by row); a different matrix
// drops every factor.
template <class Num>
class FactorCache {
 public:
  static constexpr std::size_t capacity = 8;

  // The problem's matrix: rows 0 .. k − 1, row r's nonzero entries at
  // columns column[start[r] .. start[r + 1]) with values value(r, column).
  // True if it is the matrix begun last (its factors are kept).
  template <class Value>
  bool begin(std::size_t k, const std::vector<std::size_t>& start, const std::vector<std::size_t>& column, Value value) {
    bool same = k == k_ && start == start_ && column == column_;
    for (std::size_t r = 0; same && r < k; ++r)
      for (std::size_t e = start[r]; same && e < start[r + 1]; ++e) same = value(r, column[e]) == values_[e];
    if (same) return true;
    k_ = k, start_ = start, column_ = column;
    values_.resize(column.size());
    for (std::size_t r = 0; r < k; ++r)
      for (std::size_t e = start[r]; e < start[r + 1]; ++e) values_[e] = value(r, column[e]);
    used_ = 0;
    return false;
  }

  const SparseFactor<Num>* find(const std::vector<char>& active, std::size_t last) const {
    for (std::size_t i = 0; i < used_; ++i)
      if (entries_[i].last == last && entries_[i].active == active) return &entries_[i];
    return nullptr;
  }

  // Storage for a new factor (the oldest is given up when all are used).
  SparseFactor<Num>& make_room() {
    if (entries_.size() < capacity) entries_.resize(capacity);
    if (used_ < capacity) return entries_[used_++];
    SparseFactor<Num>& slot = entries_[next_];
    next_ = (next_ + 1) % capacity;
    return slot;
  }

 private:
  std::size_t k_ = 0, used_ = 0, next_ = 0;
  std::vector<std::size_t> start_, column_;
  std::vector<Num> values_;
  std::vector<SparseFactor<Num>> entries_;
};

// The elimination itself, with its working storage kept from one call to the
// next (a pivoting solver factors often).
template <class Num>
class SparseFactorizer {
 public:
  // The minimum-degree order of all k rows, for `factor` to take the rows of
  // each active set in (a pivoting solver factors many active sets of one
  // matrix; ordering each anew cost as much as eliminating it). Eliminating
  // a subset of the rows in the order the whole takes fills no entry between
  // two free rows that the whole's elimination does not: fill joins two
  // rows through a path of rows eliminated before both, and the subset's
  // paths are the whole's (the last row, put last whatever its place in the
  // order, is never inside such a path; its own fill may be more).
  void order_of_whole(std::size_t k, const std::vector<std::size_t>& start, const std::vector<std::size_t>& column,
                      std::vector<std::size_t>& whole_order) {
    const auto for_each_neighbour = [&](std::size_t r, auto visit) {
      for (std::size_t e = start[r]; e < start[r + 1]; ++e) visit(column[e]);
    };
    minimum_degree_order(k, for_each_neighbour, ordering, whole_order);
  }

  // Factors A_SS into `out`: S the rows r < k with active[r] other than
  // `last`, in minimum-degree order (of A_SS's own pattern, or the whole's:
  // `whole_order`, a permutation of 0 .. k − 1 from order_of_whole), then
  // `last` if it is a row (< k). Row r's nonzero entries are at columns
  // column[start[r] .. start[r + 1]) (increasing), read as a(r, s).
  template <class Entry>
  void factor(std::size_t k, const std::vector<char>& active, std::size_t last, const std::vector<std::size_t>& start,
              const std::vector<std::size_t>& column, Entry a, SparseFactor<Num>& out,
              const std::vector<std::size_t>* whole_order = nullptr) {
    const Num zero{};
    clear_touched();
    out.active = active;
    out.last = last;
    out.solvable = true;
    std::vector<std::size_t>& S = out.S;
    S.clear();
    if (whole_order) {
      for (std::size_t r : *whole_order)
        if (active[r] && r != last) S.push_back(r);
    } else {
      // The free rows in an order of little fill-in.
      free_rows.clear();
      for (std::size_t r = 0; r < k; ++r)
        if (active[r] && r != last) free_rows.push_back(r);
      place.assign(k, k);  // row → its place in free_rows (k: not free)
      for (std::size_t p = 0; p < free_rows.size(); ++p) place[free_rows[p]] = p;
      const auto for_each_neighbour = [&](std::size_t p, auto visit) {
        const std::size_t r = free_rows[p];
        for (std::size_t e = start[r]; e < start[r + 1]; ++e)
          if (place[column[e]] < k) visit(place[column[e]]);
      };
      minimum_degree_order(free_rows.size(), for_each_neighbour, ordering, order);
      for (std::size_t p : order) S.push_back(free_rows[p]);
    }
    if (last < k) S.push_back(last);
    const std::size_t m = S.size();
    m_ = m;
    words_ = (m + 63) / 64;
    if (M.size() < m * m) M.resize(m * m, zero);
    if (above.size() < m * words_) above.resize(m * words_, 0);
    auto at = [&](std::size_t r, std::size_t s) -> Num& { return M[r * m + s]; };
    // A_SS is symmetric, and so is every matrix the elimination leaves
    // (the multipliers of a pivot's column are its row over the pivot): only
    // the upper triangle, diagonal included, is kept and updated, half the
    // work of updating both. Only entries that may be nonzero are visited:
    // those of A's own pattern and the fill-in as it appears, kept as bits,
    // above(r): the columns s > r of row r that may hold (r, s), met in
    // increasing order. Every entry ever written has its bit set (or is a
    // diagonal); the rest stay zero.
    in_s.assign(k, m);  // row of A → its place in S (m: not in S)
    for (std::size_t r = 0; r < m; ++r) in_s[S[r]] = r;
    for (std::size_t r = 0; r < m; ++r) {
      for (std::size_t e = start[S[r]]; e < start[S[r] + 1]; ++e) {
        const std::size_t s = in_s[column[e]];
        if (s == m || s < r) continue;
        at(r, s) = a(S[r], column[e]);
        if (r < s) above_of(r)[s / 64] |= bit(s);
      }
    }
    out.pivot.assign(m, zero);
    out.dependent.assign(m, 0);
    out.lower.clear();
    out.upper.clear();
    out.lower_start.assign(m + 1, 0);
    out.upper_start.assign(m + 1, 0);
    const Num small = num<Num>(0x1p-36);
    for (std::size_t col = 0; col < m; ++col) {
      const Num pivot = at(col, col);
      out.pivot[col] = pivot;
      out.lower_start[col] = out.lower.size();
      out.upper_start[col] = out.upper.size();
      if (!(small * a(S[col], S[col]) < pivot)) {
        out.dependent[col] = 1;
        if (S[col] == last) {
          out.solvable = false;
          std::fill(out.lower_start.begin() + static_cast<std::ptrdiff_t>(col), out.lower_start.end(), out.lower.size());
          std::fill(out.upper_start.begin() + static_cast<std::ptrdiff_t>(col), out.upper_start.end(), out.upper.size());
          return;
        }
        continue;
      }
      // Row col is final now. Only its nonzero entries change the rows
      // below (fill-in stays near the contact graph's own pattern): row r
      // of them, from its diagonal on, takes f_r = a(col, r) / pivot times
      // row col.
      upper_of_col.clear();
      for_each_bit(above_of(col), [&](std::size_t s) {
        if (!(at(col, s) == zero)) upper_of_col.push_back(s);
      });
      for (std::size_t s : upper_of_col) out.upper.push_back({s, at(col, s)});
      for (std::size_t i = 0; i < upper_of_col.size(); ++i) {
        const std::size_t r = upper_of_col[i];
        const Num f = at(col, r) / pivot;
        if (f == zero) continue;
        out.lower.push_back({r, f});
        Num* row_r = &at(r, 0);
        Bits* above_r = above_of(r);
        row_r[r] = row_r[r] - f * at(col, r);
        for (std::size_t j = i + 1; j < upper_of_col.size(); ++j) {
          const std::size_t s = upper_of_col[j];
          row_r[s] = row_r[s] - f * at(col, s);
          above_r[s / 64] |= bit(s);
        }
      }
    }
    out.lower_start[m] = out.lower.size();
    out.upper_start[m] = out.upper.size();
  }

 private:
  using Bits = std::uint64_t;
  static Bits bit(std::size_t i) { return Bits{1} << (i % 64); }
  Bits* above_of(std::size_t r) { return above.data() + r * words_; }
  // visit(i) for each bit i set in the row's words, in increasing order.
  template <class Visit>
  void for_each_bit(const Bits* row, Visit visit) const {
    for (std::size_t w = 0; w < words_; ++w)
      for (Bits bits = row[w]; bits != 0; bits &= bits - 1) visit(w * 64 + static_cast<std::size_t>(std::countr_zero(bits)));
  }

  // M and above are zero between calls: an elimination writes only
  // the diagonal and the entries whose bits are set, and this zeroes those
  // (work of the order of the fill in M, plus m²/64 words of bits: a few
  // hundred for the islands met).
  void clear_touched() {
    if (m_ == 0) return;
    const std::size_t m = m_;
    for (std::size_t r = 0; r < m; ++r) {
      M[r * m + r] = Num{};
      for_each_bit(above_of(r), [&](std::size_t s) { M[r * m + s] = Num{}; });
      std::fill_n(above_of(r), words_, Bits{0});
    }
    m_ = 0;
  }

  std::vector<std::size_t> free_rows, place, order, in_s, upper_of_col;
  MinimumDegreeScratch ordering;
  std::vector<Num> M;  // the system being eliminated, m × m, row by row
  std::vector<Bits> above;  // m rows of words_ words each
  std::size_t m_ = 0, words_ = 0;  // the size of the last system, and its words a row
};

}  // namespace collide2d
