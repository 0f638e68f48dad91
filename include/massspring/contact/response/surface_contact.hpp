#pragma once
/// @file
/// @brief SurfaceContact: the end-of-step pass that keeps a cloth's surface from crossing itself
/// and the obstacles' edges and faces. Given a start state with no crossing, the state it leaves
/// has none.
///
/// The surface is a system's triangles and their edges (MassSpringSystem::set_surface()). The
/// obstacles join with their thin parts as moving elements of infinite mass: a sphere's centre (a
/// point), a capsule's axis (an edge and its two ends), a box's corners and twelve edges, a
/// mesh's vertices, edges and triangles,
/// each carried by its collider from the pose at the start of the step to the one at its end.
/// Solid interiors stay the colliders' point response (contact/colliders/collider_set.hpp), which
/// runs first.
///
/// Pairs: a point and a triangle it is not a corner of, two edges that share no point. Between
/// parts of the cloth only when self-collision is on (contact/self_collision.hpp), and not inside
/// a patch that cannot touch itself over the step (contact/broad_phase/normal_cone_tree.hpp: its
/// parts lie side by side on one layer); between the cloth and an obstacle always. Positions move
/// on straight lines over the step, x(t) = x_start + t (x_end - x_start), t in [0, 1]. The pipeline
/// (Bridson, Fedkiw and Anderson 2002, "Robust treatment of collisions, contact and friction for
/// cloth animation", sections 7.2-7.4; Harmon et al. 2008, "Robust treatment of simultaneous
/// collisions"):
///
/// 1. Repulsion (self-collision): a pair closer than the thickness h at the end of the step whose
///    distance shrank over it gets an inelastic impulse along its normal n that cancels the
///    approach, up to the missing distance h - d, with Coulomb friction: the tangential relative
///    displacement shrinks by mu times the normal one (sticking when it is smaller).
/// 2. Continuous detection (contact/ccd/additive_ccd.hpp): a pair whose distance may fall below
///    its gap g during the step (self: h / 10; an obstacle: half the sum of a sphere's or capsule's
///    radius and the collider's thickness, from its centre, axis, edges and faces: inside the
///    distance at which its point response keeps the points, so a point resting on it is no
///    collision) is a collision. A
///    few rounds of inelastic impulses, each cancelling the pair's approach along the normal at the
///    time of impact, with friction.
/// 3. Impact zones, the fail-safe, first by inelastic projection (Harmon et al. 2008, section 4;
///    contact/response/inelastic_projection.hpp): each collision that remains adds the
///    linearised constraint that its pair stop approaching along the normal at the time of
///    impact and part a little (contact/response/impact_zone_stages.hpp has the bound), and the
///    end positions are projected, in the mass
///    norm, onto every constraint gathered so far in the step. Only normal displacements
///    change: a zone keeps its sliding, and pinned points, the obstacles' and points held by a
///    solid (infinite mass) never move. Detection runs again after each projection.
/// 4. Rigid impact zones, the last resort, when the projection rounds are spent, when a round
///    finds no new pair and no fewer collisions than the last projection (it is stuck), or when
///    a constraint cannot be met by the points that may move: the points of the collisions that
///    remain merge into zones (a zone grows with every collision that touches it), and each zone
///    moves rigidly over the step, keeping its linear and angular momentum (contact/response/
///    impact_zones.hpp); a zone that holds an obstacle's element moves with that obstacle, one
///    that holds pinned points with their common displacement, one that holds a point resting
///    on a solid stays where it started. Rigid motion keeps the distances within a zone, so the
///    loop ends: at worst every colliding point moves as one body. A zone whose pinned points
///    move differently (or not with its obstacle) has no rigid motion that keeps them on their
///    targets: the pass then stops, unresolved, and never moves a pinned point.
///
/// An impulse on a pair with points i of weights a_i (barycentric, + on one side, - on the other)
/// and inverse masses w_i changes their displacements by a_i w_i lambda n / sum a_k^2 w_k, so
/// that the relative displacement along n changes by lambda: total momentum is unchanged, and an
/// inelastic normal impulse with friction no larger than Coulomb's never adds kinetic energy.
/// Velocities change by the displacement change over dt. Pinned points (w = 0) never move.
///
/// Cost: the broad phase (contact/response/surface_candidates.hpp: with self-collision a
/// hierarchy of the cloth's triangles refitted each round, without it a spatial hash of the
/// obstacles' pairs kept from step to step), then the narrow phase of each candidate. The work
/// arrays keep their capacity, so after the first steps nothing allocates.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "massspring/contact/ccd/additive_ccd.hpp"
#include "massspring/contact/colliders/colliders.hpp"
#include "massspring/contact/coulomb_friction.hpp"
#include "massspring/contact/distance/bounding_balls.hpp"
#include "massspring/contact/distance/edge_edge.hpp"
#include "massspring/contact/distance/point_triangle.hpp"
#include "massspring/contact/response/impact_zone_stages.hpp"
#include "massspring/contact/response/surface_candidates.hpp"
#include "massspring/contact/response/surface_contact_slot.hpp"
#include "massspring/contact/response/surface_elements.hpp"
#include "massspring/contact/self_collision.hpp"
#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The end-of-step pass of surface contact (see the file comment). A system creates it at
/// set_surface() or surface_contact() (SurfaceContactSlot), and only then compiles its code.
template <class Scalar>
class SurfaceContact final : public SurfacePass<Scalar> {
 public:
  using V3 = Vector3<Scalar>;
  using M3 = Eigen::Matrix<Scalar, 3, 3>;

