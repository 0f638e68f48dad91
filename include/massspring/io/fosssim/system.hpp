#pragma once
/// @file
/// @brief make_fosssim_system(): the MassSpringSystem a FOSSSim scene describes, with its force
/// terms and its collision response.

#include <utility>
#include <vector>

#include "massspring/contact/fosssim/continuous_time.hpp"
#include "massspring/contact/fosssim/geometry.hpp"
#include "massspring/contact/fosssim/hybrid.hpp"
#include "massspring/contact/fosssim/penalty.hpp"
#include "massspring/contact/fosssim/simple_impulse.hpp"
#include "massspring/error.hpp"
#include "massspring/forces/gravitational_attraction.hpp"
#include "massspring/forces/gravity.hpp"
#include "massspring/forces/linear_drag.hpp"
#include "massspring/forces/vortex.hpp"
#include "massspring/io/fosssim/scene.hpp"
#include "massspring/types.hpp"

namespace massspring::io {

/// @brief The contact geometry of a scene: particle radii, every edge with its radius, the
/// half-planes (z = 0).
template <class Scalar>
contact::ContactGeometry<Scalar> fosssim_contact_geometry(const FosssimScene& scene) {
  contact::ContactGeometry<Scalar> g;
  const int n = scene.num_particles();
  g.radii.resize(n);
  for (int i = 0; i < n; ++i) g.radii(i) = Scalar(scene.radius(i));
  g.edges = scene.edges;
  g.edge_radii.resize(scene.edges.rows());
  for (int e = 0; e < int(scene.edges.rows()); ++e) g.edge_radii(e) = Scalar(scene.edge_radius(e));
  for (const auto& h : scene.halfplanes)
    g.planes.push_back({h.point.template cast<Scalar>(), h.normal.template cast<Scalar>()});
  return g;
}

/// @brief The system a FOSSSim scene describes, with its force terms.
///
/// - points: the particles (z = 0), their masses and initial velocities; fixed particles are
///   pinned where they start, with velocity 0;
/// - springs: one per `<springforce>` (its edge's endpoints, k, rest length l0, damping b); edges
///   without a spring are drawing only and are not in the system;
/// - `<simplegravity>` -> Gravity (an acceleration: F = m g), `<gravitationalforce>` pairs ->
///   one GravitationalAttraction, `<dragdamping>` -> LinearDrag (coefficients summed),
///   `<vortexforce>` elements -> one VortexForce;
/// - `<collision>`: the particles' and edges' radii and the half-planes make the contact geometry
///   (every `<edge>` collides, with or without a spring); "simple", "continuous-time" and
///   "hybrid" set the matching collision handler (contact/), "penalty" and "hybrid" add a
///   contact::PenaltyForce with the scene's k and thickness (none when k = 0: it would add
///   nothing); `<collisiondetection type="contest">` selects the grid broad phase.
///
/// @tparam System a MassSpringSystem<Scalar, Storage>
/// @throws Error from MassSpringSystem for a description it refuses (e.g. one built by hand with
/// an index out of range).
template <class System>
System make_fosssim_system(const FosssimScene& scene) {
  using Scalar = typename System::Scalar;
  const Eigen::Index m = Eigen::Index(scene.springs.size());
  Edges springs(m, 2);
  Vector<Scalar> k(m), l0(m), b(m);
  for (Eigen::Index s = 0; s < m; ++s) {
    const auto& f = scene.springs[std::size_t(s)];
    if (f.edge < 0 || f.edge >= scene.edges.rows())
      throw Error(detail::message("spring force ", s, ": edge ", f.edge, " out of range [0, ",
                                  scene.edges.rows(), ")"));
    springs.row(s) = scene.edges.row(f.edge);
    k(s) = Scalar(f.k);
    l0(s) = Scalar(f.l0);
    b(s) = Scalar(f.b);
  }
  System system(scene.positions.template cast<Scalar>(), springs,
                scene.masses.template cast<Scalar>(), k);
  system.set_rest_lengths(l0);
  system.set_damping(b);
  Points<Scalar> v = scene.velocities.template cast<Scalar>();
  for (int i : scene.fixed)
    if (i >= 0 && i < v.rows()) v.row(i).setZero();
  system.set_velocities(v);
  system.pin(scene.fixed);
  if (scene.gravity) system.add_force(Gravity<Scalar>(scene.gravity->template cast<Scalar>()));
  if (!scene.attractions.empty()) {
    std::vector<typename GravitationalAttraction<Scalar>::Pair> pairs;
    for (const auto& a : scene.attractions) pairs.push_back({a.i, a.j, Scalar(a.G)});
    system.add_force(GravitationalAttraction<Scalar>(std::move(pairs)));
  }
  if (scene.drag) system.add_force(LinearDrag<Scalar>(Scalar(*scene.drag)));
  if (!scene.vortices.empty()) {
    std::vector<typename VortexForce<Scalar>::Pair> pairs;
    for (const auto& f : scene.vortices) pairs.push_back({f.i, f.j, Scalar(f.kbs), Scalar(f.kvc)});
    system.add_force(VortexForce<Scalar>(std::move(pairs)));
  }
  if (scene.collision && scene.collision->type != FosssimCollision::None) {
    const auto& c = *scene.collision;
    const contact::ContactGeometry<Scalar> g = fosssim_contact_geometry<Scalar>(scene);
    const contact::BroadPhaseKind broad = scene.contest.value_or(false)
                                              ? contact::BroadPhaseKind::Grid
                                              : contact::BroadPhaseKind::AllPairs;
    const Scalar cor = Scalar(c.cor);
    switch (c.type) {
      case FosssimCollision::Simple:
        system.set_collision_handler(contact::SimpleCollisionHandler<Scalar>(g, cor, broad));
        break;
      case FosssimCollision::ContinuousTime:
        system.set_collision_handler(
            contact::ContinuousTimeCollisionHandler<Scalar>(g, cor, broad));
        break;
      case FosssimCollision::Hybrid:
        system.set_collision_handler(
            contact::HybridCollisionHandler<Scalar>(g, cor, c.max_iterations, broad));
        break;
      default:
        break;
    }
    const bool penalty = c.type == FosssimCollision::Penalty || c.type == FosssimCollision::Hybrid;
    if (penalty && c.k > 0)
      system.add_force(contact::PenaltyForce<Scalar>(g, Scalar(c.k), Scalar(c.thickness), broad));
  }
  return system;
}

}  // namespace massspring::io
