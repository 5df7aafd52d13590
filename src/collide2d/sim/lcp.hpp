// A linear complementarity problem (small, sparse), solved exactly.
//
//     w = A x + b,   x_r ≥ 0,  w_r ≥ 0,  x_r w_r = 0   (complementary rows)
//                    w_r = 0                           (equality rows)
//
// A is symmetric positive (semi)definite here (contact_graph.hpp). Principal
// pivoting: start with every row active (w = 0), solve A_SS x_S = −b_S, and
// flip the rows that break their sign condition (an active row pulling,
// x_r < 0, or an inactive one sinking, w_r < 0, each beyond its inputs'
// rounding, 2^-40 of its own `size` plus 2^-40 of the largest row's, and
// for fixed point never less than a few units of its resolution:
// resolution_floor). All breaching rows flip at once (Júdice and
// Pires' block pivoting: a pile's few dozen contacts settle in a handful of
// solves) while that lowers the number of breaches; when it stops doing so,
// one row at a time, the lowest-numbered (Murty's least-index rule). At
// most 4 k + 16 solves: a redundant pile can cycle on rows that rounding
// alone makes breach (a cycle once entered is not run out: the pivoting
// ends on the set it would have had at the cap, with the same x and count
// of rounds); projected Gauss–Seidel finishes from there (polish,
// then finish where that leaves a real breach). Equality
// rows never flip. An impact's slow partings (`holds`) become equality rows
// in the round that meets them. Every step
// is a fixed sequence of +, −, ×, ÷ in the caller's number type: the same
// bits everywhere.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "collide2d/numeric/number_traits.hpp"
#include "collide2d/sim/sparse_factor.hpp"

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
  // Pivoting rounds so far (one solve of the active rows each): what the
  // solves cost; in how many of them a factor made before was used again.
  std::size_t rounds = 0, factors_reused = 0;
  // The pivoting skips the repeats of a cycle it has entered (below), and
  // counts them; false runs them out to the cap, for the test that holds
  // the two to the same bits.
  bool skips_cycles = true;
  std::size_t cycles_skipped = 0;
  // An impact's slow partings are held (contact_graph.hpp, ContactGraph::
  // impact): with `holds`, an inactive complementary row that a round
  // leaves parting slower than `hold_below` (0 ≤ w < hold_below) becomes an
  // equality row at once, active for good, and the pivoting goes on with it
  // held. The rows held this way only grow, so holding cannot cycle.
  bool holds = false;
  Num hold_below{};

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
    holds = false;
    hold_below = Num{};
    forced = k;
    rounds = 0;
    factors_reused = 0;
    cycles_skipped = 0;
    pattern_current_ = false;
  }

  // A_rs = value (A is symmetric: set both). Unset entries are zero.
  void set(std::size_t r, std::size_t s, const Num& value) {
    A[r][s] = value;
    written_.push_back({r, s});
    pattern_current_ = false;
  }
  const Num& a(std::size_t r, std::size_t s) const { return A[r][s]; }

  // Returns the forced row if it depends on the active rows (the others
  // answer it alone), else the number of rows.
  std::size_t solve() {
    const std::size_t k = b.size();
    // A solved again unchanged (a strike's held rows added as equations,
    // contact_graph.hpp) keeps its pattern and its factors.
    if (!pattern_current_) build_pattern(k);
    // Each row's fixed parts of its tolerance, formed once a solve rather
    // than at every test of every round (the same values).
    floor_.resize(k);
    pivot_tolerance_.resize(k);
    // The elimination mixes every row of the problem, so each x carries
    // rounding of the largest row's scale, not only of its own: rows of
    // balls nearly at rest beside a struck one, judged by their own scale
    // alone, breached by 1e-19 to 1e-30 (a strike's speeds are 1e-3 to 1),
    // and the pivoting cycled on them to its cap, then swept for hundreds of
    // rounds (pile_50: a sixth of its island solves cycled, 6.5 M sweeps).
    Num largest{};
    for (std::size_t r = 0; r < k; ++r)
      if (largest < size[r]) largest = size[r];
    const Num problem_floor = num<Num>(0x1p-40) * largest;
    for (std::size_t r = 0; r < k; ++r) {
      floor_[r] = resolution_floor(r) + problem_floor;
      pivot_tolerance_[r] = num<Num>(0x1p-40) * size[r] + floor_[r];
    }
    std::size_t fewest = k + 1, single_steps_after = 0;
    const std::size_t cap = 4 * k + 16, rounds_before = rounds;
    visited_.clear();
    auto find_breaches = [&] {
      breaching_.clear();
      for (std::size_t r = 0; r < k; ++r)
        if (breaches(r)) breaching_.push_back(r);
    };
    for (std::size_t iteration = 0; iteration < cap; ++iteration) {
      ++rounds;
      if (!solve_active()) return forced;
      // Slow partings held where they are met: a round that holds one
      // changes the problem, so the count of breaches starts again.
      if (holds ? find_breaches_and_hold() : (find_breaches(), false)) {
        fewest = k + 1, single_steps_after = iteration + 3;
        visited_.clear();
        continue;
      }
      if (breaching_.empty()) break;
      // Block steps while they help (three chances), then Murty's.
      if (breaching_.size() < fewest) {
        fewest = breaching_.size(), single_steps_after = iteration + 3;
        visited_.clear();
      }
      if (iteration < single_steps_after) {
        for (std::size_t r : breaching_) active[r] = !active[r];
        continue;
      }
      // A single step's next active set is a function of this one alone
      // while the fewest breaches stay as they are. So a set met again
      // since they last fell starts a cycle that repeats to the cap: the
      // rounds left are skipped, and the pivoting ends where it would have
      // at the cap, on the set the cycle has in its last round (the same
      // x, the same flip, the same count of rounds: the same bits).
      if (const std::size_t first = skips_cycles ? visited_.find(active) : visited_.none; first != visited_.none) {
        const std::size_t period = visited_.count() - first;
        const std::size_t last = cap - 1 - (iteration - visited_.count());  // the last round, counted in visits
        const std::size_t at = first + (last - first) % period;
        if (at != first) {  // else this round's set, x and breaches are the last round's
          visited_.copy_to(at, active);
          solve_active();  // solvable: it was in the cycle's first pass
          find_breaches();
        }
        rounds = rounds_before + cap;
        ++cycles_skipped;
        active[breaching_.front()] = !active[breaching_.front()];
        break;
      }
      if (skips_cycles) visited_.add(active);
      active[breaching_.front()] = !active[breaching_.front()];
    }
    clamp_pushes();
    double left = violation();
    if (left > 0) polish(), left = violation();
    // A breach below the smallest normal double is nothing left to mend.
    if (left > std::numeric_limits<double>::min()) finish();
    return k;
  }

  // How far x is from a solution: the largest breach of a row's condition
  // beyond its tolerance (0 when x solves the problem). After solve(), which
  // forms the rows' floors it uses (resolution and problem floors).
  double violation() const {
    double worst = 0;
    for (std::size_t r = 0; r < b.size(); ++r) {
      Num w{}, tolerance{};
      residual_and_tolerance(r, w, tolerance);
      const Num breach = equality[r] || x[r] > Num{} ? NumberTraits<Num>::abs(w) : -w;
      // Compared in Num, converted once: a row within its tolerance (most
      // rows) costs no conversion.
      if (tolerance < breach) worst = std::max(worst, NumberTraits<Num>::to_double(breach - tolerance));
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
  bool pattern_current_ = false;  // the pattern is A's: no set() since it was built
  std::vector<std::size_t> breaching_;    // solve()'s rows that break their conditions, storage reused
  // The active sets of solve()'s single steps since the fewest breaches
  // last fell, in order: where a set was met before.
  struct VisitedSets {
    static constexpr std::size_t none = static_cast<std::size_t>(-1);
    std::vector<char> sets;               // one after the other, each of the problem's k rows
    std::vector<std::uint64_t> hashes;    // FNV-1a of each
    void clear() { sets.clear(), hashes.clear(); }
    std::size_t count() const { return hashes.size(); }
    static std::uint64_t hash(const std::vector<char>& set) {
      std::uint64_t h = 0xcbf29ce484222325ULL;
      for (char c : set) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
      return h;
    }
    std::size_t find(const std::vector<char>& set) const {
      const std::uint64_t h = hash(set);
      for (std::size_t v = 0; v < hashes.size(); ++v)
        if (hashes[v] == h && std::equal(set.begin(), set.end(), sets.begin() + static_cast<std::ptrdiff_t>(v * set.size())))
          return v;
      return none;
    }
    void add(const std::vector<char>& set) {
      hashes.push_back(hash(set));
      sets.insert(sets.end(), set.begin(), set.end());
    }
    void copy_to(std::size_t v, std::vector<char>& set) const {
      std::copy_n(sets.begin() + static_cast<std::ptrdiff_t>(v * set.size()), set.size(), set.begin());
    }
  } visited_;
  std::vector<std::size_t> next_in_row_;  // solve(): where each row's next written column goes
  std::vector<Num> floor_;                // solve(): each row's resolution_floor plus 2^-40 of the largest size
  std::vector<Num> pivot_tolerance_;      // solve(): 2^-40 size_r + floor_r, breaches()'s tolerance

  // Each row's nonzero entries (nonzero_start, nonzero_column), and the
  // factor cache told which matrix this is.
  void build_pattern(std::size_t k) {
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
    // The order is a function of the pattern alone: the matrix begun last
    // (an island asked again before its contacts changed) keeps its own.
    if (!factors_.begin(k, nonzero_start, nonzero_column, [&](std::size_t r, std::size_t s) { return A[r][s]; }))
      factorizer_.order_of_whole(k, nonzero_start, nonzero_column, whole_order_);
    pattern_current_ = true;
  }

  // The residual w_r (as residual(r)) and the row's rounding tolerance:
  // 2^-40 of the scale of its terms (its inputs and each A_rs x_s) plus its
  // floor (the resolution floor below and 2^-40 of the problem's largest
  // size: the sweeps and their end take the pivoting's floor). One pass
  // makes each product once.
  void residual_and_tolerance(std::size_t r, Num& w, Num& tolerance) const {
    auto magnitude = [](const Num& v) { return NumberTraits<Num>::abs(v); };
    w = b[r];
    Num scale = size[r] + magnitude(b[r]);
    for (std::size_t e = nonzero_start[r]; e < nonzero_start[r + 1]; ++e) {
      const Num term = A[r][nonzero_column[e]] * x[nonzero_column[e]];
      w = w + term;
      scale = scale + magnitude(term);
    }
    tolerance = num<Num>(0x1p-40) * scale + floor_[r];
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
      sweep_rows(num<Num>(1.0));
      if ((sweep & 7) != 7) continue;
      const double now = violation();
      if (!(now > 0)) break;
      if ((sweep & 63) != 63) continue;
      if (!(now < 0.5 * last)) break;
      last = now;
    }
    set_active_from_x();
  }

  // What the sweeps above leave off (on some redundant networks the
  // pivoting cycles to its cap: dependent rows are set to zero, not
  // exchanged, so Murty's rule has no guarantee of finishing, and 64
  // sweeps that do not halve the breach are far from the answer; two of
  // forty random networks in tests/sim/test_lcp.cpp were left off by up to
  // 2.5e-3 of their speeds) is finished by over-relaxed sweeps, with the
  // rows they leave pushing or touching solved exactly every 64 sweeps
  // (cross_over), which ends the search as soon as the sweeps have found
  // the answer's active set. They stop when no row breaches its tolerance,
  // when 2,048 sweeps have not halved the breach, or after 64 k + 4,096
  // sweeps; if they end off the conditions, the sweeps' answer above stays.
  void finish() {
    const std::size_t k = b.size();
    // Over-relaxed (projected SOR, which converges for 0 < ω < 2 on such an
    // A: Cryer 1971): on the two networks of the redundant test that the
    // pivoting leaves off its conditions, the answer's active set
    // is found after 959 and 511 sweeps, where plain Gauss–Seidel (ω = 1)
    // takes 4,799 and 7,807.
    const Num over_relaxation = num<Num>(1.8);
    const std::vector<Num> polished = x;  // kept if the finish does not finish
    double last = violation();
    std::size_t last_halved = 0;
    for (std::size_t sweep = 0; sweep < 64 * k + 4096; ++sweep) {
      sweep_rows(over_relaxation);
      if ((sweep & 7) != 7) continue;
      const double now = violation();
      if (!(now > 0)) return set_active_from_x();
      if ((sweep & 63) != 63) continue;
      if (cross_over()) return;
      if (now < 0.5 * last) last = now, last_halved = sweep;
      if (sweep - last_halved >= 2048) break;
    }
    x = polished;
    set_active_from_x();
  }

  // One projected sweep: each row in turn moves its x by ω times the step
  // that zeroes its w (ω = 1: Gauss–Seidel), clamped at 0 for a
  // complementary row. Multiplying by exactly 1 changes no bit.
  void sweep_rows(const Num& omega) {
    for (std::size_t r = 0; r < b.size(); ++r) {
      if (!(Num{} < A[r][r])) continue;
      Num next = x[r] - omega * (residual(r) / A[r][r]);
      if (!equality[r] && next < Num{}) next = Num{};
      x[r] = next;
    }
  }

  // The rows that breach (as breaches()), each inactive row's residual
  // formed once; inactive complementary rows parting slower than
  // hold_below (not sinking beyond their tolerance: those are breaches)
  // become held equations. True if any did: the breaches found are then
  // of a problem that has changed, and go unused.
  bool find_breaches_and_hold() {
    breaching_.clear();
    bool held = false;
    for (std::size_t r = 0; r < b.size(); ++r) {
      if (equality[r]) continue;
      const Num& tolerance = pivot_tolerance_[r];
      if (active[r]) {
        if (x[r] * A[r][r] < -tolerance) breaching_.push_back(r);
        continue;
      }
      const Num w = residual(r);
      if (w < -tolerance) breaching_.push_back(r);
      else if (w < hold_below) equality[r] = active[r] = 1, held = true;
    }
    return held;
  }

  // A push within rounding of none is none.
  void clamp_pushes() {
    for (std::size_t r = 0; r < b.size(); ++r)
      if (!equality[r] && x[r] < Num{}) x[r] = Num{};
  }

  // Rows pushing (x > 0), held (equality) or touching (w within its
  // tolerance) are active.
  void set_active_from_x() {
    for (std::size_t r = 0; r < b.size(); ++r) {
      Num w{}, tolerance{};
      residual_and_tolerance(r, w, tolerance);
      active[r] = equality[r] || x[r] > Num{} || !(tolerance < w);
    }
  }

  // Row r breaks its sign condition beyond its inputs' rounding: active
  // and pulling, or inactive and sinking (equality rows never do).
  bool breaches(std::size_t r) const {
    if (equality[r]) return false;
    const Num& tolerance = pivot_tolerance_[r];
    return active[r] ? x[r] * A[r][r] < -tolerance : residual(r) < -tolerance;
  }

  // The sweeps' active set, solved exactly, with up to four block steps
  // from there. True (and x the answer) if that meets every condition;
  // otherwise the sweeps' x is left as it was.
  bool cross_over() {
    const std::size_t k = b.size();
    const std::vector<Num> swept = x;
    set_active_from_x();
    for (int step = 0; step < 5; ++step) {
      if (!solve_active()) break;
      bool breach = false;
      for (std::size_t r = 0; r < k; ++r)
        if (breaches(r)) active[r] = !active[r], breach = true;
      if (breach) continue;
      clamp_pushes();
      if (!(violation() > 0)) return true;
      break;
    }
    x = swept;
    return false;
  }

  // x on the active rows solves A_SS x_S = −b_S, zero elsewhere, the forced
  // row last (sparse_factor.hpp: a factor of these rows of this A made
  // before is used again). False if the forced row depends on the others:
  // there is no answer in impulses.
  bool solve_active() {
    const SparseFactor<Num>* factor = factors_.find(active, forced);
    if (factor == nullptr) {
      SparseFactor<Num>& room = factors_.make_room();
      factorizer_.factor(b.size(), active, forced, nonzero_start, nonzero_column,
                         [&](std::size_t r, std::size_t s) { return A[r][s]; }, room, &whole_order_);
      factor = &room;
    } else {
      ++factors_reused;
    }
    if (!factor->solvable) return false;
    factor->solve(b, x, rhs_, xs_);
    return true;
  }

  FactorCache<Num> factors_;           // the factors of this problem's matrix made so far
  SparseFactorizer<Num> factorizer_;   // its working storage kept
  std::vector<std::size_t> whole_order_;  // the rows in the minimum-degree order of the whole matrix (build_pattern)
  std::vector<Num> rhs_, xs_;          // SparseFactor::solve's storage, reused
};

}  // namespace collide2d
