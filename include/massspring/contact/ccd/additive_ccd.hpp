#pragma once
/// @file
/// @brief Continuous collision detection of point-triangle and edge-edge pairs moving on straight
/// lines over one time step, by additive CCD (conservative advancement).
///
/// After Li, Kaufman and Jiang, "Codimensional Incremental Potential Contact", ACM Transactions on
/// Graphics 40(4), 2021, section 5 (additive CCD); written from the idea.
///
/// Motion: every corner moves as x_i(t) = x_i + t dx_i, t in [0, 1] (positions [m], displacements
/// [m] over the step, t a fraction of the step). d(t) is the distance between the two elements
/// (point and triangle, or segment and segment) and xi = min_distance [m] the contact distance.
///
/// Rate bound: the distance is unchanged when every corner moves by the same vector, so the mean
/// displacement m = (1/4) sum dx_i is subtracted first: p_i = dx_i - m. For any pair of points of
/// the two elements, with barycentric weights alpha of the first and beta of the second, the
/// difference moves at speed |sum alpha_i p_i - sum beta_j p_j| <= max_i |p_i| + max_j |p_j| = L,
/// and a minimum of L-Lipschitz functions is L-Lipschitz: |d'(t)| <= L.
///
/// Advancement: with the gap G(t) = d(t) - xi_eff (xi_eff = xi plus the rounding margin below),
/// the step from t is dt = (1 - s) G(t) / L with s = kAccdStopFraction = 0.1. Over [t, t + dt]
/// the distance stays >= xi_eff + s G(t) > xi. It stops:
/// - with a hit and toi = t once G(t) <= s G(0) (the pair came within a tenth of the start gap);
/// - with no hit when t + dt >= 1 (the step covers the rest of the time step);
/// - with a hit and toi = t when max_iterations distance evaluations are spent (conservative:
///   a false positive costs the caller speed, a miss would be a defect).
/// Every step is bounded below by (1 - s) s G(0) / L, so the loop ends. A pair moving together
/// (L = 0) costs no iteration. A hit's toi has d(toi) >= xi and no contact in [0, toi]; a pair
/// that reaches xi anywhere in [0, 1] is reported as a hit. A pair that comes closer than
/// xi_eff + s G(0) without reaching xi may be reported as a hit (a false positive).
///
/// Rounding: every candidate closest pair the distance routines evaluate is a pair of points of
/// the elements (contact/distance/edge_edge.hpp, point_triangle.hpp), so the computed distance
/// exceeds the exact one by no more than a few units of rounding of the coordinates' size
/// S = max |x_i| + 2 max |dx_i| (infinity norms), which bounds every position the loop forms. The
/// contact distance is therefore raised by margin = kAccdMarginUlps eps S (eps the Scalar's
/// machine epsilon, kAccdMarginUlps = 64), and L by a relative 16 eps. Not covered: a triangle
/// thinner than about sqrt(eps) times its size, whose face-region closest point may be off by up
/// to the triangle's width (point_triangle_squared_distance). A start distance <= xi_eff is a hit
/// at toi = 0; NaN or infinite input is a hit at toi = 0. No allocation, no exceptions.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "massspring/contact/distance/edge_edge.hpp"
#include "massspring/contact/distance/point_triangle.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The answer of a continuous collision query over t in [0, 1].
template <class Scalar>
struct CcdResult {
  /// @brief The distance may reach min_distance during [0, 1] (false: it certainly does not).
  bool hit = false;
  /// @brief On a hit, a time in [0, 1] at which the distance is still >= min_distance and which
  /// is <= the true first time the distance reaches min_distance; 1 when there is no hit.
  Scalar toi = 1;
  /// @brief Distance evaluations after the start one (the cost of the query).
  int iterations = 0;
};

/// @brief The fraction s of the start gap at which the advancement stops with a hit; the step is
/// (1 - s) of the gap over the rate bound.
inline constexpr double kAccdStopFraction = 0.1;
/// @brief The rounding margin added to min_distance, in machine epsilons of the coordinates' size.
inline constexpr double kAccdMarginUlps = 64;

