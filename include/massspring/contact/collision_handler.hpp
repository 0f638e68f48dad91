#pragma once
/// @file
/// @brief CollisionHandler: the one hook by which a particle collision response plugs into a time
/// step.
///
/// FOSSSim's order (Theme 2, ParticleSimulation::stepSystem): save (x, v), step the
/// integrator, then `handleCollisions(scene, detector, oldpos, oldvel, dt)`, which may change the
/// end-of-step positions and velocities. Here the end of an integrator's step (commit_step())
/// builds the step's CollisionStep once and calls
///
///     system.contact().respond(step);
///
/// (contact/contact_pipeline.hpp), which calls the handler first, before it commits (x_end,
/// v_end) to the system. The integrator does not know which response
/// the scene chose: the system carries at most one handler (MassSpringSystem::
/// set_collision_handler()), called once per step through one virtual function, never per pair.
/// Penalty responses are force terms instead (contact/fosssim/penalty.hpp) and need no hook.

#include <memory>
#include <type_traits>
#include <utility>

#include "massspring/contact/collision_step.hpp"
#include "massspring/detail/clone_slot.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief A collision response applied at the end of a step (impulses, impact zones). Derive,
/// implement handle(), clone() and name(). Handlers keep their work arrays between calls.
template <class Scalar>
class CollisionHandler {
 public:
  virtual ~CollisionHandler() = default;
  /// @brief A copy (a system copied is a new system with its own handler).
  [[nodiscard]] virtual std::unique_ptr<CollisionHandler> clone() const = 0;
  /// @brief Applies the response to s.x_end and s.v_end.
  virtual void handle(const CollisionStep<Scalar>& s) = 0;
  /// @brief For messages: "simple", "continuous-time", "hybrid", ...
  [[nodiscard]] virtual const char* name() const = 0;
};

/// @brief A value-semantic holder of at most one handler: copies clone it.
template <class Scalar>
class CollisionHandlerSlot : public massspring::detail::CloneSlot<CollisionHandler<Scalar>> {
 public:
  template <class Handler>
  void set(Handler handler) {
    static_assert(std::is_base_of_v<CollisionHandler<Scalar>, Handler>,
                  "set_collision_handler: the handler must derive from "
                  "massspring::contact::CollisionHandler<Scalar>");
    this->emplace(std::move(handler));
  }
};

}  // namespace massspring::contact
