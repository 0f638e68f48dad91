#pragma once
/// @file
/// @brief SimpleCollisionHandler: FOSSSim's "simple" response (Theme 2,
/// SimpleCollisionHandler): at the end of the step, every pair that overlaps (distance below the
/// sum of radii) and approaches gets an impulse (contact/fosssim/impulse.hpp), one pair after the
/// other in the broad phase's order, each seeing the velocities the previous ones left. Positions
/// are not changed. Misses a fast particle that crosses a primitive within one step (see
/// ContinuousTimeCollisionHandler).
///
/// Detection at the end-of-step positions x and velocities v (3-vectors):
/// - particle-particle: n = x_j - x_i, \f$ |n| < r_i + r_j \f$ and \f$ (v_i - v_j)\cdot n > 0 \f$;
/// - particle-edge: n = x_alpha - x_i (contact/distance/point_segment.hpp), \f$ |n| < r_i + r_e \f$
/// and
///   \f$ (v_i - v_\alpha)\cdot n > 0 \f$, \f$ v_\alpha = v_a + \alpha (v_b - v_a) \f$;
/// - particle-plane: n from contact/distance/point_plane.hpp, \f$ |n| < r_i \f$ and \f$ v_i\cdot n
/// > 0 \f$.

#include "massspring/contact/distance/point_plane.hpp"
#include "massspring/contact/distance/point_segment.hpp"
#include "massspring/contact/fosssim/detail/impulse_handler.hpp"
#include "massspring/contact/fosssim/impulse.hpp"

namespace massspring::contact {

/// @brief The end-of-step overlap-and-approach impulse response with restitution `cor`.
template <class Scalar>
class SimpleCollisionHandler final : public detail::ImpulseHandlerBase<Scalar> {
  using Base = detail::ImpulseHandlerBase<Scalar>;

 public:
  /// @param[in] geometry    radii, edges, planes (validated: Error otherwise)
  /// @param[in] cor         coefficient of restitution in [0, 1]
  /// @param[in] broad_phase which pairs are tested (same result, different cost)
  SimpleCollisionHandler(ContactGeometry<Scalar> geometry, Scalar cor,
                         BroadPhaseKind broad_phase = BroadPhaseKind::AllPairs)
      : Base(std::move(geometry), cor, broad_phase, "simple collision handler") {}

  [[nodiscard]] std::unique_ptr<CollisionHandler<Scalar>> clone() const override {
    return std::make_unique<SimpleCollisionHandler>(*this);
  }
  [[nodiscard]] const char* name() const override { return "simple"; }

  void handle(const CollisionStep<Scalar>& s) override {
    this->prepare(s, "simple collision handler");
    const ContactGeometry<Scalar>& g = this->geometry_;
    const Points<Scalar>& x = s.x_end;
    Points<Scalar>& v = s.v_end;
    const ImpulseTarget<Scalar> target{v};
    const Vector<Scalar>& w = s.inverse_masses;
    const Scalar e = this->cor_;
    this->broad_phase_.visit(g, x, x, Scalar(0), [&](ParticlePairKind kind, int i, int j) {
      const Vector3<Scalar> xi = this->row(x, i), vi = this->row(v, i);
      if (kind == ParticlePairKind::PointPoint) {
        const Vector3<Scalar> n = this->row(x, j) - xi;
        const Scalar s2 = g.radii(i) + g.radii(j);
        if (!(n.squaredNorm() < s2 * s2)) return;
        const Vector3<Scalar> vj = this->row(v, j);
        if (!((vi - vj).dot(n) > 0)) return;
        point_point_impulse(target, i, j, Vector3<Scalar>(n.normalized()), vi, vj, w(i), w(j), e);
      } else if (kind == ParticlePairKind::PointEdge) {
        const int a = g.edges(j, 0), b = g.edges(j, 1);
        const auto d = point_segment_distance(xi, this->row(x, a), this->row(x, b));
        if (!(d.distance < g.radii(i) + g.edge_radii(j))) return;
        const Vector3<Scalar> va = this->row(v, a), vb = this->row(v, b);
        const Vector3<Scalar> v_alpha = va + d.alpha * (vb - va);
        if (!((vi - v_alpha).dot(d.n) > 0)) return;
        point_edge_impulse(target, i, a, b, d.alpha, d.normal(), vi, va, vb, w(i), w(a), w(b), e);
      } else {
        const auto d = point_plane_distance(xi, g.planes[std::size_t(j)]);
        if (!(d.distance < g.radii(i))) return;
        if (!(vi.dot(d.n) > 0)) return;
        point_plane_impulse(target, i, d.normal(), vi, w(i), e);
      }
    });
  }
};

}  // namespace massspring::contact
