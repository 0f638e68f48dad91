#pragma once
/// @file
/// @brief MassSpringSystem<Scalar, Storage>: the model (rest positions, masses, springs, pins) and
/// the state (positions, velocities) of a mass-spring network.

#include <Eigen/Core>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include "massspring/contact/contact_pipeline.hpp"
#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/forces/force_term.hpp"
#include "massspring/storage/storage.hpp"
#include "massspring/types.hpp"

namespace massspring {

namespace detail {
/// @brief A number no other system state has had: bumped whenever Q's inputs change.
inline std::uint64_t next_revision() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}
}  // namespace detail

/// @brief A network of n point masses joined by m springs, some points pinned.
///
/// Units are SI throughout: positions in m, masses in kg, stiffness in N/m, damping in N s/m,
/// velocities in m/s. Every setter validates its input and throws massspring::Error naming the
/// offending point, spring or pin; nothing is changed when it throws.
///
/// The model is what an integrator factorizes: masses, stiffness, springs and the pinned set. Each
/// change of those gives the system a new revision(), and an integrator that sees a new revision
/// re-factorizes at its next step. Rest lengths, pin targets, positions and velocities may change
/// between steps at no such cost.
///
/// Obstacles of every shape and a surface need headers this one does not include (they are in
/// massspring/massspring.hpp): Collider::box() contact/colliders/box_shape.hpp, Collider::mesh()
/// mesh_shape.hpp, set_surface() and surface_contact() contact/response/surface_contact.hpp.
///
/// @tparam Scalar_  float or double
/// @tparam Storage_ massspring::Dense or massspring::Sparse: the type of the matrices it builds
template <class Scalar_, class Storage_ = Sparse>
class MassSpringSystem {
  static_assert(std::is_same_v<Scalar_, float> || std::is_same_v<Scalar_, double>,
                "MassSpringSystem<Scalar, Storage>: Scalar must be float or double");
  static_assert(is_storage_v<Storage_>,
                "MassSpringSystem<Scalar, Storage>: Storage must be massspring::Dense or "
                "massspring::Sparse");

 public:
  using Scalar = Scalar_;
  using Storage = Storage_;
  using Traits = storage_traits<Storage, Scalar>;
  /// @brief The Storage's matrix type (Eigen::Matrix or Eigen::SparseMatrix).
  using Matrix = typename Traits::Matrix;
  using Triplet = typename Traits::Triplet;
  using PointsType = Points<Scalar>;
  using VectorType = Vector<Scalar>;
  using Vector3Type = Vector3<Scalar>;

  /// @brief An empty system: no points, no springs.
  MassSpringSystem() = default;

  /// @brief A system with uniform mass and stiffness.
  /// @param[in] rest_positions #points by 3 rest positions [m]; positions start here, at rest.
  /// @param[in] springs        #springs by 2 point indices (0-based), no self or duplicate springs.
  /// @param[in] mass           mass of every point [kg], > 0.
  /// @param[in] stiffness      stiffness of every spring [N/m], >= 0.
  /// Rest lengths are the distances between the rest positions; damping is 0; nothing is pinned.
  template <class DerivedV, class DerivedE>
  MassSpringSystem(const Eigen::MatrixBase<DerivedV>& rest_positions,
                   const Eigen::MatrixBase<DerivedE>& springs, Scalar mass, Scalar stiffness) {
    assign_topology(rest_positions, springs);
    set_masses(VectorType::Constant(num_points(), mass));
    set_stiffness(VectorType::Constant(num_springs(), stiffness));
  }

  /// @brief A system with per-point masses and per-spring stiffness.
  /// @param[in] masses    #points masses [kg], each > 0.
  /// @param[in] stiffness #springs stiffness [N/m], each >= 0.
  template <class DerivedV, class DerivedE, class DerivedM, class DerivedK>
  MassSpringSystem(const Eigen::MatrixBase<DerivedV>& rest_positions,
                   const Eigen::MatrixBase<DerivedE>& springs,
                   const Eigen::MatrixBase<DerivedM>& masses,
                   const Eigen::MatrixBase<DerivedK>& stiffness) {
    assign_topology(rest_positions, springs);
    set_masses(masses);
    set_stiffness(stiffness);
  }

  // ---- sizes -------------------------------------------------------------------------------

  /// @brief Number of points n.
  [[nodiscard]] int num_points() const { return int(rest_positions_.rows()); }
  /// @brief Number of springs m.
  [[nodiscard]] int num_springs() const { return int(springs_.rows()); }
  /// @brief Number of pinned points p.
  [[nodiscard]] int num_pinned() const { return int(pinned_.size()); }