  /// @brief Rounds of collision impulses before impact zones take over, >= 0. Default 12.
  [[nodiscard]] int impulse_rounds() const { return impulse_rounds_; }
  /// @brief Rounds of inelastic projection before rigid zones take over, >= 0. Default 32.
  [[nodiscard]] int projection_rounds() const { return projection_rounds_; }
  /// @brief Rounds of detection in all, >= 1; a step with collisions left after them is refused.
  /// Default 64, enough for zones to merge in any realistic step.
  [[nodiscard]] int max_rounds() const { return max_rounds_; }
  /// @throws Error when `rounds` < 0.
  SurfaceContact& set_impulse_rounds(int rounds) {
    impulse_rounds_ = checked_rounds("impulse_rounds", rounds, 0);
    return *this;
  }
  /// @throws Error when `rounds` < 0.
  SurfaceContact& set_projection_rounds(int rounds) {
    projection_rounds_ = checked_rounds("projection_rounds", rounds, 0);
    return *this;
  }
  /// @throws Error when `rounds` < 1: without a round of detection no step could be checked.
  SurfaceContact& set_max_rounds(int rounds) {
    max_rounds_ = checked_rounds("max_rounds", rounds, 1);
    return *this;
  }
  /// @brief What the last resolve() did.
  [[nodiscard]] const SurfaceContactReport& last_report() const { return last_report_; }

  [[nodiscard]] std::unique_ptr<SurfacePass<Scalar>> clone() const override {
    return std::make_unique<SurfaceContact>(*this);
  }

  /// @brief The pass over one step: from in.step.x_start (no crossing), the proposed end state
  /// in.step.x_end and v_end are changed in place (see SurfaceContactInput). Nothing without
  /// triangles.
  SurfaceContactReport resolve(const SurfaceContactInput<Scalar>& in) override {
    if (in.triangles.rows() == 0) return {};
    return resolve_impl(in);
  }

 private:
  using Input = SurfaceContactInput<Scalar>;
  using Pair = ElementPair;
  using Stencil = PairStencil<Scalar>;

  static int checked_rounds(const char* name, int rounds, int least) {
    if (rounds < least)
      throw Error(massspring::detail::message("surface contact: ", name, " must be >= ", least,
                                              ", got ", rounds));
    return rounds;
  }

  // What the pass is doing with the collisions that remain.
  enum class Stage { Impulses, Projection, Rigid };

