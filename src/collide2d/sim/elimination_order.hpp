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

// `for_each_neighbour(a, visit)` calls visit(b) for every row b < n that
// row a couples to (b ≠ a). Returns a permutation of 0 .. n − 1.
template <class ForEachNeighbour>
std::vector<std::size_t> minimum_degree_order(std::size_t n, ForEachNeighbour for_each_neighbour) {
  const std::size_t words = (n + 63) / 64;
  std::vector<std::uint64_t> neighbours(n * words, 0), alive(words, 0);
  auto row = [&](std::size_t a) { return neighbours.data() + a * words; };
  auto set = [](std::uint64_t* bits, std::size_t b) { bits[b / 64] |= std::uint64_t{1} << (b % 64); };
  for (std::size_t a = 0; a < n; ++a) {
    set(alive.data(), a);
    for_each_neighbour(a, [&](std::size_t b) {
      if (b != a) set(row(a), b), set(row(b), a);
    });
  }
  auto degree_of = [&](std::size_t a) {
    std::size_t d = 0;
    for (std::size_t w = 0; w < words; ++w) d += static_cast<std::size_t>(std::popcount(row(a)[w] & alive[w]));
    return d;
  };
  std::vector<std::size_t> degree(n), order;
  for (std::size_t a = 0; a < n; ++a) degree[a] = degree_of(a);
  std::vector<char> done(n, 0);
  std::vector<std::uint64_t> clique(words);
  for (std::size_t step = 0; step < n; ++step) {
    std::size_t pick = n;
    for (std::size_t a = 0; a < n; ++a)
      if (!done[a] && (pick == n || degree[a] < degree[pick])) pick = a;
    order.push_back(pick);
    done[pick] = 1;
    alive[pick / 64] &= ~(std::uint64_t{1} << (pick % 64));
    for (std::size_t w = 0; w < words; ++w) clique[w] = row(pick)[w] & alive[w];
    for (std::size_t w = 0; w < words; ++w)
      for (std::uint64_t bits = clique[w]; bits != 0; bits &= bits - 1) {
        const std::size_t b = w * 64 + static_cast<std::size_t>(std::countr_zero(bits));
        for (std::size_t v = 0; v < words; ++v) row(b)[v] |= clique[v];
        row(b)[b / 64] &= ~(std::uint64_t{1} << (b % 64));
        degree[b] = degree_of(b);
      }
  }
  return order;
}

}  // namespace collide2d
