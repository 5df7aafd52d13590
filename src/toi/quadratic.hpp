// The one root of a quadratic that is a contact.
#pragma once

#include "numeric/number_traits.hpp"

namespace collide2d {

template <class Num>
struct RootSearch {
  bool found = false;
  Num t{};
};

// w(t) = A t² + 2 b t + C, the signed clearance of a contact (w > 0: apart).
// Returns the time in [0, H] at which w crosses from positive to zero while
// decreasing (w' = 2(A t + b) ≤ 0), never the time it becomes positive again:
// only a contact, never a separation. A quadratic has at most one such root:
//
//     t_down = (−b − √D) / A,   D = b² − A C.
//
// Written so that nothing cancels (the q-form): for b < 0 the same root is
// C / (√D − b), whose denominator adds two positive numbers; for b ≥ 0 it is
// −(b + √D) / A. The caller passes D, computed the most accurate way its
// geometry allows (compensated, or Lagrange's identity for linear motion). A
// vanishing A is the linear case −C / 2b. D < 0: no real root, w never reaches
// zero. A root before t = 0 is not a contact here; a contact already under
// way at t = 0 is the caller's business (only it knows what "overlap" means).
template <class Num>
RootSearch<Num> first_downward_root(const Num& A, const Num& b, const Num& C, const Num& D,
                                    const Num& horizon) {
  using T = NumberTraits<Num>;
  const Num zero{};
  if (D < zero) return {};
  const Num sqrt_d = T::sqrt(D);
  Num t;
  if (b < zero) {
    t = C / (sqrt_d - b);  // sqrt_d - b > 0
  } else {
    if (!(A < zero)) return {};  // A ≥ 0, b ≥ 0: w only grows after its dip before t = 0
    t = -(b + sqrt_d) / A;
  }
  if (t < zero || horizon < t) return {};
  return {true, t};
}

// b² − A C to 1.5 ulp in strict mode (Kahan's compensated discriminant).
template <class Num>
Num compensated_discriminant(const Num& A, const Num& b, const Num& C) {
  return NumberTraits<Num>::diff_of_products(b, b, A, C);
}

}  // namespace collide2d
