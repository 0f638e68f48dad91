// integrators/fast_mass_spring.hpp: precompute and step of FastMassSpring, Dense and Sparse,
// double, against the seed's plain formulas (tests/support/seed_reference.hpp) and against the
// floor of an iteration (one forward and one back substitution with the factor of Q, n x 3
// right-hand side).
//
// Setup throughout is the assignment's: dt = 1/30 s, a force (0, -9.8, 0) on every point, penalty
// pins w = 1e10, 50 local-global iterations per step starting from the current positions.
//
// Scenes: generated cloth grids N x N (N = 16, 32, 64, 128; quads with both diagonals, top corners
// pinned, stiffness 1000 N/m, Voronoi masses) and, when ../shared/scenes/jacobson is there, the
// assignment's flag and skirt.
//
// Names: <what>/<solver>/<scene>, what = Precompute | Step | Floor, solver = Sparse | Dense (ours),
// Seed (SeedFastMassSpring), EigenSolve (Eigen's SimplicialLLT::solve on the seed's factor).
// Counters: points, springs, nnz_L (stored entries of the factor of Q) and iterations (local-global
// iterations per step: for Step/Sparse and Step/Dense the mean step() reported, elsewhere the
// configured 50). After the run a summary table compares ours with the seed per scene (medians of
// the repetitions), with each iteration's time as a multiple of the floor.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <massspring/storage/storage.hpp>
#include <massspring/system/mass_spring_system.hpp>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#if MASSSPRING_BENCH_WITH_IO  // flag and skirt need massspring::io
#include <massspring/io/load_scene.hpp>
#define MASSSPRING_BENCH_HAVE_LOAD_SCENE 1
#else
#define MASSSPRING_BENCH_HAVE_LOAD_SCENE 0
#endif

#include "support/seed_reference.hpp"

