// integrators/fast_mass_spring.hpp: precompute and step of FastMassSpring, Dense and Sparse,
// double and float, plain and accelerated, against the seed's plain formulas
// (tests/support/seed_reference.hpp) and against the floor of an iteration (one forward and one
// back substitution with the factor of Q, n x 3 right-hand side, in the factor's row order).
//
// Setup throughout is the assignment's: dt = 1/30 s, a force (0, -9.8, 0) on every point, penalty
// pins w = 1e10, 50 local-global iterations per step starting from the current positions. The
// curtain (Liu 2013's: 81 x 81, one diagonal per cell, skip-one bending springs, two corners
// pinned) falls under gravity m g instead, as in Liu's paper: the assignment's 9.8 N on each of its
// 1.5e-4 kg points would pull it ~70 m in one frame.
//
// Scenes: generated cloth grids N x N (N = 32, 64, 128; quads with both diagonals, top corners
// pinned, stiffness 1000 N/m, Voronoi masses), the curtain and, when ../shared/scenes/jacobson is
// there, the assignment's flag and skirt.
//
// Names: <what>/<solver>/<scene>, what = Precompute | Step | Floor, solver = Sparse | Dense (ours,
// double, penalty pins as the seed), SparseExact / SparseFloat (ours, exact pins, double / float),
// Chebyshev / Anderson (ours, accelerated, as many iterations as reach the error of 50 plain ones),
// Seed (SeedFastMassSpring), EigenSolve (Eigen's SimplicialLLT::solve on the seed's factor),
// SparseSSE2 (ours with options.avx2 = false: the SSE2 substitution and the baseline spring pass,
// where Sparse takes the AVX2 + FMA ones when the CPU has them). Paired/Sparse times each step
// and then as many substitutions with that solver's own factor (target 1's ratio, see bm_paired).
// Counters: points, springs, nnz_L (stored entries of the factor of Q) and iterations (local-global
// iterations per step: for ours the mean step() reported, elsewhere the configured 50). After the
// run, summary tables compare ours with the seed per scene (medians of the repetitions), with each
// iteration's time as a multiple of the floor; the accelerated solvers' time to the error of 50
// plain iterations; the AVX2 code paths against the SSE2 ones; float against double.
#include <benchmark/benchmark.h>
#include <time.h>
#include <unistd.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <massspring/scene/recipes.hpp>
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
using FloatSystem = massspring::MassSpringSystem<float, massspring::Sparse>;
using massspring::test::SeedFastMassSpring;

constexpr double kDt = 1.0 / 30;
constexpr int kIterations = 50;
constexpr double kPenaltyWeight = 1e10;
constexpr int kWarmFrames = 10;  // plain steps before the step whose error is measured

// Generated grids. Dense stops at 32 x 32 (1024 points): its Q is n x n dense, so memory grows as
// n^2, factorisation as n^3 / 3 and each iteration's solve as n^2. flag (3200 points), curtain
// (6561) and skirt (9840) are Sparse only, likewise.
constexpr int kGridSizes[] = {32, 64, 128};
// Smaller cloths run only the two-thread comparison (where its crossover lies).
constexpr int kThreadOnlyGridSizes[] = {8, 16};
constexpr int kDenseLimit = 32;

// Time to error: the accelerated solvers, per scene.
struct Acceleration {
  double e0 = 0, e_star = 0, e_plain = 0;  // E(x_0), converged E*, E after 50 plain iterations
  int chebyshev = -1, anderson = -1;       // iterations that reach e_plain (-1: not within 50)
  double chebyshev_rho = 0;
  [[nodiscard]] double error(double e) const { return (e - e_star) / (e0 - e_star); }
};

struct Scene {
  std::string name;
  bool gravity = false;  // m g (the curtain) instead of the assignment's (0, -9.8, 0) N per point
  bool accelerate = false;
  std::shared_ptr<const SparseSystem> sparse;
  std::shared_ptr<const DenseSystem> dense;   // null: Dense is not run on this scene
  std::shared_ptr<const FloatSystem> single;  // float, for exact pins
  std::shared_ptr<const SparseSystem> warm;   // after kWarmFrames plain steps (accelerate)
  Acceleration acceleration;
  bool threads_only = false;  // only the two-thread comparison
};

std::vector<Scene>& scenes() {
  static std::vector<Scene> s;
  return s;
}

template <class Scalar>
massspring::FastMassSpringOptions<Scalar> options_for(const Scene& scene) {
  massspring::FastMassSpringOptions<Scalar> o;
  o.iterations = kIterations;
  o.pins = massspring::PinMode::Penalty;
  o.penalty_weight = Scalar(kPenaltyWeight);
  (scene.gravity ? o.gravity : o.external_force) = massspring::Vector3<Scalar>(0, Scalar(-9.8), 0);
  o.initial_guess = massspring::InitialGuess::Current;
  return o;
}