  SurfaceContactReport resolve_impl(const Input& in) {
    SurfaceContactReport report;
    e_.setup(in);
    zones_.begin_step();
    colliders_ = &in.colliders;
    moved_.assign(std::size_t(e_.x0.rows()), 0);
    if (!e_.any_pairs) return last_report_ = report;
    const Scalar h = in.self_collision ? in.self_collision->thickness : Scalar(0);
    const Scalar mu = in.self_collision ? in.self_collision->friction : Scalar(0);
    Stage stage = Stage::Impulses;
    int projections = 0;
    for (int round = 0; round < max_rounds_; ++round) {
      report.rounds = round + 1;
      candidates(h, round == 0);
      // Repulsion moves points: those it pushed into a solid are held, and the candidates of
      // the motion it leaves are found again.
      if (round == 0 && in.self_collision) {
        const int repelled = repel(h, mu);
        report.impulses += repelled;
        if (repelled > 0) {
          e_.hold_pushed_into_solids(in, moved_);
          candidates(h, false);
        }
      }
      const std::size_t last_hits = round == 0 ? hits_.max_size() : hits_.size();
      if (!detect(round == 0)) break;
      if (round + 1 == max_rounds_) {
        report.resolved = false;
        break;
      }
      // Impulses while they make progress; then the projection; rigid zones when it is spent or
      // stuck.
      if (stage == Stage::Impulses && round < impulse_rounds_ && hits_.size() < last_hits) {
        report.impulses += collide(mu);
        e_.hold_pushed_into_solids(in, moved_);
        continue;
      }
      if (stage != Stage::Rigid && projections < projection_rounds_) {
        stage = Stage::Projection;
        ++projections;
        using Projection = typename ImpactZoneStages<Scalar>::Projection;
        const Projection done = zones_.project(e_, in, hits_, moved_, report);
        if (done == Projection::Immobile) projections = projection_rounds_;
        if (done != Projection::Stuck) continue;
      }
      stage = Stage::Rigid;
      if (!zones_.rigid(e_, in, hits_, moved_, report)) {
        report.resolved = false;
        break;
      }
    }
    // Write back: positions, and velocities changed by the change of displacement over dt.
    const int n = e_.n;
    const Scalar inv_dt = Scalar(1) / in.step.dt;
    for (int i = 0; i < n; ++i) {
      const V3 moved = e_.x1.row(i).transpose() - in.step.x_end.row(i).transpose();
      if (moved.isZero(0)) continue;
      in.step.x_end.row(i) = e_.x1.row(i);
      in.step.v_end.row(i) += inv_dt * moved.transpose();
    }
    return last_report_ = report;
  }

  // The cloth's boxes are grown by half the largest distance two cloth elements are tested at
  // (the thickness), an obstacle's by its gap; the stored ones by a further margin of half the
  // thickness (at least 0.5 mm), room for the impulses of the rounds and for the next steps of a
  // cloth that moves less than that per step.
  void candidates(Scalar h, bool first) {
    if (first) {
      const Scalar grow = std::max(h, e_.self_gap) / 2;
      broad_.next_step(e_, grow, std::max(grow, Scalar(5e-4)));
    } else {
      broad_.refresh(e_, moved_);
    }
  }

  // Applies a change lambda of the relative displacement along n to the stencil's points, and
  // Coulomb friction on the relative tangential displacement (at most mu * lambda). Returns
  // false when every point is immobile.
  bool impulse(const Stencil& s, Scalar lambda, Scalar mu) {
    // den = sum a_k^2 w_k, kept at least max |a_k| w_k / 2 so that no point moves more than
    // 2 lambda: a free corner of small weight beside immobile ones would otherwise take a
    // displacement of lambda / a_k (the impulse then cancels only part of the approach; the next
    // round or an impact zone does the rest).
    Scalar den = 0, lever = 0;
    for (int k = 0; k < 4; ++k) {
      const Scalar a = s.a[std::size_t(k)], w = e_.w(s.p[std::size_t(k)]);
      den += a * a * w;
      lever = std::max(lever, std::abs(a) * w);
    }
    if (!(den > 0)) return false;
    den = std::max(den, lever / 2);
    V3 rel = V3::Zero();
    for (int k = 0; k < 4; ++k) rel += s.a[std::size_t(k)] * e_.d(s.p[std::size_t(k)]);
    V3 change = lambda * s.n;
    if (mu > 0) {
      const V3 t = rel - rel.dot(s.n) * s.n;
      const Scalar len2 = t.squaredNorm();
      if (len2 > 0) change -= coulomb_removed_fraction(len2, lambda, mu, mu) * t;
    }
    for (int k = 0; k < 4; ++k) {
      const int i = s.p[std::size_t(k)];
      e_.x1.row(i) += (s.a[std::size_t(k)] * e_.w(i) / den) * change.transpose();
      moved_[std::size_t(i)] = 1;
    }
    return true;
  }

