// How FastMassSpring's cost grows with the cloth: grids N x N (make_cloth: quads with both
// diagonals, top corners pinned, k = 1000 N/m, Voronoi masses, gravity m g, exact pins, dt = 1/30).
//
// Per grid: the scene's build time [s], precompute time [s] (build Q, order, factorize), nnz(L),
// the factor's bytes [MiB], the time per local-global iteration [ms] (steps of `--iterations`
// iterations), the process's peak resident memory so far [MiB] (getrusage), whether every step
// was finite and, built with OpenMP, the time per iteration again with options.threads = 2, and
// the floor [ms]: one forward and one back substitution with the solver's own factor, one thread.
// Writes them as JSON (--out FILE; Google Benchmark's layout: "context", then "benchmarks" with
// one object per grid, named Scale/cloth<N>) and a line per grid on stdout.
//
//   bench_scale --out scale.json                         # the sweep 32, 64, 128, 256, 512
//   bench_scale --grid 1000 --frames 10 --out big.json   # one grid (1000 x 1000: a million points)
//
// Times are the calling thread's CPU time (one thread's work, without the time other processes
// held the core), except the two-thread iteration (wall clock: the calling thread's CPU time
// leaves the other out). Each is the median over the frames: at least `--frames` of them and at
// least `--min-time` seconds of them, so that the small grids (a step of 32 x 32 takes half a
// millisecond) are timed over a thousand steps, not five. This is a plain program, not Google
// Benchmark, because one 1000 x 1000 precompute takes tens of seconds and the peak memory is the
// process's.
#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <massspring/forces/gravity.hpp>
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

// CPU time of the calling thread [s]: one thread's work without the time other processes held
// the core.
double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// One grid's figures (see the header).
struct Row {
  int grid = 0, points = 0, springs = 0;
  double scene_s = 0, precompute_s = 0, nnz_l = 0, factor_mib = 0, it_ms = 0, it_threads2_ms = -1,
         floor_ms = 0, peak_rss_mib = 0;
  bool finite = true;
};

double peak_rss_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

Row run(int n, int frames, double min_time, int iterations) {
  const double t_scene = thread_cpu_s();
  massspring::ClothOptions o;
  o.columns = o.rows = n;
  o.shear = massspring::ClothShear::Both;
  o.pins = massspring::ClothPins::TopCorners;
  o.stiffness = 1000;
  System system = massspring::make_system<System>(massspring::make_cloth(o));
  system.add_force(massspring::Gravity<double>(massspring::Vector3<double>(0, -9.8, 0)));
  const double scene_s = thread_cpu_s() - t_scene;

  massspring::FastMassSpring<System> solver;  // plain iterations from the current positions
  solver.options = massspring::FastMassSpringOptions<double>::reference();
  solver.options.iterations = iterations;
  const double t_pre = thread_cpu_s();
  solver.precompute(system, 1.0 / 30);
  const double precompute_s = thread_cpu_s() - t_pre;

  bool finite = true;
  // Median ms per iteration over the frames: the thread's CPU time (one thread) or the wall clock
  // (two threads: the calling thread's CPU time leaves the other out).
  const auto time_frames = [&](bool wall) {
    std::vector<double> per_iteration;
    const auto start = Clock::now();
    for (int frame = 0; frame < frames || seconds_since(start) < min_time; ++frame) {
      const auto w0 = Clock::now();
      const double c0 = thread_cpu_s();
      const massspring::StepReport r = solver.step(system);
      const double seconds = wall ? seconds_since(w0) : thread_cpu_s() - c0;
      per_iteration.push_back(seconds / std::max(r.iterations, 1));
      finite = finite && r.ok();
    }
    std::sort(per_iteration.begin(), per_iteration.end());
    return per_iteration[per_iteration.size() / 2] * 1e3;
  };
  const double it_ms = time_frames(false);
  // The floor: one forward and one back substitution with the solver's own factor (one thread,
  // as the frames above left it), n x 3, median ms (CPU) over as many as the frames'
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
      const double t0 = thread_cpu_s();
      solver.factorization().solve_in_place(x.data());
      per_solve.push_back(thread_cpu_s() - t0);
    }
    std::sort(per_solve.begin(), per_solve.end());
    floor_ms = per_solve[per_solve.size() / 2] * 1e3;
  }
  double it2_ms = -1;  // -1: not built with OpenMP
