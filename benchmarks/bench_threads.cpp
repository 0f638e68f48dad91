// Two threads against one: FastMassSpring with options.threads = 2 (the two substitutions split
// along the factor's elimination tree, OpenMP; the spring pass stays on one thread) against 1, the
// floor and the plain step of 50 iterations, on cloth8 .. cloth128 (where the crossover lies), the
// curtain, flag and skirt. Settings as in support/scenes.hpp (dt = 1/30 s, penalty pins).
//
// Benchmarks (`<what>/<solver>/<scene>`, what = Floor | Step, solver = Threads1 | Threads2;
// Threads2 only when built with OpenMP). Read real_time: the CPU time counts the calling thread
// only. Counters: support/timing.hpp's.
//
//   build/benchmarks/bench_threads --benchmark_out=threads.json --benchmark_out_format=json
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "support/main.hpp"
#include "support/scenes.hpp"
#include "support/timing.hpp"

namespace {

using namespace massspring::bench;

std::vector<Scene>& scenes() {
  static std::vector<Scene> s;
  return s;
}

void register_benchmarks() {
  const auto how = repeated(3);
  for (const Scene& s : scenes()) {
    const Scene* sc = &s;
#ifdef _OPENMP
    constexpr int kMostThreads = 2;
#else
    constexpr int kMostThreads = 1;
#endif
    for (int threads = 1; threads <= kMostThreads; ++threads) {
      const auto adjust = [threads](auto& o) { o.threads = threads; };
      const std::string solver = "Threads" + std::to_string(threads);
      add(how, "Floor", solver, s,
          [sc, adjust](benchmark::State& st) { bm_floor(st, *sc, *sc->sparse, adjust); });
      add(how, "Step", solver, s,
          [sc, adjust](benchmark::State& st) { bm_step(st, *sc, *sc->sparse, adjust); });
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  return massspring::bench::run_benchmarks(
      argc, argv,
      [] {
        for (const int n : {8, 16}) scenes().push_back(cloth_scene(n));
        for (Scene& s : standard_scenes()) scenes().push_back(std::move(s));
      },
      register_benchmarks);
}
