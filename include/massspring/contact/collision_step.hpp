#pragma once
/// @file
/// @brief CollisionStep: the one per-step contact state. commit_step() (integrators/detail/
/// commit_step.hpp) builds it once per step, after the integrator proposed the end state, and
/// every response takes it: the system's CollisionHandler, the colliders' point response
/// (ColliderSet::respond()) and surface contact (SurfaceContact::resolve()).

#include <vector>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief One step as the responses see it. Arrays are #points by 3 (vectors #points), borrowed
/// for the call.
template <class Scalar>
struct CollisionStep {
  /// @brief Positions at the start of the step [m].
  const Points<Scalar>& x_start;
  /// @brief Velocities at the start of the step [m/s].
  const Points<Scalar>& v_start;
  /// @brief Positions the integrator computed for the end of the step [m]; a response may change
  /// them.
  Points<Scalar>& x_end;
  /// @brief Velocities the integrator computed for the end of the step [m/s]; a response may
  /// change them.
  Points<Scalar>& v_end;
  /// @brief The step [s], > 0.
  Scalar dt;
  /// @brief Masses [kg], each > 0.
  const Vector<Scalar>& masses;
  /// @brief Inverse masses [1/kg]: 1 / m, and 0 for a pinned point (immobile, infinite mass)
  /// (MassSpringSystem::inverse_masses()).
  const Vector<Scalar>& inverse_masses;
  /// @brief Pinned (FOSSSim's fixed) points, ascending: never moved by a response.
  const std::vector<int>& pinned;
};

}  // namespace massspring::contact
