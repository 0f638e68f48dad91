// How FastMassSpring's cost grows with the cloth: grids N x N (make_cloth: quads with both
// diagonals, top corners pinned, k = 1000 N/m, Voronoi masses, gravity m g, exact pins, dt = 1/30).
//
// Per grid: precompute time (build Q, order, factorise), nnz(L), the factor's bytes, time per
// local-global iteration (steps of `--iterations` iterations), that time / (n log2 n), and the
// process's peak resident memory so far (getrusage), and, built with OpenMP, the time per
// iteration again with options.threads = 2 (the substitutions on two threads), and the floor: one
// forward and one back substitution with the solver's own factor, one thread, and that time /
// (n log2 n). Prints a Markdown table.
//
//   bench_scale                          # the sweep 32, 64, 128, 256, 512
//   bench_scale --grid 1000 --frames 10  # one grid (1000 x 1000: a million points)
//
// Timing is wall clock (std::chrono::steady_clock), the median over the frames: at least
// `--frames` of them and at least `--min-time` seconds of them, so that the small grids (a step of
// 32 x 32 takes half a millisecond) are timed over a thousand steps, not five, and a burst of
// outside load cannot move their median. This is a plain program, not Google Benchmark, because
// one 1000 x 1000 precompute takes tens of seconds.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <massspring/storage/storage.hpp>
#include <massspring/system/mass_spring_system.hpp>
#include <string>
#include <vector>

namespace {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double peak_rss_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

void run(int n, int frames, double min_time, int iterations) {
  const auto t_scene = Clock::now();
  massspring::ClothOptions o;
  o.columns = o.rows = n;
  o.shear = massspring::ClothShear::Both;
  o.pins = massspring::ClothPins::TopCorners;
  o.stiffness = 1000;
  System system = massspring::make_system<System>(massspring::make_cloth(o));
  const double scene_s = seconds_since(t_scene);

  massspring::FastMassSpring<System> solver;
  solver.options.gravity = {0, -9.8, 0};
  solver.options.iterations = iterations;
  const auto t_pre = Clock::now();
  solver.precompute(system, 1.0 / 30);
  const double precompute_s = seconds_since(t_pre);

  bool finite = true;
  // Median wall-clock ms per iteration over the frames.
  const auto time_frames = [&] {
    std::vector<double> per_iteration;
    const auto start = Clock::now();
    for (int frame = 0; frame < frames || seconds_since(start) < min_time; ++frame) {
      const auto t0 = Clock::now();
      const massspring::StepReport r = solver.step(system);
      per_iteration.push_back(seconds_since(t0) / std::max(r.iterations, 1));
      finite = finite && r.ok();
    }
    std::sort(per_iteration.begin(), per_iteration.end());
    return per_iteration[per_iteration.size() / 2] * 1e3;
  };
  const double it_ms = time_frames();
  // The floor: one forward and one back substitution with the solver's own factor (one thread,
  // as the frames above left it), n x 3, median wall-clock ms over as many as the frames'
  // iterations and at least min_time seconds.
  double floor_ms = 0;
  {
    const Eigen::Index rows = solver.system_matrix().rows();
    const massspring::Points<double> start = massspring::Points<double>::Random(rows, 3);
    massspring::Points<double> x = start;
    std::vector<double> per_solve;
    const auto t_start = Clock::now();
    for (int k = 0; k < frames * iterations || seconds_since(t_start) < min_time; ++k) {
      if (k % iterations == 0) x = start;  // as many solves in a row as a step's iterations
      const auto t0 = Clock::now();
      solver.factorization().solve_in_place(x.data());
      per_solve.push_back(seconds_since(t0));
    }
    std::sort(per_solve.begin(), per_solve.end());
    floor_ms = per_solve[per_solve.size() / 2] * 1e3;
  }
  std::string two_threads = "- | -";
#ifdef _OPENMP
  solver.options.threads = 2;
  const double it2_ms = time_frames();
  two_threads = std::to_string(it2_ms).substr(0, 8) + " | " +
                std::to_string(it_ms / it2_ms).substr(0, 4) + "x";
#endif
  const double points = double(system.num_points());
  const double nlogn = points * std::log2(points);
  std::printf(
      "| %d | %d | %d | %.3f | %.3f | %ld | %.1f | %.4f | %.3f | %.1f | %s | %s | %.4f | %.3f |\n",
      n, system.num_points(), system.num_springs(), scene_s, precompute_s,
      long(solver.factor_nonzeros()),
      double(solver.factorization().factor_bytes()) / (1024.0 * 1024.0), it_ms, it_ms * 1e6 / nlogn,
      peak_rss_mib(), finite ? "yes" : "NO", two_threads.c_str(), floor_ms, floor_ms * 1e6 / nlogn);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> grids = {32, 64, 128, 256, 512};
  int frames = 5, iterations = 10;
  double min_time = 1.0;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--grid" && a + 1 < argc) {
      grids = {std::atoi(argv[++a])};
    } else if (arg == "--frames" && a + 1 < argc) {
      frames = std::atoi(argv[++a]);
    } else if (arg == "--min-time" && a + 1 < argc) {
      min_time = std::atof(argv[++a]);
    } else if (arg == "--iterations" && a + 1 < argc) {
      iterations = std::atoi(argv[++a]);
    } else {
      std::fprintf(stderr,
                   "usage: bench_scale [--grid N] [--frames F (5)] [--min-time S (1.0)] "
                   "[--iterations K (10)]\n");
      return 2;
    }
  }
  std::printf(
      "| grid | points | springs | scene s | precompute s | nnz(L) | factor MiB | ms/iteration | "
      "ns/iteration / (n log2 n) | peak RSS MiB | finite | ms/iteration, 2 threads | 1 thread / "
      "2 | floor ms | floor ns / (n log2 n) |\n"
      "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|\n");
  for (const int n : grids) run(n, frames, min_time, iterations);
  return 0;
}
