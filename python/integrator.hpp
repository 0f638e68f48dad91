#pragma once
/// @file
/// @brief What every integrator's binding shares: precompute(system, dt) and step(system), with the
/// GIL released while the C++ runs (two Python threads step two systems at once).

#include <string>

#include "bindings.hpp"

namespace massspring::python {

/// @brief Adds the implicit integrators' option energy_growth (BackwardEulerOptions,
/// FastMassSpringOptions: the energy bound of integrators/detail/energy_bound.hpp, default 100) to
/// their options' class `c`; returns `c`.
template <class Class>
Class& def_energy_growth(Class& c) {
  using Options = typename Class::type;
  return c.def_readwrite(
      "energy_growth", &Options::energy_growth,
      "A step whose energy passes its start energy + energy_growth (S + S_c) "
      "is refused and reported (StepReport.blew_up); >= 0, default 100, 0: off.");
}

/// @brief Adds precompute, step and dt to an integrator class, and DivergenceGuard.step for it
/// (the guard must be bound first). `Step` is how the binding steps
/// (the integrator's own step(), or another call on it).
/// step() and precompute() run without the GIL; a second thread's call on the same system or
/// integrator meanwhile raises massspring.Error (InUse). `Refuse` (system -> message) is asked
/// before precompute() and step(): a non-empty message is raised as massspring.Error.
template <class Integrator, class Class, class Step, class Refuse = std::string (*)(const System&)>
void bind_integrator_calls(
    py::module_& m, Class& c, Step step,
    Refuse refuse = [](const System&) { return std::string(); }) {
  using Guard = DivergenceGuard<System>;
  c.def(
       "precompute",
       [refuse](Integrator& integrator, const System& system, double dt) {
         const InUse busy({&integrator, &system}, "precompute");
         if (const std::string why = refuse(system); !why.empty()) throw Error(why);
         const py::gil_scoped_release release;
         integrator.precompute(system, dt);
       },
       py::arg("system"), py::arg("dt"),
       "Sets the time step dt [s] and prepares for the system (factorizes where the method "
       "does). Call it again after the number of points changes. The GIL is released.")
      .def(
          "step",
          [step, refuse](Integrator& integrator, System& system) {
            const InUse busy({&integrator, &system}, "step");
            if (const std::string why = refuse(system); !why.empty()) throw Error(why);
            const py::gil_scoped_release release;
            return step(integrator, system);
          },
          py::arg("system"),
          "One step of dt; returns a StepReport. A failed step (report.ok() false) leaves the "
          "system as it was. The GIL is released while it runs.")
      .def_property_readonly(
          "dt", [](const Integrator& integrator) { return double(integrator.dt()); },
          "The time step [s] of the last precompute().");
  // DivergenceGuard.step(integrator, system) for this integrator (diagnostics.cpp binds the
  // guard): instantiated here, where the integrator's step() is compiled anyway.
  py::class_<Guard> guard = py::reinterpret_borrow<py::class_<Guard>>(m.attr("DivergenceGuard"));
  guard.def(
      "step",
      [step, refuse](Guard& g, Integrator& integrator, System& system) {
        struct Bound {  // what DivergenceGuard::step calls: integrator.step(system)
          Integrator& i;
          const Step& s;
          StepReport step(System& system) { return s(i, system); }
        } bound{integrator, step};
        const InUse busy({&g, &integrator, &system}, "step");
        if (const std::string why = refuse(system); !why.empty()) throw Error(why);
        const py::gil_scoped_release release;
        return g.step(bound, system);
      },
      py::arg("integrator"), py::arg("system"),
      "One step of the integrator, checked: a step whose total energy passes limit (or that is "
      "not finite) is undone and reported (blew_up, finite).");
}

/// @brief The contact_duals property of an integrator with a contact term inside its solve
/// (contact_duals() / set_contact_duals(); FastMassSpring, BackwardEuler): read a copy, assign
/// after precompute.
template <class Integrator, class Class>
void bind_contact_duals(Class& c) {
  c.def_property(
      "contact_duals", [](const Integrator& s) { return copy_array(s.contact_duals()); },
      [](Integrator& s, const py::handle& u) {
        check_idle(&s, "contact_duals");
        s.set_contact_duals(real_matrix(u, "contact_duals", 3));
      },
      "(n, 3) the contact term's dual variables [m] (contact_weight > 0), a copy: the state the "
      "next step's solve starts from. Assign a saved copy (after precompute) to resume a run bit "
      "for bit.");
}

}  // namespace massspring::python
