#pragma once
/// @file
/// @brief ColliderSet: the obstacles of a system (MassSpringSystem::colliders()) and the contact
/// response every integrator applies at the end of a step; FastMassSpring also projects its
/// iterates with it inside the local-global iteration (docs/contact.md).
///
/// The response of a point that moves from x_s to x_e over a step of dt, with end velocity v_e,
/// against a collider in contact (contact/colliders/collider.hpp: depth delta = thickness -
/// phi(x_e), outward normal n, surface velocity u), colliders taken in the order they were added:
///
/// - Position (when delta > 0): x_e += delta n, then Coulomb friction at position level on the
///   displacement relative to the surface, d = x_e - x_s - s (before the push; s the surface
///   point's displacement over the step, Collider::surface_displacement(): u dt for a collider that
///   only translates), tangential part d_t: the point sticks (x_e -= d_t) when |d_t| <= mu_s
///   delta, else slides back by mu_k delta along d_t (Macklin et al. 2014, "Unified particle
///   physics for real-time applications", section 6.1).
/// - Velocity (when the relative normal velocity v_n = (v_e - u) . n is < 0): the normal impulse
///   per unit mass j = -(1 + e) v_n makes the relative normal velocity -e v_n; the tangential
///   relative velocity v_t becomes 0 when |v_t| <= mu_s j (stick) and shrinks by mu_k j otherwise
///   (Coulomb friction at velocity level: Bridson, Fedkiw and Anderson 2002, "Robust treatment of
///   collisions, contact and friction for cloth animation", section 7.2).
///
/// For an integrator whose end position is x_s + dt v_e (symplectic and backward Euler, the
/// local-global solver), the two agree: a point on a plane under gravity stays exactly where it
/// is, and a block on an incline slides with a = g (sin t - mu cos t). Afterwards up to two rounds
/// of normal pushes take a point out of any collider another one pushed it into. Pinned points
/// are left alone.
///
/// Compile time: the response's code (the analytic shapes' contact queries) is instantiated by
/// add(), which stores a table of pointers to it, and not by the calls an integrator makes
/// (respond(), project(), begin_step(), end_step(), undo_step()), which go through that table and
/// do nothing while the set has never had a collider. A program that never adds a collider does
/// not compile the response at all; a box's and a mesh's geometry come with Collider::box() and
/// Collider::mesh() (contact/colliders/box_shape.hpp, mesh_shape.hpp), not with this header.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "massspring/contact/colliders/collider.hpp"
#include "massspring/contact/collision_step.hpp"
#include "massspring/contact/coulomb_friction.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The colliders of a system, in the order they were added.
template <class Scalar>
class ColliderSet {
 public:
  using V3 = Vector3<Scalar>;

  /// @brief Adds a collider; returns its index.
  int add(Collider<Scalar> collider) {
    static constexpr Ops kOps{&ColliderSet::respond_all, &ColliderSet::project_one,
                              &ColliderSet::begin_all, &ColliderSet::end_all,
                              &ColliderSet::undo_all};
    ops_ = &kOps;
    colliders_.push_back(std::move(collider));
    impulses_.push_back(V3::Zero());
    return int(colliders_.size()) - 1;
  }
  /// @brief Removes every collider.
  void clear() {
    colliders_.clear();
    impulses_.clear();
  }
  [[nodiscard]] bool empty() const { return colliders_.empty(); }
  [[nodiscard]] int size() const { return int(colliders_.size()); }
  /// @brief Collider i (0 <= i < size()): set its pose, velocity or material between steps.
  [[nodiscard]] Collider<Scalar>& operator[](int i) { return colliders_[std::size_t(i)]; }
  [[nodiscard]] const Collider<Scalar>& operator[](int i) const {
    return colliders_[std::size_t(i)];
  }
  [[nodiscard]] auto begin() const { return colliders_.begin(); }
  [[nodiscard]] auto end() const { return colliders_.end(); }

  /// @brief The impulse [N s] collider i gave the points in the last respond(): the sum over the
  /// points of m (v_e after - v_e before) of its velocity response.
  [[nodiscard]] const V3& impulse(int i) const { return impulses_[std::size_t(i)]; }

