#pragma once
/// @file
/// @brief The energy bound every integrator checks before it commits a step: a proposed end state
/// whose energy exceeds the step's start energy by more than growth times the scene's energy
/// scale is a blow-up, reported and not committed.

#include <Eigen/Core>
#include <algorithm>
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

/// @brief A step's energy limit: a proposed end state (x, v) from the start state (x0, v0) the
/// system holds blows up when
///
///     E(x, v) > E(x0, v0) + growth (S + S_c),   E(x, v) = K_free(v) + U(x)
///
/// with K_free the kinetic energy of the points that are not pinned (a pin's velocity is its
/// target's, set by the caller), U the potential of the springs and of every force term that has
/// one (forces/evaluate.hpp), S the scale of energy_scale() taken at reset(), and
/// S_c = 2 M V^2 the most kinetic energy the colliders can give in one step (M the total mass, V
/// the largest speed of a collider's surface over the points' bounding box, |v| + |w| r, r the
/// farthest corner from its reference point; 2 V for a full rebound). A step of an integrator that
/// is stable never passes it: implicit Euler and the local-global solver only dissipate, and
/// moving pins and colliders add, per step, work bounded by the springs they stretch and by S_c.
/// The limit is per step, so a driver that adds energy slowly for a long time (a lift, a
/// conveyor) never trips it, while a blow-up, whose energy grows by a factor each step, does.
/// `growth` 0 turns the check off, as does a scale that is not finite.
///
/// The end-of-step collision response has a limit of its own (contact_exceeded()): the energy it
/// adds to the end state, W = E(after) - E(before), blows the step up when
///
///     W > S / 2 + S_c.
///
/// Its impulses, projections and rigid zones are inelastic: they never add kinetic energy beyond
/// what moving colliders give (S_c), and they change the potential only by stretching the springs
/// around the points they move. S / 2 is the springs' energy with every spring 71% longer than at
/// rest (S counts every spring at twice its rest length): a response that adds that much in one
/// step has pushed points through the cloth's own springs, which feeds on itself over the
/// next steps (docs/contact.md, Limits).
///
/// Cost of exceeded(): two passes over the springs and the terms' energies, one over the points.
/// Allocates nothing.
template <class System>
class EnergyBound {
 public:
  using PointsType = typename System::PointsType;

  /// @brief Takes S from the system's current state (allocates).
  void reset(const System& system, double growth) {
    growth_ = growth;
    scale_ = 0;
    if (!(growth > 0)) return;
    double energy = 0;
    scale_ = energy_scale(system, energy);
    if (!std::isfinite(energy) || !std::isfinite(scale_)) growth_ = 0;
  }

  /// @brief True when the state (x, v), #points by 3, has more energy than limit(system).
  [[nodiscard]] bool exceeded(const System& system, const PointsType& x,
                              const PointsType& v) const {
    if (!(growth_ > 0)) return false;
    return exceeded(system, energy(system, x, v));
  }

  /// @brief exceeded() for a state whose energy(system, x, v) is `end_energy` [J].
  [[nodiscard]] bool exceeded(const System& system, double end_energy) const {
    if (!(growth_ > 0)) return false;
    return !(end_energy <= limit(system));  // NaN included
  }

  /// @brief True when a collision response that added `work` [J] to a step's end state added
  /// more than contact_limit(system) (the class comment); false when the check is off.
  [[nodiscard]] bool contact_exceeded(const System& system, double work) const {
    if (!(growth_ > 0)) return false;
    return !(work <= contact_limit(system));  // NaN included
  }

  /// @brief The most energy [J] the collision response may add to a step's end state:
  /// S / 2 + S_c; +infinity when the check is off.
  [[nodiscard]] double contact_limit(const System& system) const {
    if (!(growth_ > 0)) return std::numeric_limits<double>::infinity();
    return kContactShare * scale_ + collider_scale(system);
  }

  /// @brief The share of the energy scale S the collision response may add in one step.
  static constexpr double kContactShare = 0.5;

  /// @brief True when a step that takes one linear solve towards the minimum of its incremental
  /// potential phi (linearised BackwardEuler without the contact term) ended with phi higher than
  /// at the step's starting guess by more than kModelShare S: its linear model failed (an
  /// indefinite matrix, or a step far beyond the springs' curvature) and the end state is not
  /// implicit Euler's. phi_guess, phi_end [J]. False when the check is off.
  [[nodiscard]] bool uphill(double phi_guess, double phi_end) const {
    if (!(growth_ > 0)) return false;
    return !(phi_end - phi_guess <= kModelShare * scale_);  // NaN included
  }

  /// @brief True when the checks are on (growth > 0 and a finite scale at reset()).
  [[nodiscard]] bool on() const { return growth_ > 0; }

  /// @brief The share of S by which a linearised step may raise its incremental potential
  /// (rounding is about 1e-15 of it).
  static constexpr double kModelShare = 1e-6;

  /// @brief The most energy [J] a step from the system's current state may end with:
  /// E(x0, v0) + growth (S + S_c); +infinity when the check is off.
  [[nodiscard]] double limit(const System& system) const {
    if (!(growth_ > 0)) return std::numeric_limits<double>::infinity();
    return energy(system, system.positions(), system.velocities()) +
           growth_ * (scale_ + collider_scale(system));
  }

  /// @brief E(x, v) = K_free(v) + U(x) [J] of the class comment: the kinetic energy of the points
  /// that are not pinned plus the potential of the springs and force terms.
  static double energy(const System& system, const PointsType& x, const PointsType& v) {
    double kinetic = 0;
    const auto& masses = system.masses();
    for (Eigen::Index i = 0; i < x.rows(); ++i)
      if (!system.is_pinned(int(i))) kinetic += double(masses(i)) * double(v.row(i).squaredNorm());
    return 0.5 * kinetic + double(potential_energy(system, x));
  }

 private:
  // S_c = 2 M V^2 [J] (see the class).
  static double collider_scale(const System& system) {
    const auto& colliders = system.colliders();
    if (colliders.size() == 0 || system.num_points() == 0) return 0;
    const auto& x = system.positions();
    // Evaluated once (a lazy expression would reduce over the points at every corner).
    const Eigen::Matrix<double, 1, 3> low = x.colwise().minCoeff().template cast<double>(),
                                      high = x.colwise().maxCoeff().template cast<double>();
    double speed = 0;
    for (int c = 0; c < colliders.size(); ++c) {
      const auto& collider = colliders[c];
      double reach = 0;  // farthest corner of the box from the collider's reference point [m]
      for (int corner = 0; corner < 8; ++corner) {
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
          const double coordinate = (corner >> k) & 1 ? high(k) : low(k);
          const double d = coordinate - double(collider.translation()(k));
          d2 += d * d;
        }
        reach = std::max(reach, std::sqrt(d2));
      }
      speed = std::max(speed, double(collider.velocity().norm()) +
                                  double(collider.angular_velocity().norm()) * reach);
    }
    return 2 * double(system.masses().sum()) * speed * speed;
  }

  double growth_ = 0;
  double scale_ = 0;
};

}  // namespace massspring::detail