namespace {

using SparseSystem = massspring::MassSpringSystem<double, massspring::Sparse>;
using DenseSystem = massspring::MassSpringSystem<double, massspring::Dense>;
using massspring::test::SeedFastMassSpring;

constexpr double kDt = 1.0 / 30;
constexpr int kIterations = 50;
constexpr double kPenaltyWeight = 1e10;

// Generated grids. Dense stops at 32 x 32 (1024 points): its Q is n x n dense, so memory grows as
// n^2, factorisation as n^3 / 3 and each iteration's solve as n^2. Measured here: 48 x 48 (2304
// points, a 42 MB matrix) takes ~0.3 s to factorise and ~0.2 s per step; 64 x 64 (4096 points,
// 128 MB) would take ~1.7 s and ~0.7 s, and 128 x 128 a 2 GB matrix: too long for a routine run
// and far past where anyone should use Dense. flag (3200 points) and skirt (9840) are Sparse only,
// likewise.
constexpr int kGridSizes[] = {16, 32, 64, 128};
constexpr int kDenseLimit = 32;

massspring::FastMassSpringOptions<double> assignment_options() {
  massspring::FastMassSpringOptions<double> o;
  o.iterations = kIterations;
  o.pins = massspring::PinMode::Penalty;
  o.penalty_weight = kPenaltyWeight;
  o.external_force = massspring::Vector3<double>(0, -9.8, 0);
  o.initial_guess = massspring::InitialGuess::Current;
  return o;
}

SeedFastMassSpring::Options seed_options() {
  SeedFastMassSpring::Options o;
  o.iterations = kIterations;
  o.penalty_weight = kPenaltyWeight;
  o.external_force = Eigen::RowVector3d(0, -9.8, 0);
  return o;
}

struct Scene {
  std::string name;
  std::shared_ptr<const SparseSystem> sparse;
  std::shared_ptr<const DenseSystem> dense;  // null: Dense is not run on this scene
};

std::vector<Scene>& scenes() {
  static std::vector<Scene> s;
  return s;
}

template <class System>
const char* storage_name() {
  return std::is_same_v<typename System::Storage, massspring::Dense> ? "Dense" : "Sparse";
}

template <class System>
void set_counters(benchmark::State& state, const System& system, Eigen::Index factor_nonzeros,
                  double iterations) {
  state.counters["points"] = double(system.num_points());
  state.counters["springs"] = double(system.num_springs());
  state.counters["nnz_L"] = double(factor_nonzeros);
  state.counters["iterations"] = iterations;
}

// ---- ours
// ----------------------------------------------------------------------------------------

// Precomputes a solver for a benchmark; on failure marks the benchmark skipped and says why.
template <class Solver, class System>
bool precompute_or_skip(benchmark::State& state, Solver& solver, const System& system) {
  try {
    solver.precompute(system, kDt);
    return true;
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return false;
  }
}

template <class System>
void bm_precompute(benchmark::State& state, const System& proto) {
  Eigen::Index nnz = 0;
  try {
    for (auto _ : state) {
      massspring::FastMassSpring<System> solver(assignment_options());
      solver.precompute(proto, kDt);
      nnz = solver.factor_nonzeros();
      benchmark::DoNotOptimize(nnz);
    }
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  set_counters(state, proto, nnz, kIterations);
  state.SetLabel(std::string(storage_name<System>()) + ": build Q, factorise");
}

template <class System>
void bm_step(benchmark::State& state, const System& proto) {
  System system = proto;
  massspring::FastMassSpring<System> solver(assignment_options());
  if (!precompute_or_skip(state, solver, system)) return;
  double iterations = 0, steps = 0;
  for (auto _ : state) {
    const massspring::StepReport report = solver.step(system);
    if (!report.finite) {
      state.SkipWithError("step() result not finite");
      break;
    }
    iterations += report.iterations;
    steps += 1;
  }
  set_counters(state, proto, solver.factor_nonzeros(), steps > 0 ? iterations / steps : 0);
  state.SetLabel(std::string(storage_name<System>()) + ": one step");
}

// The floor of one iteration: the Cholesky solve FastMassSpring's global step does, on the factor
// of FastMassSpring's own Q, for an n x 3 right-hand side, and nothing else.
template <class System>
void bm_floor(benchmark::State& state, const System& proto) {
  massspring::FastMassSpring<System> solver(assignment_options());
  typename System::Traits::Cholesky cholesky;
  if (!precompute_or_skip(state, solver, proto)) return;
  if (!cholesky.compute(solver.system_matrix())) {
    state.SkipWithError("Q is not positive definite");
    return;
  }
  // In the factor's own row order, as FastMassSpring keeps its iterate: no permutation.
  massspring::Points<double> x = massspring::Points<double>::Random(proto.num_points(), 3);
  for (auto _ : state) {
    cholesky.solve_in_place(x.data());
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, proto, cholesky.factor_nonzeros(), kIterations);
  state.SetLabel(std::string(storage_name<System>()) + ": one L, L^T solve, n x 3");
}

// ---- the seed
// ------------------------------------------------------------------------------------

void bm_seed_precompute(benchmark::State& state, const SparseSystem& proto) {
  Eigen::Index nnz = 0;
  try {
    for (auto _ : state) {
      SeedFastMassSpring seed(seed_options());
      seed.precompute(proto, kDt);
      nnz = seed.factor_nonzeros();
      benchmark::DoNotOptimize(nnz);
    }
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  set_counters(state, proto, nnz, kIterations);
  state.SetLabel("seed: Q by sparse products, factorise");
}

void bm_seed_step(benchmark::State& state, const SparseSystem& proto) {
  SeedFastMassSpring seed(seed_options());
  if (!precompute_or_skip(state, seed, proto)) return;
  for (auto _ : state) {
    seed.step();
    benchmark::DoNotOptimize(seed.positions().data());
  }
  set_counters(state, proto, seed.factor_nonzeros(), kIterations);
  state.SetLabel("seed: one step");
}

// Eigen's own solve on the seed's factor: the seed's global step without its local step.
void bm_eigen_solve(benchmark::State& state, const SparseSystem& proto) {
  SeedFastMassSpring seed(seed_options());
  if (!precompute_or_skip(state, seed, proto)) return;
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(proto.num_points(), 3);
  Eigen::MatrixXd x(proto.num_points(), 3);
  for (auto _ : state) {
    x = seed.factorization().solve(b);
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, proto, seed.factor_nonzeros(), kIterations);
  state.SetLabel("seed: SimplicialLLT::solve, n x 3");
}

// ---- sanity: ours and the seed compute the same step
// ----------------------------------------------

std::map<std::string, double>& first_step_differences() {
  static std::map<std::string, double> d;
  return d;
}

// |X_ours - X_seed| / |X_seed| after one step from rest.
template <class System>
double first_step_difference(const System& proto, const SparseSystem& sparse) {
  System system = proto;
  massspring::FastMassSpring<System> ours(assignment_options());
  ours.precompute(system, kDt);
  ours.step(system);
  SeedFastMassSpring seed(seed_options());
  seed.precompute(sparse, kDt);
  seed.step();
  const Eigen::MatrixXd x = system.positions();
  return (x - seed.positions()).norm() / seed.positions().norm();
}

void check_agreement() {
  for (const Scene& s : scenes()) {
    const auto check = [&s](const char* storage, auto&& difference) {
      const std::string key = std::string(storage) + "/" + s.name;
      double d = 0;
      try {
        d = difference();
      } catch (const std::exception& e) {
        std::fprintf(stderr, "WARNING: sanity check %s failed: %s\n", key.c_str(), e.what());
        d = -1;
      }
      first_step_differences()[key] = d;
      if (!(d >= 0 && d <= 1e-9))
        std::fprintf(stderr,
                     "WARNING: %s: ours and the seed differ after one step (relative %.3g > "
                     "1e-9): the timings below compare different computations\n",
                     key.c_str(), d);
    };
    check("Sparse", [&s] { return first_step_difference(*s.sparse, *s.sparse); });
    if (s.dense) check("Dense", [&s] { return first_step_difference(*s.dense, *s.sparse); });
  }
}

// ---- scenes and registration
// ---------------------------------------------------------------------

void add_scenes() {
  for (const int n : kGridSizes) {
    massspring::ClothOptions o;
    o.columns = o.rows = n;
    o.shear = massspring::ClothShear::Both;
    o.pins = massspring::ClothPins::TopCorners;
    o.stiffness = 1000;
    const auto description = massspring::make_cloth(o);
    Scene s;
    s.name = "cloth" + std::to_string(n);
    s.sparse = std::make_shared<SparseSystem>(massspring::make_system<SparseSystem>(description));
    if (n <= kDenseLimit)
      s.dense = std::make_shared<DenseSystem>(massspring::make_system<DenseSystem>(description));
    scenes().push_back(std::move(s));
  }
  const std::filesystem::path jacobson =
      std::filesystem::path(MASSSPRING_BENCH_SHARED_DIR) / "scenes" / "jacobson";
  for (const char* name : {"flag", "skirt"}) {
    const std::filesystem::path file = jacobson / (std::string(name) + ".json");
    if (!std::filesystem::exists(file)) {
      std::fprintf(stderr, "note: %s not found; the %s benchmarks are not registered\n",
                   file.string().c_str(), name);
      continue;
    }
#if MASSSPRING_BENCH_HAVE_LOAD_SCENE
    try {
      Scene s;
      s.name = name;
      s.sparse = std::make_shared<SparseSystem>(massspring::io::load_scene<SparseSystem>(file));
      scenes().push_back(std::move(s));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "WARNING: loading %s failed (%s); its benchmarks are not registered\n",
                   file.string().c_str(), e.what());
    }
#else
    std::fprintf(stderr,
                 "note: built without massspring/io/load_scene.hpp; the %s benchmarks are not "
                 "registered\n",
                 name);
#endif
  }
}

void register_benchmarks() {
  // Steps and floors, the quantities of the summary, are repeated and summarised by their median;
  // precompute once. Each benchmark runs ~0.2-1 s, the whole program a few minutes on 2 cores.
  const auto once = [](benchmark::internal::Benchmark* b) {
    b->Unit(benchmark::kMillisecond)->MinTime(0.3)->UseRealTime();
  };
  const auto repeated = [](benchmark::internal::Benchmark* b) {
    b->Unit(benchmark::kMillisecond)
        ->MinTime(0.3)
        ->Repetitions(3)
        ->DisplayAggregatesOnly(true)
        ->UseRealTime();
  };
  for (const Scene& s : scenes()) {
    const auto sparse = s.sparse;
    const auto dense = s.dense;
    const auto name = [&s](const char* what, const char* solver) {
      return std::string(what) + "/" + solver + "/" + s.name;
    };
    once(benchmark::RegisterBenchmark(
        name("Precompute", "Sparse").c_str(),
        [sparse](benchmark::State& st) { bm_precompute(st, *sparse); }));
    once(benchmark::RegisterBenchmark(
        name("Precompute", "Seed").c_str(),
        [sparse](benchmark::State& st) { bm_seed_precompute(st, *sparse); }));
    if (dense)
      once(benchmark::RegisterBenchmark(
          name("Precompute", "Dense").c_str(),
          [dense](benchmark::State& st) { bm_precompute(st, *dense); }));
    repeated(benchmark::RegisterBenchmark(
        name("Step", "Sparse").c_str(), [sparse](benchmark::State& st) { bm_step(st, *sparse); }));
    repeated(benchmark::RegisterBenchmark(
        name("Step", "Seed").c_str(),
        [sparse](benchmark::State& st) { bm_seed_step(st, *sparse); }));
    if (dense)
      repeated(benchmark::RegisterBenchmark(
          name("Step", "Dense").c_str(), [dense](benchmark::State& st) { bm_step(st, *dense); }));
    repeated(
        benchmark::RegisterBenchmark(name("Floor", "Sparse").c_str(),
                                     [sparse](benchmark::State& st) { bm_floor(st, *sparse); }));
    repeated(benchmark::RegisterBenchmark(
        name("Floor", "EigenSolve").c_str(),
        [sparse](benchmark::State& st) { bm_eigen_solve(st, *sparse); }));
    if (dense)
      repeated(benchmark::RegisterBenchmark(
          name("Floor", "Dense").c_str(), [dense](benchmark::State& st) { bm_floor(st, *dense); }));
  }
}

// ---- the summary
// ---------------------------------------------------------------------------------

// The console reporter, recording each benchmark's real time per iteration [ms]: the median of
// its repetitions when it has them, else its one run.
class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  using benchmark::ConsoleReporter::ConsoleReporter;

  void ReportRuns(const std::vector<Run>& runs) override {
    benchmark::ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.error_occurred) continue;
      const double ms =
          run.GetAdjustedRealTime() / benchmark::GetTimeUnitMultiplier(run.time_unit) * 1e3;
      const std::string& key = run.run_name.function_name;
      if (run.run_type == Run::RT_Iteration)
        single_[key].push_back(ms);
      else if (run.aggregate_name == "median")
        median_[key] = ms;
    }
  }

  /// @brief Milliseconds per iteration of benchmark `name`, or a negative number when it did not
  /// run.
  [[nodiscard]] double ms(const std::string& name) const {
    if (const auto m = median_.find(name); m != median_.end()) return m->second;
    const auto s = single_.find(name);
    if (s == single_.end() || s->second.empty()) return -1;
    std::vector<double> v = s->second;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
  }

 private:
  std::map<std::string, std::vector<double>> single_;
  std::map<std::string, double> median_;
};

