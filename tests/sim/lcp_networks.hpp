// Random contact networks for the tests of the complementarity solver and
// its eliminations (test_lcp.cpp, test_sparse_factor.cpp): A = J M⁻¹ Jᵀ of
// random contacts between balls and walls, as an island's problem is made.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "collide2d/sim/lcp.hpp"

namespace collide2d::test {

// The tests' generator: a 64-bit LCG, uniform in [0, 1) from its top 53 bits.
inline double next_uniform(std::uint64_t& state) {
  state = state * 6364136223846793005ULL + 1442695040888963407ULL;
  return double(state >> 11) * 0x1p-53;
}

// A random contact network of `contacts` rows among `balls` balls (unit
// normals at random angles, masses in [0.5, 2], j == balls a wall), written
// into `lcp` after a reset with only the entries of rows that share a ball
// set: the pattern a pile's island gives.
// With `from_velocities`, b = J v for random ball velocities v in [−1, 1]²
// (an impact's right-hand side), which makes every such problem solvable
// however redundant the network: it is the optimality condition of the
// least-kinetic-energy change that stops every contact closing, and u = 0
// is allowed. Otherwise b is random in [−1, 1].
inline void random_network(Lcp<double>& lcp, std::uint64_t& state, std::size_t balls, std::size_t contacts,
                           bool from_velocities = false) {
  auto uniform = [&] { return next_uniform(state); };
  std::vector<double> inverse_mass(balls);
  for (double& w : inverse_mass) w = 1.0 / (0.5 + 1.5 * uniform());
  std::vector<double> vx(balls), vy(balls);  // drawn only when used, so the plain networks stay as they were
  if (from_velocities)
    for (std::size_t x = 0; x < balls; ++x) vx[x] = 2 * uniform() - 1, vy[x] = 2 * uniform() - 1;
  struct Contact {
    std::size_t i, j;
    double nx, ny;
  };
  std::vector<Contact> net;
  for (std::size_t c = 0; c < contacts; ++c) {
    const std::size_t i = std::size_t(uniform() * double(balls));
    std::size_t j = std::size_t(uniform() * double(balls + 1));
    if (j == i) j = balls;
    const double angle = 6.283185307179586 * uniform();
    net.push_back({i, j, std::cos(angle), std::sin(angle)});
  }
  lcp.reset(contacts);
  for (std::size_t r = 0; r < contacts; ++r) {
    for (std::size_t s = 0; s < contacts; ++s) {
      double sum = 0;
      bool shared = false;
      for (std::size_t x : {net[r].i, net[r].j}) {
        if (x == balls || (x != net[s].i && x != net[s].j)) continue;
        shared = true;
        const double sc = x == net[r].i ? 1.0 : -1.0, sd = x == net[s].i ? 1.0 : -1.0;
        sum += sc * sd * (net[r].nx * net[s].nx + net[r].ny * net[s].ny) * inverse_mass[x];
      }
      if (shared) lcp.set(r, s, sum);
    }
    if (from_velocities) {
      const Contact& c = net[r];  // n·(v_i − v_j), a wall at rest
      lcp.b[r] = c.nx * vx[c.i] + c.ny * vy[c.i] - (c.j == balls ? 0.0 : c.nx * vx[c.j] + c.ny * vy[c.j]);
    } else {
      lcp.b[r] = 2 * uniform() - 1;
    }
    lcp.size[r] = 1.0;
  }
}

// A's entries, dense (a copy taken before a solve).
inline std::vector<std::vector<double>> matrix_of(const Lcp<double>& lcp, std::size_t contacts) {
  std::vector<std::vector<double>> A(contacts, std::vector<double>(contacts));
  for (std::size_t r = 0; r < contacts; ++r)
    for (std::size_t s = 0; s < contacts; ++s) A[r][s] = lcp.a(r, s);
  return A;
}

}  // namespace collide2d::test
