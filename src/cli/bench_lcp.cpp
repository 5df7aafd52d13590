// collide2d bench lcp (bench_lcp.hpp).
#include "cli/bench_lcp.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "cli/commands.hpp"
#include "cli/parse_options.hpp"
#include "collide2d/numeric/number_mode.hpp"
#include "collide2d/numeric/number_traits.hpp"
#include "collide2d/sim/lcp.hpp"
#include "collide2d/sim/sparse_factor.hpp"
#include "lab/random_queries.hpp"

namespace collide2d::cli {
namespace {

// A contact of the lattice pile: ball a against ball b (or a wall, b < 0),
// its unit normal from b towards a.
struct LatticeContact {
  int a, b;
  double nx, ny;
  bool on_floor() const { return b < 0 && ny == 1; }
};

struct LatticePile {
  std::vector<double> mass;
  std::vector<LatticeContact> contacts;
};

// Hexagonal packing in a box: rows of `width` and `width − 1` balls of
// diameter 1 in turn, the bottom row on the floor, the long rows touching
// both side walls (a row of width diameters spans the box), each ball of a
// short row in the pocket of two below; masses 1 or 2 at random. It stands:
// every ball is at rest under its contacts, so the floor carries the whole
// weight.
LatticePile lattice_pile(int width, int height, SplitMix64& rng) {
  LatticePile pile;
  std::vector<double> x, y;
  for (int row = 0; row < height; ++row)
    for (int i = 0; i < width - row % 2; ++i) {
      x.push_back(i + 0.5 * (row % 2));
      y.push_back(row * std::sqrt(3.0) / 2);
      pile.mass.push_back(rng.uniform(0, 1) < 0.5 ? 1.0 : 2.0);
    }
  const int n = static_cast<int>(x.size());
  for (int a = 0; a < n; ++a) {
    if (y[a] == 0) pile.contacts.push_back({a, -1, 0, 1});
    if (x[a] == 0) pile.contacts.push_back({a, -1, 1, 0});           // the left wall
    if (x[a] == width - 1) pile.contacts.push_back({a, -1, -1, 0});  // the right wall
    for (int b = a + 1; b < n; ++b) {
      const double dx = x[a] - x[b], dy = y[a] - y[b], d = std::sqrt(dx * dx + dy * dy);
      if (d < 1.01) pile.contacts.push_back({a, b, dx / d, dy / d});
    }
  }
  return pile;
}

// A_cd = Σ over the balls x that c and d share of (n_c^x · n_d^x) / m_x,
// n_c^x the normal of c pointing towards x (contact_graph.hpp).
double coupling(const LatticePile& pile, const LatticeContact& c, const LatticeContact& d) {
  double sum = 0;
  for (int side_c = 0; side_c < 2; ++side_c) {
    const int x = side_c == 0 ? c.a : c.b;
    if (x < 0) continue;
    const double sc = side_c == 0 ? 1 : -1;
    for (int side_d = 0; side_d < 2; ++side_d) {
      if ((side_d == 0 ? d.a : d.b) != x) continue;
      const double sd = side_d == 0 ? 1 : -1;
      sum += sc * sd * (c.nx * d.nx + c.ny * d.ny) / pile.mass[static_cast<std::size_t>(x)];
    }
  }
  return sum;
}

template <class Num>
void bench_pile(const std::string& name, const LatticePile& pile, SplitMix64& rng) {
  const std::size_t k = pile.contacts.size();
  std::vector<std::size_t> start(1, 0), column;
  std::vector<Num> entries(k * k), b(k), size(k);
  for (std::size_t r = 0; r < k; ++r) {
    for (std::size_t s = 0; s < k; ++s) {
      const double a = coupling(pile, pile.contacts[r], pile.contacts[s]);
      if (a == 0) continue;
      entries[r * k + s] = num<Num>(a);
      column.push_back(s);
    }
    start.push_back(column.size());
    // b_c: the relative normal acceleration of gravity, zero between two
    // balls and −g against the floor (the pile presses on it).
    const LatticeContact& c = pile.contacts[r];
    b[r] = c.on_floor() ? num<Num>(-9.81) : Num{};
    size[r] = num<Num>(c.b < 0 ? 9.81 : 2 * 9.81);
  }
  const auto entry = [&](std::size_t r, std::size_t s) { return entries[r * k + s]; };
  SparseFactorizer<Num> factorizer;
  std::vector<std::size_t> order;
  factorizer.order_of_whole(k, start, column, order);
  std::vector<std::vector<char>> sets(1, std::vector<char>(k, 1));
  for (int t = 0; t < 31; ++t) {
    std::vector<char> active(k);
    for (char& a : active) a = rng.uniform(0, 1) < 0.85 ? 1 : 0;
    sets.push_back(active);
  }
  SparseFactor<Num> factor;
  const std::size_t factorizations = std::max<std::size_t>(64, 4000000 / (k * k));
  std::size_t fill = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t rep = 0; rep < factorizations; ++rep) {
    factorizer.factor(k, sets[rep % sets.size()], k, start, column, entry, factor, &order);
    fill += factor.lower.size() + factor.upper.size();
  }
  const auto t1 = std::chrono::steady_clock::now();
  // The whole problem, solved from scratch each time (a fresh Lcp's storage
  // kept, as an island's is).
  const std::size_t solves = std::max<std::size_t>(2, 200000 / (k * k));
  std::size_t rounds = 0;
  Lcp<Num> lcp;
  const auto t2 = std::chrono::steady_clock::now();
  for (std::size_t rep = 0; rep < solves; ++rep) {
    lcp.reset(k);
    for (std::size_t r = 0; r < k; ++r)
      for (std::size_t e = start[r]; e < start[r + 1]; ++e) lcp.set(r, column[e], entries[r * k + column[e]]);
    lcp.b = b;
    lcp.size = size;
    lcp.solve();
    rounds += lcp.rounds;
  }
  const auto t3 = std::chrono::steady_clock::now();
  // The floor carries the whole pile: Σ of its contacts' forces = Σ m g.
  double weight = 0, carried = 0;
  for (double m : pile.mass) weight += m * 9.81;
  for (std::size_t r = 0; r < k; ++r)
    if (pile.contacts[r].on_floor()) carried += NumberTraits<Num>::to_double(lcp.x[r]);
  const double factor_us = std::chrono::duration<double, std::micro>(t1 - t0).count() / static_cast<double>(factorizations);
  const double solve_us = std::chrono::duration<double, std::micro>(t3 - t2).count() / static_cast<double>(solves);
  std::printf("%s,%zu,%zu,%zu,%s,%.2f,%zu,%.2f,%.2f,%.3g\n", name.c_str(), pile.mass.size(), k, column.size(),
              NumberTraits<Num>::name, factor_us, fill / factorizations, solve_us,
              static_cast<double>(rounds) / static_cast<double>(solves), std::abs(carried - weight) / weight);
  std::fflush(stdout);
}

}  // namespace

int run_bench_lcp(const BenchLcpOptions& o) {
  std::printf("pile,balls,rows,nonzeros,mode,factor_us,fill,solve_us,rounds,weight_error\n");
  for (const std::int64_t width : o.widths) {
    const int w = static_cast<int>(width), h = std::max(1, static_cast<int>(2 * width / 3));
    const std::string name = "lattice_" + std::to_string(w) + "x" + std::to_string(h);
    for (const std::string& mode : o.modes) {
      SplitMix64 rng(o.seed + static_cast<std::uint64_t>(width));
      const LatticePile pile = lattice_pile(w, h, rng);
      with_number_type(number_mode_of(mode), [&](auto type) { bench_pile<typename decltype(type)::type>(name, pile, rng); });
    }
  }
  return exit_ok;
}

}  // namespace collide2d::cli