std::string cell(double value, const char* format) {
  if (!(value >= 0)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

double ratio(double a, double b) { return a >= 0 && b > 0 ? a / b : -1; }

void print_summary(const RecordingReporter& r) {
  bool header = false;
  for (const Scene& s : scenes()) {
    const auto t = [&](const char* what, const char* solver) {
      return r.ms(std::string(what) + "/" + solver + "/" + s.name);
    };
    const double ours = t("Step", "Sparse"), seed = t("Step", "Seed"), floor = t("Floor", "Sparse");
    if (ours < 0 && seed < 0 && floor < 0) continue;
    if (!header) {
      std::printf(
          "\nLocal-global step, Sparse, double: dt = 1/30, %d iterations, penalty pins w = %g; "
          "medians [ms]\n"
          "seed/ours: how many times faster our step is; it/floor: ms per iteration divided by "
          "one L, L^T solve (Floor/Sparse);\n"
          "eigen solve: SimplicialLLT::solve on the same n x 3 (the seed's); 1st diff: relative "
          "difference of ours and the seed after one step\n\n",
          kIterations, kPenaltyWeight);
      std::printf("%-9s %7s %7s %9s | %10s %10s %9s | %9s %11s %9s %9s | %9s %9s | %9s\n", "scene",
                  "points", "springs", "nnz(L)", "ours/step", "seed/step", "seed/ours", "floor",
                  "eigen solve", "ours it/f", "seed it/f", "ours pre", "seed pre", "1st diff");
      header = true;
    }
    massspring::FastMassSpring<SparseSystem> solver(assignment_options());
    solver.precompute(*s.sparse, kDt);
    const auto diff = first_step_differences().find("Sparse/" + s.name);
    std::printf("%-9s %7d %7d %9ld | %10s %10s %9s | %9s %11s %9s %9s | %9s %9s | %9s\n",
                s.name.c_str(), s.sparse->num_points(), s.sparse->num_springs(),
                long(solver.factor_nonzeros()), cell(ours, "%.3f").c_str(),
                cell(seed, "%.3f").c_str(), cell(ratio(seed, ours), "%.2fx").c_str(),
                cell(floor, "%.4f").c_str(), cell(t("Floor", "EigenSolve"), "%.4f").c_str(),
                cell(ratio(ours / kIterations, floor), "%.2f").c_str(),
                cell(ratio(seed / kIterations, floor), "%.2f").c_str(),
                cell(t("Precompute", "Sparse"), "%.2f").c_str(),
                cell(t("Precompute", "Seed"), "%.2f").c_str(),
                diff == first_step_differences().end() ? "-" : cell(diff->second, "%.1e").c_str());
  }
  header = false;
  for (const Scene& s : scenes()) {
    if (!s.dense) continue;
    const auto t = [&](const char* what, const char* solver) {
      return r.ms(std::string(what) + "/" + solver + "/" + s.name);
    };
    const double step = t("Step", "Dense"), floor = t("Floor", "Dense");
    if (step < 0 && floor < 0) continue;
    if (!header) {
      std::printf(
          "\nDense against Sparse (ours), medians [ms]; it/f: ms per iteration / that "
          "storage's floor\n\n");
      std::printf("%-9s %7s | %11s %11s | %11s %11s | %11s %11s\n", "scene", "points", "Dense pre",
                  "Sparse pre", "Dense step", "Sparse step", "Dense it/f", "Sparse it/f");
      header = true;
    }
    const double sparse_step = t("Step", "Sparse");
    std::printf("%-9s %7d | %11s %11s | %11s %11s | %11s %11s\n", s.name.c_str(),
                s.dense->num_points(), cell(t("Precompute", "Dense"), "%.2f").c_str(),
                cell(t("Precompute", "Sparse"), "%.2f").c_str(), cell(step, "%.3f").c_str(),
                cell(sparse_step, "%.3f").c_str(),
                cell(ratio(step / kIterations, floor), "%.2f").c_str(),
                cell(ratio(sparse_step / kIterations, t("Floor", "Sparse")), "%.2f").c_str());
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  try {
    add_scenes();
    check_agreement();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  register_benchmarks();
  RecordingReporter reporter(isatty(STDOUT_FILENO) ? benchmark::ConsoleReporter::OO_ColorTabular
                                                   : benchmark::ConsoleReporter::OO_Tabular);
  benchmark::RunSpecifiedBenchmarks(&reporter);
  print_summary(reporter);
  benchmark::Shutdown();
  return 0;
}
