#pragma once
/// @file
/// @brief What every integrator's binding shares: precompute(system, dt) and step(system), with the
/// GIL released while the C++ runs (two Python threads step two systems at once).

#include "bindings.hpp"

namespace massspring::python {

/// @brief Adds precompute, step and dt to an integrator class. `Step` is how the binding steps
/// (the integrator's own step(), or one that keeps the system's buffers: explicit_integrators.cpp).
/// Never share one system between threads: step() writes it without the GIL.
template <class Integrator, class Class, class Step>
void bind_integrator_calls(Class& c, Step step) {
  c.def(
       "precompute",
       [](Integrator& integrator, const System& system, double dt) {
         integrator.precompute(system, dt);
       },
       py::arg("system"), py::arg("dt"), py::call_guard<py::gil_scoped_release>(),
       "Sets the time step dt [s] and prepares for the system (factorises where the method "
       "does). Call it again after the number of points changes.")
      .def("step", step, py::arg("system"), py::call_guard<py::gil_scoped_release>(),
           "One step of dt; returns a StepReport. A failed step (report.ok() false) leaves the "
           "system as it was. The GIL is released while it runs.")
      .def_property_readonly(
          "dt", [](const Integrator& integrator) { return double(integrator.dt()); },
          "The time step [s] of the last precompute().");
}

}  // namespace massspring::python
