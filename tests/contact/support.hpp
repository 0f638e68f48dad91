#pragma once
// Small builders shared by the contact tests: 3-vectors, geometries, a CollisionStep.
#include <Eigen/Core>
#include <massspring/contact/collision_handler.hpp>
#include <massspring/contact/fosssim/geometry.hpp>
#include <vector>

namespace massspring::test {

using V3 = massspring::Vector3<double>;
using Pts = massspring::Points<double>;

inline V3 v3(double x, double y, double z = 0) { return V3(x, y, z); }

/// @brief n particles of radius r, no edge, no plane.
inline contact::ContactGeometry<double> particles(int n, double r) {
  contact::ContactGeometry<double> g;
  g.radii = Vector<double>::Constant(n, r);
  g.edge_radii.resize(0);
  return g;
}

/// @brief 1 / m, and 0 at the pinned points (the rule of MassSpringSystem::inverse_masses()).
inline Vector<double> inverse_masses(const Vector<double>& m, const std::vector<int>& pinned) {
  Vector<double> w = m.cwiseInverse();
  for (int i : pinned) w(i) = 0;
  return w;
}

/// @brief Applies a handler to one step from (xs, vs) to (xe, ve).
template <class Handler>
void apply(Handler& h, const Pts& xs, const Pts& vs, Pts& xe, Pts& ve, double dt,
           const Vector<double>& m, const std::vector<int>& pinned = {}) {
  const Vector<double> w = inverse_masses(m, pinned);
  h.handle(contact::CollisionStep<double>{xs, vs, xe, ve, dt, m, w, pinned});
}

}  // namespace massspring::test
