// Stability stress suite (docs/stability.md): every integrator over stiffness x time step, on a
// chain and a small cloth, each run stepped through a DivergenceGuard for a fixed simulated time.
//
//   stability                 # the full suite: k = 1e0..1e8 N/m, 10 simulated seconds per run
//   stability --quick         # smoke test: k = 1e0 and 1e8 N/m, 1 simulated second
//   stability --out DIR       # where the CSV files go (default out/stability)
//
// Scenes (both with gravity 9.81 m/s^2 as a Gravity term, total mass 1 kg, no damping):
//   chain: 20 points on a 1 m horizontal line along +x, point 0 pinned: it falls and swings.
//   cloth: 8 x 8 points, 1 m x 1 m, both diagonals per cell, lying horizontally (x-z plane), the
//          two corners of row 0 pinned: it falls, swings and folds.
// Integrators: ForwardEuler, SymplecticEuler, RK4, BackwardEuler (Linearized and Newton, default
// options), FastMassSpring (local-global, default options: 50 iterations, exact pins).
// Time steps: 1e-4, 1e-3, 1e-2, 1/30 s; and, per (scene, k) and explicit method, 1, 0.75 and 0.5
// times stability_limit(system, method), the edge of the linearised stability at the initial state
// (ForwardEuler is skipped there: without damping its limit is 0).
//
// Outcome of a run (see classify()):
//   diverged  a step was not finite, or its total energy passed the guard's limit E(0) + 100 S
//             (S = DivergenceGuard::scale()); the run stops there and the step and time are kept.
//   growing   the run finished, but the total energy averaged over its last 10% (which averages
//             out oscillation) is above E(0) by more than 5% of W = max(M |g| D, K_max): the
//             potential energy gravity releases when the scene (mass M) drops by its initial
//             bounding-box diagonal D, or the largest kinetic energy of the run if that is larger.
//             The exact motion keeps E(t) = E(0): the gain is the integrator's doing.
//   stable    otherwise (energy kept, or lost: implicit methods dissipate).
//
// The library's stable_time_step(system, method) is 0.5 x stability_limit (its default safety).
// "At or below stable_time_step" (the summary line and the exit code) covers the runs at 0.5 x the
// limit and every grid cell whose dt is at or below it; the runs at 1 and 0.75 x the limit show
// how much margin the factor leaves.
//
// Deformation, per run over its accepted steps: stretch_min / stretch_max, the extreme spring
// lengths l / l0; limit_ratio_min, the smallest stability_limit(system, SymplecticEuler) of the
// visited states (about 200 sampled per run) over that at the initial state. The wall time includes
// this bookkeeping.
//
// Output in DIR: results.csv (one row per run), traces.csv (per run, the total energy averaged
// over 50 equal blocks of the planned run), meta.csv (settings and the total wall time).
// Progress (done/total, elapsed, ETA) goes to stderr. Exit code 1 when some explicit run at or
// below stable_time_step() is not stable, 2 on bad arguments.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <massspring/integrators/with_integrator.hpp>
#include <massspring/massspring.hpp>
#include <string>
#include <type_traits>
#include <vector>

#include "progress.hpp"

