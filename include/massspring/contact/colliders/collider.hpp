#pragma once
/// @file
/// @brief Collider: an obstacle the points of a system cannot enter (a half-space, sphere,
/// capsule, oriented box or static triangle mesh), its material (Coulomb friction, restitution,
/// thickness) and its motion (a pose, a linear and an angular velocity). The response that uses
/// it is in contact/colliders/collider_set.hpp; docs/contact.md describes the model.
///
/// Frames. Each shape is defined in its own local frame, whose origin is the collider's reference
/// point: the plane's point, the sphere's, box's and capsule's centre (the capsule's midpoint),
/// the centre of a mesh's bounding box. The pose (R, t) maps local to world, x = R p + t; it
/// starts at the identity rotation with t the reference point, so a new collider lies where its
/// parameters say. A collider moves when the user sets its pose, or each step by its constant
/// velocity v [m/s] and angular velocity w [rad/s] (about t): t += v dt, R = exp([w] dt) R. The
/// velocity of the collider's surface at a world point x is v + w x (x - t); friction and
/// restitution act on velocities relative to it.
///
/// Contact. A point x is in contact when its signed distance phi(x) from the surface (negative
/// inside a solid) is below the thickness; the response moves it out to phi = thickness. A mesh
/// is a two-sided surface, not a solid: phi is the unsigned distance to the nearest triangle, and
/// a point whose straight path over the step crosses a triangle is caught (continuous detection)
/// and put back on the side it came from.
///
/// Compile time: a box's and a mesh's geometry (contact/distance/point_box.hpp, the mesh's
/// hierarchy) are in contact/colliders/box_shape.hpp and mesh_shape.hpp, which box() and mesh()
/// need; the collider reaches them through a table of pointers those factories set, so a program
/// that never makes a box or a mesh does not include or compile them.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "massspring/contact/colliders/collider_contact.hpp"
#include "massspring/contact/colliders/contact_zone.hpp"
#include "massspring/contact/colliders/rotation.hpp"
#include "massspring/contact/distance/point_segment.hpp"
#include "massspring/detail/is_complete.hpp"
#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

template <class Scalar>
class TriangleMesh;
// Defined in box_shape.hpp and mesh_shape.hpp, which Collider::box() and Collider::mesh() need.
template <class Scalar>
struct BoxShape;
template <class Scalar>
struct MeshShape;
// Defined in solid_path.hpp (included at the end of this file).
template <class Scalar>
struct SolidPath;

/// @brief An obstacle: shape, material and motion. Build one with the static functions plane(),
/// sphere(), capsule(), box() and mesh(); set its material and motion with the setters, which
/// validate their arguments (Error naming the parameter).
template <class Scalar>
class Collider {
 public:
  using V3 = Vector3<Scalar>;
  using M3 = Eigen::Matrix<Scalar, 3, 3>;