  // ---- model -------------------------------------------------------------------------------

  /// @brief #points by 3 rest positions [m].
  [[nodiscard]] const PointsType& rest_positions() const { return rest_positions_; }
  /// @brief #springs by 2 point indices.
  [[nodiscard]] const Edges& springs() const { return springs_; }
  /// @brief #points masses [kg].
  [[nodiscard]] const VectorType& masses() const { return masses_; }
  /// @brief #points inverse masses [1/kg]: 1 / m, and 0 for a pinned point (immobile).
  [[nodiscard]] const VectorType& inverse_masses() const { return inverse_masses_; }
  /// @brief #springs stiffness [N/m].
  [[nodiscard]] const VectorType& stiffness() const { return stiffness_; }
  /// @brief #springs rest lengths [m].
  [[nodiscard]] const VectorType& rest_lengths() const { return rest_lengths_; }
  /// @brief #springs damping coefficients along the spring axis [N s/m] (used by force terms that
  /// damp springs; the local-global solver ignores them).
  [[nodiscard]] const VectorType& damping() const { return damping_; }

  /// @brief Sets every point's mass [kg], each finite and > 0. New revision.
  template <class Derived>
  void set_masses(const Eigen::MatrixBase<Derived>& masses) {
    detail::require_rows("masses", masses.size(), num_points(), "point");
    detail::require_positive("point", "mass", masses, true);
    masses_ = masses.template cast<Scalar>();
    touch();
  }
  /// @brief Sets every spring's stiffness [N/m], each finite and >= 0. New revision.
  template <class Derived>
  void set_stiffness(const Eigen::MatrixBase<Derived>& stiffness) {
    detail::require_rows("stiffness", stiffness.size(), num_springs(), "spring");
    detail::require_positive("spring", "stiffness", stiffness, false);
    stiffness_ = stiffness.template cast<Scalar>();
    touch();
  }
  /// @brief Sets every spring's rest length [m], each finite and >= 0. Free: no new revision.
  template <class Derived>
  void set_rest_lengths(const Eigen::MatrixBase<Derived>& rest_lengths) {
    detail::require_rows("rest lengths", rest_lengths.size(), num_springs(), "spring");
    detail::require_positive("spring", "rest length", rest_lengths, false);
    rest_lengths_ = rest_lengths.template cast<Scalar>();
  }
  /// @brief Sets every spring's damping coefficient [N s/m], each finite and >= 0.
  template <class Derived>
  void set_damping(const Eigen::MatrixBase<Derived>& damping) {
    detail::require_rows("damping", damping.size(), num_springs(), "spring");
    detail::require_positive("spring", "damping", damping, false);
    damping_ = damping.template cast<Scalar>();
    damped_ = (damping_.array() != 0).any();
  }

  // ---- pins --------------------------------------------------------------------------------

  /// @brief Pins point i at its rest position. New revision (the pinned set changed).
  void pin(int i) { pin(i, rest_positions_.row(check_point("pin", i)).transpose()); }

  /// @brief Pins point i at `target` [m], or moves its target if it is pinned already.
  void pin(int i, const Vector3Type& target) {
    check_point("pin", i);
    check_target(i, target);
    const auto it = std::lower_bound(pinned_.begin(), pinned_.end(), i);
    const auto r = Eigen::Index(it - pinned_.begin());
    if (it != pinned_.end() && *it == i) {
      pin_targets_.row(r) = target.transpose();
      return;
    }
    PointsType targets(pin_targets_.rows() + 1, 3);
    targets << pin_targets_.topRows(r), target.transpose(),
        pin_targets_.bottomRows(pin_targets_.rows() - r);
    pinned_.insert(it, i);
    pin_targets_ = std::move(targets);
    touch();
  }

  /// @brief Pins each listed point at its rest position (0-based indices; repeats are harmless).
  void pin(const std::vector<int>& points) {
    for (int i : points) check_point("pin", i);
    for (int i : points) pin(i);
  }

  /// @brief Releases point i (no-op when it is not pinned). New revision when it was.
  void unpin(int i) {
    check_point("unpin", i);
    const auto it = std::lower_bound(pinned_.begin(), pinned_.end(), i);
    if (it == pinned_.end() || *it != i) return;
    const auto r = Eigen::Index(it - pinned_.begin());
    PointsType targets(pin_targets_.rows() - 1, 3);
    targets << pin_targets_.topRows(r), pin_targets_.bottomRows(pin_targets_.rows() - r - 1);
    pinned_.erase(it);
    pin_targets_ = std::move(targets);
    touch();
  }

