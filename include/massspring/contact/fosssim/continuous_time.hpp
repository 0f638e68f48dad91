#pragma once
/// @file
/// @brief ContinuousTimeCollisionHandler: FOSSSim's "continuous-time" response (FOSSSim,
/// Theme 2, ContinuousTimeCollisionHandler): each pair that overlaps and approaches at some time
/// of the step, assuming straight-line motion from the start-of-step positions qs to the
/// end-of-step positions qe (contact/fosssim/time_of_impact.hpp), gets an impulse computed from the
/// step's mean velocities u = (qe - qs) / dt, applied to the end-of-step velocities and, times
/// dt, to the end-of-step positions (as if it had acted at the start of the step). Pairs are
/// handled one after the other in the broad phase's order; each sees the positions the previous
/// ones left.

#include <algorithm>

#include "massspring/contact/fosssim/detail/impulse_handler.hpp"
#include "massspring/contact/fosssim/impulse.hpp"
#include "massspring/contact/fosssim/time_of_impact.hpp"

namespace massspring::contact {

/// @brief The continuous-time test of one candidate pair between qs and qe (3-vectors, radii from
/// the geometry).
template <class Scalar>
TimeOfImpact<Scalar> continuous_time_test(const ContactGeometry<Scalar>& g, ParticlePairKind kind,
                                          int i, int j, const Points<Scalar>& qs,
                                          const Points<Scalar>& qe) {
  const Vector3<Scalar> x1 = qs.row(i).transpose();
  const Vector3<Scalar> d1 = (qe.row(i) - qs.row(i)).transpose();
  if (kind == ParticlePairKind::PointPoint) {
    return point_point_time_of_impact<Scalar>(x1, d1, qs.row(j).transpose(),
                                              (qe.row(j) - qs.row(j)).transpose(),
                                              g.radii(i) + g.radii(j));
  }
  if (kind == ParticlePairKind::PointEdge) {
    const int a = g.edges(j, 0), b = g.edges(j, 1);
    return point_edge_time_of_impact<Scalar>(
        x1, d1, qs.row(a).transpose(), (qe.row(a) - qs.row(a)).transpose(), qs.row(b).transpose(),
        (qe.row(b) - qs.row(b)).transpose(), g.radii(i) + g.edge_radii(j));
  }
  return point_plane_time_of_impact<Scalar>(x1, d1, g.planes[std::size_t(j)], g.radii(i));
}

/// @brief Applies the impulse of a detected pair: mean velocities u = (qe - qs) / dt read from
/// `qs`, `qe`; written into `t` (velocities, and positions times dt).
template <class Scalar>
void continuous_time_impulse(const ContactGeometry<Scalar>& g, ParticlePairKind kind, int i, int j,
                             const TimeOfImpact<Scalar>& hit, const Points<Scalar>& qs,
                             const Points<Scalar>& qe, Scalar dt, const Vector<Scalar>& w,
                             Scalar cor, const ImpulseTarget<Scalar>& t) {
  auto u = [&](int k) -> Vector3<Scalar> { return ((qe.row(k) - qs.row(k)) / dt).transpose(); };
  const Vector3<Scalar> n_hat = hit.n.normalized();
  if (kind == ParticlePairKind::PointPoint) {
    point_point_impulse(t, i, j, n_hat, u(i), u(j), w(i), w(j), cor);
  } else if (kind == ParticlePairKind::PointEdge) {
    const int a = g.edges(j, 0), b = g.edges(j, 1);
    const Scalar alpha = std::clamp(hit.alpha, Scalar(0), Scalar(1));
    point_edge_impulse(t, i, a, b, alpha, n_hat, u(i), u(a), u(b), w(i), w(a), w(b), cor);
  } else {
    point_plane_impulse(t, i, n_hat, u(i), w(i), cor);
  }
}

/// @brief The sequential continuous-time impulse response with restitution `cor`.
template <class Scalar>
class ContinuousTimeCollisionHandler final : public detail::ImpulseHandlerBase<Scalar> {
  using Base = detail::ImpulseHandlerBase<Scalar>;

 public:
  ContinuousTimeCollisionHandler(ContactGeometry<Scalar> geometry, Scalar cor,
                                 BroadPhaseKind broad_phase = BroadPhaseKind::AllPairs)
      : Base(std::move(geometry), cor, broad_phase, "continuous-time collision handler") {}

  [[nodiscard]] std::unique_ptr<CollisionHandler<Scalar>> clone() const override {
    return std::make_unique<ContinuousTimeCollisionHandler>(*this);
  }
  [[nodiscard]] const char* name() const override { return "continuous-time"; }

  void handle(const CollisionStep<Scalar>& s) override {
    this->prepare(s, "continuous-time collision handler");
    const ContactGeometry<Scalar>& g = this->geometry_;
    const ImpulseTarget<Scalar> target{s.v_end, &s.x_end, s.dt};
    this->broad_phase_.visit(
        g, s.x_start, s.x_end, Scalar(0), [&](ParticlePairKind kind, int i, int j) {
          const TimeOfImpact<Scalar> hit = continuous_time_test(g, kind, i, j, s.x_start, s.x_end);
          if (!hit.hit) return;
          continuous_time_impulse(g, kind, i, j, hit, s.x_start, s.x_end, s.dt, s.inverse_masses,
                                  this->cor_, target);
        });
  }
};

}  // namespace massspring::contact
