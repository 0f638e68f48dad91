#pragma once
/// @file
/// @brief SurfaceContactSlot: how a system holds its surface contact pass (contact/response/
/// surface_contact.hpp) without including it, through the interface SurfacePass
/// (detail/clone_slot.hpp). The pass is created, and its code compiled, by the first call of
/// get(), which MassSpringSystem::set_surface() and surface_contact() make and which needs that
/// header; resolve(), the integrators' call, is one virtual call and does nothing while there is
/// no pass. A program that never sets a surface
/// neither includes nor compiles the pipeline (candidates, spatial hash, CCD, impact zones).
/// Also what a pass is given (SurfaceContactInput) and what it did (SurfaceContactReport), which
/// the integrators see without that header.

#include <memory>
#include <optional>

#include "massspring/contact/collision_step.hpp"
#include "massspring/contact/self_collision.hpp"
#include "massspring/detail/clone_slot.hpp"
#include "massspring/detail/is_complete.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

template <class Scalar>
class ColliderSet;
// Incomplete until the header named here is included: set_surface() and surface_contact() need it.
template <class Scalar>
class SurfaceContact;  // #include <massspring/contact/response/surface_contact.hpp> for a surface

/// @brief What surface contact is given for one step (see SurfaceContact::resolve()): the step's
/// contact state, the surface, the self-collision parameters (nothing: off) and the colliders
/// after their begin_step(step.dt).
template <class Scalar>
struct SurfaceContactInput {
  const CollisionStep<Scalar>& step;
  const Triangles& triangles;
  const Edges& edges;
  const std::optional<SelfCollision<Scalar>>& self_collision;
  const ColliderSet<Scalar>& colliders;
};

/// @brief What one SurfaceContact pass did.
struct SurfaceContactReport {
  /// @brief Repulsion and collision impulses applied.
  int impulses = 0;
  /// @brief Rounds of continuous detection (1 when the proposed motion had no collision).
  int rounds = 0;
  /// @brief Points moved rigidly in impact zones (in the last round that moved zones).
  int zone_points = 0;
  /// @brief Points the inelastic projection of impact zones moved, summed over its rounds.
  int projected_points = 0;
  /// @brief False when the fail-safe ran out of rounds with collisions left, or when a rigid
  /// zone would have had to move a pinned point off its prescribed motion (the state is then the
  /// last one tried; see SurfaceContact::max_rounds()).
  bool resolved = true;
};

/// @brief What a system's contact sees of its surface pass: SurfaceContact<Scalar> is the one
/// implementation.
template <class Scalar>
class SurfacePass {
 public:
  virtual ~SurfacePass() = default;
  /// @brief A copy (a system copied is a new system with its own pass).
  [[nodiscard]] virtual std::unique_ptr<SurfacePass> clone() const = 0;
  /// @brief The pass over one step (SurfaceContact::resolve()).
  virtual SurfaceContactReport resolve(const SurfaceContactInput<Scalar>& in) = 0;
};

/// @brief Owns at most one SurfaceContact<Scalar> (see the file comment); copies deep-copy it.
template <class Scalar>
class SurfaceContactSlot {
 public:
  /// @brief The pass, created on first use. Needs surface_contact.hpp.
  SurfaceContact<Scalar>& get() {
    static_assert(massspring::detail::is_complete_v<SurfaceContact<Scalar>>,
                  "set_surface() and surface_contact() need "
                  "#include <massspring/contact/response/surface_contact.hpp>");
    if (SurfacePass<Scalar>* pass = slot_.get()) return static_cast<SurfaceContact<Scalar>&>(*pass);
    return slot_.emplace(SurfaceContact<Scalar>());
  }

  /// @brief SurfaceContact::resolve() of the pass on `in`; nothing (an empty report) when there
  /// is no pass.
  SurfaceContactReport resolve(const SurfaceContactInput<Scalar>& in) {
    SurfacePass<Scalar>* pass = slot_.get();
    return pass ? pass->resolve(in) : SurfaceContactReport{};
  }

 private:
  massspring::detail::CloneSlot<SurfacePass<Scalar>> slot_;
};

}  // namespace massspring::contact
