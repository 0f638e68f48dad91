#pragma once
/// @file
/// @brief The Google Benchmark bodies the local-global programs share: precompute, one step and
/// the floor of an iteration (one forward and one back substitution with the factor of Q on the
/// n x 3 right-hand side, in the factor's row order), for FastMassSpring and for the reference
/// solver, and the registration settings.
///
/// Names are `<what>/<solver>/<scene>`. Counters on every run: points, springs, nnz_L (stored
/// entries of the factor of Q) and iterations_per_step (local-global iterations per step: for ours
/// the mean step() reported, elsewhere kIterations). Times are per benchmark iteration (one step,
/// one substitution, one precompute); read cpu_time for one thread and real_time for two.

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <exception>
#include <string>
#include <type_traits>
#include <vector>

#include "support/scenes.hpp"

namespace massspring::bench {

template <class System>
const char* storage_name() {
  return std::is_same_v<typename System::Storage, Dense> ? "Dense" : "Sparse";
}

template <class System>
void set_counters(benchmark::State& state, const System& system, Eigen::Index factor_nonzeros,
                  double iterations) {
  state.counters["points"] = double(system.num_points());
  state.counters["springs"] = double(system.num_springs());
  state.counters["nnz_L"] = double(factor_nonzeros);
  state.counters["iterations_per_step"] = iterations;
}

/// @brief Precomputes `solver` for `system`; on failure marks the benchmark skipped with the
/// reason and returns false.
template <class Solver, class System>
bool precompute_or_skip(benchmark::State& state, Solver& solver, const System& system) {
  try {
    solver.precompute(system, typename System::Scalar(kDt));
    return true;
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return false;
  }
}

/// @brief Leaves the options as options_for() sets them.
inline constexpr auto kSeedLike = [](auto&) {};

/// @brief FastMassSpring::precompute (build Q, order, factorize), one per benchmark iteration.
template <class System, class Adjust = decltype(kSeedLike)>
void bm_precompute(benchmark::State& state, const Scene& scene, const System& proto,
                   Adjust adjust = kSeedLike) {
  Eigen::Index nnz = 0;
  auto options = options_for<typename System::Scalar>(scene);
  adjust(options);
  try {
    for (auto _ : state) {
      FastMassSpring<System> solver(options);
      solver.precompute(proto, typename System::Scalar(kDt));
      nnz = solver.factor_nonzeros();
      benchmark::DoNotOptimize(nnz);
    }
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  set_counters(state, proto, nnz, kIterations);
}

/// @brief One FastMassSpring::step per benchmark iteration; options_for(scene) changed by
/// `adjust`. With a `start` state every step starts from it (untimed reset), after one untimed
/// step (on which Chebyshev estimates its rho); without, the scene keeps falling.
template <class System, class Adjust>
void bm_step(benchmark::State& state, const Scene& scene, const System& proto, Adjust adjust,
             const System* start = nullptr) {
  using Scalar = typename System::Scalar;
  System system = start ? *start : proto;
  auto options = options_for<Scalar>(scene);
  adjust(options);
  FastMassSpring<System> solver(options);
  if (!precompute_or_skip(state, solver, system)) return;
  if (start) {
    solver.step(system);
    system = *start;
  }
  double iterations = 0, steps = 0;
  for (auto _ : state) {
    if (start) {
      state.PauseTiming();
      system.positions() = start->positions();
      system.velocities() = start->velocities();
      state.ResumeTiming();
    }
    const StepReport report = solver.step(system);
    if (!report.finite) {
      state.SkipWithError("step() result not finite");
      break;
    }
    iterations += report.iterations;
    steps += 1;
  }
  set_counters(state, proto, solver.factor_nonzeros(), steps > 0 ? iterations / steps : 0);
}

/// @brief The floor of one iteration: one forward and one back substitution with the factor of
/// FastMassSpring's own Q (options_for(scene) changed by `adjust`: its order, pins, SIMD and
/// threads), n x 3, in the factor's row order, and nothing else; one per benchmark iteration.
template <class System, class Adjust>
void bm_floor(benchmark::State& state, const Scene& scene, const System& proto, Adjust adjust) {
  using Scalar = typename System::Scalar;
  auto options = options_for<Scalar>(scene);
  adjust(options);
  FastMassSpring<System> solver(options);
  typename System::Traits::Cholesky cholesky;
  if constexpr (std::is_same_v<typename System::Storage, Sparse>) {
    if (options.threads > 1) cholesky.set_threads(options.threads);
    cholesky.set_simd(options.simd);
  }
  if (!precompute_or_skip(state, solver, proto)) return;
  bool ok = false;
  if constexpr (std::is_same_v<typename System::Storage, Sparse>) {
    // The solver's own elimination order (options.ordering may have chosen nested dissection).
    const Eigen::VectorXi& perm = solver.factorization().permutation();
    std::vector<int> order(std::size_t(perm.size()));
    for (Eigen::Index i = 0; i < perm.size(); ++i) order[std::size_t(perm(i))] = int(i);
    ok = cholesky.compute(solver.system_matrix(), order);
  } else {
    ok = cholesky.compute(solver.system_matrix());
  }
  if (!ok) {
    state.SkipWithError("Q is not positive definite");
    return;
  }
  const Eigen::Index rows = solver.system_matrix().rows();
  Points<Scalar> x = Points<Scalar>::Random(rows, 3);
  for (auto _ : state) {
    cholesky.solve_in_place(x.data());
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, proto, cholesky.factor_nonzeros(), kIterations);
}

/// @brief SeedFastMassSpring::precompute (Q by sparse products, SimplicialLLT in AMD's order).
inline void bm_seed_precompute(benchmark::State& state, const Scene& scene,
                               const SparseSystem& proto) {
  Eigen::Index nnz = 0;
  try {
    for (auto _ : state) {
      SeedFastMassSpring seed(seed_options(scene));
      seed.precompute(proto, kDt);
      nnz = seed.factor_nonzeros();
      benchmark::DoNotOptimize(nnz);
    }
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  set_counters(state, proto, nnz, kIterations);
}

/// @brief One SeedFastMassSpring::step (kIterations iterations) per benchmark iteration.
inline void bm_seed_step(benchmark::State& state, const Scene& scene, const SparseSystem& proto) {
  SeedFastMassSpring seed(seed_options(scene));
  if (!precompute_or_skip(state, seed, proto)) return;
  for (auto _ : state) {
    seed.step();
    benchmark::DoNotOptimize(seed.positions().data());
  }
  set_counters(state, proto, seed.factor_nonzeros(), kIterations);
}

/// @brief Registration: a single run (precompute), no repetitions.
inline void once(benchmark::internal::Benchmark* b) {
  b->Unit(benchmark::kMillisecond)->MinTime(0.3)->UseRealTime();
}

/// @brief Registration: `count` repetitions, summarised by their median (what the docs quote).
inline auto repeated(int count) {
  return [count](benchmark::internal::Benchmark* b) {
    b->Unit(benchmark::kMillisecond)
        ->MinTime(0.3)
        ->Repetitions(count)
        ->DisplayAggregatesOnly(true)
        ->UseRealTime();
  };
}

/// @brief Registers `body` as `<what>/<solver>/<scene>` with the settings `how`.
template <class How, class Body>
void add(How how, const std::string& what, const std::string& solver, const Scene& scene,
         Body body) {
  how(benchmark::RegisterBenchmark((what + "/" + solver + "/" + scene.name).c_str(), body));
}

}  // namespace massspring::bench
