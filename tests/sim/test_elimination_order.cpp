// minimum_degree_order: a permutation, leaves before hubs, and far less
// fill-in than an order that knows nothing of the graph.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <set>
#include <vector>

#include "collide2d/sim/elimination_order.hpp"

namespace {

using Graph = std::vector<std::set<std::size_t>>;

std::vector<std::size_t> order_of(const Graph& g) {
  return collide2d::minimum_degree_order(g.size(), [&](std::size_t a, auto visit) {
    for (std::size_t b : g[a]) visit(b);
  });
}

// Node v is eliminated: its remaining neighbours are joined to one another
// (symbolic Gaussian elimination). Returns the entries this creates.
std::size_t eliminate(Graph& g, std::vector<char>& gone, std::size_t v) {
  gone[v] = 1;
  std::vector<std::size_t> left;
  for (std::size_t u : g[v])
    if (!gone[u]) left.push_back(u);
  std::size_t fill = 0;
  for (std::size_t a : left)
    for (std::size_t b : left)
      if (a < b && g[a].insert(b).second) g[b].insert(a), ++fill;
  return fill;
}

// The entries Gaussian elimination in `order` creates.
std::size_t fill_in(Graph g, const std::vector<std::size_t>& order) {
  std::vector<char> gone(g.size(), 0);
  std::size_t fill = 0;
  for (std::size_t v : order) fill += eliminate(g, gone, v);
  return fill;
}

void join(Graph& g, std::size_t a, std::size_t b) { g[a].insert(b), g[b].insert(a); }

}  // namespace

TEST_CASE("minimum degree: a permutation of the rows", "[elimination_order]") {
  for (std::size_t n : {0u, 1u, 2u, 63u, 64u, 65u, 130u}) {
    Graph g(n);
    for (std::size_t a = 0; a + 1 < n; ++a) join(g, a, (a * 7 + 3) % n == a ? (a + 1) % n : (a * 7 + 3) % n);
    std::vector<std::size_t> order = order_of(g);
    REQUIRE(order.size() == n);
    std::sort(order.begin(), order.end());
    for (std::size_t i = 0; i < n; ++i) CHECK(order[i] == i);
  }
}

TEST_CASE("minimum degree: a star's leaves go before its centre", "[elimination_order]") {
  Graph g(6);
  for (std::size_t leaf = 1; leaf < 6; ++leaf) join(g, 0, leaf);
  const std::vector<std::size_t> order = order_of(g);
  // The centre's degree is 5 until four leaves are gone; then centre and last
  // leaf tie at 1 and the lower index goes first.
  CHECK(std::find(order.begin(), order.end(), 0) - order.begin() == 4);
  CHECK(fill_in(g, order) == 0);
}

TEST_CASE("minimum degree: a shuffled grid fills in far less than in its label order", "[elimination_order]") {
  // A 12 × 12 grid (a contact network's line graph is as local) whose labels
  // are shuffled, as a pile's ball indices are after a pour.
  const std::size_t side = 12, n = side * side;
  std::vector<std::size_t> label(n);
  std::uint64_t state = 12345;
  for (std::size_t i = 0; i < n; ++i) label[i] = i;
  for (std::size_t i = n; i-- > 1;) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    std::swap(label[i], label[(state >> 33) % (i + 1)]);
  }
  Graph g(n);
  for (std::size_t r = 0; r < side; ++r)
    for (std::size_t c = 0; c < side; ++c) {
      if (c + 1 < side) join(g, label[r * side + c], label[r * side + c + 1]);
      if (r + 1 < side) join(g, label[r * side + c], label[(r + 1) * side + c]);
    }
  std::vector<std::size_t> natural(n);
  for (std::size_t i = 0; i < n; ++i) natural[i] = i;
  const std::size_t by_label = fill_in(g, natural), by_degree = fill_in(g, order_of(g));
  INFO("fill-in: label order " << by_label << ", minimum degree " << by_degree);
  // Nested dissection's bound for a k × k grid is O(k² log k) ≈ 1e3 here; a
  // label order approaches the dense (n²/2 ≈ 1e4) one.
  CHECK(by_degree * 3 < by_label);
}

namespace {

// The rule stated in elimination_order.hpp, written the plain way: scan every
// row for the fewest uneliminated neighbours (lowest index on ties), then
// eliminate it, with sets instead of the library's bit rows: the oracle
// whose order the library's must be exactly (the order fixes the LCP's
// operations, and so the bits of every pile run).
std::vector<std::size_t> plain_minimum_degree_order(Graph g) {
  const std::size_t n = g.size();
  std::vector<char> gone(n, 0);
  std::vector<std::size_t> order;
  auto degree = [&](std::size_t a) {
    std::size_t d = 0;
    for (std::size_t b : g[a]) d += gone[b] ? 0 : 1;
    return d;
  };
  for (std::size_t step = 0; step < n; ++step) {
    std::size_t pick = n;
    for (std::size_t a = 0; a < n; ++a)
      if (!gone[a] && (pick == n || degree(a) < degree(pick))) pick = a;
    order.push_back(pick);
    eliminate(g, gone, pick);
  }
  return order;
}

}  // namespace

TEST_CASE("minimum degree: the same order as the plain scan, on random sparse graphs", "[elimination_order]") {
  std::uint64_t state = 777;
  auto next = [&](std::uint64_t bound) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (state >> 33) % bound;
  };
  for (int trial = 0; trial < 80; ++trial) {
    const std::size_t n = 1 + next(400);
    const std::size_t edges = next(4 * n + 1);
    Graph g(n);
    for (std::size_t e = 0; e < edges; ++e) {
      const std::size_t a = next(n), b = next(n);
      if (a != b) join(g, a, b);
    }
    INFO("trial " << trial << ": " << n << " rows, " << edges << " edges drawn");
    CHECK(order_of(g) == plain_minimum_degree_order(g));
  }
}

TEST_CASE("minimum degree: exactly the greedy order of its definition", "[elimination_order]") {
  // The order decides the rounding of every contact force, so it is pinned
  // to its definition, computed here the plain way: each step takes the
  // remaining row with the fewest remaining neighbours (ties: the lowest
  // index) and joins its remaining neighbours to one another.
  std::uint64_t state = 777;
  auto next = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return state >> 33;
  };
  for (std::size_t n : {1u, 5u, 40u, 64u, 65u, 129u, 200u}) {
    for (int trial = 0; trial < 4; ++trial) {
      Graph g(n);
      for (std::size_t e = 0; e < 2 * n; ++e) {
        const std::size_t a = next() % n, b = next() % n;
        if (a != b) join(g, a, b);
      }
      Graph work = g;
      std::vector<char> gone(n, 0);
      std::vector<std::size_t> expected;
      for (std::size_t step = 0; step < n; ++step) {
        std::size_t pick = n, fewest = n + 1;
        for (std::size_t v = 0; v < n; ++v) {
          if (gone[v]) continue;
          std::size_t d = 0;
          for (std::size_t u : work[v]) d += gone[u] ? 0 : 1;
          if (d < fewest) fewest = d, pick = v;
        }
        expected.push_back(pick);
        eliminate(work, gone, pick);
      }
      CHECK(order_of(g) == expected);
    }
  }
}