  /// @brief The half-space {x : (x - point) . normal >= 0} is free; the other side is solid.
  /// The normal [any length > 0] is normalised.
  static Collider plane(const V3& point, const V3& normal) {
    check_finite(point, "plane: point");
    check_finite(normal, "plane: normal");
    const Scalar len = normal.norm();
    if (!(len > 0)) throw Error("plane collider: the normal must not be zero");
    Collider c(ColliderShape::Plane, point);
    c.axis_ = normal / len;
    c.refresh();
    return c;
  }
  /// @brief A solid ball of radius > 0 [m] about center [m].
  static Collider sphere(const V3& center, Scalar radius) {
    check_finite(center, "sphere: center");
    check_positive(radius, "sphere collider: radius");
    Collider c(ColliderShape::Sphere, center);
    c.radius_ = radius;
    c.refresh();
    return c;
  }
  /// @brief The solid points within radius > 0 [m] of the segment [a, b] (a = b is a sphere).
  static Collider capsule(const V3& a, const V3& b, Scalar radius) {
    check_finite(a, "capsule: a");
    check_finite(b, "capsule: b");
    check_positive(radius, "capsule collider: radius");
    Collider c(ColliderShape::Capsule, (a + b) / 2);
    c.axis_ = (b - a) / 2;  // local segment: [-axis_, +axis_]
    c.radius_ = radius;
    c.refresh();
    return c;
  }
  /// @brief A solid box with the given centre [m], half extents (each > 0) [m] along its axes,
  /// and orientation: the unit quaternion (w, x, y, z) (normalised here; not zero). Defined in
  /// contact/colliders/box_shape.hpp.
  template <class S = Scalar>
  static Collider box(const V3& center, const V3& half_extents,
                      const Eigen::Matrix<Scalar, 4, 1>& wxyz = Eigen::Matrix<Scalar, 4, 1>(1, 0, 0,
                                                                                            0)) {
    static_assert(massspring::detail::is_complete_v<BoxShape<S>>,
                  "Collider::box() needs #include <massspring/contact/colliders/box_shape.hpp>");
    return BoxShape<S>::make(center, half_extents, wxyz);
  }
  /// @brief A static triangle mesh (vertices [m], triangles as 0-based indices), two-sided.
  /// Throws Error for a degenerate mesh (see TriangleMesh). Defined in
  /// contact/colliders/mesh_shape.hpp.
  template <class S = Scalar>
  static Collider mesh(Points<Scalar> vertices, Triangles triangles) {
    static_assert(massspring::detail::is_complete_v<MeshShape<S>>,
                  "Collider::mesh() needs #include <massspring/contact/colliders/mesh_shape.hpp>");
    return MeshShape<S>::make(std::move(vertices), std::move(triangles));
  }

  [[nodiscard]] ColliderShape shape() const { return shape_; }

  // ---- material ---------------------------------------------------------------------------------

  /// @brief Coulomb friction coefficient, static = kinetic = mu (>= 0, finite; default 0).
  Collider& set_friction(Scalar mu) { return set_friction(mu, mu); }
  /// @brief Static and kinetic Coulomb coefficients (0 <= kinetic <= static, finite).
  Collider& set_friction(Scalar mu_static, Scalar mu_kinetic) {
    if (!(mu_static >= 0 && mu_kinetic >= 0) || !std::isfinite(double(mu_static)) ||
        !std::isfinite(double(mu_kinetic)))
      throw Error(massspring::detail::message(to_string(shape_),
                                              " collider: friction must be finite and >= 0, got ",
                                              mu_static, " and ", mu_kinetic));
    if (mu_kinetic > mu_static)
      throw Error(massspring::detail::message(to_string(shape_), " collider: kinetic friction ",
                                              mu_kinetic, " exceeds static friction ", mu_static,
                                              " (Coulomb: kinetic <= static)"));
    mu_static_ = mu_static;
    mu_kinetic_ = mu_kinetic;
    return *this;
  }
  /// @brief Coefficient of restitution e in [0, 1] (default 0, inelastic): the normal velocity
  /// relative to the collider after contact is -e times the one before.
  Collider& set_restitution(Scalar e) {
    if (!(e >= 0 && e <= 1))
      throw Error(massspring::detail::message(to_string(shape_),
                                              " collider: restitution must be in [0, 1], got ", e));
    restitution_ = e;
    return *this;
  }
  /// @brief Distance [m] from the surface at which contact starts (>= 0, finite; default 0).
  Collider& set_thickness(Scalar thickness) {
    if (!(thickness >= 0) || !std::isfinite(double(thickness)))
      throw Error(massspring::detail::message(
          to_string(shape_), " collider: thickness must be finite and >= 0, got ", thickness));
    thickness_ = thickness;
    refresh();
    return *this;
  }
  [[nodiscard]] Scalar static_friction() const { return mu_static_; }
  [[nodiscard]] Scalar kinetic_friction() const { return mu_kinetic_; }
  [[nodiscard]] Scalar restitution() const { return restitution_; }
  [[nodiscard]] Scalar thickness() const { return thickness_; }