namespace {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using Clock = std::chrono::steady_clock;

constexpr double kGravity = 9.81;                     // m/s^2
constexpr int kBlocks = 50;                           // energy trace resolution per run
constexpr long kLimitSamples = 200;                   // stability_limit samples per run
constexpr double kGrowth = 0.05;                      // "growing": gain above 5% of W
constexpr double kBoundFactors[] = {1.0, 0.75, 0.5};  // runs at factor x stability_limit
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using Method = massspring::IntegratorKind;
// In the order of the results (plot_stability.py reads them by label).
constexpr Method kMethods[] = {Method::ForwardEuler,  Method::SymplecticEuler,
                               Method::RK4,           Method::LinearizedBackwardEuler,
                               Method::BackwardEuler, Method::FastMassSpring};

// The label in the results: ForwardEuler, ..., BackwardEuler-Newton, LocalGlobal.
const char* name(Method m) { return massspring::to_string(m, massspring::IntegratorNaming::Label); }

bool is_explicit(Method m) {
  return m == Method::ForwardEuler || m == Method::SymplecticEuler || m == Method::RK4;
}

massspring::ExplicitMethod explicit_method(Method m) {
  switch (m) {
    case Method::ForwardEuler:
      return massspring::ExplicitMethod::ForwardEuler;
    case Method::RK4:
      return massspring::ExplicitMethod::RK4;
    default:
      return massspring::ExplicitMethod::SymplecticEuler;
  }
}

// Rough cost of one step per point, relative to a SymplecticEuler step (measured on the 8 x 8
// cloth): only for the ETA.
double cost_weight(Method m) {
  switch (m) {
    case Method::ForwardEuler:
    case Method::SymplecticEuler:
      return 1;
    case Method::RK4:
      return 3;
    case Method::LinearizedBackwardEuler:
      return 40;
    case Method::BackwardEuler:
      return 80;
    case Method::FastMassSpring:
      return 45;
  }
  return 1;
}

struct SceneSpec {
  std::string name;
  int size;  // chain: points; cloth: points per side
  [[nodiscard]] int points() const { return name == "chain" ? size : size * size; }
};

System make_scene(const SceneSpec& spec, double k) {
  massspring::SceneDescription<double> desc;
  if (spec.name == "chain") {
    massspring::ChainOptions o = massspring::chain_recipe();
    o.points = spec.size;
    o.pins = massspring::ChainPins::First;
    o.stiffness = k;
    o.mass = 1.0 / spec.size;
    desc = massspring::make_chain(o);
  } else {
    massspring::ClothOptions o = massspring::hanging_cloth_recipe(spec.size);
    o.plane = massspring::ClothPlane::Horizontal;
    o.stiffness = k;
    o.mass = 1.0 / (spec.size * spec.size);
    desc = massspring::make_cloth(o);
  }
  System system = massspring::make_system<System>(desc);
  system.add_force(massspring::Gravity<double>({0, -kGravity, 0}));
  return system;
}

struct Run {
  long planned = 0, done = 0;
  bool failed = false;
  std::string reason;  // "non-finite", "energy blow-up", or an exception's message
  long fail_step = -1;
  double fail_time = kNaN;
  double e0 = kNaN, scale = kNaN, w = kNaN, e_end = kNaN, e_tail = kNaN, e_max = kNaN,
         ke_max = kNaN, gain = kNaN;
  std::vector<double> blocks = std::vector<double>(kBlocks, kNaN);  // mean E per block
  double wall = 0;
  long unconverged = 0;  // BackwardEuler-Newton: steps that stopped at iterations
  long indefinite = 0;   // BackwardEuler: steps whose solve was not a Cholesky one
  // Deformation over the accepted steps: the extreme spring lengths l / l0 (every step), and the
  // smallest stability_limit (symplectic Euler) of the states visited over that at the initial
  // state (sampled at about kLimitSamples evenly spaced steps).
  double stretch_min = kNaN, stretch_max = kNaN, limit_ratio_min = kNaN;
  std::string outcome;
  std::string rule;  // what decided the outcome
};

// Updates run.stretch_min/max from the current spring lengths and, when limit0 is a number,
// run.limit_ratio_min from stability_limit at the current state.
void track_deformation(const System& system, double limit0, Run& run) {
  const auto& x = system.positions();
  const auto& springs = system.springs();
  const auto& rest = system.rest_lengths();
  for (int e = 0; e < system.num_springs(); ++e) {
    const double r = (x.row(springs(e, 0)) - x.row(springs(e, 1))).norm() / rest(e);
    run.stretch_min = std::isnan(run.stretch_min) ? r : std::min(run.stretch_min, r);
    run.stretch_max = std::isnan(run.stretch_max) ? r : std::max(run.stretch_max, r);
  }
  if (std::isnan(limit0) || !std::isfinite(limit0) || limit0 <= 0) return;
  const double ratio =
      massspring::stability_limit(system, massspring::ExplicitMethod::SymplecticEuler) / limit0;
  run.limit_ratio_min =
      std::isnan(run.limit_ratio_min) ? ratio : std::min(run.limit_ratio_min, ratio);
}

template <class Integrator>
void simulate(System system, Integrator& integrator, double dt, long steps, Run& run) {
  const auto t0 = Clock::now();
  run.planned = steps;
  std::vector<double> sum(kBlocks, 0.0);
  std::vector<long> count(kBlocks, 0);
  const long tail_start = steps - std::max(1L, steps / 10);  // the last 10% of the steps
  double tail_sum = 0;
  long tail_count = 0;
  try {
    const auto& x = system.positions();
    const double diagonal = (x.colwise().maxCoeff() - x.colwise().minCoeff()).norm();
    const double motion = system.masses().sum() * kGravity * diagonal;  // M |g| D
    integrator.precompute(system, dt);
    massspring::DivergenceGuard<System> guard(system);
    run.e0 = run.e_max = run.e_end = guard.initial_energy();
    run.scale = guard.scale();
    run.ke_max = double(massspring::kinetic_energy(system));
    const double limit0 =
        massspring::stability_limit(system, massspring::ExplicitMethod::SymplecticEuler);
    const long limit_every = std::max(1L, steps / kLimitSamples);
    for (long s = 1; s <= steps; ++s) {
      const massspring::StepReport r = guard.step(integrator, system);
      if constexpr (std::is_same_v<Integrator, massspring::BackwardEuler<System>>) {
        if (integrator.last_solver_path() != massspring::LinearSolverPath::Cholesky)
          ++run.indefinite;
        if (integrator.options.mode == massspring::BackwardEulerMode::Newton && !r.converged)
          ++run.unconverged;
      }
      if (!r.ok()) {
        run.failed = true;
        run.reason = r.blew_up && r.finite ? "energy blow-up" : "non-finite";
        run.fail_step = s;
        run.fail_time = double(s) * dt;
        break;
      }
      run.done = s;
      const double e = guard.energy();
      run.e_end = e;
      run.e_max = std::max(run.e_max, e);
      run.ke_max = std::max(run.ke_max, double(massspring::kinetic_energy(system)));
      track_deformation(system, s % limit_every == 0 ? limit0 : kNaN, run);
      const auto b = std::size_t((s - 1) * kBlocks / steps);
      sum[b] += e;
      ++count[b];
      if (s > tail_start) {
        tail_sum += e;
        ++tail_count;
      }
    }
    run.w = std::max(motion, run.ke_max);
    if (tail_count > 0) {
      run.e_tail = tail_sum / double(tail_count);
      run.gain = (run.e_tail - run.e0) / run.w;
    }
  } catch (const std::exception& error) {
    run.failed = true;
    run.reason = error.what();
    run.fail_step = run.done + 1;
    run.fail_time = double(run.done + 1) * dt;
  }
  for (std::size_t b = 0; b < std::size_t(kBlocks); ++b)
    if (count[b] > 0) run.blocks[b] = sum[b] / double(count[b]);
  run.wall = std::chrono::duration<double>(Clock::now() - t0).count();
}

// The outcome rule (documented at the top of this file and in docs/stability.md).
void classify(Run& run) {
  if (run.failed) {
    run.outcome = "diverged";
    run.rule = run.reason;
  } else if (run.gain > kGrowth) {
    run.outcome = "growing";
    run.rule = "mean E over the last 10% > E(0) + 5% W";
  } else {
    run.outcome = "stable";
    run.rule = "";
  }
}

Run run_method(Method m, const System& proto, double dt, long steps) {
  Run run;
  // BackwardEuler in the kind's mode, FastMassSpring with default options (50 iterations)
  massspring::with_integrator<System>(
      m, [&](auto& integrator) { simulate(proto, integrator, dt, steps, run); });
  classify(run);
  return run;
}

std::string csv_escape(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string num(double v) {
  if (std::isnan(v)) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string dt_label(double dt) {
  if (std::abs(dt - 1.0 / 30) < 1e-12) return "1/30";
  return num(dt);
}

long steps_for(double end_time, double dt) { return long(std::ceil(end_time / dt - 1e-9)); }

int usage() {
  std::fprintf(stderr, "usage: stability [--quick] [--out DIR (out/stability)]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string out = "out/stability";
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--quick") {
      quick = true;
    } else if (arg == "--out" && a + 1 < argc) {
      out = argv[++a];
    } else {
      return usage();
    }
  }
  const std::vector<SceneSpec> scenes = {{"chain", 20}, {"cloth", 8}};
  std::vector<double> ks;
  if (quick)
    ks = {1e0, 1e8};
  else
    for (int e = 0; e <= 8; ++e) ks.push_back(std::pow(10.0, e));
  const std::vector<double> dts = {1e-4, 1e-3, 1e-2, 1.0 / 30};
  const double end_time = quick ? 1.0 : 10.0;

  std::filesystem::create_directories(out);
  std::ofstream results(out + "/results.csv");
  std::ofstream traces(out + "/traces.csv");
  if (!results || !traces) {
    std::fprintf(stderr, "stability: cannot write into %s\n", out.c_str());
    return 2;
  }
  results << "scene,points,springs,k,integrator,kind,factor,dt,dt_label,bound_dt,"
             "at_or_below_bound,steps_planned,steps_done,outcome,rule,fail_step,fail_time,E0,"
             "guard_scale,W,E_end,E_tail,E_max,KE_max,gain,unconverged_steps,indefinite_solves,"
             "stretch_min,stretch_max,limit_ratio_min,"
             "wall_s\n";
  traces << "run,block,t_mid,energy\n";

  // Estimated work (for the ETA): steps x points x cost weight, bound runs included.
  double total = 0;
  for (const auto& scene : scenes)
    for (const double k : ks) {
      const System proto = make_scene(scene, k);
      for (const Method m : kMethods) {
        for (const double dt : dts)
          total += double(steps_for(end_time, dt)) * scene.points() * cost_weight(m);
        if (is_explicit(m) && m != Method::ForwardEuler)
          for (const double f : kBoundFactors)
            total += double(steps_for(end_time,
                                      f * massspring::stability_limit(proto, explicit_method(m)))) *
                     scene.points() * cost_weight(m);
      }
    }
  massspring::bench::Progress progress("stability", total);
  const auto t_start = Clock::now();

  int run_id = 0;
  long below_runs = 0, below_stable = 0;
  std::vector<std::string> below_failures;
  int skipped = 0;
  auto record = [&](const SceneSpec& scene, const System& proto, double k, Method m,
                    const char* kind, double factor, double dt, double bound, const Run& run) {
    // "At or below stable_time_step": dt <= safety x the limit (0.5 by default).
    const double stable = massspring::default_stability_safety * bound;
    const bool below = is_explicit(m) && bound > 0 && dt > 0 && dt <= stable * (1 + 1e-12);
    const bool at_bound = std::string(kind) == "bound";
    results << scene.name << ',' << proto.num_points() << ',' << proto.num_springs() << ','
            << num(k) << ',' << name(m) << ',' << kind << ',' << num(factor) << ',' << num(dt)
            << ',' << (at_bound ? "x" + num(factor) : dt_label(dt)) << ',' << num(bound) << ','
            << (below ? 1 : 0) << ',' << run.planned << ',' << run.done << ',' << run.outcome << ','
            << csv_escape(run.rule) << ','
            << (run.failed ? std::to_string(run.fail_step) : std::string()) << ','
            << num(run.fail_time) << ',' << num(run.e0) << ',' << num(run.scale) << ','
            << num(run.w) << ',' << num(run.e_end) << ',' << num(run.e_tail) << ','
            << num(run.e_max) << ',' << num(run.ke_max) << ',' << num(run.gain) << ','
            << run.unconverged << ',' << run.indefinite << ',' << num(run.stretch_min) << ','
            << num(run.stretch_max) << ',' << num(run.limit_ratio_min) << ',' << num(run.wall)
            << '\n';
    for (int b = 0; b < kBlocks; ++b)
      traces << run_id << ',' << b << ',' << num((b + 0.5) * double(run.planned) * dt / kBlocks)
             << ',' << num(run.blocks[std::size_t(b)]) << '\n';
    ++run_id;
    if (!below) return;
    ++below_runs;
    if (run.outcome == "stable") {
      ++below_stable;
    } else {
      char buf[320];
      std::snprintf(buf, sizeof buf, "%s k=%g %s dt=%.6g (%.3g x the limit %.6g): %s (%s)",
                    scene.name.c_str(), k, name(m), dt, dt / bound, bound, run.outcome.c_str(),
                    run.rule.c_str());
      below_failures.push_back(buf);
    }
  };

  for (const auto& scene : scenes) {
    for (const double k : ks) {
      const System proto = make_scene(scene, k);
      for (const Method m : kMethods) {
        const double bound =
            is_explicit(m) ? massspring::stability_limit(proto, explicit_method(m)) : kNaN;
        for (const double dt : dts) {
          const long steps = steps_for(end_time, dt);
          const Run run = run_method(m, proto, dt, steps);
          record(scene, proto, k, m, "grid", kNaN, dt, bound, run);
          char label[200];
          std::snprintf(label, sizeof label, "%s k=%g %s dt=%s: %s", scene.name.c_str(), k, name(m),
                        dt_label(dt).c_str(), run.outcome.c_str());
          progress.advance(double(steps) * scene.points() * cost_weight(m), label);
        }
        if (!is_explicit(m)) continue;
        for (const double factor : kBoundFactors) {
          if (!(bound > 0)) {  // ForwardEuler without damping: no stable step exists
            ++skipped;
            Run run;
            run.outcome = "skipped";
            run.rule = "stability_limit = 0: no stable step without damping";
            record(scene, proto, k, m, "bound", factor, 0.0, bound, run);
            continue;
          }
          const double dt = factor * bound;
          const long steps = steps_for(end_time, dt);
          const Run run = run_method(m, proto, dt, steps);
          record(scene, proto, k, m, "bound", factor, dt, bound, run);
          char label[200];
          std::snprintf(label, sizeof label, "%s k=%g %s at %g x the limit (dt=%.3g): %s",
                        scene.name.c_str(), k, name(m), factor, dt, run.outcome.c_str());
          progress.advance(double(steps) * scene.points() * cost_weight(m), label);
        }
      }
    }
  }
  const double wall = std::chrono::duration<double>(Clock::now() - t_start).count();

  std::ofstream meta(out + "/meta.csv");
  meta << "key,value\n"
       << "mode," << (quick ? "quick" : "full") << '\n'
       << "end_time," << num(end_time) << '\n'
       << "wall_s," << num(wall) << '\n'
       << "runs," << run_id << '\n'
       << "growth_threshold," << num(kGrowth) << '\n'
       << "explicit_at_or_below_bound," << below_runs << '\n'
       << "explicit_at_or_below_bound_stable," << below_stable << '\n'
       << "forward_euler_bound_skipped," << skipped << '\n';

  std::printf("stability: %d runs in %.1f s (%s mode, %g simulated seconds each); results in %s\n",
              run_id, wall, quick ? "quick" : "full", end_time, out.c_str());
  std::printf(
      "ForwardEuler at the limit: skipped %d times (stability_limit = 0: no stable step "
      "without damping)\n",
      skipped);
  for (const auto& f : below_failures)
    std::printf("not stable at or below stable_time_step: %s\n", f.c_str());
  std::printf(
      "explicit runs at or below stable_time_step (%g x stability_limit): %ld, all stable: %s\n",
      massspring::default_stability_safety, below_runs, below_runs == below_stable ? "yes" : "no");
  return below_runs == below_stable ? 0 : 1;
}
