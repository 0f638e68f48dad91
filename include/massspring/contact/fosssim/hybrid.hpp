#pragma once
/// @file
/// @brief HybridCollisionHandler: FOSSSim's "hybrid" response (Theme 2,
/// HybridCollisionHandler::handleCollisions; Bridson, Fedkiw and Anderson 2002):
/// 1. up to `maxiters` rounds: detect every continuous-time collision between the start-of-step
///    positions qs and the current end-of-step positions qe (contact/fosssim/time_of_impact.hpp),
///    then apply all their impulses at once (each computed from the same qe;
///    contact/fosssim/impulse.hpp);
/// 2. if collisions remain, rigid impact zones: the colliding particles' groups (merged when they
///    share a particle) are moved rigidly from qs (contact/response/impact_zones.hpp), collisions
///    are detected again, new ones grow the zones, until the zones stop changing.
/// The scene's penalty force (k, thickness) is a separate force term (contact/fosssim/penalty.hpp).

#include <array>
#include <vector>

#include "massspring/contact/fosssim/continuous_time.hpp"
#include "massspring/contact/response/impact_zones.hpp"

namespace massspring::contact {

/// @brief Iterated simultaneous continuous-time impulses, then rigid impact zones.
template <class Scalar>
class HybridCollisionHandler final : public detail::ImpulseHandlerBase<Scalar> {
  using Base = detail::ImpulseHandlerBase<Scalar>;

 public:
  /// @param[in] max_iterations rounds of impulses before the impact zones (>= 0; 0: zones only)
  HybridCollisionHandler(ContactGeometry<Scalar> geometry, Scalar cor, int max_iterations,
                         BroadPhaseKind broad_phase = BroadPhaseKind::AllPairs)
      : Base(std::move(geometry), cor, broad_phase, "hybrid collision handler"),
        max_iterations_(max_iterations) {
    if (max_iterations < 0)
      throw Error(massspring::detail::message(
          "hybrid collision handler: maxiters must be >= 0, got ", max_iterations));
  }

  [[nodiscard]] std::unique_ptr<CollisionHandler<Scalar>> clone() const override {
    return std::make_unique<HybridCollisionHandler>(*this);
  }
  [[nodiscard]] const char* name() const override { return "hybrid"; }
  [[nodiscard]] int max_iterations() const { return max_iterations_; }
  /// @brief Impulse rounds of the last step.
  [[nodiscard]] int last_iterations() const { return last_iterations_; }
  /// @brief Impact-zone rounds of the last step (0 when the impulses sufficed).
  [[nodiscard]] int last_zone_rounds() const { return last_zone_rounds_; }

  void handle(const CollisionStep<Scalar>& s) override {
    this->prepare(s, "hybrid collision handler");
    const Points<Scalar>& qs = s.x_start;
    qe_ = s.x_end;
    ve_ = s.v_end;
    detect(qs, qe_);
    last_iterations_ = 0;
    last_zone_rounds_ = 0;
    for (int it = 0; it < max_iterations_ && !hits_.empty(); ++it) {
      qm_ = qe_;
      vm_ = ve_;
      const ImpulseTarget<Scalar> target{vm_, &qm_, s.dt};
      for (const Hit& h : hits_)
        continuous_time_impulse(this->geometry_, h.kind, h.i, h.j, h.toi, qs, qe_, s.dt,
                                s.inverse_masses, this->cor_, target);
      qe_.swap(qm_);
      ve_.swap(vm_);
      detect(qs, qe_);
      ++last_iterations_;
    }
    if (!hits_.empty()) zones(s);
    s.x_end = qe_;
    s.v_end = ve_;
  }

 private:
  struct Hit {
    ParticlePairKind kind;
    int i, j;
    TimeOfImpact<Scalar> toi;
  };

  void detect(const Points<Scalar>& qs, const Points<Scalar>& qe) {
    hits_.clear();
    this->broad_phase_.visit(this->geometry_, qs, qe, Scalar(0),
                             [&](ParticlePairKind kind, int i, int j) {
                               const TimeOfImpact<Scalar> hit =
                                   continuous_time_test(this->geometry_, kind, i, j, qs, qe);
                               if (hit.hit) hits_.push_back({kind, i, j, hit});
                             });
  }

  /// @brief Grows the zones with the collisions in hits_; true when they changed.
  bool grow() {
    bool changed = false;
    for (const Hit& h : hits_) {
      std::array<int, 3> p{h.i, 0, 0};
      int count = 1;
      if (h.kind == ParticlePairKind::PointPoint) {
        p[1] = h.j;
        count = 2;
      } else if (h.kind == ParticlePairKind::PointEdge) {
        p[1] = this->geometry_.edges(h.j, 0);
        p[2] = this->geometry_.edges(h.j, 1);
        count = 3;
      }
      changed = zones_.add(p, count, h.kind == ParticlePairKind::PointPlane) || changed;
    }
    return changed;
  }

  void zones(const CollisionStep<Scalar>& s) {
    const Points<Scalar>& qs = s.x_start;
    zones_.reset(int(qs.rows()));
    grow();
    for (;;) {
      ++last_zone_rounds_;
      zones_.groups(members_, starts_);
      for (std::size_t z = 0; z + 1 < starts_.size(); ++z) {
        const int* m = members_.data() + starts_[z];
        const int count = starts_[z + 1] - starts_[z];
        bool fixed = zones_.has_plane(zones_.zone_of(m[0]));
        for (int k = 0; k < count && !fixed; ++k) fixed = s.inverse_masses(m[k]) == 0;
        rigid_zone_motion(m, count, fixed, s.masses, qs, s.dt, qe_, ve_);
      }
      detect(qs, qe_);
      if (!grow()) break;
    }
  }

  int max_iterations_ = 10;
  int last_iterations_ = 0, last_zone_rounds_ = 0;
  Points<Scalar> qe_, ve_, qm_, vm_;
  std::vector<Hit> hits_;
  ImpactZones zones_;
  std::vector<int> members_, starts_;
};

}  // namespace massspring::contact
