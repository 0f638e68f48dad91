// Time to a given error: FastMassSpring with Chebyshev (Wang 2015) and Anderson (Peng et al. 2018)
// acceleration, each run for as many iterations as reach the step error of 50 plain iterations,
// against the reference solver's 50 (reference/seed/seed_reference.hpp) and our plain 50.
// Scenes: the curtain (gravity m g) and the JSON+OBJ scenes' skirt (9.8 N per point), settings as
// in support/scenes.hpp (dt = 1/30 s, penalty pins w = 1e10).
//
// Set-up, untimed: 10 plain steps from rest give the start state; from it, E(x_0), E after 50
// plain iterations, and E* (the lowest of 3000 Chebyshev and 3000 Anderson iterations) are
// computed; k is the fewest iterations (at most 50) whose E is at or below the plain 50's. The
// step error of k iterations is (E(x_k) - E*) / (E(x_0) - E*), E the implicit-Euler objective
// of DESIGN.md. Every timed step starts from the start state (reset untimed).
//
// Benchmarks (`Step/<solver>/<scene>`): Seed (the reference solver), Sparse (plain, 50
// iterations), Chebyshev and Anderson (k iterations each), ChebyshevThreads2 (Chebyshev with
// options.threads = 2, when built with OpenMP; read its real_time). Counters besides
// support/timing.hpp's: plain_error (the step error of 50 plain iterations) on every run, rho
// (Chebyshev's estimated spectral radius) on the Chebyshev runs.
//
//   bench_acceleration --benchmark_out=acceleration.json --benchmark_out_format=json
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "support/main.hpp"
#include "support/scenes.hpp"
#include "support/timing.hpp"

namespace {

using namespace massspring::bench;

constexpr int kWarmFrames = 10;  // plain steps before the step whose error is measured

struct Accelerated {
  Scene scene;
  std::shared_ptr<const SparseSystem> start;  // after kWarmFrames plain steps
  double e0 = 0, e_star = 0, e_plain = 0;     // E(x_0), converged E*, E after 50 plain iterations
  int chebyshev = -1, anderson = -1;          // iterations that reach e_plain (-1: not within 50)
  double rho = 0;
  [[nodiscard]] double error(double e) const { return (e - e_star) / (e0 - e_star); }
};

const auto kChebyshev = [](auto& o) { o.acceleration = massspring::Acceleration::Chebyshev; };
const auto kAnderson = [](auto& o) { o.acceleration = massspring::Acceleration::Anderson; };

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

// E after one step of `iterations` iterations from `start`; Chebyshev's rho into `rho`.
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

Accelerated measure(Scene scene) {
  Accelerated a;
  auto start = std::make_shared<SparseSystem>(*scene.sparse);
  {
    massspring::FastMassSpring<SparseSystem> solver(options_for<double>(scene));
    solver.precompute(*start, kDt);
    for (int frame = 0; frame < kWarmFrames; ++frame) solver.step(*start);
  }
  a.start = start;
  a.e0 = step_energy(scene, *start, start->positions());
  a.e_plain = energy_after(scene, *start, kIterations, kSeedLike);
  // E*: the lowest of long accelerated runs (each never increases E past its plain fallback).
  a.e_star = std::min(energy_after(scene, *start, 3000, kChebyshev),
                      energy_after(scene, *start, 3000, kAnderson));
  for (int k = 1; k <= kIterations && (a.chebyshev < 0 || a.anderson < 0); ++k) {
    if (a.chebyshev < 0 && energy_after(scene, *start, k, kChebyshev, &a.rho) <= a.e_plain)
      a.chebyshev = k;
    if (a.anderson < 0 && energy_after(scene, *start, k, kAnderson) <= a.e_plain) a.anderson = k;
  }
  a.scene = std::move(scene);
  return a;
}

std::vector<Accelerated>& scenes() {
  static std::vector<Accelerated> s;
  return s;
}

void register_benchmarks() {
  const auto how = repeated(3);
  for (const Accelerated& a : scenes()) {
    const Accelerated* ap = &a;
    const Scene& s = a.scene;
    const double plain_error = a.error(a.e_plain);
    const auto counters = [plain_error](benchmark::State& st) {
      st.counters["plain_error"] = plain_error;
    };
    add(how, "Step", "Seed", s, [ap, counters](benchmark::State& st) {
      bm_seed_step(st, ap->scene, *ap->start);
      counters(st);
    });
    add(how, "Step", "Sparse", s, [ap, counters](benchmark::State& st) {
      bm_step(st, ap->scene, *ap->scene.sparse, kSeedLike, ap->start.get());
      counters(st);
    });
#ifdef _OPENMP
    constexpr int kMostThreads = 2;
#else
    constexpr int kMostThreads = 1;
#endif
    for (int threads = 1; a.chebyshev > 0 && threads <= kMostThreads; ++threads) {
      const int k = a.chebyshev;
      add(how, "Step", threads == 1 ? "Chebyshev" : "ChebyshevThreads2", s,
          [ap, k, threads, counters](benchmark::State& st) {
            bm_step(
                st, ap->scene, *ap->scene.sparse,
                [k, threads](auto& o) {
                  kChebyshev(o);
                  o.iterations = k;
                  o.threads = threads;
                },
                ap->start.get());
            counters(st);
            st.counters["rho"] = ap->rho;
          });
    }
    if (a.anderson > 0) {
      const int k = a.anderson;
      add(how, "Step", "Anderson", s, [ap, k, counters](benchmark::State& st) {
        bm_step(
            st, ap->scene, *ap->scene.sparse,
            [k](auto& o) {
              kAnderson(o);
              o.iterations = k;
            },
            ap->start.get());
        counters(st);
      });
    }
    if (a.chebyshev < 0 || a.anderson < 0)
      std::fprintf(stderr, "note: %s: %s does not reach the error of 50 plain iterations in 50\n",
                   s.name.c_str(), a.chebyshev < 0 ? "Chebyshev" : "Anderson");
  }
}

}  // namespace

int main(int argc, char** argv) {
  return massspring::bench::run_benchmarks(
      argc, argv,
      [] {
        scenes().push_back(measure(curtain_scene()));
        for (Scene& s : jacobson_scene("skirt")) scenes().push_back(measure(std::move(s)));
      },
      register_benchmarks);
}