  // ---- motion -----------------------------------------------------------------------------------

  /// @brief Moves the collider to the pose (R, t): R a rotation (orthonormal, det +1, to 1e-6), t
  /// the reference point's new position [m]; a box's R includes its orientation (the pose maps
  /// its axes). Takes effect at once; no re-factorization is ever needed. Friction sees the
  /// collider's velocity (set_velocity), not the jump from one pose to the next.
  Collider& set_pose(const M3& rotation, const V3& translation) {
    check_finite(translation, "pose: translation");
    const Scalar tol = std::max(Scalar(1e-6), 100 * std::numeric_limits<Scalar>::epsilon());
    if (!rotation.allFinite() ||
        !((rotation.transpose() * rotation - M3::Identity()).cwiseAbs().maxCoeff() <= tol) ||
        !(rotation.determinant() > 0))
      throw Error(massspring::detail::message(
          to_string(shape_),
          " collider: pose rotation must be a rotation matrix (R^T R = I, "
          "det R = +1)"));
    rotation_ = rotation;
    translation_ = translation;
    end_rotation_ = rotation;
    end_translation_ = translation;
    previous_rotation_ = rotation;
    previous_translation_ = translation;
    refresh();
    return *this;
  }
  /// @brief Constant linear velocity [m/s] of the reference point (default 0).
  Collider& set_velocity(const V3& v) {
    check_finite(v, "velocity");
    velocity_ = v;
    refresh();
    return *this;
  }
  /// @brief Constant angular velocity [rad/s] about the reference point (default 0).
  Collider& set_angular_velocity(const V3& w) {
    check_finite(w, "angular_velocity");
    angular_velocity_ = w;
    refresh();
    return *this;
  }
  [[nodiscard]] const M3& rotation() const { return rotation_; }
  [[nodiscard]] const V3& translation() const { return translation_; }
  /// @brief The pose set by the last begin_step(): where the collider will be at the step's end.
  [[nodiscard]] const M3& end_rotation() const { return end_rotation_; }
  [[nodiscard]] const V3& end_translation() const { return end_translation_; }
  [[nodiscard]] const V3& velocity() const { return velocity_; }
  [[nodiscard]] const V3& angular_velocity() const { return angular_velocity_; }
  /// @brief The mesh of a mesh collider (null for the others).
  [[nodiscard]] const std::shared_ptr<const TriangleMesh<Scalar>>& triangle_mesh() const {
    return mesh_;
  }
  /// @brief Local-frame parameters: the plane's unit normal, the capsule's half segment
  /// (b - a) / 2, the box's half extents; the sphere's and capsule's radius.
  [[nodiscard]] const V3& axis() const { return axis_; }
  [[nodiscard]] Scalar radius() const { return radius_; }
  /// @brief The collider's part of the contact tolerance [m]: a few rounding units of its
  /// position and thickness (ColliderSet adds the point's).
  [[nodiscard]] Scalar slop() const { return slop_; }

