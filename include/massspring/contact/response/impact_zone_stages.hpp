#pragma once
/// @file
/// @brief ImpactZoneStages: the fail-safe stages of surface contact (contact/response/
/// surface_contact.hpp), for the collisions its impulses leave.
///
/// - project(): the inelastic projection (Harmon, Vouga, Tamstorf and Grinspun 2008, "Robust
///   treatment of simultaneous collisions", section 4; contact/response/inelastic_projection.hpp).
///   Each collision adds the linearised constraint that its pair's relative displacement along
///   the normal n at the time of impact be at least a tenth of the pair's gap g more than the
///   largest of 0 (the approach cancelled: an inelastic impact), its present value (so that a
///   collision found again always parts further) and g less the pair's separation along n at the
///   start (so that the pair ends at least g apart along n), and the end
///   positions are projected, in the mass norm, onto every constraint gathered so far in the
///   step. Only normal displacements change, so a zone keeps its sliding; points of infinite
///   mass (pinned, an obstacle's, held by a solid) never move. A pair found again replaces its
///   own constraint (one constraint per pair). The projection is stuck, and the rigid stage
///   takes over, when a round finds no new pair and no fewer collisions than the last
///   projection round: projecting the same constraints again cannot part them.
/// - rigid(): rigid impact zones, the last resort (Bridson, Fedkiw and Anderson 2002, section
///   7.4; contact/response/impact_zones.hpp). The collisions' points merge into zones; a zone
///   that holds an obstacle's element moves with that obstacle, one that holds pinned points with
///   their displacement, one that holds a point held by a solid stays where it started, any other
///   rigidly, keeping its linear and angular momentum. A zone whose pinned points do not all move
///   with that motion (two pins moving differently, or a pin not moving with the zone's obstacle)
///   has none that keeps them on their targets: rigid() then reports failure, and no pinned point
///   is ever moved.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "massspring/contact/colliders/colliders.hpp"
#include "massspring/contact/response/impact_zones.hpp"
#include "massspring/contact/response/inelastic_projection.hpp"
#include "massspring/contact/response/surface_contact_slot.hpp"
#include "massspring/contact/response/surface_elements.hpp"
#include "massspring/detail/merge_sorted_tail.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief A collision continuous detection found: the pair, its time of impact in [0, 1], the
/// distance it keeps [m] and the pair's own gap [m] (more than the distance kept when the pair
/// started closer than its gap).
template <class Scalar>
struct SurfaceHit {
  ElementPair pair;
  Scalar toi;
  Scalar gap;
  Scalar nominal_gap;
};

/// @brief The projection and the rigid zones of one pass (see the file comment); the work arrays
/// keep their capacity.
template <class Scalar>
class ImpactZoneStages {
 public:
  using V3 = Vector3<Scalar>;
  using M3 = Eigen::Matrix<Scalar, 3, 3>;
  using Elements = SurfaceElements<Scalar>;
  using Input = SurfaceContactInput<Scalar>;
  using Hits = std::vector<SurfaceHit<Scalar>>;

  /// @brief Projected Gauss-Seidel sweeps per projection; the multipliers carry over to the next.
  static constexpr int kSweeps = 100;

  /// @brief A new step: no constraint, no rigid zone.
  void begin_step() {
    projection_.clear();
    known_.clear();
    last_projected_hits_ = std::numeric_limits<std::size_t>::max();
    rigid_active_ = false;
  }

  /// @brief True when the four points lie in one rigid zone (their distances then cannot change).
  bool same_rigid_zone(const std::array<int, 4>& p) {
    if (!rigid_active_) return false;
    const int z = zones_.zone_of(p[0]);
    return z >= 0 && zones_.zone_of(p[1]) == z && zones_.zone_of(p[2]) == z &&
           zones_.zone_of(p[3]) == z;
  }

  /// @brief What project() did.
  enum class Projection {
    Projected,  ///< the end positions were projected
    Immobile,   ///< projected, but a constraint that stays violated has no point it may move
    Stuck       ///< nothing done: no new pair and no fewer collisions than the last projection
  };

