// The grid of nearby pairs finds every pair that overlaps, as the plain
// double loop does, so the checks built on it (overlap at t = 0, the deepest
// overlap of a frame) say what the loop would.
#include <catch2/catch.hpp>

#include <cmath>
#include <set>
#include <utility>

#include "collide2d/geometry/nearby_pairs.hpp"
#include "collide2d/sim/simulate.hpp"

using namespace collide2d;

namespace {

struct Scatter {
  std::vector<Vec2<double>> centre;
  std::vector<double> radius;
};

// n balls in a square of side `side`, radii from r/4 to r (a fixed LCG), so
// that some overlap; `far_ones`: every 97th a million sides away, so that
// the grid is too wide to be dense and the pairs are found by sorting.
Scatter scatter(std::size_t n, double side, double r, std::uint64_t seed, bool far_ones = true) {
  Scatter s;
  auto uniform = [&] {  // in [0, 1)
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(seed >> 11) * 0x1p-53;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const double far = far_ones && i % 97 == 3 ? 1e6 : 1.0;
    s.centre.push_back({far * side * uniform() - side / 2, side * uniform() - side / 2});
    s.radius.push_back(r * (0.25 + 0.75 * uniform()));
  }
  return s;
}

}  // namespace

TEST_CASE("nearby pairs: every overlapping pair is visited once, as by the plain loop", "[geometry]") {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    for (bool far_ones : {true, false}) {  // sorted cells, dense grid
      const Scatter s = scatter(700, 20, 0.5, seed, far_ones);
      double r_max = 0;
      for (double r : s.radius) r_max = std::max(r_max, r);
      std::set<std::pair<std::size_t, std::size_t>> visited, overlapping_found, overlapping;
      for_each_nearby_pair(s.centre.size(), r_max, [&](std::size_t i) { return s.centre[i]; },
                           [&](std::size_t i, std::size_t k) {
                             REQUIRE(i < k);
                             REQUIRE(visited.insert({i, k}).second);  // once
                             if (length(s.centre[i] - s.centre[k]) < s.radius[i] + s.radius[k]) overlapping_found.insert({i, k});
                           });
      for (std::size_t i = 0; i < s.centre.size(); ++i)
        for (std::size_t k = i + 1; k < s.centre.size(); ++k)
          if (length(s.centre[i] - s.centre[k]) < s.radius[i] + s.radius[k]) overlapping.insert({i, k});
      INFO("seed " << seed << (far_ones ? ", some far away" : ", all near"));
      CHECK(overlapping.size() > 20);                 // the scatter does overlap
      CHECK(visited.size() < 700 * 699 / 2 / 10);     // and the grid visited far fewer than all pairs
      CHECK(overlapping_found == overlapping);
    }
  }
}

// Overlapping pairs far from the lowest ball, a few ulps apart: their
// offsets from it carry rounding errors larger than a cell of 2 r_max, which
// once put them two or more cells apart (nearby_pairs.hpp derives the cell
// that prevents it). Each case: a far ball at -Y, two at X and X + k ulps
// whose radii make them overlap; the grid must visit that pair. The grid of
// 2 r_max (1 + 1e-9) missed 192 of these 20000 pairs; the halved coordinates
// also keep a ball at 1.7e308 from overflowing the offsets.
TEST_CASE("nearby pairs: overlapping balls far from the others, a few ulps apart, are visited", "[geometry]") {
  std::uint64_t seed = 2024;
  auto uniform = [&] {  // in [0, 1)
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(seed >> 11) * 0x1p-53;
  };
  int cases = 0, missed = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double X = std::pow(10.0, 3 + 12 * uniform()) * (uniform() < 0.5 ? -1 : 1);
    const double Y = trial % 100 == 0 ? 1.7e308 : std::pow(10.0, 3 + 12 * uniform());
    double b = X;
    for (int k = 1 + static_cast<int>(50 * uniform()); k > 0; --k) b = std::nextafter(b, INFINITY);
    const double r = (b - X) * (0.51 + uniform());  // 2r > the distance: they overlap
    const std::vector<Vec2<double>> c = {{-Y, 0}, {X, 0}, {b, 0}};
    bool visited = false;
    for_each_nearby_pair(c.size(), r, [&](std::size_t i) { return c[i]; },
                         [&](std::size_t i, std::size_t k) { visited = visited || (i == 1 && k == 2); });
    ++cases;
    if (!visited) ++missed;
  }
  CHECK(cases == 20000);
  CHECK(missed == 0);
}

TEST_CASE("nearby pairs: a non-finite centre is left out, the others still checked", "[geometry]") {
  std::vector<Vec2<double>> c = {{0, 0}, {NAN, 0}, {0.5, 0}, {INFINITY, 1}};
  std::set<std::pair<std::size_t, std::size_t>> visited;
  for_each_nearby_pair(c.size(), 0.5, [&](std::size_t i) { return c[i]; },
                       [&](std::size_t i, std::size_t k) { visited.insert({i, k}); });
  CHECK(visited == std::set<std::pair<std::size_t, std::size_t>>{{0, 2}});
}

TEST_CASE("deepest overlap of a frame: the plain loop's answer", "[geometry]") {
  const Scatter s = scatter(500, 15, 0.5, 7);
  FrameRecord f;
  for (const Vec2<double>& c : s.centre) f.position.insert(f.position.end(), {c.x, c.y});
  const std::vector<std::array<double, 4>> walls = {{-7, -7, 7, -7}, {-7, -7, -7, 7}};
  double plain = 0;
  for (std::size_t i = 0; i < s.centre.size(); ++i) {
    for (std::size_t k = i + 1; k < s.centre.size(); ++k)
      plain = std::max(plain, s.radius[i] + s.radius[k] - length(s.centre[i] - s.centre[k]));
    for (const auto& w : walls)
      plain = std::max(plain, s.radius[i] - distance_to_segment(s.centre[i], Segment<double>{{w[0], w[1]}, {w[2], w[3]}}));
  }
  CHECK(plain > 0.1);
  CHECK(deepest_overlap(f, s.radius, walls) == plain);
}

TEST_CASE("nearby pairs: an extent that leaves a centre out is refused, not overrun", "[geometry]") {
  const std::vector<Vec2<double>> c = {{0, 0}, {0.5, 0}, {9, 9}};
  auto centre = [&](std::size_t i) { return c[i]; };
  NearbyExtent e;
  for (std::size_t i = 0; i < 2; ++i) e.include(c[i]);  // not the third
  ++e.finite_count;
  CHECK_THROWS_AS(for_each_nearby_pair_within(e, c.size(), 0.5, centre, [](std::size_t, std::size_t) {}),
                  std::logic_error);
  NearbyExtent whole;
  for (const auto& x : c) whole.include(x);
  std::size_t pairs = 0;
  for_each_nearby_pair_within(whole, c.size(), 0.5, centre, [&](std::size_t, std::size_t) { ++pairs; });
  CHECK(pairs == 1);
}
