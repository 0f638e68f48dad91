#pragma once
/// @file
/// @brief ContactProjection: FastMassSpring's projection of an iterate out of the system's
/// colliders (contact/colliders.hpp: the position response, with friction), on the rows of the
/// points that are not pinned. Each local step projects its iterate first, so the springs see where
/// contact leaves the points: the collision projection of projective dynamics (Bouaziz et al.
/// 2014, "Projective Dynamics", section 5), here without a change of Q.

#include <algorithm>
#include <cstddef>
#include <vector>

#include "massspring/contact/colliders.hpp"
#include "massspring/integrators/local_global/reduced_system.hpp"

namespace massspring::local_global {

template <class Scalar>
class ContactProjection {
 public:
  /// @brief The rows the colliders act on: every unknown of Q but a (penalty-)pinned point's.
  /// Allocates; called when Q is built.
  template <class System>
  void build(const System& system, const ReducedSystem<Scalar>& reduced) {
    rows_.clear();
    points_.clear();
    for (int r = 0; r < reduced.nr; ++r) {
      const int i = reduced.point[std::size_t(r)];
      if (!std::binary_search(system.pinned().begin(), system.pinned().end(), i)) {
        rows_.push_back(r);
        points_.push_back(i);
      }
    }
  }

  /// @brief The step's colliders (their end-of-step poses set) and start positions, or nothing
  /// to do when the system has no collider.
  template <class System>
  void prepare(System& system, Scalar dt) {
    colliders_ = system.colliders().empty() ? nullptr : &system.colliders();
    if (!colliders_) return;
    system.colliders().begin_step(dt);
    x_start_ = system.positions().data();
    dt_ = dt;
  }

  /// @brief True when prepare() found colliders.
  [[nodiscard]] bool active() const { return colliders_ != nullptr; }

  /// @brief Projects the iterate x (3 values per row) in place.
  void apply(Scalar* x) const {
    for (std::size_t k = 0; k < rows_.size(); ++k)
      colliders_->project(x_start_ + 3 * points_[k], x + 3 * rows_[k], dt_);
  }

 private:
  std::vector<int> rows_, points_;
  const contact::ColliderSet<Scalar>* colliders_ = nullptr;
  const Scalar* x_start_ = nullptr;
  Scalar dt_ = 0;
};

}  // namespace massspring::local_global
