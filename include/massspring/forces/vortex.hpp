#pragma once
/// @file
/// @brief VortexForce: FOSSSim's vortex force (Theme 1, VortexForce::addGradEToTotal,
/// scene t1m3/VortexExample.xml): particle j swirls around particle i.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/forces/force_term.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief For each pair (i, j) with d = x_j - x_i, r = |d|:
/// \f[ F_j = \frac{k_{vc}}{r^2}\left(k_{bs}\, \hat z \times \frac{d}{r} - (v_j - v_i)\right),
/// \qquad F_i = -F_j \f]
/// a tangential push of strength kbs (z^ x d / r is d / r turned 90 degrees counter-clockwise in
/// the plane z = 0: FOSSSim's (-d_y, d_x) / r) against the relative velocity, both falling off
/// as 1 / r^2. kbs [m/s], kvc [kg m^2 / s]: F in N. Internal: F_i + F_j = 0.
///
/// FOSSSim defines no energy and no Jacobians for it (its addEnergyToTotal and addHess*
/// exit with "No energy defined for VortexForce"), so neither is given here: implicit
/// integrators treat the term explicitly. Velocity-dependent. Coincident points (r = 0) give a
/// non-finite force, as in FOSSSim.
template <class Scalar>
class VortexForce {
 public:
  struct Pair {
    int i, j;
    Scalar kbs, kvc;
  };

  VortexForce() = default;
  /// @param[in] pairs  (i, j, kbs, kvc), i != j, kbs and kvc finite; indices are checked against
  ///                   the system when the term is added to it.
  explicit VortexForce(std::vector<Pair> pairs) : pairs_(std::move(pairs)) {
    for (std::size_t k = 0; k < pairs_.size(); ++k) {
      const Pair& p = pairs_[k];
      if (p.i < 0 || p.j < 0)
        throw Error(
            detail::message("vortex force ", k, " = (", p.i, ", ", p.j, "): negative point index"));
      if (p.i == p.j)
        throw Error(
            detail::message("vortex force ", k, " acts between point ", p.i, " and itself"));
      if (!std::isfinite(double(p.kbs)) || !std::isfinite(double(p.kvc)))
        throw Error(detail::message("vortex force ", k, ": kbs and kvc must be finite, got ", p.kbs,
                                    " and ", p.kvc));
    }
  }

  [[nodiscard]] const std::vector<Pair>& pairs() const { return pairs_; }
  [[nodiscard]] int max_index() const {
    int m = -1;
    for (const Pair& p : pairs_) m = std::max({m, p.i, p.j});
    return m;
  }
  static constexpr bool velocity_dependent = true;
  [[nodiscard]] const char* name() const { return "vortex force"; }

  void add_force(const ForceContext<Scalar>& c, Points<Scalar>& f) const {
    for (const Pair& p : pairs_) {
      const Vector3<Scalar> d = (c.x.row(p.j) - c.x.row(p.i)).transpose();
      const Scalar r = d.norm();
      const Vector3<Scalar> turned = Vector3<Scalar>::UnitZ().cross(d) / r;
      const Vector3<Scalar> dv = (c.v.row(p.j) - c.v.row(p.i)).transpose();
      const Vector3<Scalar> fj = (p.kvc / (r * r)) * (p.kbs * turned - dv);
      f.row(p.j) += fj.transpose();
      f.row(p.i) -= fj.transpose();
    }
  }

 private:
  std::vector<Pair> pairs_;
};

}  // namespace massspring