  /// @brief The projection stage (see the file comment) on the hits; moved[i] is set for the
  /// points of every hit and each point moved.
  Projection project(Elements& e, const Input& in, const Hits& hits, std::vector<char>& moved,
                     SurfaceContactReport& report) {
    // Each hit's pair: an index into the constraints when it has one from an earlier round.
    // known_ holds (pair key, constraint index), sorted by key; a round's pairs are distinct.
    hit_constraint_.assign(hits.size(), kNew);
    bool any_new = false;
    for (std::size_t h = 0; h < hits.size(); ++h) {
      const std::uint64_t key = pair_key(hits[h].pair);
      const auto it = std::lower_bound(known_.begin(), known_.end(), key,
                                       [](const std::pair<std::uint64_t, std::size_t>& k,
                                          std::uint64_t v) { return k.first < v; });
      if (it != known_.end() && it->first == key)
        hit_constraint_[h] = it->second;
      else
        any_new = true;
    }
    if (!any_new && hits.size() >= last_projected_hits_) return Projection::Stuck;
    last_projected_hits_ = hits.size();
    const std::size_t known_before = known_.size();
    for (std::size_t h = 0; h < hits.size(); ++h) {
      const SurfaceHit<Scalar>& hit = hits[h];
      const Scalar toi = hit.toi;
      const PairStencil<Scalar> s =
          e.stencil(hit.pair, [&](int i) { return V3(e.p0(i) + toi * e.d(i)); });
      ProjectionConstraint<Scalar> c;
      c.p = s.p;
      c.a = s.a;
      c.n = s.n;
      // The relative displacement along n now (g) and the separation along n at the start.
      Scalar g = 0, start = 0;
      for (int k = 0; k < 4; ++k) {
        g += s.a[std::size_t(k)] * s.n.dot(e.d(s.p[std::size_t(k)]));
        start += s.a[std::size_t(k)] * s.n.dot(e.p0(s.p[std::size_t(k)]));
      }
      c.target = std::max({Scalar(0), g, hit.gap - start}) + hit.gap / 10;
      if (hit_constraint_[h] != kNew) {
        projection_.replace(hit_constraint_[h], c);
      } else {
        known_.emplace_back(pair_key(hit.pair), projection_.size());
        projection_.add(c);
      }
      for (int i : s.p) moved[std::size_t(i)] = 1;  // tested again, moved or not
    }
    massspring::detail::merge_sorted_tail(known_, known_before, merged_);
    // A constraint holds when the pair parts by at least half its target, or to within a
    // thousandth of its own gap (a pair that started touching has target 0: rounding alone would
    // keep the sweeps going).
    Scalar tolerance = std::numeric_limits<Scalar>::infinity();
    for (std::size_t c = 0; c < projection_.size(); ++c)
      tolerance = std::min(tolerance, projection_.constraint(c).target / 2);
    Scalar least_gap = std::numeric_limits<Scalar>::infinity();
    for (const SurfaceHit<Scalar>& hit : hits) least_gap = std::min(least_gap, hit.nominal_gap);
    tolerance = std::max(tolerance, least_gap / 1000);
    projected_.assign(moved.size(), 0);
    const ProjectionResult<Scalar> r =
        projection_.solve(e.w, e.x0, e.x1, tolerance, kSweeps, projected_);
    for (std::size_t i = 0; i < projected_.size(); ++i)
      if (projected_[i]) {
        moved[i] = 1;
        ++report.projected_points;
      }
    e.hold_pushed_into_solids(in, moved);
    return r.immobile_violated ? Projection::Immobile : Projection::Projected;
  }

