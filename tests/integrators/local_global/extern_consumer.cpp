// Compiled with MASSSPRING_EXTERN_TEMPLATES (tests/CMakeLists.txt) and never linked: its object
// file is read by extern_templates.cmake, which checks that this unit calls FastMassSpring's
// precompute() and step() without instantiating them (the point of the macro: compile time).
#include <massspring/integrators/fast_mass_spring.hpp>

int extern_consumer() {
  using System = massspring::MassSpringSystem<double, massspring::Sparse>;
  massspring::Points<double> rest(3, 3);
  rest << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  massspring::Edges springs(2, 2);
  springs << 0, 1, 1, 2;
  System system(rest, springs, 1.0, 500.0);
  system.pin(0);
  massspring::FastMassSpring<System> solver;
  solver.precompute(system, 0.01);
  return solver.step(system).ok() ? 0 : 1;
}
