// A small dense linear complementarity problem, solved exactly.
//
//     w = A x + b,   x_r ≥ 0,  w_r ≥ 0,  x_r w_r = 0   (complementary rows)
//                    w_r = 0                           (equality rows)
//
// A is symmetric positive (semi)definite here (contact_graph.hpp), for which
// Murty's least-index principal pivoting ends: start with every row active
// (w = 0), solve A_SS x_S = −b_S, and flip the lowest-numbered row that
// breaks its sign condition (an active row pulling, x_r < 0, or an inactive
// one sinking, w_r < 0, each beyond its inputs' rounding, 2^-40 of `size`),
// until none does. Equality rows never flip. Every step is a fixed sequence
// of +, −, ×, ÷ in the caller's number type: the same bits everywhere.
#pragma once

#include <cstddef>
#include <vector>

#include "numeric/number_traits.hpp"

namespace collide2d {

template <class Num>
struct Lcp {
  std::vector<std::vector<Num>> A;
  std::vector<Num> b, size;  // size: the scale of row r's inputs (for the rounding tolerance)
  std::vector<char> equality, active;
  std::vector<Num> x;

  explicit Lcp(std::size_t k)
      : A(k, std::vector<Num>(k, Num{})), b(k, Num{}), size(k, Num{}), equality(k, 0), active(k, 1), x(k, Num{}) {}

  // Returns the row of a zero pivot (A_SS singular), or the number of rows.
  std::size_t solve() {
    // Equality rows are eliminated first (cheap and well posed in almost
    // every case); if that leaves the conditions breached (a strike in a
    // wedge whose walls are nearly parallel: the held contact is judged
    // redundant), once more with them last, where their own equation is
    // solved however small its pivot; projected Gauss–Seidel finishes what
    // neither order could.
    const std::vector<char> start = active;
    equalities_first_ = true;
    std::size_t singular = pivot();
    if (singular < b.size() || !(violation() > 0)) return singular;
    const std::vector<Num> first_x = x;
    const std::vector<char> first_active = active;
    const double first_violation = violation();
    active = start;
    equalities_first_ = false;
    singular = pivot();
    if (singular < b.size() || first_violation < violation()) x = first_x, active = first_active;
    if (violation() > 0) polish();
    return b.size();
  }

 private:
  bool equalities_first_ = true;

  std::size_t pivot() {
    const std::size_t k = b.size();
    const Num rounding = num<Num>(0x1p-40);
    for (std::size_t iteration = 0; iteration < 64 * k + 64; ++iteration) {
      std::size_t singular = k;
      if (!solve_active(singular)) return singular;
      bool flipped = false;
      for (std::size_t r = 0; r < k && !flipped; ++r) {
        if (equality[r]) continue;
        Num w = b[r];
        for (std::size_t s = 0; s < k; ++s) w = w + A[r][s] * x[s];
        const Num tolerance = rounding * size[r];
        if ((active[r] && x[r] * A[r][r] < -tolerance) || (!active[r] && w < -tolerance)) {
          active[r] = !active[r];
          flipped = true;
        }
      }
      if (!flipped) break;
    }
    for (std::size_t r = 0; r < k; ++r)
      if (!equality[r] && x[r] < Num{}) x[r] = Num{};  // a push within rounding of none
    return k;
  }

 public:

  // How far x is from a solution: the largest breach of a row's condition
  // beyond its tolerance (0 when x solves the problem).
  double violation() const {
    double worst = 0;
    for (std::size_t r = 0; r < b.size(); ++r) {
      const Num w = residual(r);
      const double tolerance = NumberTraits<Num>::to_double(tolerance_of(r));
      const double wd = NumberTraits<Num>::to_double(w);
      double breach = 0;
      if (equality[r] || x[r] > Num{}) breach = wd < 0 ? -wd : wd;
      else breach = -wd;
      if (breach - tolerance > worst) worst = breach - tolerance;
    }
    return worst;
  }