  /// @brief Keeps x (outside the solid, at the end pose) out of the band the solves keep clear
  /// about a box's edges and corners (to rho + thickness() from them: BoxShape::push_off_edges())
  /// or a capsule's axis (radially, to max(r + thickness(), sqrt(r^2 + rho^2 / 2))), rho =
  /// `distance` [m] the solves' edge distance (integrators/detail/contact_dual.hpp says why no
  /// segment of length sqrt(2) rho between two points so kept meets the solid). The band is never
  /// wider than the distance of x_start (the point's position at the step's start, at the start
  /// pose) from the edges or the axis: a point that starts the step inside the band is kept from
  /// going deeper, not thrown out to its width (a long surface edge's band can be metres wide;
  /// the end-of-step pass keeps the no-crossing guarantee). Other shapes: false. True when x
  /// moved; `push` then holds its unit direction (normal), length (depth) and the surface's
  /// velocity at x. Called inside the solves (ColliderSet::project()).
  bool push_off_edges(V3& x, const V3& x_start, Scalar distance,
                      ColliderContact<Scalar>& push) const {
    V3 p = end_rotation_.transpose() * (x - end_translation_);
    const V3 p_start = rotation_.transpose() * (x_start - translation_);
    if (shape_ == ColliderShape::Capsule
            ? !push_off_axis(p, p_start, distance)
            : !geometry_ || !geometry_->push_off_edges ||
                  !geometry_->push_off_edges(*this, p, p_start, distance + thickness_))
      return false;
    const V3 to = end_rotation_ * p + end_translation_, moved = to - x;
    x = to;
    push.depth = moved.norm();
    if (!(push.depth > 0)) return false;
    push.normal = moved / push.depth;
    push.velocity = surface_velocity(x);
    return true;
  }
  /// @brief The displacement [m] over the step begin_step(dt) set of the surface point at x at
  /// the step's end: x - (R R_end^T (x - t_end) + t) (R, t the current pose), exact for the rigid
  /// motion of a turning collider; dt times the velocity for one that only translates, 0 at rest.
  /// Position-level friction compares a point's displacement with it (ColliderSet).
  [[nodiscard]] V3 surface_displacement(const V3& x, Scalar dt) const {
    if (!moving_) return V3::Zero();
    if (angular_velocity_.isZero(0)) return dt * velocity_;
    return x - (rotation_ * (end_rotation_.transpose() * (x - end_translation_)) + translation_);
  }
  /// @brief Sets the pose the collider will have at the end of a step of dt [s] (its velocities
  /// applied); contact() uses it. Called by ColliderSet::begin_step().
  void begin_step(Scalar dt) {
    end_translation_ = translation_ + dt * velocity_;
    end_rotation_ = rotation_exp<Scalar>(angular_velocity_ * dt) * rotation_;
    // How far a point of the collider moves over the step.
    zone_.motion =
        (end_translation_ - translation_).norm() + angular_velocity_.norm() * dt * bound_;
    refresh();
  }
  /// @brief Makes the end-of-step pose the current one (after a successful step).
  void end_step() {
    previous_rotation_ = rotation_;
    previous_translation_ = translation_;
    rest_at(end_rotation_, end_translation_);
  }
  /// @brief Back to the pose before the last end_step() (a step rejected after it was
  /// committed, e.g. by DivergenceGuard).
  void undo_step() { rest_at(previous_rotation_, previous_translation_); }

