// The LCP solver (lcp.hpp) on problems whose answers are known: a column of
// balls on a floor (every contact carries the weight above it), and random
// contact networks whose answers must meet the complementarity conditions,
// checked from A and b alone.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "collide2d/sim/lcp.hpp"
#include "lcp_networks.hpp"

namespace {

using collide2d::Lcp;
using collide2d::test::matrix_of;
using collide2d::test::next_uniform;
using collide2d::test::random_network;

// A column of n unit-mass balls on a floor under g = 1: contact 0 is the
// floor's (ball 0 alone), contact c > 0 joins balls c − 1 and c. With
// normals all up, A is the tridiagonal 1, 2, 2, ... with −1 off the
// diagonal, and b_c is the relative acceleration: −1 for the floor, 0
// between falling balls.
Lcp<double> column(std::size_t n) {
  Lcp<double> lcp(n);
  for (std::size_t c = 0; c < n; ++c) {
    lcp.set(c, c, c == 0 ? 1.0 : 2.0);
    if (c > 0) lcp.set(c, c - 1, -1.0);
    if (c + 1 < n) lcp.set(c, c + 1, -1.0);
    lcp.b[c] = c == 0 ? -1.0 : 0.0;
    lcp.size[c] = 1.0;
  }
  return lcp;
}

}  // namespace

TEST_CASE("lcp: a column of balls on a floor, each contact carries the weight above it", "[lcp]") {
  // A λ + b = 0 row by row: λ_0 − λ_1 = 1, −λ_{c−1} + 2 λ_c − λ_{c+1} = 0,
  // −λ_{n−2} + 2 λ_{n−1} = 0; the answer is λ_c = n − c (contact c carries
  // the n − c balls from c up). Rounding: elimination without pivoting of a
  // positive definite A errs by at most a small multiple of κ(A) ε |λ|max;
  // this chain's eigenvalues are 2 − 2 cos((2k − 1) π / (2n + 1)), k = 1..n,
  // all below 4 and the smallest ≈ π² / (2n + 1)², so κ < 2 n² for n ≥ 1 and
  // the bound is 64 n³ units of 2^-52 (16 κ ε n). (In minimum-
  // degree order every pivot is 1 and the answer comes out exact.)
  for (std::size_t n : {1u, 2u, 5u, 40u, 400u}) {
    Lcp<double> lcp = column(n);
    REQUIRE(lcp.solve() == n);
    const double bound = 64 * 0x1p-52 * double(n) * double(n) * double(n);
    for (std::size_t c = 0; c < n; ++c) CHECK(std::abs(lcp.x[c] - double(n - c)) <= bound);
  }
}

namespace {

// x ≥ 0 and w = A x + b ≥ 0 with x_r w_r = 0 for every row, each to the
// solver's stated tolerance, 2^-40 of the row's scale, here with a factor 16
// for the products recomputed from A (a copy taken before the solve).
void check_complementarity(const Lcp<double>& lcp, const std::vector<std::vector<double>>& A, int trial) {
  const std::size_t contacts = A.size();
  for (std::size_t r = 0; r < contacts; ++r) {
    double w = lcp.b[r], scale = 1.0 + std::abs(lcp.b[r]);
    for (std::size_t s = 0; s < contacts; ++s) w += A[r][s] * lcp.x[s], scale += std::abs(A[r][s] * lcp.x[s]);
    const double tolerance = 16 * 0x1p-40 * scale;
    INFO("trial " << trial << ", row " << r << " of " << contacts << ": x " << lcp.x[r] << ", w " << w);
    CHECK(lcp.x[r] >= 0);
    CHECK(w >= -tolerance);
    CHECK(std::abs(lcp.x[r] * w) <= tolerance * (1.0 + lcp.x[r]));
  }
}

}  // namespace

TEST_CASE("lcp: random contact networks meet the complementarity conditions", "[lcp]") {
  // N balls with masses in [0.5, 2], C ≤ N contacts: pairs of balls or a
  // ball and a wall, each with a random unit normal; A = J M⁻¹ Jᵀ, b random
  // in [−1, 1]. Most such networks have fewer contacts than any ball set
  // they touch has degrees of freedom; where one is redundant (three
  // contacts on one ball) the forces are not unique, and whichever the
  // solver picks must meet the same conditions.
  std::uint64_t state = 4242;
  auto uniform = [&] { return next_uniform(state); };
  for (int trial = 0; trial < 40; ++trial) {
    const std::size_t balls = 2 + std::size_t(uniform() * 60), contacts = 1 + std::size_t(uniform() * double(balls));
    Lcp<double> lcp;
    random_network(lcp, state, balls, contacts);
    const std::vector<std::vector<double>> A = matrix_of(lcp, contacts);
    REQUIRE(lcp.solve() == contacts);
    check_complementarity(lcp, A, trial);
  }
}

