// Diagnostics (diagnostics/energy.hpp, stable_time_step.hpp, divergence_guard.hpp): energies [J],
// momentum [kg m/s], frequency bounds and the stable explicit time step [s] of the current state,
// and DivergenceGuard (its step(integrator, system) is added by each integrator's file).

#include "bindings.hpp"

namespace massspring::python {

void bind_diagnostics(py::module_& m) {
  py::enum_<ExplicitMethod>(m, "ExplicitMethod")
      .value("ForwardEuler", ExplicitMethod::ForwardEuler)
      .value("SymplecticEuler", ExplicitMethod::SymplecticEuler)
      .value("RK4", ExplicitMethod::RK4);

  py::class_<FrequencyBounds>(m, "FrequencyBounds",
                              "Gershgorin bounds of the linearised system (rad/s, 1/s).")
      .def_readonly("omega_max", &FrequencyBounds::omega_max)
      .def_readonly("damping_max", &FrequencyBounds::damping_max)
      .def_readonly("damping_min", &FrequencyBounds::damping_min);

  m.def(
      "kinetic_energy", [](const System& s) { return kinetic_energy(s); }, py::arg("system"),
      "1/2 sum_i m_i |v_i|^2 [J].");
  m.def(
      "potential_energy", [](const System& s) { return potential_energy(s); }, py::arg("system"),
      "Springs and every force term that has an energy, at the current positions [J].");
  m.def(
      "total_energy", [](const System& s) { return total_energy(s); }, py::arg("system"),
      "Kinetic plus potential energy [J].");
  m.def(
      "linear_momentum", [](const System& s) { return copy_array(linear_momentum(s), true); },
      py::arg("system"), "sum_i m_i v_i [kg m/s].");
  m.def(
      "frequency_bounds", [](const System& s) { return frequency_bounds(s); }, py::arg("system"));
  m.def(
      "stability_limit",
      [](const System& s, ExplicitMethod method) { return stability_limit(s, method); },
      py::arg("system"), py::arg("method") = ExplicitMethod::SymplecticEuler,
      "The largest stable h [s] of the method at the current state (the edge; inf when nothing "
      "limits h).");
  m.def(
      "stable_time_step",
      [](const System& s, ExplicitMethod method, double safety) {
        return stable_time_step(s, method, safety);
      },
      py::arg("system"), py::arg("method") = ExplicitMethod::SymplecticEuler,
      py::arg("safety") = default_stability_safety,
      "safety x stability_limit(system, method) [s]; safety in (0, 1], default 0.5.");

  using Guard = DivergenceGuard<System>;
  py::class_<Guard>(m, "DivergenceGuard",
                    "Undoes a step whose total energy passes E(0) + growth x scale "
                    "(diagnostics/divergence_guard.hpp); massspring-simulate's --guard-growth.\n"
                    "DivergenceGuard(system, growth=100); guard.step(integrator, system)")
      .def(py::init(
               [](const System& s, double growth) { return Guard(s, DivergenceOptions{growth}); }),
           py::arg("system"), py::arg("growth") = DivergenceOptions{}.growth)
      .def_property_readonly("initial_energy", &Guard::initial_energy, "E(0) [J].")
      .def_property_readonly("scale", &Guard::scale, "The energy scale S [J].")
      .def_property_readonly("limit", &Guard::limit, "E(0) + growth S [J].")
      .def_property_readonly("energy", &Guard::energy,
                             "Total energy after the last accepted step.");
}

}  // namespace massspring::python