SeedFastMassSpring::Options seed_options(const Scene& scene) {
  SeedFastMassSpring::Options o;
  o.iterations = kIterations;
  o.penalty_weight = kPenaltyWeight;
  o.external_force = scene.gravity ? Eigen::RowVector3d::Zero() : Eigen::RowVector3d(0, -9.8, 0);
  o.gravity = scene.gravity ? Eigen::RowVector3d(0, -9.8, 0) : Eigen::RowVector3d::Zero();
  return o;
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
    solver.precompute(system, typename System::Scalar(kDt));
    return true;
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return false;
  }
}

template <class System>
void bm_precompute(benchmark::State& state, const Scene& scene, const System& proto) {
  Eigen::Index nnz = 0;
  try {
    for (auto _ : state) {
      massspring::FastMassSpring<System> solver(options_for<typename System::Scalar>(scene));
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

// One step per benchmark iteration. Options: the scene's, changed by `adjust`. With a `start`
// state, every step starts from it (the accelerated solvers' iteration counts hold for that step).
template <class System, class Adjust>
void bm_step(benchmark::State& state, const Scene& scene, const System& proto, Adjust adjust,
             const System* start, const char* label) {
  using Scalar = typename System::Scalar;
  System system = start ? *start : proto;
  auto options = options_for<Scalar>(scene);
  adjust(options);
  massspring::FastMassSpring<System> solver(options);
  if (!precompute_or_skip(state, solver, system)) return;
  if (start) {  // untimed: a first step (Chebyshev estimates its rho on it)
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
    const massspring::StepReport report = solver.step(system);
    if (!report.finite) {
      state.SkipWithError("step() result not finite");
      break;
    }
    iterations += report.iterations;
    steps += 1;
  }
  set_counters(state, proto, solver.factor_nonzeros(), steps > 0 ? iterations / steps : 0);
  state.SetLabel(label);
}

// The floor of one iteration: one forward and one back substitution with the factor of
// FastMassSpring's own Q, for an n x 3 right-hand side in the factor's row order (as FastMassSpring
// keeps its iterate), and nothing else.
template <class System, class Adjust>
void bm_floor(benchmark::State& state, const Scene& scene, const System& proto, Adjust adjust,
              int threads = 1) {
  using Scalar = typename System::Scalar;
  auto options = options_for<Scalar>(scene);
  adjust(options);
  massspring::FastMassSpring<System> solver(options);
  typename System::Traits::Cholesky cholesky;
  if constexpr (std::is_same_v<System, SparseSystem>) {
    if (threads > 1) cholesky.set_threads(threads);
    cholesky.set_avx2(options.avx2);
  }
  if (!precompute_or_skip(state, solver, proto)) return;
  bool ok = false;
  if constexpr (std::is_same_v<typename System::Storage, massspring::Sparse>) {
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
  massspring::Points<Scalar> x = massspring::Points<Scalar>::Random(rows, 3);
  for (auto _ : state) {
    cholesky.solve_in_place(x.data());
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, proto, cholesky.factor_nonzeros(), kIterations);
  state.SetLabel(std::string(storage_name<System>()) + ": one L, L^T solve, n x 3");
}

// CPU time of the calling thread [ns].
double thread_cpu_ns() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e9 + double(t.tv_nsec);
}

// Iteration / floor measured in pairs (target 1's figure): each benchmark iteration times one
// step() and then as many substitutions as the step had iterations, with the step's own factor
// (solver.factorization(): the same arrays at the same addresses), both by the thread's CPU
// clock. Floor/Sparse and Step/Sparse each build their own solver; on this shared machine the
// same factor substitutes up to 1.45x slower in one instance than in another (where its pages
// land, docs/performance.md), so their ratio carries that instance noise twice. Here the two
// parts share the instance and alternate in time. Counters: step_ms (per step), floor_ms (per
// substitution) and it_per_floor, their times summed over the repetition and divided (as many
// substitutions as iterations).
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
  state.SetLabel("Sparse: one step, then as many L, L^T solves with its own factor");
}

const auto kSeedLike = [](auto&) {};
const auto kExact = [](auto& o) { o.pins = massspring::PinMode::Exact; };
const auto kAmdOrder = [](auto& o) { o.ordering = massspring::FillOrdering::Solver; };
const auto kSse2 = [](auto& o) { o.avx2 = false; };

// ---- the seed
// ------------------------------------------------------------------------------------

void bm_seed_precompute(benchmark::State& state, const Scene& scene, const SparseSystem& proto) {
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
  state.SetLabel("seed: Q by sparse products, factorise");
}

void bm_seed_step(benchmark::State& state, const Scene& scene, const SparseSystem& proto) {
  SeedFastMassSpring seed(seed_options(scene));
  if (!precompute_or_skip(state, seed, proto)) return;
  for (auto _ : state) {
    seed.step();
    benchmark::DoNotOptimize(seed.positions().data());
  }
  set_counters(state, proto, seed.factor_nonzeros(), kIterations);
  state.SetLabel("seed: one step");
}

// Eigen's own solve on the seed's factor: the seed's global step without its local step.
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
double first_step_difference(const Scene& scene, const System& proto, const SparseSystem& sparse) {
  System system = proto;
  massspring::FastMassSpring<System> ours(options_for<double>(scene));
  ours.precompute(system, kDt);
  ours.step(system);
  SeedFastMassSpring seed(seed_options(scene));
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
    check("Sparse", [&s] { return first_step_difference(s, *s.sparse, *s.sparse); });
    if (s.dense) check("Dense", [&s] { return first_step_difference(s, *s.dense, *s.sparse); });
  }
}

// ---- time to error (untimed set-up)
// -------------------------------------------------------------------------------

// E(X) of DESIGN.md for the step from `start` with penalty pins, written out term by term: the
// objective every solver here minimises (report.energy is the same function).
double step_energy(const Scene& scene, const SparseSystem& start, const Eigen::MatrixXd& x) {
  const auto& springs = start.springs();
  double e = 0;
  for (int s = 0; s < start.num_springs(); ++s) {
    const double l = (x.row(springs(s, 0)) - x.row(springs(s, 1))).norm();
    e += 0.5 * start.stiffness()(s) * (l - start.rest_lengths()(s)) * (l - start.rest_lengths()(s));
  }
  for (int i = 0; i < start.num_points(); ++i) {
    const double m = start.masses()(i);
    const Eigen::RowVector3d y = start.positions().row(i) + kDt * start.velocities().row(i);
    const Eigen::RowVector3d f =
        scene.gravity ? Eigen::RowVector3d(0, -9.8 * m, 0) : Eigen::RowVector3d(0, -9.8, 0);
    e += m / (2 * kDt * kDt) * (x.row(i) - y).squaredNorm() - x.row(i).dot(f);
  }
  for (int p = 0; p < start.num_pinned(); ++p)
    e += 0.5 * kPenaltyWeight *
         (x.row(start.pinned()[std::size_t(p)]) - start.pin_targets().row(p)).squaredNorm();
  return e;
}

template <class Adjust>
double energy_after(const Scene& scene, const SparseSystem& start, int iterations, Adjust adjust,
                    double* rho = nullptr) {
  SparseSystem system = start;
  auto options = options_for<double>(scene);
  adjust(options);
  options.iterations = iterations;
  massspring::FastMassSpring<SparseSystem> solver(options);
  solver.precompute(system, kDt);
  const massspring::StepReport report = solver.step(system);
  if (rho) *rho = solver.chebyshev_rho();
  const double e = step_energy(scene, start, system.positions());
  if (std::abs(report.energy - e) > 1e-9 * std::abs(e) + 1e-12)
    std::fprintf(stderr, "WARNING: %s: report.energy %.17g differs from E %.17g\n",
                 scene.name.c_str(), report.energy, e);
  return e;
}

const auto kChebyshev = [](auto& o) { o.acceleration = massspring::Acceleration::Chebyshev; };
const auto kAnderson = [](auto& o) { o.acceleration = massspring::Acceleration::Anderson; };

void measure_acceleration(Scene& scene) {
  auto warm = std::make_shared<SparseSystem>(*scene.sparse);
  {
    massspring::FastMassSpring<SparseSystem> solver(options_for<double>(scene));
    solver.precompute(*warm, kDt);
    for (int frame = 0; frame < kWarmFrames; ++frame) solver.step(*warm);
  }
  scene.warm = warm;
  Acceleration& a = scene.acceleration;
  a.e0 = step_energy(scene, *warm, warm->positions());
  a.e_plain = energy_after(scene, *warm, kIterations, kSeedLike);
  // E*: the lowest of long accelerated runs (each never increases E past its plain fallback).
  a.e_star = std::min(energy_after(scene, *warm, 3000, kChebyshev),
                      energy_after(scene, *warm, 3000, kAnderson));
  for (int k = 1; k <= kIterations && (a.chebyshev < 0 || a.anderson < 0); ++k) {
    if (a.chebyshev < 0 && energy_after(scene, *warm, k, kChebyshev, &a.chebyshev_rho) <= a.e_plain)
      a.chebyshev = k;
    if (a.anderson < 0 && energy_after(scene, *warm, k, kAnderson) <= a.e_plain) a.anderson = k;
  }
}

// ---- scenes and registration
// ---------------------------------------------------------------------

template <class System, class Description>
std::shared_ptr<const System> make(const Description& d) {
  return std::make_shared<const System>(massspring::make_system<System>(d));
}

void add_scenes() {
  for (const int n : kThreadOnlyGridSizes) {
    massspring::ClothOptions o;
    o.columns = o.rows = n;
    o.shear = massspring::ClothShear::Both;
    o.pins = massspring::ClothPins::TopCorners;
    o.stiffness = 1000;
    Scene s;
    s.name = "cloth" + std::to_string(n);
    s.threads_only = true;
    s.sparse = make<SparseSystem>(massspring::make_cloth(o));
    scenes().push_back(std::move(s));
  }
  for (const int n : kGridSizes) {
    massspring::ClothOptions o;
    o.columns = o.rows = n;
    o.shear = massspring::ClothShear::Both;
    o.pins = massspring::ClothPins::TopCorners;
    o.stiffness = 1000;
    const auto description = massspring::make_cloth(o);
    Scene s;
    s.name = "cloth" + std::to_string(n);
    s.sparse = make<SparseSystem>(description);
    s.single = make<FloatSystem>(description);
    if (n <= kDenseLimit) s.dense = make<DenseSystem>(description);
    scenes().push_back(std::move(s));
  }
  {
    // Liu et al. 2013's curtain (massspring/scene/recipes.hpp; examples/scenes/curtain).
    const auto description = massspring::make_cloth(massspring::curtain_recipe());
    Scene s;
    s.name = "curtain";
    s.gravity = true;
    s.accelerate = true;
    s.sparse = make<SparseSystem>(description);
    s.single = make<FloatSystem>(description);
    if (s.sparse->num_points() != 6561 || s.sparse->num_springs() != 32158)
      std::fprintf(stderr,
                   "WARNING: the curtain has %d points and %d springs, not 6561 and 32158\n",
                   s.sparse->num_points(), s.sparse->num_springs());
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
      s.accelerate = std::string(name) == "skirt";
      s.sparse = std::make_shared<SparseSystem>(massspring::io::load_scene<SparseSystem>(file));
      s.single = std::make_shared<FloatSystem>(massspring::io::load_scene<FloatSystem>(file));
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
  for (Scene& s : scenes())
    if (s.accelerate) measure_acceleration(s);
}

void register_benchmarks() {
  // Steps and floors, the quantities of the summary, are repeated and summarised by their median;
  // precompute once.
  const auto once = [](benchmark::internal::Benchmark* b) {
    b->Unit(benchmark::kMillisecond)->MinTime(0.3)->UseRealTime();
  };
  const auto repetitions = [](int count) {
    return [count](benchmark::internal::Benchmark* b) {
      b->Unit(benchmark::kMillisecond)
          ->MinTime(0.3)
          ->Repetitions(count)
          ->DisplayAggregatesOnly(true)
          ->UseRealTime();
    };
  };
  const auto repeated = repetitions(3);
  // The paired measurement of target 1: more repetitions, as each compares two parts of one run.
  const auto paired = repetitions(5);
  for (const Scene& s : scenes()) {
    const Scene* sc = &s;
    const auto name = [&s](const char* what, const char* solver) {
      return std::string(what) + "/" + solver + "/" + s.name;
    };
    const auto reg = [&](auto how, const char* what, const char* solver, auto body) {
      how(benchmark::RegisterBenchmark(name(what, solver).c_str(), body));
    };
    // One thread against two (options.threads, OpenMP): the floor and the plain step.
    reg(repeated, "Floor", "Threads1",
        [sc](benchmark::State& st) { bm_floor(st, *sc, *sc->sparse, kSeedLike, 1); });
    reg(repeated, "Step", "Threads1", [sc](benchmark::State& st) {
      bm_step(st, *sc, *sc->sparse, kSeedLike, static_cast<const SparseSystem*>(nullptr),
              "Sparse: one step, one thread");
    });
#ifdef _OPENMP
    reg(repeated, "Floor", "Threads2",
        [sc](benchmark::State& st) { bm_floor(st, *sc, *sc->sparse, kSeedLike, 2); });
    reg(repeated, "Step", "Threads2", [sc](benchmark::State& st) {
      bm_step(
          st, *sc, *sc->sparse, [](auto& o) { o.threads = 2; },
          static_cast<const SparseSystem*>(nullptr), "Sparse: one step, two threads");
    });
#endif
    if (s.threads_only) continue;
    reg(once, "Precompute", "Sparse",
        [sc](benchmark::State& st) { bm_precompute(st, *sc, *sc->sparse); });
    reg(once, "Precompute", "Seed",
        [sc](benchmark::State& st) { bm_seed_precompute(st, *sc, *sc->sparse); });
    if (s.dense)
      reg(once, "Precompute", "Dense",
          [sc](benchmark::State& st) { bm_precompute(st, *sc, *sc->dense); });
    reg(repeated, "Step", "Sparse", [sc](benchmark::State& st) {
      bm_step(st, *sc, *sc->sparse, kSeedLike, static_cast<const SparseSystem*>(nullptr),
              "Sparse: one step");
    });
    // The same step and floor in AMD's order (FillOrdering::Solver): what Auto's choice of order
    // gains where it picks nested dissection (the curtain, cloth128), nothing elsewhere.
    reg(repeated, "Step", "SparseAMD", [sc](benchmark::State& st) {
      bm_step(st, *sc, *sc->sparse, kAmdOrder, static_cast<const SparseSystem*>(nullptr),
              "Sparse, AMD order: one step");
    });
    reg(repeated, "Floor", "SparseAMD",
        [sc](benchmark::State& st) { bm_floor(st, *sc, *sc->sparse, kAmdOrder); });
    reg(repeated, "Step", "Seed",
        [sc](benchmark::State& st) { bm_seed_step(st, *sc, *sc->sparse); });
    if (s.dense)
      reg(repeated, "Step", "Dense", [sc](benchmark::State& st) {
        bm_step(st, *sc, *sc->dense, kSeedLike, static_cast<const DenseSystem*>(nullptr),
                "Dense: one step");
      });
    reg(repeated, "Step", "SparseExact", [sc](benchmark::State& st) {
      bm_step(st, *sc, *sc->sparse, kExact, static_cast<const SparseSystem*>(nullptr),
              "Sparse, exact pins: one step");
    });
    reg(repeated, "Step", "SparseFloat", [sc](benchmark::State& st) {
      bm_step(st, *sc, *sc->single, kExact, static_cast<const FloatSystem*>(nullptr),
              "Sparse float, exact pins: one step");
    });
    reg(repeated, "Floor", "Sparse",
        [sc](benchmark::State& st) { bm_floor(st, *sc, *sc->sparse, kSeedLike); });
    reg(paired, "Paired", "Sparse",
        [sc](benchmark::State& st) { bm_paired(st, *sc, *sc->sparse); });
    // options.avx2 = false (the SSE2 substitution; the step also the baseline spring pass): what
    // the AVX2 + FMA paths gain.
    reg(repeated, "Floor", "SparseSSE2",
        [sc](benchmark::State& st) { bm_floor(st, *sc, *sc->sparse, kSse2); });
    reg(repeated, "Step", "SparseSSE2", [sc](benchmark::State& st) {
      bm_step(st, *sc, *sc->sparse, kSse2, static_cast<const SparseSystem*>(nullptr),
              "Sparse, SSE2 substitution and spring pass: one step");
    });
    reg(repeated, "Floor", "SparseExact",
        [sc](benchmark::State& st) { bm_floor(st, *sc, *sc->sparse, kExact); });
    reg(repeated, "Floor", "SparseFloat",
        [sc](benchmark::State& st) { bm_floor(st, *sc, *sc->single, kExact); });
    reg(repeated, "Floor", "EigenSolve",
        [sc](benchmark::State& st) { bm_eigen_solve(st, *sc, *sc->sparse); });
    if (s.dense)
      reg(repeated, "Floor", "Dense",
          [sc](benchmark::State& st) { bm_floor(st, *sc, *sc->dense, kSeedLike); });
      // Chebyshev to the error of 50 plain iterations; on two threads too when built with OpenMP.
#ifdef _OPENMP
    constexpr int kMostThreads = 2;
#else
    constexpr int kMostThreads = 1;
#endif
    for (int threads = 1; s.accelerate && s.acceleration.chebyshev > 0 && threads <= kMostThreads;
         ++threads) {
      const int k = s.acceleration.chebyshev;
      reg(repeated, "Step", threads == 1 ? "Chebyshev" : "ChebyshevThreads2",
          [sc, k, threads](benchmark::State& st) {
            bm_step(
                st, *sc, *sc->sparse,
                [k, threads](auto& o) {
                  kChebyshev(o);
                  o.iterations = k;
                  o.threads = threads;
                },
                sc->warm.get(),
                threads == 1 ? "Sparse, Chebyshev: one step to the error of 50 plain iterations"
                             : "Sparse, Chebyshev, two threads: one step to the error of 50 plain");
          });
    }
    if (s.accelerate && s.acceleration.anderson > 0) {
      const int k = s.acceleration.anderson;
      reg(repeated, "Step", "Anderson", [sc, k](benchmark::State& st) {
        bm_step(
            st, *sc, *sc->sparse,
            [k](auto& o) {
              kAnderson(o);
              o.iterations = k;
            },
            sc->warm.get(), "Sparse, Anderson: one step to the error of 50 plain iterations");
      });
    }
  }
  // The divider alone: k r / sqrt(x) for the curtain's 32158 springs' worth of values, one value
  // at a time (std::sqrt then /, as the spring pass did before its pairs) and in pairs through
  // detail::lengths2 (the spring pass's own helper: one SSE2 sqrtpd and divpd per pair). The
  // values per second are items_per_second; docs/performance.md quotes 1e9 / that, ns per value.
  const auto divider = [](bool pairs) {
    return [pairs](benchmark::State& state) {
      constexpr int kValues = 32158;
      std::vector<double> sq(kValues), num(kValues, 1000.0), len(kValues), quotient(kValues);
      for (int i = 0; i < kValues; ++i) sq[std::size_t(i)] = 1e-4 * (1 + i % 97);
      for (auto _ : state) {
        if (pairs) {
          for (std::size_t i = 0; i < kValues; i += 2)
            massspring::detail::lengths2(&sq[i], &num[i], &len[i], &quotient[i]);
        } else {
          for (std::size_t i = 0; i < kValues; ++i) {
            len[i] = std::sqrt(sq[i]);
            quotient[i] = num[i] / len[i];
          }
        }
        benchmark::DoNotOptimize(quotient.data());
        benchmark::ClobberMemory();
      }
      state.SetItemsProcessed(std::int64_t(state.iterations()) * kValues);
    };
  };
  benchmark::RegisterBenchmark("Divider/OneAtATime", divider(false))->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("Divider/Pairs", divider(true))->Unit(benchmark::kMicrosecond);
}

// ---- the summary
// ---------------------------------------------------------------------------------

// The console reporter, recording each benchmark's CPU time per iteration [ms]: the median of
// its repetitions when it has them, else its one run.
class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  using benchmark::ConsoleReporter::ConsoleReporter;

  void ReportRuns(const std::vector<Run>& runs) override {
    benchmark::ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.error_occurred) continue;
      // CPU time: these programs are single-threaded, and on a shared machine the wall clock also
      // counts the time other processes held the core.
      const double ms =
          run.GetAdjustedCPUTime() / benchmark::GetTimeUnitMultiplier(run.time_unit) * 1e3;
      const std::string& key = run.run_name.function_name;
      if (run.run_type == Run::RT_Iteration)
        single_[key].push_back(ms);
      else if (run.aggregate_name == "median")
        median_[key] = ms;
      // Wall clock, for the two-thread comparison (CPU time counts one thread only).
      if (run.run_type != Run::RT_Iteration && run.aggregate_name == "median") {
        real_median_[key] =
            run.GetAdjustedRealTime() / benchmark::GetTimeUnitMultiplier(run.time_unit) * 1e3;
        for (const auto& [counter, value] : run.counters)
          counter_median_[key + "#" + counter] = value.value;
      }
    }
  }

  /// @brief Wall-clock milliseconds per iteration (median of the repetitions) of benchmark
  /// `name`, or a negative number when it did not run.
  [[nodiscard]] double real_ms(const std::string& name) const {
    const auto m = real_median_.find(name);
    return m == real_median_.end() ? -1 : m->second;
  }

  /// @brief Median over the repetitions of benchmark `name`'s counter `counter`, or a negative
  /// number when it did not run.
  [[nodiscard]] double counter(const std::string& name, const std::string& counter) const {
    const auto m = counter_median_.find(name + "#" + counter);
    return m == counter_median_.end() ? -1 : m->second;
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
  std::map<std::string, double> median_, real_median_, counter_median_;
};

