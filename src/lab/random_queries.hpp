// Reproducible random time-of-impact queries, by family, for benchmarks and
// properties. Own generator and own uniform mapping (std distributions differ
// between standard libraries), so a seed gives the same queries everywhere.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "collide2d/toi/query.hpp"

namespace collide2d {

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  // Uniform in [lo, hi) with 53 random bits.
  double uniform(double lo, double hi) {
    const double u = static_cast<double>(next() >> 11) * 0x1p-53;
    return lo + (hi - lo) * u;
  }

 private:
  std::uint64_t state_;
};

// The benchmark families of `collide2d bench toi`.
enum class QueryFamily { wall, wall_gravity, ball_quadratic, ball_quartic };
std::string to_string(QueryFamily f);
const std::vector<QueryFamily>& all_query_families();

// A valid query (no overlap at t = 0) of the family: a ball in a 10 × 10
// region with speeds up to 10 and horizon 1, against a random wall (length 1
// to 10) or ball (radius 0.05 to 1). ball_quadratic: two balls under the same
// gravity (linear relative motion); ball_quartic: a ball under gravity
// against a fixed ball. About half of the queries hit.
ToiQuery random_query(QueryFamily family, SplitMix64& rng);

}  // namespace collide2d