  /// @brief Moves the target of pinned point i [m]. Free: no new revision.
  void set_pin_target(int i, const Vector3Type& target) {
    const int r = pin_row(i);
    if (r < 0) throw Error(detail::message("pin target: point ", i, " is not pinned"));
    check_target(i, target);
    pin_targets_.row(r) = target.transpose();
  }

  /// @brief Pinned point indices, ascending.
  [[nodiscard]] const std::vector<int>& pinned() const { return pinned_; }
  /// @brief #pinned by 3 targets, row r for point pinned()[r].
  [[nodiscard]] const PointsType& pin_targets() const { return pin_targets_; }
  /// @brief True when point i is pinned.
  [[nodiscard]] bool is_pinned(int i) const { return pin_row(i) >= 0; }
  /// @brief Row of point i in pinned() and pin_targets(), or -1.
  [[nodiscard]] int pin_row(int i) const {
    const auto it = std::lower_bound(pinned_.begin(), pinned_.end(), i);
    return it != pinned_.end() && *it == i ? int(it - pinned_.begin()) : -1;
  }

  // ---- state -------------------------------------------------------------------------------

  /// @brief #points by 3 positions [m].
  [[nodiscard]] const PointsType& positions() const { return positions_; }
  /// @brief #points by 3 velocities [m/s].
  [[nodiscard]] const PointsType& velocities() const { return velocities_; }

  /// @brief Direct access to the positions, for integrators: the caller keeps them finite.
  [[nodiscard]] PointsType& positions() { return positions_; }
  /// @brief Direct access to the velocities, for integrators: the caller keeps them finite.
  [[nodiscard]] PointsType& velocities() { return velocities_; }

  /// @brief Sets the positions [m]: #points by 3, finite.
  template <class Derived>
  void set_positions(const Eigen::MatrixBase<Derived>& positions) {
    check_state("positions", positions);
    positions_ = positions.template cast<Scalar>();
  }
  /// @brief Sets the velocities [m/s]: #points by 3, finite.
  template <class Derived>
  void set_velocities(const Eigen::MatrixBase<Derived>& velocities) {
    check_state("velocities", velocities);
    velocities_ = velocities.template cast<Scalar>();
  }

  // ---- force terms beyond the springs --------------------------------------------------------

  /// @brief Adds a force term (Gravity, ConstantForce, LinearDrag, GravitationalAttraction, or a
  /// type of your own: see forces/force_term.hpp). The system's own springs (Hooke, and damping
  /// where b > 0) are always applied and are not in this list. New revision (FastMassSpring folds
  /// linear drag into its matrix).
  /// @return the term's index in forces().
  template <class Term>
  int add_force(Term term) {
    if constexpr (detail::has_max_index<Term>::value) {
      const int top = term.max_index();
      if (top >= num_points())
        throw Error(detail::message(detail::term_name(term), ": point index ", top,
                                    " out of range [0, ", num_points(), ")"));
    }
    const int k = forces_.add(std::move(term));
    touch();
    return k;
  }
  /// @brief The force terms added with add_force().
  [[nodiscard]] const ForceSet<Scalar>& forces() const { return forces_; }
  /// @brief Removes every added force term (the springs stay). New revision.
  void clear_forces() {
    forces_.clear();
    touch();
  }
  /// @brief True when some spring has damping b > 0.
  [[nodiscard]] bool has_spring_damping() const { return damped_; }
  /// @brief The context force terms read: this system's model at positions x, velocities v.
  [[nodiscard]] ForceContext<Scalar> force_context(const PointsType& x, const PointsType& v,
                                                   bool definite = false) const {
    return {x, v, masses_, springs_, stiffness_, rest_lengths_, damping_, definite};
  }

  // ---- contact (contact/contact_pipeline.hpp: what each call below does) --------------------
  // None of these is a model change: no new revision, no re-factorization.

  /// @brief The system's contact: handler, colliders, surface, self-collision and the surface
  /// pass, and the response the integrators apply at the end of every step. Copies of the system
  /// get their own.
  [[nodiscard]] contact::ContactPipeline<Scalar>& contact() { return contact_; }
  [[nodiscard]] const contact::ContactPipeline<Scalar>& contact() const { return contact_; }

  /// @brief Sets the handler the integrators apply at the end of every step (a type derived from
  /// contact::CollisionHandler<Scalar>: SimpleCollisionHandler, ContinuousTimeCollisionHandler,
  /// HybridCollisionHandler, or your own), replacing any previous one.
  template <class Handler>
  void set_collision_handler(Handler handler) {
    contact_.set_collision_handler(std::move(handler));
  }
  /// @brief Removes the collision handler.
  void clear_collision_handler() { contact_.clear_collision_handler(); }
  /// @brief The collision handler, or nullptr when there is none.
  [[nodiscard]] contact::CollisionHandler<Scalar>* collision_handler() const {
    return contact_.collision_handler();
  }

