// The eliminations of the complementarity solver (sparse_factor.hpp) held to
// their definition: symmetric Gaussian elimination of A_SS in the factor's
// own order S, done densely here over every entry of the upper triangle
// (the part left to eliminate stays symmetric), and the two substitutions. The sparse factor visits only the entries that may be
// nonzero and keeps its fill pattern as bits; whatever it keeps, each pivot,
// each dependent row and every unknown must be the dense elimination's, to
// the bit. One factorizer serves every trial, large and small in turn, so an
// entry or a bit left over from an earlier problem would show.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

#include "collide2d/sim/sparse_factor.hpp"
#include "lcp_networks.hpp"

namespace {

using collide2d::Lcp;
using collide2d::SparseFactor;
using collide2d::SparseFactorizer;
using collide2d::test::matrix_of;
using collide2d::test::next_uniform;
using collide2d::test::random_network;

using Dense = std::vector<std::vector<double>>;

// What the definition gives: pivots, dependent places, and x (zero off S
// and on dependent places), or solvable = false if the last row depends on
// the others.
struct DenseAnswer {
  std::vector<double> pivot, x;
  std::vector<char> dependent;
  bool solvable = true;
};

DenseAnswer eliminate_densely(const Dense& A, const std::vector<std::size_t>& S, std::size_t last,
                              const std::vector<double>& b) {
  const std::size_t m = S.size();
  Dense D(m, std::vector<double>(m)), L(m, std::vector<double>(m));
  for (std::size_t p = 0; p < m; ++p)
    for (std::size_t q = 0; q < m; ++q) D[p][q] = A[S[p]][S[q]];
  DenseAnswer out;
  out.pivot.assign(m, 0.0);
  out.dependent.assign(m, 0);
  for (std::size_t col = 0; col < m; ++col) {
    const double pivot = D[col][col];
    out.pivot[col] = pivot;
    // A pivot fallen to rounding, 2^-36 of its diagonal: the row depends
    // on those before it (sparse_factor.hpp).
    if (!(0x1p-36 * A[S[col]][S[col]] < pivot)) {
      out.dependent[col] = 1;
      if (S[col] == last) {
        out.solvable = false;
        return out;
      }
      continue;
    }
    // The matrix left stays symmetric: only its upper triangle is updated,
    // and column col's multipliers are read off row col.
    for (std::size_t r = col + 1; r < m; ++r) {
      if (D[col][r] == 0.0) continue;
      const double f = D[col][r] / pivot;
      if (f == 0.0) continue;
      L[r][col] = f;
      for (std::size_t s = r; s < m; ++s)
        if (D[col][s] != 0.0) D[r][s] = D[r][s] - f * D[col][s];
    }
  }
  // L y = −b_S, then U x = y with U's rows summed in increasing column
  // order (D's row col is final once col is eliminated).
  std::vector<double> rhs(m), xs(m, 0.0);
  for (std::size_t p = 0; p < m; ++p) rhs[p] = -b[S[p]];
  for (std::size_t col = 0; col < m; ++col) {
    const double v = rhs[col];
    if (out.dependent[col] || v == 0.0) continue;
    for (std::size_t r = col + 1; r < m; ++r)
      if (L[r][col] != 0.0) rhs[r] = rhs[r] - L[r][col] * v;
  }
  for (std::size_t col = m; col-- > 0;) {
    if (out.dependent[col]) continue;
    double sum = rhs[col];
    for (std::size_t s = col + 1; s < m; ++s)
      if (D[col][s] != 0.0) sum = sum - D[col][s] * xs[s];
    xs[col] = sum / out.pivot[col];
  }
  out.x.assign(b.size(), 0.0);
  for (std::size_t p = 0; p < m; ++p) out.x[S[p]] = xs[p];
  return out;
}

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

// Row r's nonzero columns of A, in increasing order (as Lcp::solve lists
// them): column[start[r] .. start[r + 1]).
void pattern_of(const Dense& A, std::size_t k, std::vector<std::size_t>& start, std::vector<std::size_t>& column) {
  start.assign(1, 0);
  column.clear();
  for (std::size_t r = 0; r < k; ++r) {
    for (std::size_t s = 0; s < k; ++s)
      if (A[r][s] != 0.0) column.push_back(s);
    start.push_back(column.size());
  }
}

}  // namespace