  /// @brief The rigid stage (see the file comment): the hits' points join zones, and each zone
  /// moves. moved[i] is set for every zone point. @return false when a zone's pinned points
  /// cannot all keep their prescribed motion (nothing is moved then).
  bool rigid(Elements& e, const Input& in, const Hits& hits, std::vector<char>& moved,
             SurfaceContactReport& report) {
    if (!rigid_active_) {
      zones_.reset(int(e.x0.rows()));
      rigid_active_ = true;
    }
    for (const SurfaceHit<Scalar>& hit : hits) {
      const PairStencil<Scalar> s = e.stencil(hit.pair, [&](int i) { return e.p0(i); });
      bool immobile = false;
      for (int i : s.p) immobile = immobile || e.w(i) == 0;
      zones_.add(s.p, 4, immobile);
    }
    zones_.groups(members_, starts_);
    // First check that every zone has a motion its pinned points follow.
    for (std::size_t z = 0; z + 1 < starts_.size(); ++z) {
      const int* m = members_.data() + starts_[z];
      const int count = starts_[z + 1] - starts_[z];
      const Anchors a = anchors(e, m, count);
      for (int k = 0; k < count; ++k)
        if (e.pinned[std::size_t(m[k])] && !same_place(carried(e, in, a, m[k]), e.p1(m[k])))
          return false;
    }
    int total = 0;
    velocity_scratch_.resize(e.x1.rows(), 3);
    for (std::size_t z = 0; z + 1 < starts_.size(); ++z) {
      const int* m = members_.data() + starts_[z];
      const int count = starts_[z + 1] - starts_[z];
      const Anchors a = anchors(e, m, count);
      const auto movable = [&](int i) {
        return e.owner[std::size_t(i)] < 0 && !e.pinned[std::size_t(i)];
      };
      if (a.obstacle >= 0 || a.pin >= 0 || a.held >= 0) {
        for (int k = 0; k < count; ++k)
          if (movable(m[k])) e.x1.row(m[k]) = carried(e, in, a, m[k]).transpose();
      } else {
        rigid_zone_motion<Scalar>(m, count, false, in.step.masses, e.x0, in.step.dt, e.x1,
                                  velocity_scratch_);
        // A rigid motion that would take a point into a solid: the zone stays where it started.
        bool blocked = false;
        for (int k = 0; k < count && !blocked; ++k) blocked = e.inside_solid(in.colliders, m[k]);
        if (blocked)
          for (int k = 0; k < count; ++k) e.x1.row(m[k]) = e.x0.row(m[k]);
      }
      for (int k = 0; k < count; ++k) moved[std::size_t(m[k])] = 1;
      total += count;
    }
    report.zone_points = total;
    return true;
  }

 private:
  // What carries a zone: an obstacle (its index), a pinned point, a point held by a solid (-1:
  // none). The first that is present decides.
  struct Anchors {
    int obstacle = -1, pin = -1, held = -1;
  };
  static Anchors anchors(const Elements& e, const int* m, int count) {
    Anchors a;
    for (int k = 0; k < count; ++k) {
      const int i = m[k];
      if (e.owner[std::size_t(i)] >= 0)
        a.obstacle = e.owner[std::size_t(i)];
      else if (e.pinned[std::size_t(i)])
        a.pin = i;
      else if (e.w(i) == 0)
        a.held = i;
    }
    return a;
  }
  // Where the zone's anchor carries point i at the end of the step: with the obstacle,
  // x1 = R_e R_s^T (x0 - t_s) + t_e; with a pinned point, by its displacement; a point held by
  // a solid keeps the zone where it started.
  static V3 carried(const Elements& e, const Input& in, const Anchors& a, int i) {
    if (a.obstacle >= 0) {
      const Collider<Scalar>& c = in.colliders[a.obstacle];
      const M3 rel = c.end_rotation() * c.rotation().transpose();
      return rel * (e.p0(i) - c.translation()) + c.end_translation();
    }
    if (a.pin >= 0) return e.p0(i) + e.d(a.pin);
    return e.p0(i);
  }
  // Whether a zone's motion puts a pinned point where its own motion does, to rounding.
  static bool same_place(const V3& carried, const V3& target) {
    const Scalar scale = 1 + carried.cwiseAbs().maxCoeff() + target.cwiseAbs().maxCoeff();
    return (carried - target).cwiseAbs().maxCoeff() <=
           1024 * std::numeric_limits<Scalar>::epsilon() * scale;
  }

  // A pair's key: its kind, then its two element indices (each below 2^31).
  static std::uint64_t pair_key(const ElementPair& q) {
    return (std::uint64_t(q.kind) << 62) | (std::uint64_t(q.a) << 31) | std::uint64_t(q.b);
  }
  static constexpr std::size_t kNew = std::numeric_limits<std::size_t>::max();

  std::vector<std::pair<std::uint64_t, std::size_t>> known_, merged_;  // (key, constraint)
  std::vector<std::size_t> hit_constraint_;  // per hit: its constraint or kNew
  std::size_t last_projected_hits_ = std::numeric_limits<std::size_t>::max();
  bool rigid_active_ = false;
  ImpactZones zones_;
  std::vector<int> members_, starts_;
  Points<Scalar> velocity_scratch_;
  InelasticProjection<Scalar> projection_;
  std::vector<char> projected_;  // points the last projection moved
};

}  // namespace massspring::contact