// Not named detail: massspring::contact::detail would hide massspring::detail from code in
// massspring::contact that writes detail::.
namespace additive_ccd_detail {

/// @brief Additive CCD of a pair of elements with four corners in all: corners [0, first) are the
/// first element, [first, 4) the second. distance(x) returns the distance of corners x.
template <class Scalar, class Distance>
CcdResult<Scalar> additive_ccd(const Vector3<Scalar> (&x)[4], const Vector3<Scalar> (&dx)[4],
                               int first, const Distance& distance, Scalar min_distance,
                               int max_iterations) {
  using V = Vector3<Scalar>;
  constexpr Scalar eps = std::numeric_limits<Scalar>::epsilon();
  CcdResult<Scalar> hit_at_start;
  hit_at_start.hit = true;
  hit_at_start.toi = 0;

  const V mean = Scalar(0.25) * (dx[0] + dx[1] + dx[2] + dx[3]);
  V p[4];
  Scalar max_first = 0, max_second = 0, size_x = 0, size_dx = 0;
  for (int i = 0; i < 4; ++i) {
    p[i] = dx[i] - mean;
    Scalar& max_own = i < first ? max_first : max_second;
    max_own = std::max(max_own, p[i].norm());
    size_x = std::max(size_x, x[i].cwiseAbs().maxCoeff());
    size_dx = std::max(size_dx, dx[i].cwiseAbs().maxCoeff());
  }
  const Scalar rate = (max_first + max_second) * (1 + 16 * eps);
  const Scalar margin = Scalar(kAccdMarginUlps) * eps * (size_x + 2 * size_dx);
  const Scalar xi = min_distance + margin;
  if (!std::isfinite(rate) || !std::isfinite(margin) || !std::isfinite(xi)) return hit_at_start;

  Scalar gap = distance(x) - xi;
  if (!(gap > 0)) return hit_at_start;  // also NaN
  CcdResult<Scalar> result;
  if (!(rate > 0)) return result;  // the pair moves rigidly: the distance never changes
  const Scalar s = Scalar(kAccdStopFraction);
  const Scalar stop_gap = s * gap;
  Scalar t = 0;
  V xt[4];
  while (true) {
    const Scalar dt = (1 - s) * gap / rate;
    if (t + dt >= 1) return result;  // no contact on [t, 1]
    if (result.iterations >= max_iterations) break;
    t += dt;
    for (int i = 0; i < 4; ++i) xt[i] = x[i] + t * p[i];
    ++result.iterations;
    gap = distance(xt) - xi;
    if (!(gap > stop_gap)) break;  // also NaN
  }
  result.hit = true;
  result.toi = t;
  return result;
}

}  // namespace additive_ccd_detail

/// @brief Continuous collision of point p with triangle (a, b, c) over x(t) = x0 + t dx, t in
/// [0, 1]; min_distance [m] >= 0. See the file comment for the contract and the margin.
template <class Scalar>
CcdResult<Scalar> point_triangle_ccd(const Vector3<Scalar>& p, const Vector3<Scalar>& a,
                                     const Vector3<Scalar>& b, const Vector3<Scalar>& c,
                                     const Vector3<Scalar>& dp, const Vector3<Scalar>& da,
                                     const Vector3<Scalar>& db, const Vector3<Scalar>& dc,
                                     Scalar min_distance, int max_iterations = 64) {
  const Vector3<Scalar> x[4] = {p, a, b, c}, dx[4] = {dp, da, db, dc};
  const auto distance = [](const Vector3<Scalar>(&y)[4]) {
    return std::sqrt(point_triangle_squared_distance(y[0], y[1], y[2], y[3]));
  };
  return additive_ccd_detail::additive_ccd(x, dx, 1, distance, min_distance, max_iterations);
}

/// @brief Continuous collision of segment [a0, a1] with segment [b0, b1] over x(t) = x0 + t dx,
/// t in [0, 1]; min_distance [m] >= 0. See the file comment for the contract and the margin.
template <class Scalar>
CcdResult<Scalar> edge_edge_ccd(const Vector3<Scalar>& a0, const Vector3<Scalar>& a1,
                                const Vector3<Scalar>& b0, const Vector3<Scalar>& b1,
                                const Vector3<Scalar>& da0, const Vector3<Scalar>& da1,
                                const Vector3<Scalar>& db0, const Vector3<Scalar>& db1,
                                Scalar min_distance, int max_iterations = 64) {
  const Vector3<Scalar> x[4] = {a0, a1, b0, b1}, dx[4] = {da0, da1, db0, db1};
  const auto distance = [](const Vector3<Scalar>(&y)[4]) {
    return std::sqrt(edge_edge_distance(y[0], y[1], y[2], y[3]).squared_distance);
  };
  return additive_ccd_detail::additive_ccd(x, dx, 2, distance, min_distance, max_iterations);
}

}  // namespace massspring::contact