  /// @brief Adds an obstacle (contact::Collider<Scalar>::plane(), sphere(), capsule(), box(),
  /// mesh()) that every integrator keeps the points out of; returns its index in colliders().
  int add_collider(contact::Collider<Scalar> collider) {
    return contact_.colliders().add(std::move(collider));
  }
  /// @brief The obstacles: move one, or change its material, between steps.
  [[nodiscard]] contact::ColliderSet<Scalar>& colliders() { return contact_.colliders(); }
  [[nodiscard]] const contact::ColliderSet<Scalar>& colliders() const {
    return contact_.colliders();
  }
  /// @brief True when a step has a collision response to apply (a handler, a collider, or
  /// self-collision).
  [[nodiscard]] bool has_collision_response() const { return contact_.active(); }

  /// @brief Sets the cloth's surface: #triangles by 3 point indices (0-based). Its triangles and
  /// their edges are what self-collision and the obstacles' edges test; springs stay the
  /// mechanics and may differ from its edges. An empty matrix removes it. Needs
  /// contact/response/surface_contact.hpp.
  /// @throws Error naming the triangle for an index out of range, a point repeated in a
  /// triangle, or a triangle of zero area at the rest positions; nothing is changed then.
  void set_surface(const Triangles& triangles) { contact_.set_surface(triangles, rest_positions_); }
  /// @brief The surface's triangles (#triangles by 3, 0-based; empty when none was set).
  [[nodiscard]] const Triangles& surface() const { return contact_.surface(); }
  /// @brief The surface's edges: each side of a triangle once, (i, j) with i < j, ascending.
  [[nodiscard]] const Edges& surface_edges() const { return contact_.surface_edges(); }

  /// @brief Turns self-collision on with these parameters (contact/self_collision.hpp); it acts
  /// on the surface, so set_surface() must have given one.
  /// @throws Error for a parameter out of range, or when the system has no surface.
  void set_self_collision(const contact::SelfCollision<Scalar>& parameters) {
    contact_.set_self_collision(parameters);
  }
  /// @brief Turns self-collision off (the default).
  void clear_self_collision() { contact_.clear_self_collision(); }
  /// @brief The self-collision parameters, or nothing when it is off.
  [[nodiscard]] const std::optional<contact::SelfCollision<Scalar>>& self_collision() const {
    return contact_.self_collision();
  }
  /// @brief The end-of-step surface contact pass (its rounds may be set), made on first use.
  /// Needs contact/response/surface_contact.hpp.
  [[nodiscard]] contact::SurfaceContact<Scalar>& surface_contact() {
    return contact_.surface_contact();
  }

  /// @brief Identifies the model Q is built from: it changes, to a value no system had before,
  /// whenever masses, stiffness, springs, the pinned set or the force terms change. Copies share
  /// it.
  [[nodiscard]] std::uint64_t revision() const { return revision_; }

  // ---- matrices (built from triplets, in the Storage's matrix type) --------------------------

  /// @brief Signed incidence matrix A (#springs by #points): row e of spring (i, j) has +1 at
  /// column i and -1 at column j.
  [[nodiscard]] Matrix incidence() const {
    std::vector<Triplet> t;
    t.reserve(2 * std::size_t(num_springs()));
    for (int e = 0; e < num_springs(); ++e) {
      t.emplace_back(e, springs_(e, 0), Scalar(1));
      t.emplace_back(e, springs_(e, 1), Scalar(-1));
    }
    return Traits::from_triplets(num_springs(), num_points(), t);
  }

  /// @brief Mass matrix M = diag(masses) (#points by #points).
  [[nodiscard]] Matrix mass_matrix() const { return diagonal(masses_); }

  /// @brief Stiffness matrix K = diag(stiffness) (#springs by #springs).
  [[nodiscard]] Matrix stiffness_matrix() const { return diagonal(stiffness_); }

  /// @brief Pin selector C (#pinned by #points): row r has 1 at column pinned()[r], so C X is
  /// the pinned points' positions.
  [[nodiscard]] Matrix pin_selector() const {
    std::vector<Triplet> t;
    t.reserve(pinned_.size());
    for (int r = 0; r < num_pinned(); ++r) t.emplace_back(r, pinned_[std::size_t(r)], Scalar(1));
    return Traits::from_triplets(num_pinned(), num_points(), t);
  }