  /// @brief Each collider's pose at the end of a step of dt [s] (used by the responses).
  void begin_step(Scalar dt) {
    if (ops_) ops_->begin_step(*this, dt);
  }
  /// @brief Each collider moves to its end-of-step pose: called once a step succeeded.
  void end_step() {
    if (ops_) ops_->end_step(*this);
  }
  /// @brief Each collider back to its pose before the last end_step().
  void undo_step() {
    if (ops_) ops_->undo_step(*this);
  }

  /// @brief The end-of-step response (see the file comment) of every point not pinned, from the
  /// step's start positions to its end state (step.x_end, step.v_end, changed in place); the
  /// masses weigh the impulses impulse() reports. Calls begin_step(step.dt). Allocates nothing.
  /// Without `friction`, the colliders act as frictionless (FastMassSpring's end-of-step state
  /// already holds the friction its contact term applied).
  void respond(const CollisionStep<Scalar>& step, bool friction = true) {
    if (ops_) ops_->respond(*this, step, friction);
  }

  /// @brief The position response of one point (3 coordinates each), x_end moved in place:
  /// FastMassSpring's projection of an iterate. With `edge_distance` rho > 0 [m] the point is then
  /// also kept out of the band about each box's edges and corners and each capsule's axis that
  /// Collider::push_off_edges() describes (never wider than x_start's distance from the edges or
  /// the axis), with Coulomb friction on that push as on the solid's (the solves' contact term
  /// passes the point's rho from detail::edge_distances(), so that the cloth's edges cannot cut a
  /// box's rim or a rod).
  /// begin_step(dt) must have been called.
  void project(const Scalar* x_start, Scalar* x_end, Scalar dt, Scalar edge_distance = 0) const {
    if (ops_) ops_->project(*this, x_start, x_end, dt, edge_distance);
  }

  /// @brief The contact tolerance at a point x [m]: a point within a few rounding units of a
  /// surface touches it (units of the point's coordinates, and of the collider's position and
  /// thickness); the response adds each collider's own slop().
  [[nodiscard]] static Scalar point_slop(const V3& x) {
    return 16 * std::numeric_limits<Scalar>::epsilon() * (1 + x.cwiseAbs().maxCoeff());
  }

  /// @brief False when the path x_start -> x_end is far from every collider (Collider::far(),
  /// its margin grown by `margin` [m]).
  template <class A, class B>
  [[nodiscard]] bool near(const A& x_start, const B& x_end, Scalar margin = 0) const {
    for (const auto& c : colliders_)
      if (!c.far(x_start, x_end, margin)) return true;
    return false;
  }

  /// @brief The least Collider::clearance() of x_start [m] (+infinity without colliders): for
  /// every x_end with |x_end - x_start| below it, project() without an edge distance leaves
  /// x_end as it is (with one, below it less the distance). For a caller
  /// that projects many ends of one start (FastMassSpring's iterations); begin_step(dt) must have
  /// been called.
  [[nodiscard]] Scalar clearance(const V3& x_start) const {
    Scalar least = std::numeric_limits<Scalar>::infinity();
    for (const auto& c : colliders_) least = std::min(least, c.clearance(x_start));
    return least;
  }

 private:
  // The response's entry points (see the file comment): add() stores their addresses, and only
  // add() names them, so that only a program that adds a collider instantiates them.
  struct Ops {
    void (*respond)(ColliderSet&, const CollisionStep<Scalar>&, bool);
    void (*project)(const ColliderSet&, const Scalar*, Scalar*, Scalar, Scalar);
    void (*begin_step)(ColliderSet&, Scalar);
    void (*end_step)(ColliderSet&);
    void (*undo_step)(ColliderSet&);
  };
  static void begin_all(ColliderSet& set, Scalar dt) {
    for (auto& c : set.colliders_) c.begin_step(dt);
  }
  static void end_all(ColliderSet& set) {
    for (auto& c : set.colliders_) c.end_step();
  }
  static void undo_all(ColliderSet& set) {
    for (auto& c : set.colliders_) c.undo_step();
  }
  static void respond_all(ColliderSet& set, const CollisionStep<Scalar>& step, bool friction) {
    set.respond_impl(step, friction);
  }
  static void project_one(const ColliderSet& set, const Scalar* x_start, Scalar* x_end, Scalar dt,
                          Scalar edge_distance) {
    set.project_impl(x_start, x_end, dt, edge_distance);
  }