TEST_CASE("lcp: with holds, every row pushes, is held, or parts at least hold_below", "[lcp]") {
  // An impact holds its slow partings (contact_graph.hpp): a row that would
  // part slower than hold_below is held as an equation (w = 0, any x) as
  // soon as a pivoting round meets it. Whatever the rounds met, the answer
  // must be one of the model's: every row held with w = 0, or pushing
  // (x > 0, w = 0), or touching, or parting at hold_below or faster, and
  // no row pulling unless held. Checked from A and b alone, on the random
  // networks above with the parting threshold a third of b's scale.
  std::uint64_t state = 12345;
  auto uniform = [&] { return next_uniform(state); };
  int trials_with_holds = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const std::size_t balls = 2 + std::size_t(uniform() * 60), contacts = 1 + std::size_t(uniform() * double(balls));
    Lcp<double> lcp;
    random_network(lcp, state, balls, contacts);
    const std::vector<std::vector<double>> A = matrix_of(lcp, contacts);
    const double hold_below = 1.0 / 3.0;
    lcp.holds = true;
    lcp.hold_below = hold_below;
    REQUIRE(lcp.solve() == contacts);
    bool held = false;
    for (std::size_t r = 0; r < contacts; ++r) {
      double w = lcp.b[r], scale = 1.0 + std::abs(lcp.b[r]);
      for (std::size_t s = 0; s < contacts; ++s) w += A[r][s] * lcp.x[s], scale += std::abs(A[r][s] * lcp.x[s]);
      const double tolerance = 16 * 0x1p-40 * scale;
      INFO("trial " << trial << ", row " << r << " of " << contacts << ": x " << lcp.x[r] << ", w " << w
                    << (lcp.equality[r] ? " (held)" : ""));
      if (lcp.equality[r]) {
        held = true;
        CHECK(std::abs(w) <= tolerance);
        continue;
      }
      CHECK(lcp.x[r] >= 0);
      CHECK(w >= -tolerance);
      CHECK(std::abs(lcp.x[r] * w) <= tolerance * (1.0 + lcp.x[r]));
      if (w > tolerance) CHECK(w >= hold_below - tolerance);
    }
    trials_with_holds += held ? 1 : 0;
  }
  CHECK(trials_with_holds >= 10);  // the check above met held rows, not only free ones
}

TEST_CASE("lcp: redundant contact networks, more contacts than freedoms, meet the complementarity conditions",
          "[lcp]") {
  // As above with C from N to 3 N contacts and b = J v: a pile's islands
  // struck, where every ball has several partners and the impulses are far
  // from unique. Whatever answer the solver ends on must meet the
  // conditions. On trials 28 and 29 (59 and 78 contacts) the pivoting
  // cycles to its cap and 64 plain sweeps leave rows off by up to 2.5e-3
  // of their speeds; the over-relaxed sweeps with exact solves that follow
  // (lcp.hpp, finish) find the answers.
  std::uint64_t state = 777;
  auto uniform = [&] { return next_uniform(state); };
  for (int trial = 0; trial < 40; ++trial) {
    const std::size_t balls = 2 + std::size_t(uniform() * 40);
    const std::size_t contacts = balls + std::size_t(uniform() * double(2 * balls));
    Lcp<double> lcp;
    random_network(lcp, state, balls, contacts, true);
    const std::vector<std::vector<double>> A = matrix_of(lcp, contacts);
    REQUIRE(lcp.solve() == contacts);
    check_complementarity(lcp, A, trial);
  }
}

TEST_CASE("lcp: a problem solved in a reused Lcp gives the bits of a fresh one", "[lcp]") {
  // The contact graph keeps one Lcp for all its islands: reset() zeroes only
  // the entries the last problem set, and each pivoting round only the
  // entries its elimination touched. An entry left over from an earlier
  // (often larger) problem would change the answer, or what a(r, s) reads
  // back where nothing was set (strike_along_free_part reads every pair).
  Lcp<double> reused;
  std::uint64_t seed = 99;
  for (int trial = 0; trial < 60; ++trial) {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    const std::size_t balls = 2 + (seed >> 33) % 50, contacts = 1 + (seed >> 20) % (2 * balls);
    std::uint64_t fresh_state = seed, reused_state = seed;
    Lcp<double> fresh;
    random_network(fresh, fresh_state, balls, contacts);
    random_network(reused, reused_state, balls, contacts);
    INFO("trial " << trial << ": " << contacts << " rows");
    REQUIRE(reused.solve() == fresh.solve());
    CHECK(reused.rounds == fresh.rounds);
    for (std::size_t r = 0; r < contacts; ++r) {
      CHECK(std::bit_cast<std::uint64_t>(reused.x[r]) == std::bit_cast<std::uint64_t>(fresh.x[r]));
      for (std::size_t s = 0; s < contacts; ++s) CHECK(reused.a(r, s) == fresh.a(r, s));
    }
  }
}

