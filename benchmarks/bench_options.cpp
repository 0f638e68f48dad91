// What FastMassSpring's choices cost, each against the default in the same run: the SIMD code
// off (options.simd = false), exact pins instead of penalty pins, float instead of double (exact
// pins: penalty pins of 1e10 need double), AMD's order instead of the one FillOrdering::Auto
// picks, and Dense storage instead of Sparse (cloth32 only: Dense's Q is n x n, its factorization
// grows as n^3). Scenes and settings: support/scenes.hpp (cloth32, cloth64, cloth128, curtain,
// flag, skirt; dt = 1/30 s, 50 iterations per step).
//
// Benchmarks (`<what>/<solver>/<scene>`, what = Step | Floor, Precompute for Sparse and Dense):
//   Sparse        the default: double, penalty pins, SIMD where the CPU has AVX2 + FMA
//   SparseNoSimd  options.simd = false (the baseline code paths, no AVX2 + FMA)
//   SparseExact   options.pins = PinMode::Exact
//   SparseFloat   float, exact pins
//   SparseAMD     options.ordering = FillOrdering::Solver (Eigen's AMD)
//   Dense         Dense storage (Eigen::LLT), penalty pins
// Counters: support/timing.hpp's; `simd` on every run is 1 when the CPU takes the SIMD path.
//
//   build/benchmarks/bench_options --benchmark_out=options.json --benchmark_out_format=json
#include <benchmark/benchmark.h>

#include <massspring/detail/simd.hpp>
#include <vector>

#include "support/main.hpp"
#include "support/scenes.hpp"
#include "support/timing.hpp"

namespace {

using namespace massspring::bench;

const auto kNoSimd = [](auto& o) { o.simd = false; };
const auto kExact = [](auto& o) { o.pins = massspring::PinMode::Exact; };
const auto kAmdOrder = [](auto& o) { o.ordering = massspring::FillOrdering::Solver; };

std::vector<Scene>& scenes() {
  static std::vector<Scene> s;
  return s;
}

// Step and Floor of one variant: `proto` in `scene`, options changed by `adjust`. Five
// repetitions: every ratio divides by the default's one median.
template <class System, class Adjust>
void add_variant(const Scene& scene, const char* solver, const System* proto, Adjust adjust) {
  const auto how = repeated(5);
  const Scene* sc = &scene;
  const double simd = massspring::detail::cpu_has_avx2_fma() ? 1 : 0;
  add(how, "Step", solver, scene, [sc, proto, adjust, simd](benchmark::State& st) {
    bm_step(st, *sc, *proto, adjust);
    st.counters["simd"] = simd;
  });
  add(how, "Floor", solver, scene, [sc, proto, adjust, simd](benchmark::State& st) {
    bm_floor(st, *sc, *proto, adjust);
    st.counters["simd"] = simd;
  });
}

void register_benchmarks() {
  for (const Scene& s : scenes()) {
    const Scene* sc = &s;
    add(once, "Precompute", "Sparse", s,
        [sc](benchmark::State& st) { bm_precompute(st, *sc, *sc->sparse); });
    if (s.dense)
      add(once, "Precompute", "Dense", s,
          [sc](benchmark::State& st) { bm_precompute(st, *sc, *sc->dense); });
    add_variant(s, "Sparse", s.sparse.get(), kSeedLike);
    add_variant(s, "SparseNoSimd", s.sparse.get(), kNoSimd);
    add_variant(s, "SparseExact", s.sparse.get(), kExact);
    if (s.single) add_variant(s, "SparseFloat", s.single.get(), kExact);
    add_variant(s, "SparseAMD", s.sparse.get(), kAmdOrder);
    if (s.dense) add_variant(s, "Dense", s.dense.get(), kSeedLike);
  }
}

}  // namespace

int main(int argc, char** argv) {
  return massspring::bench::run_benchmarks(
      argc, argv,
      [] {
        Build build;
        build.single = true;
        scenes() = standard_scenes(build);
        scenes().front() = cloth_scene(32, Build{true, true});  // Dense on the smallest grid only
      },
      register_benchmarks);
}
