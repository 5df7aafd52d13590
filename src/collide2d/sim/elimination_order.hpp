// An order in which to eliminate the unknowns of a sparse symmetric system
// so that Gaussian elimination creates little fill-in: greedy minimum
// degree (Tinney and Walker's scheme 2; George and Liu, "The evolution of
// the minimum degree ordering algorithm", SIAM Review 31, 1989).
//
// A pile's contact rows couple only through a shared ball, so the pattern of
// A is the line graph of the contact network, nearly planar. Eliminated in
// the contacts' key order (by ball index, which after a pour says nothing of
// where a ball is) the fill-in grows towards dense, m^3 work for m rows; in
// minimum-degree order it stays near the graph's own pattern. Each step
// takes the row with the fewest uneliminated neighbours (ties: the lowest
// index, so the order is a function of the pattern alone, the same on every
// machine), and joins its neighbours to one another, as its elimination
// will. Integer work only: the numbers are untouched, only their order.
#pragma once

#include <bit>
#include <cstdint>
#include <vector>

namespace collide2d {

// The working storage of minimum_degree_order, kept by a caller that orders
// often (lcp.hpp: every new matrix).
struct MinimumDegreeScratch {
  std::vector<std::uint64_t> neighbours, alive, by_degree, clique;
  std::vector<std::size_t> degree;
};

namespace detail {

// The order below with rows of `FixedWords` 64-bit words (0: as many as n
// needs): a pile's islands mostly have at most 64 rows, one word, and the
// loops over words then vanish.
template <std::size_t FixedWords, class ForEachNeighbour>
void minimum_degree_order(std::size_t n, ForEachNeighbour& for_each_neighbour, MinimumDegreeScratch& scratch,
                          std::vector<std::size_t>& order) {
  const std::size_t words = FixedWords != 0 ? FixedWords : (n + 63) / 64;
  using Bits = std::uint64_t;
  auto bit = [](std::size_t b) { return Bits{1} << (b % 64); };
  // Kernighan's count: the sets counted here are small.
  auto count = [](Bits bits) {
    std::size_t c = 0;
    for (; bits != 0; bits &= bits - 1) ++c;
    return c;
  };
  std::vector<Bits>&neighbours = scratch.neighbours, &alive = scratch.alive;
  neighbours.assign(n * words, 0);
  alive.assign(words, 0);
  auto row = [&](std::size_t a) { return neighbours.data() + a * words; };
  for (std::size_t a = 0; a < n; ++a) {
    alive[a / 64] |= bit(a);
    for_each_neighbour(a, [&](std::size_t b) {
      if (b != a) row(a)[b / 64] |= bit(b), row(b)[a / 64] |= bit(a);
    });
  }
  // degree[a] = |row(a) ∩ alive| for every uneliminated a, and a's bit is
  // set in by_degree[degree[a]]: the row of least degree, ties to the lowest
  // index, is the lowest bit of the first nonempty set.
  std::vector<std::size_t>& degree = scratch.degree;
  degree.assign(n, 0);
  std::vector<Bits>& by_degree = scratch.by_degree;
  by_degree.assign(n * words, 0);
  auto bucket = [&](std::size_t d) { return by_degree.data() + d * words; };
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t w = 0; w < words; ++w) degree[a] += count(row(a)[w]);
    bucket(degree[a])[a / 64] |= bit(a);
  }
  order.clear();
  order.reserve(n);
  std::vector<Bits>& clique = scratch.clique;
  clique.assign(words, 0);
  // The least degree falls by at most one a step (a neighbour of the row
  // eliminated loses it, and may gain others; no other row changes): the
  // search for it starts one below the last.
  std::size_t least = 0;
  for (std::size_t step = 0; step < n; ++step) {
    std::size_t pick = n;
    for (std::size_t d = least; pick == n; ++d)
      for (std::size_t w = 0; w < words; ++w)
        if (bucket(d)[w] != 0) {
          pick = w * 64 + static_cast<std::size_t>(std::countr_zero(bucket(d)[w]));
          least = d == 0 ? 0 : d - 1;
          break;
        }
    order.push_back(pick);
    bucket(degree[pick])[pick / 64] &= ~bit(pick);
    alive[pick / 64] &= ~bit(pick);
    for (std::size_t w = 0; w < words; ++w) clique[w] = row(pick)[w] & alive[w];
    // Each neighbour b loses pick and gains the clique's members it lacked.
    for (std::size_t w = 0; w < words; ++w)
      for (Bits bits = clique[w]; bits != 0; bits &= bits - 1) {
        const std::size_t b = w * 64 + static_cast<std::size_t>(std::countr_zero(bits));
        std::size_t d = degree[b] - 1;
        for (std::size_t v = 0; v < words; ++v) {
          Bits added = clique[v] & ~row(b)[v];
          if (v == b / 64) added &= ~bit(b);
          d += count(added);
          row(b)[v] |= added;
        }
        bucket(degree[b])[b / 64] &= ~bit(b);
        degree[b] = d;
        bucket(d)[b / 64] |= bit(b);
      }
  }
}

}  // namespace detail

// `for_each_neighbour(a, visit)` calls visit(b) for every row b < n that
// row a couples to (b ≠ a). Writes a permutation of 0 .. n − 1 to `order`.
template <class ForEachNeighbour>
void minimum_degree_order(std::size_t n, ForEachNeighbour for_each_neighbour, MinimumDegreeScratch& scratch,
                          std::vector<std::size_t>& order) {
  if (n <= 64) detail::minimum_degree_order<1>(n, for_each_neighbour, scratch, order);
  else detail::minimum_degree_order<0>(n, for_each_neighbour, scratch, order);
}

template <class ForEachNeighbour>
std::vector<std::size_t> minimum_degree_order(std::size_t n, ForEachNeighbour for_each_neighbour) {
  MinimumDegreeScratch scratch;
  std::vector<std::size_t> order;
  minimum_degree_order(n, for_each_neighbour, scratch, order);
  return order;
}

}  // namespace collide2d