TEST_CASE("sparse factor: pivots and unknowns are those of the dense elimination in its order, to the bit",
          "[lcp][sparse_factor]") {
  // Sizes on both sides of one, two and three 64-bit words of the fill
  // pattern, in an order that makes each problem follow a larger or a
  // smaller one; networks plain and redundant (more contacts than freedoms:
  // dependent rows), with and without a last row (a strike).
  const std::vector<std::size_t> sizes = {65, 3, 129, 64, 200, 1, 63, 128, 130, 17, 192, 127, 40, 191, 66};
  SparseFactorizer<double> factorizer;
  std::uint64_t state = 2026;
  std::size_t dependent_places = 0, multiword = 0, unsolvable = 0, in_whole = 0;
  for (int round = 0; round < 4; ++round) {
    for (const std::size_t k : sizes) {
      const bool redundant = round % 2 == 1;
      const std::size_t balls = redundant ? 1 + k / 4 : k + 2;  // redundant: twice as many contacts as freedoms
      Lcp<double> lcp;
      random_network(lcp, state, balls, k, redundant);
      const Dense A = matrix_of(lcp, k);
      std::vector<std::size_t> start, column;
      pattern_of(A, k, start, column);
      std::vector<char> active(k);
      for (char& a : active) a = next_uniform(state) < 0.85 ? 1 : 0;
      std::size_t last = k;  // none
      if (round >= 2) {
        last = std::size_t(next_uniform(state) * double(k));
        active[last] = 1;
      }
      // Every other problem takes its rows in the order of the whole matrix
      // (as Lcp does): S is then that order's active rows, the last row last.
      const bool in_whole_order = (k + static_cast<std::size_t>(round)) % 2 == 0;
      std::vector<std::size_t> whole_order;
      if (in_whole_order) factorizer.order_of_whole(k, start, column, whole_order);
      SparseFactor<double> factor;
      factorizer.factor(k, active, last, start, column, [&](std::size_t r, std::size_t s) { return A[r][s]; },
                        factor, in_whole_order ? &whole_order : nullptr);
      if (in_whole_order) {
        std::vector<std::size_t> expected_order;
        for (std::size_t r : whole_order)
          if (active[r] && r != last) expected_order.push_back(r);
        if (last < k) expected_order.push_back(last);
        REQUIRE(factor.S == expected_order);
        ++in_whole;
      }

      // S: every active row once, the last row last.
      std::vector<std::size_t> sorted = factor.S;
      std::sort(sorted.begin(), sorted.end());
      std::vector<std::size_t> expected;
      for (std::size_t r = 0; r < k; ++r)
        if (active[r]) expected.push_back(r);
      INFO("round " << round << ", " << k << " rows" << (last < k ? ", a last row" : ""));
      REQUIRE(sorted == expected);
      if (last < k) REQUIRE(factor.S.back() == last);

      const DenseAnswer dense = eliminate_densely(A, factor.S, last, lcp.b);
      REQUIRE(factor.solvable == dense.solvable);
      if (factor.S.size() > 64) ++multiword;
      if (!dense.solvable) {
        ++unsolvable;
        continue;
      }
      for (std::size_t p = 0; p < factor.S.size(); ++p) {
        INFO("place " << p << " (row " << factor.S[p] << ")");
        CHECK(bits(factor.pivot[p]) == bits(dense.pivot[p]));
        CHECK(factor.dependent[p] == dense.dependent[p]);
        dependent_places += dense.dependent[p] != 0;
      }
      std::vector<double> x, rhs, xs;
      factor.solve(lcp.b, x, rhs, xs);
      REQUIRE(x.size() == k);
      for (std::size_t r = 0; r < k; ++r) {
        INFO("row " << r);
        CHECK(bits(x[r]) == bits(dense.x[r]));
      }
    }
  }
  // The trials reach what they are for: systems of several words, and
  // redundant rows the elimination sets aside.
  INFO(multiword << " systems of more than one word, " << dependent_places << " dependent places, " << unsolvable
                 << " last rows dependent");
  CHECK(multiword >= 20);
  CHECK(dependent_places >= 20);
  CHECK(in_whole >= 20);
}

