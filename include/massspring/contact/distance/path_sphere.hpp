#pragma once
/// @file
/// @brief A straight path p(s) = a + s d, s in [0, 1], against a sphere centred at the origin, in
/// closed form: the parameter of the path's point nearest to the centre, and the parameter where
/// the path enters the ball of radius rho. Units: those of a and d (metres in the colliders).

#include <algorithm>
#include <cmath>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The s in [0, 1] that minimises |a + s d|: clamp(-a.d / |d|^2, 0, 1), 0 when d = 0.
template <class Scalar>
Scalar path_nearest_to_origin(const Vector3<Scalar>& a, const Vector3<Scalar>& d) {
  const Scalar dd = d.squaredNorm();
  return dd > 0 ? std::clamp(-a.dot(d) / dd, Scalar(0), Scalar(1)) : Scalar(0);
}

/// @brief Where a path that starts outside the ball of radius rho enters it: the smaller root s
/// of |a + s d|^2 = rho^2, written as c0 / q with c0 = |a|^2 - rho^2 = (|a| - rho)(|a| + rho)
/// (`norm_a` = |a|) and q = -a.d + sqrt((a.d)^2 - |d|^2 c0), which does not cancel because a.d < 0
/// on the way in (Press et al., Numerical Recipes, 3rd ed., section 5.6). False, s unchanged, when
/// the path does not head in (a.d >= 0) or misses the ball.
template <class Scalar>
bool path_enters_ball(const Vector3<Scalar>& a, const Vector3<Scalar>& d, Scalar norm_a, Scalar rho,
                      Scalar& s) {
  const Scalar ad = a.dot(d);
  const Scalar c0 = std::max(Scalar(0), (norm_a - rho) * (norm_a + rho));
  const Scalar disc = ad * ad - d.squaredNorm() * c0;
  if (!(ad < 0 && disc >= 0)) return false;
  s = c0 / (std::sqrt(disc) - ad);
  return true;
}

}  // namespace massspring::contact
