#pragma once
// The main() of the local-global benchmark programs: Google Benchmark's flags, then the scenes
// (an exception while loading them is reported as "error: ..." with exit code 1, before anything
// runs), then the registrations and the run.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <exception>

namespace massspring::bench {

/// @brief Parses Google Benchmark's flags (an unknown one: exit code 1), calls `load()` then
/// `register_all()`, and runs the benchmarks the flags select. Returns main()'s exit code.
template <class Load, class Register>
int run_benchmarks(int argc, char** argv, Load load, Register register_all) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  try {
    load();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace massspring::bench