#ifdef _OPENMP
  solver.options.threads = 2;
  it2_ms = time_frames(true);
#endif
  Row r;
  r.grid = n;
  r.points = system.num_points();
  r.springs = system.num_springs();
  r.scene_s = scene_s;
  r.precompute_s = precompute_s;
  r.nnz_l = double(solver.factor_nonzeros());
  r.factor_mib = double(solver.factorization().factor_bytes()) / (1024.0 * 1024.0);
  r.it_ms = it_ms;
  r.it_threads2_ms = it2_ms;
  r.floor_ms = floor_ms;
  r.peak_rss_mib = peak_rss_mib();
  r.finite = finite;
  std::printf(
      "cloth%d: %d points, precompute %.3f s, nnz(L) %.0f, %.4f ms/iteration (2 threads: %.4f), "
      "floor %.4f ms, peak RSS %.1f MiB%s\n",
      n, r.points, r.precompute_s, r.nnz_l, r.it_ms, r.it_threads2_ms, r.floor_ms, r.peak_rss_mib,
      finite ? "" : ", NOT FINITE");
  std::fflush(stdout);
  return r;
}

// The rows as JSON in Google Benchmark's layout (numbers only, names without quotes to escape).
bool write_json(const char* path, const std::vector<Row>& rows, int frames, double min_time,
                int iterations) {
  std::FILE* f = std::fopen(path, "w");
  if (!f) return false;
  std::fprintf(f,
               "{\n  \"context\": {\"program\": \"bench_scale\", \"frames\": %d, "
               "\"min_time_s\": %g, \"iterations\": %d, \"time_unit\": \"ms\"},\n"
               "  \"benchmarks\": [\n",
               frames, min_time, iterations);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const Row& r = rows[k];
    std::fprintf(f,
                 "    {\"name\": \"Scale/cloth%d\", \"grid\": %d, \"points\": %d, "
                 "\"springs\": %d, \"scene_s\": %.6g, \"precompute_s\": %.6g, "
                 "\"nnz_L\": %.0f, \"factor_mib\": %.6g, \"iteration_ms\": %.6g, "
                 "\"iteration_threads2_ms\": %.6g, \"floor_ms\": %.6g, "
                 "\"peak_rss_mib\": %.6g, \"finite\": %s}%s\n",
                 r.grid, r.grid, r.points, r.springs, r.scene_s, r.precompute_s, r.nnz_l,
                 r.factor_mib, r.it_ms, r.it_threads2_ms, r.floor_ms, r.peak_rss_mib,
                 r.finite ? "true" : "false", k + 1 < rows.size() ? "," : "");
  }
  std::fprintf(f, "  ]\n}\n");
  return std::fclose(f) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> grids = {32, 64, 128, 256, 512};
  int frames = 5, iterations = 10;
  double min_time = 1.0;
  const char* out = nullptr;
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
    } else if (arg == "--out" && a + 1 < argc) {
      out = argv[++a];
    } else {
      std::fprintf(stderr,
                   "usage: bench_scale [--grid N] [--frames F (5)] [--min-time S (1.0)] "
                   "[--iterations K (10)] [--out FILE.json]\n");
      return 2;
    }
  }
  std::vector<Row> rows;
  for (const int n : grids) rows.push_back(run(n, frames, min_time, iterations));
  if (out && !write_json(out, rows, frames, min_time, iterations)) {
    std::fprintf(stderr, "bench_scale: cannot write %s\n", out);
    return 1;
  }
  return 0;
}
