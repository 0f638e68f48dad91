#pragma once
// Uniform forces as force terms on a system (forces/gravity.hpp), for the tests: gravity, an
// acceleration g [m/s^2] (F_i = m_i g), and one force f [N] on every point whatever its mass.
#include <massspring/forces/gravity.hpp>
#include <massspring/types.hpp>

namespace massspring::test {

template <class System>
void add_gravity(System& system, const Vector3<typename System::Scalar>& g) {
  system.add_force(Gravity<typename System::Scalar>(g));
}

template <class System>
void add_uniform_force(System& system, const Vector3<typename System::Scalar>& f) {
  system.add_force(ConstantForce<typename System::Scalar>(f));
}

}  // namespace massspring::test
