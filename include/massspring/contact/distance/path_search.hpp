#pragma once
/// @file
/// @brief One-dimensional searches along a path parameter s in [0, 1]: the minimum of a unimodal
/// function (golden-section search) and the last point of an interval where a predicate holds
/// (bisection). The colliders use them for a point's straight path against a convex solid, whose
/// signed distance is convex along the path.

#include <algorithm>
#include <limits>
#include <utility>

namespace massspring::contact {

/// @brief The minimiser s in [0, 1] of a unimodal f and f(s), by golden-section search (Kiefer
/// 1953; Press et al., Numerical Recipes, 3rd ed., section 10.2): each of the `iterations` steps
/// evaluates f once and shrinks the bracket by 1 / phi = 0.618, so 60 steps reach 3e-13.
template <class Scalar, class F>
std::pair<Scalar, Scalar> golden_section_minimum(const F& f, int iterations = 60) {
  const Scalar shrink = Scalar(0.6180339887498949);  // (sqrt(5) - 1) / 2
  Scalar lo = 0, hi = 1, s1 = hi - shrink * (hi - lo), s2 = lo + shrink * (hi - lo);
  Scalar f1 = f(s1), f2 = f(s2);
  for (int k = 0; k < iterations; ++k) {
    if (f1 < f2) {
      hi = s2, s2 = s1, f2 = f1;
      s1 = hi - shrink * (hi - lo);
      f1 = f(s1);
    } else {
      lo = s1, s1 = s2, f1 = f2;
      s2 = lo + shrink * (hi - lo);
      f2 = f(s2);
    }
  }
  return f1 < f2 ? std::pair<Scalar, Scalar>{s1, f1} : std::pair<Scalar, Scalar>{s2, f2};
}

/// @brief For a predicate that holds at lo and fails at hi, with one change between: the last
/// point found where it holds, by bisection (at most `halvings` halvings, and none once the
/// bracket is below machine epsilon). Returns lo when lo == hi.
template <class Scalar, class Predicate>
Scalar bisect_last(const Predicate& holds, Scalar lo, Scalar hi, int halvings = 48) {
  for (int k = 0; k < halvings && hi - lo > std::numeric_limits<Scalar>::epsilon(); ++k) {
    const Scalar mid = (lo + hi) / 2;
    if (holds(mid))
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

}  // namespace massspring::contact
