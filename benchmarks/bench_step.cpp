// What one local-global step and one iteration cost: FastMassSpring (Sparse, double, penalty pins
// as the reference solver's) against the floor of an iteration and against the reference solver
// (reference/seed/seed_reference.hpp: the same step written plainly, with Eigen's sparse products
// and SimplicialLLT::solve). Scenes and settings: support/scenes.hpp (cloth32, cloth64, cloth128,
// curtain, flag, skirt; dt = 1/30 s, 50 iterations per step).
//
// Benchmarks (`<what>/<solver>/<scene>`):
//   Precompute/Sparse, Precompute/Seed   build Q and factorize (ours in the order
//                                        FillOrdering::Auto picks, the reference solver in
//                                        AMD's)
//   Step/Sparse, Step/Seed               one step of 50 iterations
//   Floor/Sparse                         one forward and one back substitution with our factor,
//                                        n x 3, in the factor's row order
//   Floor/EigenSolve                     SimplicialLLT::solve on the reference solver's factor,
//                                        n x 3 (its global step without its local step)
//   Paired/Sparse                        each step followed by as many substitutions with that
//                                        step's own factor, both on the thread's CPU clock
// Counters besides support/timing.hpp's: first_step_diff on Step/Seed (|X_ours - X_ref| /
// |X_ref| after one step from rest, X_ref the reference solver's; the program warns above 1e-9),
// and on Paired/Sparse step_ms (per step), floor_ms (per substitution) and it_per_floor (the
// step's time per iteration over the substitution's, summed over the repetition).
//
//   build/benchmarks/bench_step --benchmark_out=step.json --benchmark_out_format=json
//   build/benchmarks/bench_step --benchmark_filter='^Paired/'   # iteration / floor alone
#include <benchmark/benchmark.h>
#include <time.h>

#include <Eigen/Core>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "support/main.hpp"
#include "support/scenes.hpp"
#include "support/timing.hpp"

namespace {

using namespace massspring::bench;

// CPU time of the calling thread [ns].
double thread_cpu_ns() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e9 + double(t.tv_nsec);
}

// Iteration / floor measured in pairs: each benchmark iteration times one step() and then as many
// substitutions as the step had iterations with the step's own factor (solver.factorization(): the
// same arrays at the same addresses), both by the thread's CPU clock. Floor/Sparse and Step/Sparse
// each build their own solver, and the same factor can substitute markedly slower in one instance
// than in another (where its pages land); here the two parts share the instance and alternate.
void bm_paired(benchmark::State& state, const Scene& scene, const SparseSystem& proto) {
  SparseSystem system = proto;
  massspring::FastMassSpring<SparseSystem> solver(options_for<double>(scene));
  if (!precompute_or_skip(state, solver, system)) return;
  const auto& factor = solver.factorization();
  const Eigen::Index rows = solver.system_matrix().rows();
  const massspring::Points<double> start = massspring::Points<double>::Random(rows, 3);
  massspring::Points<double> x = start;
  double step_ns = 0, floor_ns = 0, iterations = 0;
  for (auto _ : state) {
    const double t0 = thread_cpu_ns();
    const massspring::StepReport report = solver.step(system);
    const double t1 = thread_cpu_ns();
    if (!report.finite) {
      state.SkipWithError("step() result not finite");
      break;
    }
    x = start;  // untimed: the floor's right-hand side, the same for every batch
    const double t2 = thread_cpu_ns();
    for (int k = 0; k < report.iterations; ++k) {
      factor.solve_in_place(x.data());
      benchmark::DoNotOptimize(x.data());
      benchmark::ClobberMemory();
    }
    const double t3 = thread_cpu_ns();
    step_ns += t1 - t0;
    floor_ns += t3 - t2;
    iterations += report.iterations;
  }
  if (iterations > 0 && floor_ns > 0) {
    const double steps = double(state.iterations());
    state.counters["step_ms"] = step_ns / steps * 1e-6;
    state.counters["floor_ms"] = floor_ns / iterations * 1e-6;
    state.counters["it_per_floor"] = step_ns / floor_ns;
  }
  set_counters(state, proto, solver.factor_nonzeros(), iterations / double(state.iterations()));
}

// Eigen's own solve on the reference solver's factor: its global step without its local step.
void bm_eigen_solve(benchmark::State& state, const Scene& scene, const SparseSystem& proto) {
  SeedFastMassSpring seed(seed_options(scene));
  if (!precompute_or_skip(state, seed, proto)) return;
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(proto.num_points(), 3);
  Eigen::MatrixXd x(proto.num_points(), 3);
  for (auto _ : state) {
    x = seed.factorization().solve(b);
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, proto, seed.factor_nonzeros(), kIterations);
}

// |X_ours - X_ref| / |X_ref| (X_ref: the reference solver's) after one step from rest, or -1 when
// either throws.
double first_step_difference(const Scene& scene) {
  try {
    SparseSystem system = *scene.sparse;
    massspring::FastMassSpring<SparseSystem> ours(options_for<double>(scene));
    ours.precompute(system, kDt);
    ours.step(system);
    SeedFastMassSpring seed(seed_options(scene));
    seed.precompute(*scene.sparse, kDt);
    seed.step();
    const Eigen::MatrixXd x = system.positions();
    return (x - seed.positions()).norm() / seed.positions().norm();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "WARNING: %s: the first-step check failed: %s\n", scene.name.c_str(),
                 e.what());
    return -1;
  }
}

std::vector<Scene>& scenes() {
  static std::vector<Scene> s;
  return s;
}

void register_benchmarks() {
  const auto repeated3 = repeated(3);
  // The paired figure compares two parts of one run: more repetitions.
  const auto repeated5 = repeated(5);
  for (const Scene& s : scenes()) {
    const Scene* sc = &s;
    const double diff = first_step_difference(s);
    if (!(diff >= 0 && diff <= 1e-9))
      std::fprintf(stderr,
                   "WARNING: %s: ours and the reference solver differ after one step (relative "
                   "%.3g > 1e-9): the timings compare different computations\n",
                   s.name.c_str(), diff);
    add(once, "Precompute", "Sparse", s,
        [sc](benchmark::State& st) { bm_precompute(st, *sc, *sc->sparse); });
    add(once, "Precompute", "Seed", s,
        [sc](benchmark::State& st) { bm_seed_precompute(st, *sc, *sc->sparse); });
    add(repeated3, "Step", "Sparse", s,
        [sc](benchmark::State& st) { bm_step(st, *sc, *sc->sparse, kSeedLike); });
    add(repeated3, "Step", "Seed", s, [sc, diff](benchmark::State& st) {
      bm_seed_step(st, *sc, *sc->sparse);
      st.counters["first_step_diff"] = diff;
    });
    add(repeated3, "Floor", "Sparse", s,
        [sc](benchmark::State& st) { bm_floor(st, *sc, *sc->sparse, kSeedLike); });
    add(repeated3, "Floor", "EigenSolve", s,
        [sc](benchmark::State& st) { bm_eigen_solve(st, *sc, *sc->sparse); });
    add(repeated5, "Paired", "Sparse", s,
        [sc](benchmark::State& st) { bm_paired(st, *sc, *sc->sparse); });
  }
}

}  // namespace

int main(int argc, char** argv) {
  return massspring::bench::run_benchmarks(
      argc, argv, [] { scenes() = standard_scenes(); }, register_benchmarks);
}
