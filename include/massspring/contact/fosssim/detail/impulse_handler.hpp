#pragma once
/// @file
/// @brief What the impulse handlers share: geometry, coefficient of restitution, broad phase and
/// the inverse masses of the step (0 for pinned points).

#include <Eigen/Core>
#include <string>
#include <utility>

#include "massspring/contact/collision_handler.hpp"
#include "massspring/contact/fosssim/broad_phase.hpp"
#include "massspring/contact/fosssim/geometry.hpp"
#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"

namespace massspring::contact::detail {

template <class Scalar>
class ImpulseHandlerBase : public CollisionHandler<Scalar> {
 public:
  ImpulseHandlerBase(ContactGeometry<Scalar> geometry, Scalar cor, BroadPhaseKind broad_phase,
                     const char* who)
      : geometry_(std::move(geometry)), cor_(cor), broad_phase_(broad_phase) {
    geometry_.validate(who);
    if (!(cor >= 0 && cor <= 1))
      throw Error(massspring::detail::message(who, ": COR must be in [0, 1], got ", cor));
  }

  [[nodiscard]] const ContactGeometry<Scalar>& geometry() const { return geometry_; }
  [[nodiscard]] Scalar cor() const { return cor_; }
  [[nodiscard]] BroadPhaseKind broad_phase() const { return broad_phase_.kind(); }

 protected:
  /// @brief Checks the sizes.
  void prepare(const CollisionStep<Scalar>& s, const char* who) const {
    const Eigen::Index n = s.masses.size();
    if (geometry_.num_particles() != n || s.x_end.rows() != n)
      throw Error(massspring::detail::message(who, ": the handler has ", geometry_.num_particles(),
                                              " particle radii, the system ", n, " points"));
  }
  [[nodiscard]] Vector3<Scalar> row(const Points<Scalar>& p, int i) const {
    return p.row(i).transpose();
  }

  ContactGeometry<Scalar> geometry_;
  Scalar cor_ = 1;
  FosssimBroadPhase<Scalar> broad_phase_;
};

}  // namespace massspring::contact::detail