 private:
  // 2^-40 of the scale of row r's terms: its inputs and each A_rs x_s.
  Num tolerance_of(std::size_t r) const {
    auto magnitude = [](const Num& v) { return v < Num{} ? -v : v; };
    Num scale = size[r] + magnitude(b[r]);
    for (std::size_t s = 0; s < b.size(); ++s) scale = scale + magnitude(A[r][s] * x[s]);
    return num<Num>(0x1p-40) * scale;
  }
  Num residual(std::size_t r) const {
    Num w = b[r];
    for (std::size_t s = 0; s < b.size(); ++s) w = w + A[r][s] * x[s];
    return w;
  }

  // Redundant contacts can leave the pivoting with a dependent row that
  // sinks (its conditions cannot be met by the rows before it). Projected
  // Gauss–Seidel then finishes the job from there: each row in turn takes
  // the x that zeroes its w, clamped at 0 for a complementary row; sweeps
  // repeat until no row breaches its tolerance or 64 k + 256 sweeps have
  // run. It converges for any positive semidefinite A with a positive
  // diagonal, and every step is in a fixed order.
  void polish() {
    const std::size_t k = b.size();
    for (std::size_t sweep = 0; sweep < 64 * k + 256; ++sweep) {
      for (std::size_t r = 0; r < k; ++r) {
        if (!(Num{} < A[r][r])) continue;
        Num next = x[r] - residual(r) / A[r][r];
        if (!equality[r] && next < Num{}) next = Num{};
        x[r] = next;
      }
      if ((sweep & 7) == 7 && !(violation() > 0)) break;
    }
    for (std::size_t r = 0; r < k; ++r) active[r] = equality[r] || x[r] > Num{} || !(tolerance_of(r) < residual(r));
  }

 public:

 private:
  // x on the active rows solves A_SS x_S = −b_S, zero elsewhere, by
  // symmetric Gaussian elimination in row order (A is symmetric positive
  // semidefinite, for which this is stable without pivoting). Contacts of a
  // pile are often redundant (more contacts than the balls have degrees of
  // freedom): a row whose pivot has fallen to rounding, 2^-36 of its
  // diagonal, depends on the rows before it; its unknown is set to zero and
  // the others carry it (the forces of a redundant pile are not unique, any
  // admissible choice is as good; this one is fixed by the row order). An
  // equality row is solved unless its pivot is exactly zero: its impulse
  // may be large, the velocities it gives are not.
  bool solve_active(std::size_t& singular) {
    (void)singular;
    const Num zero{};
    const std::size_t k = b.size();
    std::vector<std::size_t> S;
    for (int pass = 0; pass < 2; ++pass)
      for (std::size_t r = 0; r < k; ++r)
        if (active[r] && (equality[r] != 0) == (equalities_first_ == (pass == 0))) S.push_back(r);
    const std::size_t m = S.size();
    std::vector<std::vector<Num>> M(m, std::vector<Num>(m + 1, zero));
    for (std::size_t r = 0; r < m; ++r) {
      for (std::size_t s = 0; s < m; ++s) M[r][s] = A[S[r]][S[s]];
      M[r][m] = -b[S[r]];
    }
    std::vector<char> dependent(m, 0);
    const Num small = num<Num>(0x1p-36);
    for (std::size_t col = 0; col < m; ++col) {
      const Num pivot = M[col][col];
      if (equality[S[col]] ? pivot == zero : !(small * A[S[col]][S[col]] < pivot)) {
        dependent[col] = 1;
        continue;
      }
      for (std::size_t r = col + 1; r < m; ++r) {
        const Num f = M[r][col] / pivot;
        if (f == zero) continue;
        for (std::size_t s = col; s <= m; ++s) M[r][s] = M[r][s] - f * M[col][s];
      }
    }
    std::vector<Num> xs(m, zero);
    for (std::size_t col = m; col-- > 0;) {
      if (dependent[col]) continue;
      Num sum = M[col][m];
      for (std::size_t s = col + 1; s < m; ++s) sum = sum - M[col][s] * xs[s];
      xs[col] = sum / M[col][col];
    }
    x.assign(k, zero);
    for (std::size_t r = 0; r < m; ++r) x[S[r]] = xs[r];
    return true;
  }
};

}  // namespace collide2d
