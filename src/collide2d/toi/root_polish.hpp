// Safeguarded Newton iteration on an interval where a function is monotone.
#pragma once

#include "collide2d/numeric/number_traits.hpp"

namespace collide2d {

// f(lo), f(hi) have opposite signs (or f(hi) is zero) and f has one root in
// [lo, hi]. `eval(t)` returns {f(t), f'(t)}. Newton steps from `lo` (or `hi`
// with start_at_hi: the end where f f'' > 0, from which Newton approaches the
// root from one side without overshooting, when f is convex or concave on
// the interval) are kept only
// while they stay strictly inside the shrinking bracket and halve it at least
// every two steps; otherwise the step is a bisection. Stops when no number of
// the type lies between two iterates, or between the bracket ends: the root is
// then as accurate as f can be evaluated. Deterministic: no tolerance depends
// on anything but the number type.
template <class Num, class Eval>
Num polish_root_monotone(Eval eval, Num lo, Num hi, bool f_lo_positive, bool start_at_hi = false) {
  using T = NumberTraits<Num>;
  const Num zero{};
  Num t = start_at_hi ? hi : lo;
  Num step = hi - lo, step_before = hi - lo;
  for (int i = 0; i < T::max_root_iterations; ++i) {
    const auto [f, df] = eval(t);
    if (f == zero) return t;
    if ((zero < f) == f_lo_positive) lo = t; else hi = t;
    if (T::no_value_between(lo, hi)) break;
    // Newton's step f / f' is only formed when it is shorter than the bracket, so
    // it never overflows (a fixed-point division would throw). A step too
    // small to move t is convergence; a step that leaves the bracket, or has
    // not halved since the step before last (slow convergence), is replaced
    // by a bisection (as in rtsafe).
    Num next{};
    bool bisect = !(T::abs(f) < T::abs(df) * (hi - lo));
    if (!bisect) {
      const Num newton_step = f / df;
      next = t - newton_step;
      if (next < t ? T::no_value_between(next, t) : T::no_value_between(t, next)) return next;
      bisect = !(lo < next && next < hi) || T::half(T::abs(step_before)) < T::abs(newton_step);
    }
    if (bisect) next = lo + T::half(hi - lo);
    step_before = step;
    step = next - t;
    t = next;
  }
  // The bracket end on the far side of the root (where f has f(hi)'s sign).
  return hi;
}

}  // namespace collide2d
