// massspring.ForwardEuler, SymplecticEuler and RK4 (integrators/). Their one option is the energy
// bound's growth (set_energy_growth); set_swap_buffers is fixed here (below), not exposed.
//
// By default the C++ integrators end a step by swapping their work buffers with the system's
// positions and velocities (no copy). A numpy view of sys.positions points at the system's
// buffer, which after such a swap would belong to the integrator (and die with it). So the
// binding's integrators are set to copy their end state into the system's buffers instead
// (set_swap_buffers(false)): the views always show the system's state and live as long as the
// system. The copy (n x 3 doubles per array) changes no value: the trajectory is the C++ one bit
// for bit.

#include "integrator.hpp"

namespace massspring::python {

namespace {

template <class Integrator>
void bind_explicit(py::module_& m, const char* name, const char* doc) {
  py::class_<Integrator> c(m, name, doc);
  c.def(py::init([] {
    Integrator integrator;
    integrator.set_swap_buffers(false);  // the system's arrays keep their memory
    return integrator;
  }));
  c.def("set_energy_growth", &Integrator::set_energy_growth, py::arg("growth"),
        "A step whose energy passes its start energy + growth (S + S_c) is refused and reported "
        "(StepReport.blew_up); "
        ">= 0, default 0: off. Takes effect at the next precompute().");
  bind_integrator_calls<Integrator>(m, c,
                                    [](Integrator& i, System& system) { return i.step(system); });
}

}  // namespace

void bind_explicit_integrators(py::module_& m) {
  bind_explicit<ForwardEuler<System>>(
      m, "ForwardEuler",
      "Explicit Euler: x += h v, v += h M^-1 F(x, v) (both from the old state).");
  bind_explicit<SymplecticEuler<System>>(
      m, "SymplecticEuler", "Symplectic Euler: v += h M^-1 F(x, v), then x += h v (the new v).");
  bind_explicit<RK4<System>>(m, "RK4", "Classical fourth-order Runge-Kutta.");
}

}  // namespace massspring::python
