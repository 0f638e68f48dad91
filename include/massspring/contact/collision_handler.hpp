#pragma once
/// @file
/// @brief CollisionHandler: the one hook by which collision response plugs into a time step, and
/// handle_collisions(), the call an integrator makes after it computed the end-of-step state.
///
/// FOSSSim's order (Theme 2, ParticleSimulation::stepSystem): save (x, v), step the
/// integrator, then `handleCollisions(scene, detector, oldpos, oldvel, dt)`, which may change the
/// end-of-step positions and velocities. Here an integrator calls
///
///     contact::handle_collisions(system, x_start, v_start, x_end, v_end, dt);
///
/// before it commits (x_end, v_end) to the system. The integrator does not know which response
/// the scene chose: the system carries at most one handler (MassSpringSystem::
/// set_collision_handler()), called once per step through one virtual function, never per pair.
/// Penalty responses are force terms instead (contact/fosssim/penalty.hpp) and need no hook.

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief What a handler sees of one step. Arrays are #points by 3, borrowed for the call.
template <class Scalar>
struct CollisionStep {
  /// @brief Positions at the start of the step [m].
  const Points<Scalar>& x_start;
  /// @brief Velocities at the start of the step [m/s].
  const Points<Scalar>& v_start;
  /// @brief Positions the integrator computed for the end of the step [m]; the handler may change
  /// them.
  Points<Scalar>& x_end;
  /// @brief Velocities the integrator computed for the end of the step [m/s]; the handler may
  /// change them.
  Points<Scalar>& v_end;
  /// @brief The step [s], > 0.
  Scalar dt;
  /// @brief #points masses [kg].
  const Vector<Scalar>& masses;
  /// @brief Pinned (FOSSSim's fixed) points, ascending: infinite mass, never moved.
  const std::vector<int>& pinned;
};

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
class CollisionHandlerSlot {
 public:
  CollisionHandlerSlot() = default;
  CollisionHandlerSlot(const CollisionHandlerSlot& o) : h_(o.h_ ? o.h_->clone() : nullptr) {}
  CollisionHandlerSlot(CollisionHandlerSlot&&) noexcept = default;
  CollisionHandlerSlot& operator=(const CollisionHandlerSlot& o) {
    if (this != &o) h_ = o.h_ ? o.h_->clone() : nullptr;
    return *this;
  }
  CollisionHandlerSlot& operator=(CollisionHandlerSlot&&) noexcept = default;
  ~CollisionHandlerSlot() = default;

  template <class Handler>
  void set(Handler handler) {
    static_assert(std::is_base_of_v<CollisionHandler<Scalar>, Handler>,
                  "set_collision_handler: the handler must derive from "
                  "massspring::contact::CollisionHandler<Scalar>");
    h_ = std::make_unique<Handler>(std::move(handler));
  }
  void reset() { h_.reset(); }
  [[nodiscard]] CollisionHandler<Scalar>* get() const { return h_.get(); }

 private:
  std::unique_ptr<CollisionHandler<Scalar>> h_;
};

/// @brief Applies the system's collision response to the end-of-step state: its handler, if it
/// has one, then its colliders (contact/colliders/collider_set.hpp), which also take their
/// end-of-step pose. The one call an integrator makes, after computing (x_end, v_end) from
/// (x_start, v_start) and before committing them; once the step is committed, the integrator calls
/// system.colliders().end_step().
/// @tparam System a MassSpringSystem (anything with collision_handler(), colliders(), masses(),
/// pinned())
/// `collider_friction` false: the colliders act as frictionless (FastMassSpring, whose contact
/// term applied their friction inside the iteration).
template <class System>
void handle_collisions(System& system, const typename System::PointsType& x_start,
                       const typename System::PointsType& v_start,
                       typename System::PointsType& x_end, typename System::PointsType& v_end,
                       typename System::Scalar dt, bool collider_friction = true) {
  if (auto* handler = system.collision_handler())
    handler->handle({x_start, v_start, x_end, v_end, dt, system.masses(), system.pinned()});
  if (!system.colliders().empty())
    system.colliders().respond(x_start, x_end, v_end, dt, system.masses(), system.pinned(),
                               collider_friction);
}

}  // namespace massspring::contact
