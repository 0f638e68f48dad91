// scripts/compile_time.sh: a consumer translation unit that includes what it needs and steps a
// FastMassSpring<MassSpringSystem<double, Sparse>> (precompute + step), as an engine would. The
// test integrators.extern_templates_not_instantiated compiles it with MASSSPRING_EXTERN_TEMPLATES.
#include <massspring/integrators/fast_mass_spring.hpp>

int main() {
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