  void respond_impl(const CollisionStep<Scalar>& step, bool friction) {
    begin_all(*this, step.dt);
    for (V3& j : impulses_) j.setZero();
    for (int i = 0; i < int(step.x_start.rows()); ++i) {
      if (step.inverse_masses(i) == 0) continue;  // pinned
      const V3 xs = step.x_start.row(i).transpose();
      V3 xe = step.x_end.row(i).transpose();
      if (!near(xs, xe)) continue;
      V3 ve = step.v_end.row(i).transpose();
      push(xs, xe, &ve, step.dt, step.masses(i), impulses_.data(), friction);
      step.x_end.row(i) = xe.transpose();
      step.v_end.row(i) = ve.transpose();
    }
  }

  void project_impl(const Scalar* x_start, Scalar* x_end, Scalar dt, Scalar edge_distance) const {
    const Eigen::Map<const V3> xs(x_start);
    const Eigen::Map<const V3> xe(x_end);
    if (!near(xs, xe, edge_distance)) return;  // most points: a few flops each
    V3 moved = xe;
    bool any = push(xs, moved, nullptr, dt, 0, nullptr, true);
    if (edge_distance > 0)
      for (const auto& c : colliders_) {
        ColliderContact<Scalar> k;
        const V3 d = moved - xs;  // before the push
        if (!c.push_off_edges(moved, xs, edge_distance, k)) continue;
        any = true;
        rub(c, k, V3(d - c.surface_displacement(moved, dt)), moved);
      }
    if (any)
      for (int c = 0; c < 3; ++c) x_end[c] = moved(c);
  }

  // Coulomb friction at position level on a push of k.depth along k.normal: takes
  // coulomb_removed_fraction() of the tangential part of d (the point's displacement over the
  // step less Collider::surface_displacement(), before the push) off xe.
  static void rub(const Collider<Scalar>& c, const ColliderContact<Scalar>& k, const V3& d,
                  V3& xe) {
    if (!(c.static_friction() > 0)) return;
    const V3 d_t = d - d.dot(k.normal) * k.normal;
    const Scalar f = coulomb_removed_fraction(d_t.squaredNorm(), k.depth, c.static_friction(),
                                              c.kinetic_friction());
    xe -= f * d_t;
  }

  // The response of one point (velocity too when ve is not null); true when anything moved.
  bool push(const V3& xs, V3& xe, V3* ve, Scalar dt, Scalar mass, V3* impulses,
            bool friction) const {
    bool moved = false;
    std::size_t pushed = colliders_.size();  // the collider that pushed the point last
    ColliderContact<Scalar> k;
    const Scalar slop = point_slop(xe);
    for (std::size_t ci = 0; ci < colliders_.size(); ++ci) {
      const Collider<Scalar>& c = colliders_[ci];
      if (!c.contact(xs, xe, slop + c.slop(), k)) continue;
      if (k.depth > 0) {
        const V3 d = xe - xs - c.surface_displacement(xe, dt);
        xe += k.depth * k.normal;
        moved = true;
        pushed = ci;
        if (friction) rub(c, k, d, xe);
      }
      if (ve) {
        const V3 vr = *ve - k.velocity;
        const Scalar vn = vr.dot(k.normal);
        if (vn < 0) {
          const Scalar e = c.restitution();
          const Scalar j = -(1 + e) * vn;
          V3 vt = vr - vn * k.normal;
          if (friction) {
            const Scalar f = coulomb_removed_fraction(vt.squaredNorm(), j, c.static_friction(),
                                                      c.kinetic_friction());
            if (f == 1)
              vt.setZero();
            else
              vt *= 1 - f;
          }
          const V3 after = k.velocity - e * vn * k.normal + vt;
          if (impulses) impulses[ci] += mass * (after - *ve);
          *ve = after;
          moved = true;
        }
      }
    }
    // A push out of one collider may have put the point into another: normal pushes only, up to
    // two rounds (the collider that pushed last has just left the point on its surface).
    for (int round = 0; pushed < colliders_.size() && round < 2 && colliders_.size() > 1; ++round) {
      const std::size_t last = pushed;
      pushed = colliders_.size();
      for (std::size_t ci = 0; ci < colliders_.size(); ++ci)
        if (ci != last && colliders_[ci].contact(xs, xe, Scalar(0), k) && k.depth > 0) {
          xe += k.depth * k.normal;
          pushed = ci;
        }
    }
    return moved;
  }

  std::vector<Collider<Scalar>> colliders_;
  std::vector<V3> impulses_;
  const Ops* ops_ = nullptr;  // set by the first add()
};

}  // namespace massspring::contact
