// Factorizations and orders of FastMassSpring's Q compared (exact pins, dt = 1/30 s, k = 1000 N/m,
// Q in the points' order): for each, nnz(L), the factorization (compute(): ordering, symbolic,
// numeric) and one fused n x 3 substitution with that factor. On the curtain and the cloth grids
// 128^2, 256^2 and 512^2 (support/scenes.hpp's cloths).
//
// Benchmarks `Factorize/<method>/<scene>`, method:
//   EigenAMD, EigenND, EigenCOLAMD, EigenNatural   SparseCholesky (Eigen's SimplicialLLT) with
//       AMD, geometric nested dissection of the rest positions (massspring::nested_dissection;
//       its time counted in the factorization's), COLAMD (up to 20000 rows: it fills ~10x more)
//       and the natural order (up to 20000 rows: a band);
//   CholmodDefault, CholmodAMD, CholmodMETIS, CholmodNESDIS   CholmodCholesky (supernodal) with
//       its own choice, AMD, METIS and NESDIS, only when built with massspring::cholmod.
// The time is one factorization (one iteration per repetition, 3 repetitions; read cpu_time, the
// process's CPU time, all threads). Counters: rows, nnz_L, solve_ms (the median CPU time of 21
// substitutions, 5 above 100000 rows).
//
//   bench_factorization --benchmark_out=factorization.json --benchmark_out_format=json
#include <benchmark/benchmark.h>
#include <time.h>

#include <algorithm>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/storage/nested_dissection.hpp>
#include <massspring/storage/storage.hpp>
#include <memory>
#include <string>
#include <vector>
#if MASSSPRING_HAS_CHOLMOD
#include <massspring/storage/cholmod.hpp>
#endif

#include "support/main.hpp"
#include "support/scenes.hpp"

namespace {

using massspring::bench::SparseSystem;
using Matrix = SparseSystem::Matrix;

// CPU time of the process, all its threads [ms].
double process_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + 1e-6 * double(t.tv_nsec);
}

// Q of one scene, in the points' order, and the rest positions of its free points.
struct Problem {
  std::string name;
  Matrix q;
  Eigen::Matrix<double, Eigen::Dynamic, 3> xyz;
};

Problem make_problem(const massspring::bench::Scene& scene) {
  massspring::FastMassSpring<SparseSystem> solver(
      massspring::FastMassSpringOptions<double>::reference());
  solver.options.ordering = massspring::FillOrdering::Solver;
  solver.precompute(*scene.sparse, 1.0 / 30);
  Problem p;
  p.name = scene.name;
  p.q = solver.system_matrix();
  p.xyz.resize(p.q.rows(), 3);
  for (Eigen::Index r = 0; r < p.q.rows(); ++r)
    p.xyz.row(r) = scene.sparse->rest_positions().row(solver.free_points()[std::size_t(r)]);
  return p;
}

// Times `compute` (returns false on failure) once per iteration, then the substitution.
template <class Cholesky, class Compute>
void bm_factorize(benchmark::State& state, const Problem& p, Compute compute) {
  Cholesky llt;
  for (auto _ : state) {
    if (!compute(llt)) {
      state.SkipWithError("factorization failed");
      return;
    }
  }
  massspring::Points<double> w = massspring::Points<double>::Random(p.q.rows(), 3);
  std::vector<double> t;
  const int solves = p.q.rows() > 100000 ? 5 : 21;
  for (int r = 0; r < solves; ++r) {
    const double t0 = process_cpu_ms();
    llt.solve_in_place(w.data());
    benchmark::DoNotOptimize(w.data());
    t.push_back(process_cpu_ms() - t0);
  }
  std::nth_element(t.begin(), t.begin() + std::ptrdiff_t(t.size() / 2), t.end());
  state.counters["rows"] = double(p.q.rows());
  state.counters["nnz_L"] = double(llt.factor_nonzeros());
  state.counters["solve_ms"] = t[t.size() / 2];
}

std::vector<std::unique_ptr<Problem>>& problems() {
  static std::vector<std::unique_ptr<Problem>> p;
  return p;
}

template <class Cholesky, class Compute>
void add(const char* method, const Problem& p, Compute compute) {
  benchmark::RegisterBenchmark(
      ("Factorize/" + std::string(method) + "/" + p.name).c_str(),
      [&p, compute](benchmark::State& st) { bm_factorize<Cholesky>(st, p, compute); })
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1)
      ->Repetitions(3)
      ->DisplayAggregatesOnly(true)
      ->MeasureProcessCPUTime();
}

void register_benchmarks() {
  using Amd = massspring::SparseCholesky<double, Eigen::AMDOrdering<int>>;
  using Given = massspring::SparseCholesky<double>;
  using Colamd = massspring::SparseCholesky<double, Eigen::COLAMDOrdering<int>>;
  using Natural = massspring::SparseCholesky<double, Eigen::NaturalOrdering<int>>;
  for (const auto& problem : problems()) {
    const Problem& p = *problem;
    add<Amd>("EigenAMD", p, [&p](Amd& llt) { return llt.compute(p.q); });
    add<Given>("EigenND", p, [&p](Given& llt) {
      return llt.compute(p.q, massspring::nested_dissection(p.xyz, massspring::graph_of(p.q)));
    });
    if (p.q.rows() <= 20000) {
      add<Colamd>("EigenCOLAMD", p, [&p](Colamd& llt) { return llt.compute(p.q); });
      add<Natural>("EigenNatural", p, [&p](Natural& llt) { return llt.compute(p.q); });
    }
#if MASSSPRING_HAS_CHOLMOD
    using Cholmod = massspring::CholmodCholesky<double>;
    const std::pair<massspring::CholmodOrdering, const char*> orderings[] = {
        {massspring::CholmodOrdering::Default, "CholmodDefault"},
        {massspring::CholmodOrdering::AMD, "CholmodAMD"},
        {massspring::CholmodOrdering::METIS, "CholmodMETIS"},
        {massspring::CholmodOrdering::NESDIS, "CholmodNESDIS"},
    };
    for (const auto& [ordering, name] : orderings) {
      const massspring::CholmodOrdering o = ordering;
      add<Cholmod>(name, p, [&p, o](Cholmod& llt) {
        llt.ordering = o;
        return llt.compute(p.q);
      });
    }
#endif
  }
}

}  // namespace

int main(int argc, char** argv) {
  return massspring::bench::run_benchmarks(
      argc, argv,
      [] {
        problems().push_back(
            std::make_unique<Problem>(make_problem(massspring::bench::curtain_scene())));
        for (const int n : {128, 256, 512})
          problems().push_back(
              std::make_unique<Problem>(make_problem(massspring::bench::cloth_scene(n))));
      },
      register_benchmarks);
}