  /// @brief True when no point of the path x_start -> x_end can be in contact: the quick test
  /// contact() starts with (ContactZone::far(); slop [m] adds to its margin).
  template <class A, class B>
  [[nodiscard]] bool far(const A& x_start, const B& x_end, Scalar slop) const {
    return zone_.far(x_start, x_end, slop);
  }
  /// @brief ContactZone::clearance(): no path from x_start shorter than it [m] comes into
  /// contact. begin_step() must have been called.
  [[nodiscard]] Scalar clearance(const V3& x_start) const { return zone_.clearance(x_start); }
  /// @brief The contact of a point that moves from x_start (start of the step, collider at its
  /// current pose) to x_end (end of the step, collider at its end pose): true, with c set, when
  /// phi(x_end) < thickness + slop, or the path crosses a triangle (mesh), or the path starts
  /// outside a sphere, capsule or box, passes through it and ends beyond it (c then pushes x_end
  /// back onto the plane tangent where the path entered).
  bool contact(const V3& x_start, const V3& x_end, Scalar slop, ColliderContact<Scalar>& c) const {
    if (far(x_start, x_end, slop)) return false;
    Scalar phi = 0;
    switch (shape_) {
      // local_phi() in the world frame, for the two shapes a rotation leaves as they are: no
      // change of frame. A point at a sphere's centre takes local_phi()'s normal e_z, rotated.
      case ColliderShape::Plane:
        phi = zone_.normal.dot(x_end - end_translation_);
        c.normal = zone_.normal;
        break;
      case ColliderShape::Sphere: {
        const V3 p = x_end - end_translation_;
        const Scalar r = p.norm();
        phi = r - radius_;
        c.normal = r > 0 ? V3(p / r) : V3(end_rotation_.col(2));
        break;
      }
      case ColliderShape::Capsule:
      case ColliderShape::Box: {
        V3 n_local;
        phi = local_phi(end_rotation_.transpose() * (x_end - end_translation_), n_local);
        c.normal = end_rotation_ * n_local;
        break;
      }
      case ColliderShape::Mesh:
        return geometry_->contact(*this, x_start,
                                  end_rotation_.transpose() * (x_end - end_translation_), slop, c);
    }
    if (!(phi < thickness_ + slop)) {
      if (shape_ == ColliderShape::Plane ||
          !SolidPath<Scalar>::crossed(*this, x_start, x_end, phi, slop, c))
        return false;
      c.velocity = surface_velocity(x_end);
      return true;
    }
    c.depth = thickness_ - phi;
    // The nearest surface point may be on the far side (a point dragged past a sphere's centre
    // would be pushed out of its bottom): when the push would go on along the point's path, or
    // the point is deeper than half the solid's inner size, a point that came from outside
    // leaves through the tangent plane where its path entered instead.
    if (c.depth > 0 && (c.normal.dot(x_start - x_end) < 0 || c.depth > inner_ / 2))
      SolidPath<Scalar>::entry_push(*this, x_start, x_end, slop, 1, c);
    c.velocity = surface_velocity(x_end);
    return true;
  }

 private:
  friend struct BoxShape<Scalar>;
  friend struct MeshShape<Scalar>;
  friend struct SolidPath<Scalar>;
  // A box's or a mesh's geometry (box_shape.hpp, mesh_shape.hpp): phi and the outward normal at
  // a local point (box), the contact of a path (mesh, as contact() with x_end in the end frame),
  // the radius of a ball about the reference point that holds the shape.
  struct Geometry {
    Scalar (*phi)(const Collider&, const V3& p, V3& n);
    bool (*contact)(const Collider&, const V3& x_start, const V3& b, Scalar slop,
                    ColliderContact<Scalar>& c);
    Scalar (*bound)(const Collider&);
    bool (*push_off_edges)(const Collider&, V3& p, const V3& p_start, Scalar distance);
  };

  Collider(ColliderShape shape, const V3& reference) : shape_(shape), translation_(reference) {
    end_translation_ = reference;
    previous_translation_ = reference;
  }

  // Between steps at this pose: the current and the end-of-step pose both this one, no motion.
  void rest_at(const M3& rotation, const V3& translation) {
    rotation_ = rotation;
    translation_ = translation;
    end_rotation_ = rotation;
    end_translation_ = translation;
    zone_.motion = 0;
    refresh();
  }
  // The contact zone at the end pose (contact_zone.hpp) and the slop, from the shape and pose.
  void refresh() {
    switch (shape_) {
      case ColliderShape::Plane:
        bound_ = 0;
        inner_ = std::numeric_limits<Scalar>::infinity();
        break;
      case ColliderShape::Sphere:
        bound_ = radius_;
        inner_ = radius_;
        break;
      case ColliderShape::Capsule:
        bound_ = axis_.norm() + radius_;
        inner_ = radius_;
        break;
      case ColliderShape::Box:
        bound_ = axis_.norm();
        inner_ = axis_.minCoeff();
        break;
      case ColliderShape::Mesh:
        bound_ = geometry_->bound(*this);
        break;
    }
    const Scalar margin = std::sqrt(std::numeric_limits<Scalar>::epsilon()) *
                          (1 + bound_ + thickness_ + end_translation_.cwiseAbs().maxCoeff());
    zone_.shape = shape_;
    zone_.normal = end_rotation_ * axis_;
    zone_.centre = end_translation_;
    zone_.offset = zone_.normal.dot(end_translation_) + thickness_ + margin;
    zone_.reach = bound_ + thickness_ + margin;
    moving_ = !velocity_.isZero(0) || !angular_velocity_.isZero(0);
    slop_ = 16 * std::numeric_limits<Scalar>::epsilon() *
            (end_translation_.cwiseAbs().maxCoeff() + thickness_);
  }