  // 1. Repulsion: pairs closer than h at the end of the step that came closer over it.
  int repel(Scalar h, Scalar mu) {
    int count = 0;
    for (const Pair& q : broad_.pairs()) {
      const std::array<int, 4> p = e_.points_of(q);
      const int split = q.split();
      if (!cloth_pair(q) || apart(p, split, h, false) ||
          !balls_within<Scalar>(at(p, e_.x1), split, h))
        continue;
      const Stencil s = e_.stencil(q, [&](int i) { return e_.p1(i); });
      if (!(s.distance < h)) continue;
      Scalar approach = 0;  // relative displacement along n over the step (< 0: closer)
      for (int k = 0; k < 4; ++k)
        approach += s.a[std::size_t(k)] * e_.d(s.p[std::size_t(k)]).dot(s.n);
      // Cancel the approach, up to the missing distance, and push a pair within half the
      // thickness a tenth of the way back out.
      const Scalar push = std::min(std::max(-approach, Scalar(0)), h - s.distance) +
                          (s.distance < h / 2 ? (h - s.distance) / 10 : Scalar(0));
      if (push > 0 && impulse(s, push, mu)) ++count;
    }
    return count;
  }
  // Whether the boxes of points p[0..split) and p[split..4), over the step (swept) or at its
  // end, are more than `distance` apart along some axis (then so are the elements).
  [[nodiscard]] bool apart(const std::array<int, 4>& p, int split, Scalar distance,
                           bool swept) const {
    for (int c = 0; c < 3; ++c) {
      Scalar lo[2] = {std::numeric_limits<Scalar>::infinity(),
                      std::numeric_limits<Scalar>::infinity()};
      Scalar hi[2] = {-lo[0], -lo[0]};
      for (int k = 0; k < 4; ++k) {
        const int side = k < split ? 0 : 1, i = p[std::size_t(k)];
        const Scalar a = e_.x1(i, c), b = swept ? e_.x0(i, c) : a;
        lo[side] = std::min({lo[side], a, b});
        hi[side] = std::max({hi[side], a, b});
      }
      if (lo[0] - hi[1] > distance || lo[1] - hi[0] > distance) return true;
    }
    return false;
  }
  // The positions of points p in x (x0 or x1).
  static std::array<V3, 4> at(const std::array<int, 4>& p, const Points<Scalar>& x) {
    return {V3(x.row(p[0]).transpose()), V3(x.row(p[1]).transpose()), V3(x.row(p[2]).transpose()),
            V3(x.row(p[3]).transpose())};
  }
  [[nodiscard]] bool cloth_pair(const Pair& q) const {
    const std::array<int, 2> owners = e_.owners_of(q);
    return owners[0] < 0 && owners[1] < 0;
  }

