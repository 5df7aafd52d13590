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
// vanishing A is the linear case (the b < 0 branch gives C / (|b| + |b|)).
// The discriminant is passed as a function so that it is only computed when
// a root can matter. D < 0: no real root, w never reaches
// zero. A root before t = 0 is not a contact here; a contact already under
// way at t = 0 is the caller's business (only it knows what "overlap" means).
template <class Num, class Discriminant>
RootSearch<Num> first_downward_root(const Num& A, const Num& b, const Num& C, Discriminant discriminant,
                                    const Num& horizon) {
  using T = NumberTraits<Num>;
  const Num zero{};
  if (!(b < zero) && !(A < zero)) return {};  // A ≥ 0, b ≥ 0: w only grows after its dip before t = 0
  if (A == zero) {                            // linear: w = 2 b t + C with b < 0
    const Num t = C / -(b + b);
    if (t < zero || horizon < t) return {};
    return {true, t};
  }
  const Num D = discriminant();
  if (D < zero) return {};
  const Num sqrt_d = T::sqrt(D);
  const Num t = b < zero ? C / (sqrt_d - b) : -(b + sqrt_d) / A;  // sqrt_d - b > 0; A < 0
  if (t < zero || horizon < t) return {};
  return {true, t};
}

// b² − A C to about 2 ulp in strict mode, even for near-double roots
// (Kahan's test). The plain difference is used when it loses at most two
// bits to cancellation (|D| ≥ (b² + |AC|) / 4); otherwise both products are
// formed exactly (TwoProduct) and subtracted.
template <class Num>
Num compensated_discriminant(const Num& A, const Num& b, const Num& C) {
  using T = NumberTraits<Num>;
  const Num bb = b * b, ac = A * C;
  const Num plain = bb - ac;
  if (!(T::abs(plain) < T::half(T::half(bb + T::abs(ac))))) return plain;
  return T::diff_of_products(b, b, A, C);
}

}  // namespace collide2d