  static void check_finite(const V3& v, const char* what) {
    if (!v.allFinite())
      throw Error(massspring::detail::message("collider ", what, " must be finite, got (", v(0),
                                              ", ", v(1), ", ", v(2), ")"));
  }
  static void check_positive(Scalar x, const char* what) {
    if (!(x > 0) || !std::isfinite(double(x)))
      throw Error(massspring::detail::message(what, " must be finite and > 0, got ", x));
  }

  // phi and the outward normal of an analytic solid at a local point p.
  Scalar local_phi(const V3& p, V3& n) const {
    switch (shape_) {
      case ColliderShape::Plane:
        n = axis_;
        return axis_.dot(p);
      case ColliderShape::Sphere: {
        const Scalar r = p.norm();
        n = r > 0 ? V3(p / r) : V3::UnitZ();
        return r - radius_;
      }
      case ColliderShape::Capsule: {
        const auto d = point_segment_distance<Scalar>(p, -axis_, axis_);
        n = d.distance > 0 ? V3(-d.n / d.distance) : perpendicular<Scalar>(axis_);
        return d.distance - radius_;
      }
      case ColliderShape::Box:
        return geometry_->phi(*this, p, n);
      case ColliderShape::Mesh:
        break;
    }
    n = V3::UnitZ();
    return 0;
  }

  // push_off_edges() of a capsule: p (local) closer than D to the axis moves radially from its
  // nearest axis point to D (along a perpendicular when on the axis), D at most p_start's
  // distance from the axis and at least r + thickness.
  bool push_off_axis(V3& p, const V3& p_start, Scalar rho) const {
    const auto d = point_segment_distance<Scalar>(p, -axis_, axis_);
    const Scalar band = std::min(std::sqrt(radius_ * radius_ + rho * rho / 2),
                                 point_segment_distance<Scalar>(p_start, -axis_, axis_).distance);
    const Scalar keep = std::max(radius_ + thickness_, band);
    if (!(d.distance < keep)) return false;
    p = d.closest + keep * (d.distance > 0 ? V3(-d.n / d.distance) : perpendicular<Scalar>(axis_));
    return true;
  }

  V3 surface_velocity(const V3& x) const {
    if (!moving_) return V3::Zero();
    return velocity_ + angular_velocity_.cross(x - end_translation_);
  }

  ColliderShape shape_;
  V3 axis_ = V3::Zero();
  Scalar radius_ = 0;
  std::shared_ptr<const TriangleMesh<Scalar>> mesh_;
  const Geometry* geometry_ = nullptr;  // a box's or a mesh's (set by box() or mesh())
  Scalar mu_static_ = 0, mu_kinetic_ = 0, restitution_ = 0, thickness_ = 0;
  M3 rotation_ = M3::Identity();
  V3 translation_;
  V3 velocity_ = V3::Zero(), angular_velocity_ = V3::Zero();
  M3 end_rotation_ = M3::Identity();       // the pose at the end of the current step (begin_step())
  M3 previous_rotation_ = M3::Identity();  // the pose before the last end_step()
  V3 previous_translation_ = V3::Zero();
  V3 end_translation_;
  ContactZone<Scalar> zone_;  // refresh(); its motion by begin_step() and rest_at()
  Scalar bound_ = 0;          // the shape's bounding radius about its reference point
  Scalar slop_ = 0;           // slop()
  Scalar inner_ = 0;          // half the solid's smallest size: deeper, SolidPath decides
  bool moving_ = false;       // a velocity or an angular velocity is not zero
};

}  // namespace massspring::contact

#include "massspring/contact/colliders/solid_path.hpp"