// Eliminating some of the rows in the order of the whole matrix fills no
// entry between two free rows that eliminating them all in that order leaves
// empty (fill joins two rows through rows eliminated before both; the
// subset's such paths are the whole's, and a last row, put last, is inside
// none): the kept order costs a pivoting round no such fill the whole would
// not. The last row's own entries are not held to it.
TEST_CASE("sparse factor: an active set in the whole matrix's order fills within the whole's fill",
          "[lcp][sparse_factor]") {
  SparseFactorizer<double> factorizer;
  std::uint64_t state = 77;
  std::size_t compared = 0, fill_seen = 0;
  for (const std::size_t k : {40, 90, 150}) {
    for (const bool redundant : {false, true}) {
      Lcp<double> lcp;
      random_network(lcp, state, redundant ? 1 + k / 4 : k + 2, k, redundant);
      const Dense A = matrix_of(lcp, k);
      std::vector<std::size_t> start, column;
      pattern_of(A, k, start, column);
      std::vector<std::size_t> whole_order;
      factorizer.order_of_whole(k, start, column, whole_order);
      auto entries_of = [&](const SparseFactor<double>& f) {  // (row, row) pairs of U, by row of A
        std::vector<std::pair<std::size_t, std::size_t>> out;
        for (std::size_t col = 0; col < f.S.size(); ++col)
          for (std::size_t e = f.upper_start[col]; e < f.upper_start[col + 1]; ++e)
            out.push_back({std::min(f.S[col], f.S[f.upper[e].first]), std::max(f.S[col], f.S[f.upper[e].first])});
        std::sort(out.begin(), out.end());
        return out;
      };
      // The whole's fill, from the pattern alone (every row eliminated in
      // turn joins its later neighbours; a dependent row of the numbers
      // would leave some of it out).
      std::vector<std::vector<char>> joined(k, std::vector<char>(k, 0));
      for (std::size_t r = 0; r < k; ++r)
        for (std::size_t s = 0; s < k; ++s) joined[r][s] = A[r][s] != 0.0;
      std::vector<std::size_t> place_of(k);
      for (std::size_t p = 0; p < k; ++p) place_of[whole_order[p]] = p;
      for (std::size_t p = 0; p < k; ++p) {
        const std::size_t pivot = whole_order[p];
        std::vector<std::size_t> later;
        for (std::size_t s = 0; s < k; ++s)
          if (joined[pivot][s] && place_of[s] > p) later.push_back(s);
        for (std::size_t u : later)
          for (std::size_t v : later) joined[u][v] = 1;
      }
      std::vector<std::pair<std::size_t, std::size_t>> whole_entries;
      for (std::size_t r = 0; r < k; ++r)
        for (std::size_t s = r + 1; s < k; ++s)
          if (joined[r][s]) whole_entries.push_back({r, s});
      for (int trial = 0; trial < 6; ++trial) {
        std::vector<char> active(k);
        for (char& a : active) a = next_uniform(state) < 0.7 ? 1 : 0;
        std::size_t last = k;  // none in even trials, a strike's row in odd ones
        if (trial % 2 == 1) {
          last = std::size_t(next_uniform(state) * double(k));
          active[last] = 1;
        }
        SparseFactor<double> part;
        factorizer.factor(k, active, last, start, column, [&](std::size_t r, std::size_t s) { return A[r][s]; }, part,
                          &whole_order);
        for (const auto& entry : entries_of(part)) {
          if (entry.first == last || entry.second == last) continue;
          INFO(k << " rows" << (redundant ? ", redundant" : "") << ", trial " << trial << ": entry (" << entry.first << ", "
                 << entry.second << ")");
          CHECK(std::binary_search(whole_entries.begin(), whole_entries.end(), entry));
          ++compared;
          fill_seen += A[entry.first][entry.second] == 0.0;
        }
      }
    }
  }
  INFO(compared << " entries compared, " << fill_seen << " of them fill");
  CHECK(fill_seen > 0);  // the claim is tested on fill, not only on A's own entries
}
