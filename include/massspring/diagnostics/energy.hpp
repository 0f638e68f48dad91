#pragma once
/// @file
/// @brief Energies and momentum of a system's current state.

#include <Eigen/Core>

#include "massspring/forces/evaluate.hpp"
#include "massspring/system/mass_spring_system.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief Kinetic energy 1/2 sum_i m_i |v_i|^2 [J].
template <class System>
typename System::Scalar kinetic_energy(const System& system) {
  return typename System::Scalar(0.5) *
         (system.masses().array() * system.velocities().rowwise().squaredNorm().array()).sum();
}

/// @brief Potential energy of the current positions [J] (springs and every term that has one).
template <class System>
typename System::Scalar potential_energy(const System& system) {
  return potential_energy(system, system.positions());
}

/// @brief Kinetic plus potential energy [J].
template <class System>
typename System::Scalar total_energy(const System& system) {
  return kinetic_energy(system) + potential_energy(system);
}

/// @brief Linear momentum sum_i m_i v_i [kg m/s].
template <class System>
Vector3<typename System::Scalar> linear_momentum(const System& system) {
  return (system.velocities().transpose() * system.masses());
}

}  // namespace massspring
