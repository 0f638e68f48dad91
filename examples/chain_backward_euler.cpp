// A chain built from arrays (points and springs), one end pinned, stepped by backward Euler with
// Newton's method at a large step. Run: prints where the free end is after 1 s.
#include <cstdio>
#include <massspring/forces/gravity.hpp>
#include <massspring/forces/linear_drag.hpp>
#include <massspring/integrators/backward_euler.hpp>

using System = massspring::MassSpringSystem<double, massspring::Sparse>;

int main() {
  try {
    massspring::Points<double> points(5, 3);  // #points by 3 rest positions [m]
    points << 0, 0, 0, 0.25, 0, 0, 0.5, 0, 0, 0.75, 0, 0, 1, 0, 0;
    massspring::Edges springs(4, 2);  // #springs by 2 point indices (0-based)
    springs << 0, 1, 1, 2, 2, 3, 3, 4;
    System chain(points, springs, /*mass [kg]*/ 0.1, /*stiffness [N/m]*/ 1000.0);
    chain.pin(0);  // held at its rest position
    chain.add_force(massspring::Gravity<double>({0, -9.8, 0}));
    chain.add_force(massspring::LinearDrag<double>(0.01));  // [N s/m]

    massspring::BackwardEuler<System> solver;
    solver.options.mode = massspring::BackwardEulerMode::Newton;
    solver.options.iterations = 20;  // most Newton iterations per step
    solver.precompute(chain, 0.05);  // dt [s]: far above explicit Euler's stable step
    for (int step = 0; step < 20; ++step) {
      const massspring::StepReport report = solver.step(chain);
      if (!report.ok()) return 2;
    }
    const auto end = chain.positions().row(4);
    std::printf("the free end after 1 s: (%.3f, %.3f) m\n", end(0), end(1));
    return end(1) < -0.3 ? 0 : 1;         // it swung down
  } catch (const massspring::Error& e) {  // bad input names the item
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