 private:
  template <class DerivedV, class DerivedE>
  void assign_topology(const Eigen::MatrixBase<DerivedV>& rest_positions,
                       const Eigen::MatrixBase<DerivedE>& springs) {
    static_assert(std::is_integral_v<typename DerivedE::Scalar>,
                  "MassSpringSystem: springs must be an integer matrix (#springs by 2 indices)");
    if (rest_positions.cols() != 3)
      throw Error(detail::message("rest positions: expected #points by 3, got ",
                                  rest_positions.rows(), " by ", rest_positions.cols()));
    if (springs.cols() != 2 && springs.rows() > 0)
      throw Error(detail::message("springs: expected #springs by 2 point indices, got ",
                                  springs.rows(), " by ", springs.cols()));
    detail::require_finite_rows("point", "rest position", rest_positions);
    const Eigen::Index n = rest_positions.rows();
    const Eigen::Index m = springs.rows();
    std::vector<std::pair<std::pair<int, int>, int>> keys;
    keys.reserve(std::size_t(m));
    for (Eigen::Index e = 0; e < m; ++e) {
      const auto i = springs(e, 0), j = springs(e, 1);
      for (const auto p : {i, j})
        if (p < 0 || p >= n)
          throw Error(detail::message("spring ", e, " = (", i, ", ", j, "): point index ", p,
                                      " out of range [0, ", n, ")"));
      if (i == j) throw Error(detail::message("spring ", e, " connects point ", i, " to itself"));
      keys.push_back({{int(std::min(i, j)), int(std::max(i, j))}, int(e)});
    }
    std::sort(keys.begin(), keys.end());
    for (std::size_t k = 1; k < keys.size(); ++k)
      if (keys[k].first == keys[k - 1].first)
        throw Error(detail::message("spring ", keys[k].second, " duplicates spring ",
                                    keys[k - 1].second, ": both join points ", keys[k].first.first,
                                    " and ", keys[k].first.second));
    rest_positions_ = rest_positions.template cast<Scalar>();
    springs_ = springs.template cast<int>();
    positions_ = rest_positions_;
    velocities_ = PointsType::Zero(n, 3);
    rest_lengths_.resize(m);
    for (Eigen::Index e = 0; e < m; ++e)
      rest_lengths_(e) =
          (rest_positions_.row(springs_(e, 0)) - rest_positions_.row(springs_(e, 1))).norm();
    damping_ = VectorType::Zero(m);
    damped_ = false;
    masses_ = VectorType::Ones(n);
    stiffness_ = VectorType::Zero(m);
    touch();
  }

  int check_point(const char* what, int i) const {
    if (i < 0 || i >= num_points())
      throw Error(
          detail::message(what, ": point index ", i, " out of range [0, ", num_points(), ")"));
    return i;
  }

  void check_target(int i, const Vector3Type& target) const {
    if (!target.allFinite())
      throw Error(
          detail::message("pin ", i, ": target must be finite, got ", detail::format_row(target)));
  }

  template <class Derived>
  void check_state(const char* what, const Eigen::MatrixBase<Derived>& m) const {
    if (m.rows() != num_points() || m.cols() != 3)
      throw Error(detail::message(what, ": expected ", num_points(), " by 3, got ", m.rows(),
                                  " by ", m.cols()));
    detail::require_finite_rows("point", what, m);
  }

  [[nodiscard]] Matrix diagonal(const VectorType& d) const {
    std::vector<Triplet> t;
    t.reserve(std::size_t(d.size()));
    for (int i = 0; i < int(d.size()); ++i) t.emplace_back(i, i, d(i));
    return Traits::from_triplets(d.size(), d.size(), t);
  }

  // A new revision: masses, pins, springs or force terms changed.
  void touch() {
    revision_ = detail::next_revision();
    inverse_masses_ = masses_.cwiseInverse();
    for (int i : pinned_) inverse_masses_(i) = 0;
  }

  PointsType rest_positions_ = PointsType(0, 3);
  Edges springs_ = Edges(0, 2);
  VectorType masses_, inverse_masses_, stiffness_, rest_lengths_, damping_;
  std::vector<int> pinned_;
  ForceSet<Scalar> forces_;
  contact::ContactPipeline<Scalar> contact_;
  bool damped_ = false;
  PointsType pin_targets_ = PointsType(0, 3);
  PointsType positions_ = PointsType(0, 3);
  PointsType velocities_ = PointsType(0, 3);
  std::uint64_t revision_ = detail::next_revision();
};

}  // namespace massspring
