#pragma once
/// @file
/// @brief PenaltyForce: FOSSSim's penalty response (Theme 2, PenaltyForce), a force
/// term like any other, so every integrator uses it.
///
/// For each candidate pair (contact/fosssim/broad_phase.hpp) with n the shortest vector from the
/// particle to the other primitive (contact/distance/point_point.hpp, point_segment.hpp,
/// point_plane.hpp) and s = r_1 + r_2 + thickness (particle-particle), r + r_e + thickness
/// (particle-edge), r + thickness (particle-plane): when \f$ 0 < |n| < s \f$ (FOSSSim skips |n| <
/// 1e-10), \f[ E = \frac{k}{2} (s - |n|)^2, \qquad F_1 = k (|n| - s)\,\hat n \f] on the particle
/// (pushed away), and \f$ -F_1 \f$ on the other particle, \f$ -(1-\alpha) F_1,
/// -\alpha F_1 \f$ on an edge's ends (a plane takes the reaction). F = -dE/dx exactly (alpha's
/// own variation does not change |n| to first order). Units: k [N/m], lengths [m], E [J], F [N].
///
/// No dF/dx: FOSSSim's PenaltyForce has none ("implicit integration of penalty forces is not
/// supported"), and the pairs in contact change from step to step, while the implicit
/// integrators need a fixed pattern of Jacobian entries (forces/force_term.hpp); BackwardEuler
/// treats the term explicitly.

#include <Eigen/Core>
#include <cmath>
#include <utility>
#include <vector>

#include "massspring/contact/distance/point_plane.hpp"
#include "massspring/contact/distance/point_segment.hpp"
#include "massspring/contact/fosssim/broad_phase.hpp"
#include "massspring/contact/fosssim/geometry.hpp"
#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/forces/force_term.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief Penalty contact between particles, edges and planes, with stiffness k and thickness.
template <class Scalar>
class PenaltyForce {
 public:
  /// @param[in] geometry    radii, edges, planes (validated)
  /// @param[in] k           stiffness [N/m], finite, >= 0
  /// @param[in] thickness   distance added to the radii [m], finite, >= 0
  /// @param[in] broad_phase all pairs or the grid (same force, different cost)
  PenaltyForce(ContactGeometry<Scalar> geometry, Scalar k, Scalar thickness,
               BroadPhaseKind broad_phase = BroadPhaseKind::AllPairs)
      : geometry_(std::move(geometry)), k_(k), thickness_(thickness), broad_phase_(broad_phase) {
    geometry_.validate("penalty force");
    massspring::detail::require_number("penalty force", "k", double(k), false);
    massspring::detail::require_number("penalty force", "thickness", double(thickness), false);
  }

  static constexpr bool velocity_dependent = false;
  [[nodiscard]] const char* name() const { return "penalty contact"; }
  [[nodiscard]] int max_index() const { return geometry_.max_index(); }
  [[nodiscard]] const ContactGeometry<Scalar>& geometry() const { return geometry_; }
  [[nodiscard]] Scalar stiffness() const { return k_; }
  [[nodiscard]] Scalar thickness() const { return thickness_; }
  [[nodiscard]] BroadPhaseKind broad_phase() const { return broad_phase_.kind(); }

  void add_force(const ForceContext<Scalar>& c, Points<Scalar>& f) const {
    for (const Contact& k : contacts(c.x)) {
      f.row(k.i) += k.f.transpose();
      if (k.j1 >= 0) f.row(k.j1) -= (k.s1 * k.f).transpose();
      if (k.j2 >= 0) f.row(k.j2) -= (k.s2 * k.f).transpose();
    }
  }

  [[nodiscard]] Scalar energy(const ForceContext<Scalar>& c) const {
    Scalar e = 0;
    // |F_1| = k (s - |n|), so E = |F_1|^2 / (2 k)
    for (const Contact& k : contacts(c.x)) e += k.f.squaredNorm() / (2 * k_);
    return e;
  }

 private:
  /// @brief A pair in contact: F on particle i, -s1 F on j1 and -s2 F on j2 (-1: none).
  struct Contact {
    Vector3<Scalar> f;
    int i, j1, j2;
    Scalar s1, s2;
  };

  /// @brief The pairs in contact at x. The last positions' list is kept: the energy after a step
  /// and the force at the start of the next are evaluated at the same positions, and the second
  /// reuses the first's detection.
  const std::vector<Contact>& contacts(const Points<Scalar>& x) const {
    if (cached_ && x.rows() == x_.rows() && (x.array() == x_.array()).all()) return contacts_;
    contacts_.clear();
    visit(x, [&](int i, const Vector3<Scalar>& fi, int j1, Scalar s1, int j2, Scalar s2) {
      contacts_.push_back({fi, i, j1, j2, s1, s2});
    });
    x_ = x;
    cached_ = true;
    return contacts_;
  }

  /// @brief Calls emit(i, F_i, j1, share1, j2, share2) for every pair in contact: F_i on the
  /// particle, -share * F_i on the others (j = -1: none).
  template <class Emit>
  void visit(const Points<Scalar>& x, Emit&& emit) const {
    if (!(k_ > 0)) return;
    const ContactGeometry<Scalar>& g = geometry_;
    constexpr Scalar tiny = Scalar(1e-10);  // FOSSSim's cut-off: no direction below it
    broad_phase_.visit(
        g, x, x, thickness_,
        [&](ParticlePairKind kind, int i, int j) {
          const Vector3<Scalar> xi = x.row(i).transpose();
          if (kind == ParticlePairKind::PointPoint) {
            const Vector3<Scalar> n = x.row(j).transpose() - xi;
            const Scalar s = g.radii(i) + g.radii(j) + thickness_;
            const Scalar d2 = n.squaredNorm();
            if (!(d2 < s * s)) return;
            const Scalar d = std::sqrt(d2);
            if (d < tiny) return;
            emit(i, Vector3<Scalar>((k_ * (d - s) / d) * n), j, Scalar(1), -1, Scalar(0));
          } else if (kind == ParticlePairKind::PointEdge) {
            const int a = g.edges(j, 0), b = g.edges(j, 1);
            const auto r =
                point_segment_distance<Scalar>(xi, x.row(a).transpose(), x.row(b).transpose());
            const Scalar s = g.radii(i) + g.edge_radii(j) + thickness_;
            if (r.distance < tiny || !(r.distance < s)) return;
            emit(i, Vector3<Scalar>((k_ * (r.distance - s) / r.distance) * r.n), a, 1 - r.alpha, b,
                 r.alpha);
          } else {
            const auto r = point_plane_distance<Scalar>(xi, g.planes[std::size_t(j)]);
            const Scalar s = g.radii(i) + thickness_;
            if (r.distance < tiny || !(r.distance < s)) return;
            emit(i, Vector3<Scalar>((k_ * (r.distance - s) / r.distance) * r.n), -1, Scalar(0), -1,
                 Scalar(0));
          }
        },
        false);
  }

  ContactGeometry<Scalar> geometry_;
  Scalar k_ = 0, thickness_ = 0;
  // work arrays only: the force is a function of x
  mutable FosssimBroadPhase<Scalar> broad_phase_;
  mutable std::vector<Contact> contacts_;
  mutable Points<Scalar> x_;
  mutable bool cached_ = false;
};

}  // namespace massspring::contact
