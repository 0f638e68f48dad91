#pragma once
/// @file
/// @brief The energy bound every integrator checks before it commits a step: a proposed end state
/// whose energy exceeds E(0) + growth S is a blow-up, reported and not committed.

#include <cmath>
#include <limits>

#include "massspring/forces/evaluate.hpp"

namespace massspring::detail {

/// @brief The energy scale S of a system's current state [J], and its total energy E (kinetic of
/// every point plus potential) in `energy`:
///
///     S = |E| + K + sum_e k_e l0_e^2 / 2 + D sum_i |F_i(x, v)|
///
/// (K the kinetic energy, the springs' energy when stretched to twice their rest length, and the
/// work the current forces do over D, the diagonal of the bounding box). A motion that stays
/// bounded by the scene's own size cannot release that much energy. Allocates (one force array).
template <class System>
double energy_scale(const System& system, double& energy) {
  using PointsType = typename System::PointsType;
  const PointsType& x = system.positions();
  const PointsType& v = system.velocities();
  const double kinetic =
      0.5 * double((system.masses().array() * v.rowwise().squaredNorm().array()).sum());
  energy = kinetic + double(potential_energy(system, x));
  double scale = std::abs(energy) + kinetic;
  for (int e = 0; e < system.num_springs(); ++e) {
    const double l0 = double(system.rest_lengths()(e));
    scale += 0.5 * double(system.stiffness()(e)) * l0 * l0;
  }
  if (system.num_points() > 0) {
    const double diagonal = double((x.colwise().maxCoeff() - x.colwise().minCoeff()).norm());
    PointsType f;
    total_force(system, x, v, f);
    scale += diagonal * double(f.rowwise().norm().sum());
  }
  return scale;
}

/// @brief A step's energy limit, taken when the integrator is prepared: a proposed end state
/// (x, v) blows up when
///
///     K_free(v) + U(x) > E(0) + growth S
///
/// with K_free the kinetic energy of the points that are not pinned (a pin's velocity is its
/// target's, set by the caller), U the potential of the springs and of every force term that has
/// one (forces/evaluate.hpp), and E(0), S the energy and scale of energy_scale() at reset(). An
/// integrator that is stable never passes it: implicit Euler and the local-global solver only
/// dissipate, and moving pins add work bounded by the springs they stretch. `growth` 0 turns the
/// check off; the limit is +infinity when E(0) or S is not finite.
///
/// Cost of exceeded(): one pass over the springs and the terms' energies. Allocates nothing.
template <class System>
class EnergyBound {
 public:
  using PointsType = typename System::PointsType;

  /// @brief Takes E(0) and S from the system's current state (allocates).
  void reset(const System& system, double growth) {
    growth_ = growth;
    if (!(growth > 0)) {
      limit_ = std::numeric_limits<double>::infinity();
      return;
    }
    double energy = 0;
    const double scale = energy_scale(system, energy);
    limit_ = std::isfinite(energy) && std::isfinite(scale)
                 ? energy + growth * scale
                 : std::numeric_limits<double>::infinity();
  }

  /// @brief True when the state (x, v), #points by 3, has more energy than limit().
  [[nodiscard]] bool exceeded(const System& system, const PointsType& x,
                              const PointsType& v) const {
    if (!(growth_ > 0) || std::isinf(limit_)) return false;
    double kinetic = 0;
    const auto& masses = system.masses();
    for (Eigen::Index i = 0; i < x.rows(); ++i)
      if (!system.is_pinned(int(i))) kinetic += double(masses(i)) * double(v.row(i).squaredNorm());
    const double energy = 0.5 * kinetic + double(potential_energy(system, x));
    return !(energy <= limit_);  // NaN included
  }

  /// @brief E(0) + growth S [J]; +infinity when the check is off.
  [[nodiscard]] double limit() const { return limit_; }

 private:
  double growth_ = 0;
  double limit_ = std::numeric_limits<double>::infinity();
};

}  // namespace massspring::detail