  // 2. Continuous detection of every candidate; the hits go to hits_ (pair, time of impact).
  bool detect(bool all) {
    hits_.clear();
    for (const Pair& q : broad_.pairs()) {
      const std::array<int, 4> p = e_.points_of(q);
      // A pair none of whose points moved since the last detection was clear then.
      if (!all && !(moved_[std::size_t(p[0])] || moved_[std::size_t(p[1])] ||
                    moved_[std::size_t(p[2])] || moved_[std::size_t(p[3])]))
        continue;
      const std::array<int, 2> owners = e_.owners_of(q);
      const Scalar gap = e_.pair_gap(owners[0], owners[1]);
      if (zones_.same_rigid_zone(p)) continue;
      // Swept boxes farther apart than the gap along an axis, or bounding balls that stay
      // farther apart: no contact during the step.
      const int split = q.split();
      if (apart(p, split, gap, true) ||
          !swept_balls_within<Scalar>(at(p, e_.x0), at(p, e_.x1), split, gap))
        continue;
      // The gap first; only a pair it reports needs the start distance (a pair that starts
      // closer keeps half of it): with a smaller gap the CCD could only report less.
      CcdResult<Scalar> r = ccd(q.kind, p, gap);
      Scalar kept = gap;
      if (r.hit) {
        kept = start_gap(q, gap);
        if (kept < gap) r = ccd(q.kind, p, kept);
      }
      if (r.hit) hits_.push_back({q, r.toi, kept, gap});
    }
    std::fill(moved_.begin(), moved_.end(), char(0));
    return !hits_.empty();
  }
  CcdResult<Scalar> ccd(ElementPairKind kind, const std::array<int, 4>& p, Scalar gap) const {
    const auto x = [&](int k) { return e_.p0(p[std::size_t(k)]); };
    const auto v = [&](int k) { return e_.d(p[std::size_t(k)]); };
    return kind == ElementPairKind::PointTriangle
               ? point_triangle_ccd<Scalar>(x(0), x(1), x(2), x(3), v(0), v(1), v(2), v(3), gap)
               : edge_edge_ccd<Scalar>(x(0), x(1), x(2), x(3), v(0), v(1), v(2), v(3), gap);
  }
  // A pair that starts closer than its gap (a user's start state) keeps at least half its start
  // distance instead.
  Scalar start_gap(const Pair& q, Scalar gap) const {
    const Stencil s = e_.stencil(q, [&](int i) { return e_.p0(i); });
    return s.distance < gap ? s.distance / 2 : gap;
  }

  // 2'. One round of inelastic impulses on the hits: each cancels its pair's approach along the
  // normal at the time of impact.
  int collide(Scalar mu) {
    int count = 0;
    for (const SurfaceHit<Scalar>& hit : hits_) {
      const Scalar toi = hit.toi;
      const Stencil s = e_.stencil(hit.pair, [&](int i) { return V3(e_.p0(i) + toi * e_.d(i)); });
      Scalar approach = 0;
      for (int k = 0; k < 4; ++k)
        approach += s.a[std::size_t(k)] * e_.d(s.p[std::size_t(k)]).dot(s.n);
      if (!(approach < 0)) approach = -std::numeric_limits<Scalar>::epsilon();
      // Friction between two cloth parts uses the self-collision coefficient; against an
      // obstacle's edges, the collider's kinetic one.
      const Scalar friction = cloth_pair(hit.pair) ? mu : obstacle_friction(hit.pair);
      for (int i : s.p) moved_[std::size_t(i)] = 1;  // tested again, moved or not
      if (impulse(s, -approach * Scalar(1.01), friction)) ++count;
    }
    return count;
  }
  // The kinetic friction of the collider on the pair's obstacle side.
  [[nodiscard]] Scalar obstacle_friction(const Pair& q) const {
    const std::array<int, 2> owners = e_.owners_of(q);
    const int owner = std::max(owners[0], owners[1]);
    return owner >= 0 ? (*colliders_)[owner].kinetic_friction() : Scalar(0);
  }

  int impulse_rounds_ = 12;
  int projection_rounds_ = 32;
  int max_rounds_ = 64;
  SurfaceContactReport last_report_;
  const ColliderSet<Scalar>* colliders_ = nullptr;  // the last resolve()'s
  SurfaceElements<Scalar> e_;
  std::vector<char> moved_;  // points whose end position changed since the last detection
  SurfaceCandidates<Scalar> broad_;
  std::vector<SurfaceHit<Scalar>> hits_;
  ImpactZoneStages<Scalar> zones_;
};

}  // namespace massspring::contact
