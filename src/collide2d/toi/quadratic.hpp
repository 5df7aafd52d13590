// The one root of a quadratic that is a contact.
#pragma once

#include <algorithm>

#include "collide2d/numeric/number_traits.hpp"

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
  check_in_range(A, "a contact quadratic");
  check_in_range(b, "a contact quadratic");
  check_in_range(C, "a contact quadratic");
  if (!(b < zero) && !(A < zero)) return {};  // A ≥ 0, b ≥ 0: w only grows after its dip before t = 0
  // t = numerator / denominator with denominator > 0.
  Num numerator, denominator;
  if (A == zero) {  // linear: w = 2 b t + C with b < 0
    numerator = C;
    denominator = -(b + b);
  } else {
    const Num D = discriminant();
    check_in_range(D, "a contact discriminant");
    if (D < zero) return {};
    const Num sqrt_d = T::sqrt(D);
    numerator = b < zero ? C : b + sqrt_d;
    denominator = b < zero ? sqrt_d - b : -A;  // sqrt_d - b > 0; A < 0
  }
  // A root before 0 or far past the horizon is refused before dividing: in
  // fixed point the quotient of a nearly vanishing denominator could
  // overflow. (Only roots below 0 or beyond H + 1 are refused here, which
  // the checks after the division refuse anyway: the outcome never differs.)
  const Num one = num<Num>(1.0);
  if (numerator < zero) return {};
  if (denominator < one && (horizon + one) * denominator < numerator) return {};
  const Num t = numerator / denominator;
  if (t < zero || horizon < t) return {};
  return {true, t};
}

// The roots of A t² + 2 b t + C depend only on the ratios A : b : C. Fixed
// point rounds to an absolute 2^-64, so a quadratic of tiny coefficients
// (a ball and wall of size 2^-16 give coefficients near 2^-31 and D near
// 2^-62: a few units) would lose its discriminant. Scaling all three by one
// power of two, a shift, is exact and brings the largest to [2^14, 2^15),
// where b² and A C still fit (< 2^31) with 78 bits each. Floating point
// rounds relatively and is left alone.
template <class Num>
void normalise_quadratic(Num& A, Num& b, Num& C) {
  using T = NumberTraits<Num>;
  if constexpr (T::rounds_absolutely) {
    const int largest = std::max({T::exponent(A), T::exponent(b), T::exponent(C)});
    const int k = 14 - largest;
    if (largest < -Num::fraction_bits || k <= 0) return;  // all zero, or large enough already
    A = T::times_power_of_two(A, k);
    b = T::times_power_of_two(b, k);
    C = T::times_power_of_two(C, k);
  }
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
