#pragma once
/// @file
/// @brief ContactPipeline: everything a system's contact keeps between steps, and the one call
/// the end of every integrator's step makes (integrators/detail/commit_step.hpp):
///
///     const contact::SurfaceContactReport r = system.contact().respond(step, collider_friction);
///
/// It owns, in the order respond() applies them to the step's end state:
/// 1. at most one CollisionHandler (contact/collision_handler.hpp: FOSSSim's particle responses,
///    or a user's own);
/// 2. the colliders and their point response (contact/colliders/collider_set.hpp);
/// 3. the surface (triangles and their edges), the self-collision parameters and the surface
///    contact pass with its work arrays (contact/response/surface_contact.hpp), which keeps edges
///    from crossing triangles of the cloth and the obstacles' edges.
/// Every response takes the same CollisionStep (contact/collision_step.hpp), built once per step.
/// A program that never sets a handler, adds a collider or sets a surface compiles none of their
/// code: the handler and the surface pass are held through detail::CloneSlot, the colliders'
/// response through ColliderSet's table of entry points, each set where it is first used.

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "massspring/contact/colliders/collider_set.hpp"
#include "massspring/contact/collision_handler.hpp"
#include "massspring/contact/collision_step.hpp"
#include "massspring/contact/response/surface_contact_slot.hpp"
#include "massspring/contact/self_collision.hpp"
#include "massspring/detail/triangle_edges.hpp"
#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief A system's contact: handler, colliders, surface and self-collision, and the surface
/// pass (see the file comment). Copies are deep (a copied system has its own).
template <class Scalar>
class ContactPipeline {
 public:
  // ---- the handler ------------------------------------------------------------------------
  /// @brief Sets the handler (a type derived from CollisionHandler<Scalar>), replacing any other.
  template <class Handler>
  void set_collision_handler(Handler handler) {
    handler_.set(std::move(handler));
  }
  void clear_collision_handler() { handler_.reset(); }
  /// @brief The handler, or nullptr when there is none.
  [[nodiscard]] CollisionHandler<Scalar>* collision_handler() const { return handler_.get(); }

  // ---- the colliders ----------------------------------------------------------------------
  [[nodiscard]] ColliderSet<Scalar>& colliders() { return colliders_; }
  [[nodiscard]] const ColliderSet<Scalar>& colliders() const { return colliders_; }

  // ---- the surface and self-collision -----------------------------------------------------
  /// @brief Sets the surface: #triangles by 3 point indices, checked against the rest positions
  /// (detail::require_surface: indices in range, no point repeated, no zero area); an empty
  /// matrix removes it. Creates the surface pass (needs contact/response/surface_contact.hpp).
  /// @throws Error naming the triangle; nothing is changed then.
  void set_surface(const Triangles& triangles, const Points<Scalar>& rest_positions) {
    massspring::detail::require_surface(triangles, rest_positions);
    std::vector<std::pair<int, int>> edges;
    massspring::detail::triangle_edges(triangles, edges);
    Edges table(Eigen::Index(edges.size()), 2);
    for (std::size_t e = 0; e < edges.size(); ++e)
      table.row(Eigen::Index(e)) << edges[e].first, edges[e].second;
    surface_ = triangles;
    surface_edges_ = std::move(table);
    if (surface_.rows() > 0) static_cast<void>(pass_.get());  // creates the pass
  }
  [[nodiscard]] const Triangles& surface() const { return surface_; }
  /// @brief Each side of a surface triangle once, (i, j) with i < j, ascending.
  [[nodiscard]] const Edges& surface_edges() const { return surface_edges_; }
  /// @throws Error for a parameter out of range, or when there is no surface.
  void set_self_collision(const SelfCollision<Scalar>& parameters) {
    parameters.validate();
    if (surface_.rows() == 0)
      throw Error("self-collision: the system has no surface (set_surface(), or a scene's faces)");
    self_collision_ = parameters;
  }
  void clear_self_collision() { self_collision_.reset(); }
  [[nodiscard]] const std::optional<SelfCollision<Scalar>>& self_collision() const {
    return self_collision_;
  }
  /// @brief The surface pass (its rounds may be set), made on first use. Needs
  /// contact/response/surface_contact.hpp.
  [[nodiscard]] SurfaceContact<Scalar>& surface_contact() { return pass_.get(); }

  // ---- the step ---------------------------------------------------------------------------
  /// @brief True when a step has a response to apply (a handler, a collider, or self-collision).
  [[nodiscard]] bool active() const {
    return handler_.get() != nullptr || !colliders_.empty() || self_collision_;
  }
  /// @brief Applies the response to step.x_end and step.v_end: the handler, the colliders (which
  /// also take their end-of-step pose: begin_step(step.dt)), then the surface pass; returns what
  /// the surface pass did (an empty report without a surface). `collider_friction` false: the
  /// colliders act as frictionless (FastMassSpring's contact term applied their friction inside
  /// the iteration). Once the step is committed, the caller calls colliders().end_step().
  /// Allocates nothing once the work arrays have grown.
  SurfaceContactReport respond(const CollisionStep<Scalar>& step, bool collider_friction = true) {
    if (auto* handler = handler_.get()) handler->handle(step);
    if (!colliders_.empty()) colliders_.respond(step, collider_friction);
    return pass_.resolve({step, surface_, surface_edges_, self_collision_, colliders_});
  }

 private:
  CollisionHandlerSlot<Scalar> handler_;
  ColliderSet<Scalar> colliders_;
  Triangles surface_ = Triangles(0, 3);
  Edges surface_edges_ = Edges(0, 2);
  std::optional<SelfCollision<Scalar>> self_collision_;
  SurfaceContactSlot<Scalar> pass_;
};

}  // namespace massspring::contact
