#pragma once
/// @file
/// @brief commit_step(): the end of every integrator's step, written once.

#include <Eigen/Core>
#include <cmath>
#include <limits>

#include "massspring/contact/collision_step.hpp"
#include "massspring/contact/response/surface_contact_slot.hpp"
#include "massspring/integrators/detail/energy_bound.hpp"
#include "massspring/integrators/step_report.hpp"

namespace massspring::detail {

/// @brief Ends a step whose proposed end state is (x_end, v_end), #points by 3, from the state
/// the system holds (the start of the step), in this order:
/// 1. pinned points at their targets, with the velocity (target - x_start) / dt;
/// 2. the collision response, on the step's CollisionStep built once (contact/
///    contact_pipeline.hpp: the system's handler, the colliders' point response, then surface
///    contact, after which no edge crosses a triangle of the cloth or an obstacle's edge);
/// 3. pinned points at their targets again (an impact zone may have moved one), and
///    report.contact_work, the energy E(x, v) (energy_bound.hpp) of the end state after the
///    response less before it;
/// 4. when every value is finite, the contact was resolved, the end state's energy is within
///    `bound` and the collision response added no more than the bound's contact limit
///    (energy_bound.hpp; else report.blew_up): the end state is written to the system and
///    the colliders take their end-of-step pose; otherwise the system is left as it was. With
///    `swap_buffers`, x_end and v_end are swapped in (they hold the start state afterwards);
///    without, copied (the system's arrays keep their memory, which Python's views of them need).
/// Sets report.finite, report.blew_up and the contact fields. With a collision response, costs
/// one more evaluation of the energy (the one after it serves the bound as well). Allocates nothing
/// once the contact's work arrays have grown. `collider_friction` false: the colliders act as
/// frictionless (FastMassSpring's contact term applied their friction inside the iteration).
/// `snap_pins` false skips step 1 (FastMassSpring's penalty pins, whose solve leaves each pinned
/// point where its stiff spring holds it; step 3 still runs when there is a collision response).
template <class System>
void commit_step(System& system, typename System::PointsType& x_end,
                 typename System::PointsType& v_end, typename System::Scalar dt, StepReport& report,
                 const EnergyBound<System>& bound, bool collider_friction = true,
                 bool swap_buffers = false, bool snap_pins = true) {
  const auto& x0 = system.positions();
  const auto& pinned = system.pinned();
  const auto pin = [&] {
    for (std::size_t r = 0; r < pinned.size(); ++r) {
      const int i = pinned[r];
      x_end.row(i) = system.pin_targets().row(Eigen::Index(r));
      v_end.row(i) = (x_end.row(i) - x0.row(i)) / dt;
    }
  };
  if (snap_pins) pin();
  double end_energy = std::numeric_limits<double>::quiet_NaN();  // not evaluated yet
  if (system.has_collision_response()) {
    const double proposed_energy = EnergyBound<System>::energy(system, x_end, v_end);
    const contact::CollisionStep<typename System::Scalar> step{
        x0,    system.velocities(), x_end, v_end, dt, system.masses(), system.inverse_masses(),
        pinned};
    const contact::SurfaceContactReport r = system.contact().respond(step, collider_friction);
    report.contact_impulses = r.impulses;
    report.contact_zone_points = r.zone_points;
    report.contact_resolved = r.resolved;
    pin();
    end_energy = EnergyBound<System>::energy(system, x_end, v_end);
    report.contact_work = end_energy - proposed_energy;
  }
  // One vectorised pass: a sum is finite only when every term is (a sum of finite values can
  // overflow only when they are near 1e308, which is divergence anyway).
  report.finite = std::isfinite(x_end.sum() + v_end.sum());
  if (report.finite && report.contact_resolved)
    report.blew_up = std::isnan(end_energy)
                         ? bound.exceeded(system, x_end, v_end)
                         : bound.exceeded(system, end_energy) ||
                               bound.contact_exceeded(system, report.contact_work);
  if (report.finite && report.contact_resolved && !report.blew_up) {
    if (swap_buffers) {
      system.positions().swap(x_end);
      system.velocities().swap(v_end);
    } else {  // same sizes: no allocation
      system.positions() = x_end;
      system.velocities() = v_end;
    }
    system.colliders().end_step();
  }
}

}  // namespace massspring::detail
