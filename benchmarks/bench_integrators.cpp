// integrators/forward_euler.hpp, symplectic_euler.hpp, backward_euler.hpp: one step on generated
// cloths, and what the force-term machinery costs.
//
// "A scene pays only for the terms it has": Step/SymplecticEuler/springs runs the library's
// symplectic Euler on a spring-only cloth; Baseline/springs is the same step written by hand for
// springs alone (no force list, no context). Their ratio is the overhead of the machinery for a
// spring-only scene; +gravity and +drag show what each term adds.
//
// Scenes: N x N cloths (quads with both diagonals, top corners pinned, k = 1000 N/m, Voronoi
// masses), dt = 1e-4 s for the explicit methods (below their stability limit), 1/30 s for
// backward Euler.
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cmath>
#include <massspring/forces/gravitational_attraction.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/forces/linear_drag.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/forward_euler.hpp>
#include <massspring/integrators/symplectic_euler.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>

namespace {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using Points = massspring::Points<double>;

System cloth(int n) {
  massspring::ClothOptions o;
  o.columns = n;
  o.rows = n;
  o.shear = massspring::ClothShear::Both;
  o.plane = massspring::ClothPlane::Horizontal;
  return massspring::make_system<System>(massspring::make_cloth(o));
}

enum Extra { kSprings = 0, kGravity = 1, kGravityDrag = 2 };

void add_extras(System& s, int extra) {
  if (extra >= kGravity) s.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
  if (extra >= kGravityDrag) s.add_force(massspring::LinearDrag<double>(0.01));
}

template <template <class> class Integrator>
void BM_Explicit(benchmark::State& state) {
  System s = cloth(int(state.range(0)));
  add_extras(s, int(state.range(1)));
  Integrator<System> integrator;
  integrator.precompute(s, 1e-4);
  for (auto _ : state) benchmark::DoNotOptimize(integrator.step(s));
  state.counters["points"] = s.num_points();
  state.counters["springs"] = s.num_springs();
}

// Symplectic Euler for springs alone, written directly: the floor the library is measured against.
void BM_Baseline(benchmark::State& state) {
  System s = cloth(int(state.range(0)));
  const int n = s.num_points(), m = s.num_springs();
  const double h = 1e-4;
  const auto& e = s.springs();
  const Eigen::VectorXd k = s.stiffness(), l0 = s.rest_lengths(), inv_m = s.masses().cwiseInverse();
  Points x = s.positions(), v = s.velocities(), f(n, 3);
  for (auto _ : state) {
    f.setZero();
    for (int j = 0; j < m; ++j) {
      const int a = e(j, 0), b = e(j, 1);
      const Eigen::RowVector3d d = x.row(b) - x.row(a);
      const double l = d.norm();
      const Eigen::RowVector3d fa = k(j) * (l - l0(j)) / l * d;
      f.row(a) += fa;
      f.row(b) -= fa;
    }
    v += h * (f.array().colwise() * inv_m.array()).matrix();
    x += h * v;
    for (std::size_t r = 0; r < s.pinned().size(); ++r) {
      const int i = s.pinned()[r];
      x.row(i) = s.pin_targets().row(Eigen::Index(r));
      v.row(i).setZero();
    }
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
}

void BM_BackwardEuler(benchmark::State& state) {
  System s = cloth(int(state.range(0)));
  add_extras(s, kGravity);
  massspring::BackwardEuler<System> be;
  be.options.mode = state.range(1) == 0 ? massspring::BackwardEulerMode::Linearized
                                        : massspring::BackwardEulerMode::Newton;
  be.precompute(s, 1.0 / 30);
  double iterations = 0;
  for (auto _ : state) iterations += be.step(s).iterations;
  state.counters["points"] = s.num_points();
  state.counters["iterations"] = benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
}

}  // namespace

BENCHMARK(BM_Baseline)->Name("Baseline/springs")->Arg(32)->Arg(64)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Explicit<massspring::SymplecticEuler>)
    ->Name("Step/SymplecticEuler")
    ->ArgNames({"N", "extra"})
    ->ArgsProduct({{32, 64}, {kSprings, kGravity, kGravityDrag}})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Explicit<massspring::ForwardEuler>)
    ->Name("Step/ForwardEuler")
    ->ArgNames({"N", "extra"})
    ->ArgsProduct({{32, 64}, {kSprings}})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BackwardEuler)
    ->Name("Step/BackwardEuler")
    ->ArgNames({"N", "newton"})
    ->ArgsProduct({{16, 32}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
