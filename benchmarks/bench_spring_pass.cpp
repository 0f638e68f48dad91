// integrators/local_global/spring_pass.hpp and share_pass.hpp: does the SIMD share pass earn its
// place? Its rule (docs/performance.md): kept only while a step of flag, skirt and curtain takes
// at least 5% less time with it, in the same run.
//
// - Step/<scene>/share and Step/<scene>/baseline: one FastMassSpring step (50 plain iterations,
//   penalty pins, the assignment's (0, -9.8, 0) N per point) with options.simd on and off, both
//   with the SIMD substitution (a Cholesky that keeps it whatever the option says): the two differ
//   only in the spring pass, and in where the right-hand side is assembled (inside the forward
//   substitution for the share pass).
// - Pass/<scene>/share and Pass/<scene>/baseline: the pass alone at the rest positions, the share
//   pass followed by the explicit assembly of every row (as Dense storage does).
// Scenes: the curtain (Liu et al. 2013: 81 x 81 points, 32158 springs, generated), and the
// assignment's flag and skirt when ../shared/scenes/jacobson is there.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/io/load_scene.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <massspring/scene/recipes.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;

// SparseCholesky with the SIMD substitution whatever FastMassSpring's options.simd asks for.
class WideCholesky : public massspring::SparseCholesky<double> {
 public:
  void set_avx2(bool /*allowed*/) { massspring::SparseCholesky<double>::set_avx2(true); }
};

struct Scene {
  std::string name;
  std::shared_ptr<const System> system;
};

std::vector<Scene> load_scenes() {
  std::vector<Scene> scenes;
  scenes.push_back({"curtain", std::make_shared<System>(massspring::make_system<System>(
                                   massspring::make_cloth(massspring::curtain_recipe())))});
  const std::filesystem::path jacobson =
      std::filesystem::path(MASSSPRING_BENCH_SHARED_DIR) / "scenes" / "jacobson";
  for (const char* name : {"flag", "skirt"}) {
    const std::filesystem::path file = jacobson / (std::string(name) + ".json");
    if (!std::filesystem::exists(file)) {
      std::fprintf(stderr, "note: %s not found; its benchmarks are not registered\n",
                   file.string().c_str());
      continue;
    }
    scenes.push_back({name, std::make_shared<System>(massspring::io::load_scene<System>(file))});
  }
  return scenes;
}

void step(benchmark::State& state, const Scene& scene, bool simd) {
  System system = *scene.system;
  massspring::FastMassSpring<System, WideCholesky> solver;
  solver.options.iterations = 50;
  solver.options.pins = massspring::PinMode::Penalty;
  system.add_force(massspring::ConstantForce<double>({0, -9.8, 0}));
  solver.options.simd = simd;
  solver.precompute(system, 1.0 / 30);
  const System start = system;
  for (auto _ : state) {
    state.PauseTiming();
    system.positions() = start.positions();
    system.velocities() = start.velocities();
    state.ResumeTiming();
    benchmark::DoNotOptimize(solver.step(system));
  }
  state.counters["springs"] = system.num_springs();
}

// Pair/<scene>: the two steps above alternated inside one loop (which goes first alternates too),
// each timed on its own; the counter share_over_baseline is the median of the per-pair ratios,
// which a machine whose speed drifts between repetitions moves much less than two medians.
void pair(benchmark::State& state, const Scene& scene) {
  struct Arm {
    explicit Arm(const System& s) : system(s) {}
    System system;
    massspring::FastMassSpring<System, WideCholesky> solver;
  };
  const auto make = [&scene](bool simd) {
    auto arm = std::make_unique<Arm>(*scene.system);
    arm->solver.options.iterations = 50;
    arm->solver.options.pins = massspring::PinMode::Penalty;
    arm->system.add_force(massspring::ConstantForce<double>({0, -9.8, 0}));
    arm->solver.options.simd = simd;
    arm->solver.precompute(arm->system, 1.0 / 30);
    return arm;
  };
  const std::unique_ptr<Arm> share = make(true), baseline = make(false);
  const System start = share->system;
  const auto timed = [&start](Arm& arm) {
    arm.system.positions() = start.positions();
    arm.system.velocities() = start.velocities();
    const auto t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(arm.solver.step(arm.system));
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  std::vector<double> ratios, share_s, baseline_s;
  bool share_first = true;
  for (auto _ : state) {
    double a = 0, b = 0;
    if (share_first) {
      a = timed(*share);
      b = timed(*baseline);
    } else {
      b = timed(*baseline);
      a = timed(*share);
    }
    share_first = !share_first;
    state.SetIterationTime(a + b);
    ratios.push_back(a / b);
    share_s.push_back(a);
    baseline_s.push_back(b);
  }
  const auto median = [](std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  state.counters["share_over_baseline"] = median(ratios);
  state.counters["share_ms"] = 1e3 * median(share_s);
  state.counters["baseline_ms"] = 1e3 * median(baseline_s);
}

void pass(benchmark::State& state, const Scene& scene, bool simd) {
  const System& system = *scene.system;
  const int n = system.num_points();
  std::vector<int> row(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) row[static_cast<std::size_t>(i)] = i;
  massspring::local_global::PackedSprings<double> springs;
  springs.build(system, row, n);
  springs.set_rest_lengths(system.rest_lengths());
  massspring::local_global::SharePass shares;
  shares.build(springs, n);
  if (simd && !massspring::local_global::SharePass::available()) {
    state.SkipWithError("no AVX2 + FMA on this CPU");
    return;
  }
  massspring::Vector<double> x(3 * n + 1), w(3 * n), base = massspring::Vector<double>::Zero(3 * n);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) x(3 * i + c) = system.positions()(i, c);
  x(3 * n) = 0;
  for (auto _ : state) {
#ifdef MASSSPRING_HAVE_AVX2_PATH
    if (simd) {
      shares.run<false>(x.data(), springs);
      const auto rows = shares.rows(base.data());
      for (int r = 0; r < n; ++r) rows.row(r, w.data() + 3 * r);
      benchmark::DoNotOptimize(w.data());
      continue;
    }
#endif
    w.setZero();
    springs.pass<true, false>(x.data(), w.data(), n);
    benchmark::DoNotOptimize(w.data());
  }
}

}  // namespace

int main(int argc, char** argv) {
  static const std::vector<Scene> scenes = load_scenes();
  for (const Scene& scene : scenes)
    benchmark::RegisterBenchmark(("Pair/" + scene.name).c_str(),
                                 [&scene](benchmark::State& s) { pair(s, scene); })
        ->Unit(benchmark::kMillisecond)
        ->UseManualTime()
        ->Iterations(100);
  for (const Scene& scene : scenes)
    for (const bool simd : {true, false}) {
      const std::string kind = simd ? "share" : "baseline";
      benchmark::RegisterBenchmark(("Step/" + scene.name + "/" + kind).c_str(),
                                   [&scene, simd](benchmark::State& s) { step(s, scene, simd); })
          ->Unit(benchmark::kMillisecond)
          ->Repetitions(5)
          ->ReportAggregatesOnly(true);
      benchmark::RegisterBenchmark(("Pass/" + scene.name + "/" + kind).c_str(),
                                   [&scene, simd](benchmark::State& s) { pass(s, scene, simd); })
          ->Unit(benchmark::kMicrosecond)
          ->Repetitions(5)
          ->ReportAggregatesOnly(true);
    }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