TEST_CASE("lcp: a factor kept from an earlier solve of the same matrix gives the bits of a fresh one", "[lcp]") {
  // An island's problem comes back with the same A and another b (every
  // strike's refinement step; an island struck again before its contacts
  // changed): the Lcp then uses the factors of A_SS it made before
  // (sparse_factor.hpp) and does only the substitutions, which must give the
  // very bits a fresh Lcp computes, for complementary rows and for a strike
  // (an equation solved last), and must actually be used.
  Lcp<double> reused;
  std::uint64_t seed = 7;
  std::size_t used = 0;
  for (int trial = 0; trial < 60; ++trial) {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    const std::size_t balls = 2 + (seed >> 33) % 50, contacts = 1 + (seed >> 20) % (2 * balls);
    const bool strike = trial % 2 == 1;
    std::uint64_t other_b = seed ^ 0x9e3779b97f4a7c15ULL;
    std::vector<double> b2(contacts);
    for (double& v : b2) {
      other_b = other_b * 6364136223846793005ULL + 1442695040888963407ULL;
      v = 2 * (double(other_b >> 11) * 0x1p-53) - 1;
    }
    // The reused Lcp has solved the matrix with and without the strike
    // before: a factor is kept for its rows and for its last row both.
    auto pose = [&](Lcp<double>& lcp, bool second, bool struck) {
      std::uint64_t state = seed;
      random_network(lcp, state, balls, contacts);
      if (second) lcp.b = b2;
      if (struck) lcp.equality[contacts - 1] = 1, lcp.forced = contacts - 1;
    };
    pose(reused, false, !strike);
    reused.solve();
    pose(reused, false, strike);
    reused.solve();
    pose(reused, true, strike);
    Lcp<double> fresh;
    pose(fresh, true, strike);
    INFO("trial " << trial << ": " << contacts << " rows" << (strike ? ", the last a strike" : ""));
    REQUIRE(reused.solve() == fresh.solve());
    CHECK(fresh.factors_reused == 0);
    used += reused.factors_reused;
    CHECK(reused.rounds == fresh.rounds);
    CHECK(reused.active == fresh.active);
    for (std::size_t r = 0; r < contacts; ++r)
      CHECK(std::bit_cast<std::uint64_t>(reused.x[r]) == std::bit_cast<std::uint64_t>(fresh.x[r]));
  }
  // At least the first round (every row active) of most last solves: a
  // factor is given up after eight newer ones, which the two solves before
  // may make.
  CHECK(used >= 30);
}

TEST_CASE("lcp: a pivoting cycle skipped ends where running it out to the cap ends, to the bit", "[lcp]") {
  // Murty's single steps on a redundant network can cycle (rounding makes
  // rows breach that no order of pivots satisfies) until the cap of
  // 4 k + 16 rounds; from a set met again the rounds repeat, so the solver
  // jumps to the set the cap would end on. The same networks solved with
  // the cycles run out must give the same x, active set and count of
  // rounds, after the sweeps that follow as well; and some must cycle.
  std::uint64_t state = 777;
  auto uniform = [&] { return next_uniform(state); };
  std::size_t skipped = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const std::size_t balls = 2 + std::size_t(uniform() * 40);
    const std::size_t contacts = balls + std::size_t(uniform() * double(2 * balls));
    std::uint64_t state_a = state, state_b = state;
    Lcp<double> skipping, running;
    running.skips_cycles = false;
    random_network(skipping, state_a, balls, contacts, true);
    random_network(running, state_b, balls, contacts, true);
    state = state_a;
    INFO("trial " << trial << ": " << contacts << " rows");
    REQUIRE(skipping.solve() == running.solve());
    CHECK(running.cycles_skipped == 0);
    skipped += skipping.cycles_skipped;
    CHECK(skipping.rounds == running.rounds);
    CHECK(skipping.active == running.active);
    for (std::size_t r = 0; r < contacts; ++r)
      CHECK(std::bit_cast<std::uint64_t>(skipping.x[r]) == std::bit_cast<std::uint64_t>(running.x[r]));
  }
  CHECK(skipped >= 2);
}