std::string cell(double value, const char* format) {
  if (!(value >= 0)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

double ratio(double a, double b) { return a >= 0 && b > 0 ? a / b : -1; }

// The summary, as Markdown tables (scripts/plot_performance.py reads them back).
void print_summary(const RecordingReporter& r) {
  const auto t = [&r](const Scene& s, const char* what, const char* solver) {
    return r.ms(std::string(what) + "/" + solver + "/" + s.name);
  };
  std::printf(
      "\n## summary: local-global step, Sparse, double, dt = 1/30, %d iterations, penalty pins "
      "w = %g; medians [ms]\n\n"
      "seed/ours: how many times faster our step is; it/floor: ms per iteration divided by one "
      "L, L^T solve in the factor's order (Floor/Sparse); eigen solve: SimplicialLLT::solve on the "
      "same n x 3 (the seed's); 1st diff: relative difference of ours and the seed after one "
      "step; paired it/floor: the same ratio measured in pairs (Paired/Sparse: each step followed "
      "by as many solves with its own factor; median of the repetitions' ratios)\n\n",
      kIterations, kPenaltyWeight);
  std::printf(
      "| scene | points | springs | nnz(L) | ours ms/step | ours ms/iteration | seed ms/step | "
      "seed/ours | floor ms | eigen solve ms | ours it/floor | seed it/floor | ours precompute "
      "ms | seed precompute ms | 1st diff | paired it/floor |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Scene& s : scenes()) {
    const double ours = t(s, "Step", "Sparse"), seed = t(s, "Step", "Seed"),
                 floor = t(s, "Floor", "Sparse");
    if (ours < 0 && seed < 0 && floor < 0) continue;
    massspring::FastMassSpring<SparseSystem> solver(options_for<double>(s));
    solver.precompute(*s.sparse, kDt);
    const auto diff = first_step_differences().find("Sparse/" + s.name);
    std::printf(
        "| %s | %d | %d | %ld | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n",
        s.name.c_str(), s.sparse->num_points(), s.sparse->num_springs(),
        long(solver.factor_nonzeros()), cell(ours, "%.3f").c_str(),
        cell(ours / kIterations, "%.4f").c_str(), cell(seed, "%.3f").c_str(),
        cell(ratio(seed, ours), "%.2fx").c_str(), cell(floor, "%.4f").c_str(),
        cell(t(s, "Floor", "EigenSolve"), "%.4f").c_str(),
        cell(ratio(ours / kIterations, floor), "%.2f").c_str(),
        cell(ratio(seed / kIterations, floor), "%.2f").c_str(),
        cell(t(s, "Precompute", "Sparse"), "%.2f").c_str(),
        cell(t(s, "Precompute", "Seed"), "%.2f").c_str(),
        diff == first_step_differences().end() ? "-" : cell(diff->second, "%.1e").c_str(),
        cell(r.counter("Paired/Sparse/" + s.name, "it_per_floor"), "%.2f").c_str());
  }

  std::printf(
      "\n## acceleration: time to the step error of %d plain iterations (from the state after %d "
      "plain steps), medians [ms]\n\n"
      "error = (E(x_k) - E*) / (E(x_0) - E*), E* the lowest of 3000 Chebyshev and 3000 Anderson "
      "iterations; k: iterations that reach E(x_50) of the plain iteration; seed/x: the seed's "
      "step (50 iterations) divided by x's step of k iterations\n\n",
      kIterations, kWarmFrames);
  std::printf(
      "| scene | plain error at 50 | rho (estimated) | Chebyshev k | Chebyshev ms | seed/Chebyshev "
      "| Anderson k | Anderson ms | seed/Anderson | seed ms | Chebyshev, 2 threads, wall ms | "
      "seed/that (wall) |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Scene& s : scenes()) {
    if (!s.accelerate) continue;
    const Acceleration& a = s.acceleration;
    const double seed = t(s, "Step", "Seed"), cheb = t(s, "Step", "Chebyshev"),
                 anderson = t(s, "Step", "Anderson");
    const double cheb2 = r.real_ms("Step/ChebyshevThreads2/" + s.name),
                 seed_wall = r.real_ms("Step/Seed/" + s.name);
    std::printf("| %s | %.3g | %.5f | %d | %s | %s | %d | %s | %s | %s | %s | %s |\n",
                s.name.c_str(), a.error(a.e_plain), a.chebyshev_rho, a.chebyshev,
                cell(cheb, "%.3f").c_str(), cell(ratio(seed, cheb), "%.1fx").c_str(), a.anderson,
                cell(anderson, "%.3f").c_str(), cell(ratio(seed, anderson), "%.1fx").c_str(),
                cell(seed, "%.3f").c_str(), cell(cheb2, "%.3f").c_str(),
                cell(ratio(seed_wall, cheb2), "%.1fx").c_str());
  }

  std::printf(
      "\n## AVX2 + FMA against SSE2 (options.avx2), double, %d iterations, medians [ms]: the floor "
      "is the substitutions alone, the step also has the spring pass%s\n\n",
      kIterations,
      massspring::detail::cpu_has_avx2_fma() ? "" : " (this CPU has no AVX2 + FMA: both SSE2)");
  std::printf(
      "| scene | AVX2 floor | SSE2 floor | SSE2/AVX2 floor | AVX2 ms/step | SSE2 ms/step | "
      "SSE2/AVX2 step |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
  for (const Scene& s : scenes()) {
    const double af = t(s, "Floor", "Sparse"), nf = t(s, "Floor", "SparseSSE2"),
                 as = t(s, "Step", "Sparse"), ns = t(s, "Step", "SparseSSE2");
    if (af < 0 || nf < 0) continue;
    std::printf("| %s | %s | %s | %s | %s | %s | %s |\n", s.name.c_str(), cell(af, "%.4f").c_str(),
                cell(nf, "%.4f").c_str(), cell(ratio(nf, af), "%.2fx").c_str(),
                cell(as, "%.3f").c_str(), cell(ns, "%.3f").c_str(),
                cell(ratio(ns, as), "%.2fx").c_str());
  }

  std::printf("\n## float against double: exact pins, %d iterations, medians [ms]\n\n",
              kIterations);
  std::printf(
      "| scene | double ms/step | float ms/step | double/float | double floor | float floor | "
      "double it/floor | float it/floor |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Scene& s : scenes()) {
    const double d = t(s, "Step", "SparseExact"), f = t(s, "Step", "SparseFloat"),
                 df = t(s, "Floor", "SparseExact"), ff = t(s, "Floor", "SparseFloat");
    if (d < 0 && f < 0) continue;
    std::printf("| %s | %s | %s | %s | %s | %s | %s | %s |\n", s.name.c_str(),
                cell(d, "%.3f").c_str(), cell(f, "%.3f").c_str(),
                cell(ratio(d, f), "%.2fx").c_str(), cell(df, "%.4f").c_str(),
                cell(ff, "%.4f").c_str(), cell(ratio(d / kIterations, df), "%.2f").c_str(),
                cell(ratio(f / kIterations, ff), "%.2f").c_str());
  }

  std::printf(
      "\n## two threads against one: options.threads = 2 (OpenMP), plain step with %d "
      "iterations and the floor, medians of the wall clock [ms]\n\n",
      kIterations);
  std::printf(
      "| scene | points | nnz(L) | floor, 1 thread | floor, 2 threads | floor 1/2 | step, 1 thread "
      "| "
      "step, 2 threads | step 1/2 |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Scene& s : scenes()) {
    const auto real = [&](const char* what, const char* solver) {
      return r.real_ms(std::string(what) + "/" + solver + "/" + s.name);
    };
    const double f1 = real("Floor", "Threads1"), f2 = real("Floor", "Threads2"),
                 s1 = real("Step", "Threads1"), s2 = real("Step", "Threads2");
    if (f1 < 0 && s1 < 0) continue;
    massspring::FastMassSpring<SparseSystem> solver(options_for<double>(s));
    solver.precompute(*s.sparse, kDt);
    std::printf("| %s | %d | %ld | %s | %s | %s | %s | %s | %s |\n", s.name.c_str(),
                s.sparse->num_points(), long(solver.factor_nonzeros()), cell(f1, "%.4f").c_str(),
                cell(f2, "%.4f").c_str(), cell(ratio(f1, f2), "%.2fx").c_str(),
                cell(s1, "%.3f").c_str(), cell(s2, "%.3f").c_str(),
                cell(ratio(s1, s2), "%.2fx").c_str());
  }

  bool header = false;
  for (const Scene& s : scenes()) {
    if (!s.dense) continue;
    const double step = t(s, "Step", "Dense"), floor = t(s, "Floor", "Dense");
    if (step < 0 && floor < 0) continue;
    if (!header) {
      std::printf(
          "\n## Dense against Sparse (ours), medians [ms]; it/floor: ms per iteration / that "
          "storage's floor\n\n");
      std::printf(
          "| scene | points | Dense precompute | Sparse precompute | Dense step | Sparse step | "
          "Dense it/floor | Sparse it/floor |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
      header = true;
    }
    const double sparse_step = t(s, "Step", "Sparse");
    std::printf("| %s | %d | %s | %s | %s | %s | %s | %s |\n", s.name.c_str(),
                s.dense->num_points(), cell(t(s, "Precompute", "Dense"), "%.2f").c_str(),
                cell(t(s, "Precompute", "Sparse"), "%.2f").c_str(), cell(step, "%.3f").c_str(),
                cell(sparse_step, "%.3f").c_str(),
                cell(ratio(step / kIterations, floor), "%.2f").c_str(),
                cell(ratio(sparse_step / kIterations, t(s, "Floor", "Sparse")), "%.2f").c_str());
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
