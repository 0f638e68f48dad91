#pragma once
/// @file
/// @brief GravitationalAttraction: Newtonian attraction between listed pairs of points.

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "massspring/detail/validate.hpp"
#include "massspring/forces/force_term.hpp"
#include "massspring/forces/springs.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief Attraction between pairs (i, j) with constant G [N m^2/kg^2]:
/// E = -G m_i m_j / r, F_i = G m_i m_j d / r^3 (towards j), with d = x_j - x_i and
/// r = sqrt(|d|^2 + eps^2), eps the softening length [m] (default 0: exact Newton).
///
/// Only the listed pairs are evaluated; all_pairs() lists every pair of n points (O(n^2): ask for
/// it only when you mean it).
template <class Scalar>
class GravitationalAttraction {
 public:
  struct Pair {
    int i, j;
    Scalar G;
  };

  GravitationalAttraction() = default;
  /// @param[in] pairs     point pairs (i != j) and their G (finite, >= 0); indices are checked
  ///                      against the system when the term is added to it.
  /// @param[in] softening eps [m], finite and >= 0.
  explicit GravitationalAttraction(std::vector<Pair> pairs, Scalar softening = 0)
      : pairs_(std::move(pairs)), softening_(softening), eps2_(softening * softening) {
    detail::require_number("gravitational attraction", "softening length", double(softening),
                           false);
    for (std::size_t k = 0; k < pairs_.size(); ++k) {
      const Pair& p = pairs_[k];
      if (p.i < 0 || p.j < 0)
        throw Error(detail::message("gravitational attraction pair ", k, " = (", p.i, ", ", p.j,
                                    "): negative point index"));
      if (p.i == p.j)
        throw Error(detail::message("gravitational attraction pair ", k, " attracts point ", p.i,
                                    " to itself"));
      detail::require_number(detail::message("gravitational attraction pair ", k).c_str(), "G",
                             double(p.G), false);
    }
  }
  /// @brief Every pair of n points with the same G.
  static GravitationalAttraction all_pairs(int n, Scalar G, Scalar softening = 0) {
    std::vector<Pair> pairs;
    pairs.reserve(std::size_t(n) * std::size_t(n > 0 ? n - 1 : 0) / 2);
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) pairs.push_back({i, j, G});
    return GravitationalAttraction(std::move(pairs), softening);
  }

  [[nodiscard]] const std::vector<Pair>& pairs() const { return pairs_; }
  /// @brief The softening length eps [m], as given.
  [[nodiscard]] Scalar softening() const { return softening_; }
  /// @brief Largest point index used (-1 when there are no pairs).
  [[nodiscard]] int max_index() const {
    int m = -1;
    for (const Pair& p : pairs_) m = std::max({m, p.i, p.j});
    return m;
  }

  static constexpr bool velocity_dependent = false;
  [[nodiscard]] const char* name() const { return "gravitational attraction"; }

  void add_force(const ForceContext<Scalar>& c, Points<Scalar>& f) const {
    for (const Pair& p : pairs_) {
      const Vector3<Scalar> d = (c.x.row(p.j) - c.x.row(p.i)).transpose();
      const Scalar r2 = d.squaredNorm() + eps2_;
      const Scalar r = std::sqrt(r2);
      const Vector3<Scalar> fi = (p.G * c.masses(p.i) * c.masses(p.j) / (r2 * r)) * d;
      f.row(p.i) += fi.transpose();
      f.row(p.j) -= fi.transpose();
    }
  }
  [[nodiscard]] Scalar energy(const ForceContext<Scalar>& c) const {
    Scalar sum = 0;
    for (const Pair& p : pairs_) {
      const Scalar r = std::sqrt((c.x.row(p.j) - c.x.row(p.i)).squaredNorm() + eps2_);
      sum -= p.G * c.masses(p.i) * c.masses(p.j) / r;
    }
    return sum;
  }
  void add_dfdx(const ForceContext<Scalar>& c, JacobianSink<Scalar>& jac) const {
    using M3 = Eigen::Matrix<Scalar, 3, 3>;
    for (const Pair& p : pairs_) {
      const Vector3<Scalar> d = (c.x.row(p.j) - c.x.row(p.i)).transpose();
      const Scalar r2 = d.squaredNorm() + eps2_;
      const Scalar r = std::sqrt(r2);
      const Scalar a = p.G * c.masses(p.i) * c.masses(p.j) / (r2 * r);
      // dF_i/dx_j = a (I - 3 d d^T / r^2).
      M3 block = a * (M3::Identity() - Scalar(3) / r2 * d * d.transpose());
      if (c.definite) {
        // Eigenvalues: a across d, a (1 - 3 |d|^2 / r^2) along d; clamp the latter at 0.
        const Scalar l2 = d.squaredNorm();
        const M3 nn = l2 > 0 ? M3(d * d.transpose() / l2) : M3(M3::Zero());
        block = a * (M3::Identity() - nn) + std::max(Scalar(0), a * (1 - Scalar(3) * l2 / r2)) * nn;
      }
      detail::add_pair_blocks(jac, p.i, p.j, block);
    }
  }

 private:
  std::vector<Pair> pairs_;
  Scalar softening_ = 0;
  Scalar eps2_ = 0;
};

}  // namespace massspring
