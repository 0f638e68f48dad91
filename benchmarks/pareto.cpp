// Run time against error (docs/benchmarks.md): every integrator over a sweep of time
// steps, and local-global over iteration counts and tolerances, on a chain, a net, 32x32 and 64x64
// cloths and a circular orbit. Each run is one point (compute seconds per simulated second,
// trajectory error at the end time against an RK4 reference). Then Liu et al. 2013's table: the
// relative step error of one frame of a hanging cloth after 1, 10, 100, 1000 local-global
// iterations, next to one and to converged Newton iterations, with times.
//
//   pareto [--out DIR] [--cache DIR] [--budget SECONDS] [--min-time SECONDS] [--scenes a,b,...]
//          [--quick] [--references-only]
//
// Writes DIR/pareto.csv (one row per point), DIR/references.csv (the reference of each scene) and
// DIR/liu_table.csv; scripts/plot_pareto.py turns them into docs/benchmarks.md and
// docs/images/pareto_*.png (scripts/pareto.sh does all of it). Progress goes to stderr.
//
// Timing: wall clock (std::chrono::steady_clock) of the stepping loop only; precompute (one
// factorization) is excluded, as it is paid once per scene. A plain program rather than Google
// Benchmark because each point is one long simulation, not a loop of identical calls. A finished
// run whose loop takes less than --min-time seconds (default 0.2; 0 with --quick) is repeated,
// each time on a new copy of the scene with a new integrator (the same trajectory), until its
// loops add up to that time; its time is the fastest loop's (pareto.csv's `repetitions` says how
// many ran). A run whose projected time (from its first steps) exceeds the budget is not
// finished: it is written with status "skipped" and its projected cost, and it is left out of the
// fronts. It cannot be the cheapest way to any error the measured points reach below that cost.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <massspring/massspring.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "progress.hpp"

namespace {

using namespace massspring;
using System = MassSpringSystem<double, Sparse>;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

struct Scene {
  std::string name;
  std::string description;
  System system;
  double end_time;
};

// A scene of the recipe's system under gravity 9.81 m/s^2 (a Gravity term), for 1 s.
Scene under_gravity(std::string name, std::string description, const SceneDescription<double>& d) {
  System s = make_system<System>(d);
  s.add_force(Gravity<double>({0, -9.81, 0}));
  return {std::move(name), std::move(description), std::move(s), 1.0};
}

Scene cloth_scene(int n, double stiffness) {
  // Hanging from its top corners and released from its rest shape. The stiffness must let it
  // stretch under its weight and swing (k = 50 N/m does): at the JSON+OBJ scenes' k = 1000 N/m it
  // barely sags, so not moving at all would already be "accurate". A cloth dropped from
  // horizontal or pushed sideways at k = 1000 has no RK4 reference: its stiff, undamped motion is
  // chaotic within a second, so halving the step does not converge the solution.
  ClothOptions o = hanging_cloth_recipe(n);
  o.stiffness = stiffness;
  char k[32];
  std::snprintf(k, sizeof k, "%g", stiffness);
  return under_gravity("cloth" + std::to_string(n),
                       std::to_string(n) + "x" + std::to_string(n) +
                           " cloth, 1 m x 1 m vertical, quads with both diagonals, k = " + k +
                           " N/m, Voronoi masses (1 kg in all), top corners pinned, gravity 9.81 "
                           "m/s^2, released from its rest shape",
                       make_cloth(o));
}

Scene chain_scene() {
  ChainOptions o = chain_recipe();
  o.points = 20;
  o.mass = 0.05;
  return under_gravity("chain",
                       "20 points on 1 m, both ends pinned, k = 500 N/m, 0.05 kg each, gravity, "
                       "from straight and at rest (it sags and swings)",
                       make_chain(o));
}

Scene net_scene() {
  NetOptions o = net_recipe();
  o.mass = 1.0 / 64;
  return under_gravity("net",
                       "8x8 net (1 m x 1 m, horizontal), corners pinned, k = 300 N/m, 1/64 kg "
                       "each, gravity, from rest",
                       make_net(o));
}

Scene orbit_scene() {
  Points<double> x = Points<double>::Zero(2, 3);
  x(1, 0) = 1;
  System s(x, Edges(0, 2), 1.0, 0.0);
  s.pin(0);
  Points<double> v = Points<double>::Zero(2, 3);
  v(1, 1) = 1;
  s.set_velocities(v);
  s.add_force(GravitationalAttraction<double>({{0, 1, 1.0}}));
  return {"orbit",
          "circular orbit: G m1 m2 = 1, radius 1 m, speed 1 m/s around a pinned mass, 3/4 of a "
          "period (1.5 pi s; after a whole one, not moving at all would score 0)",
          std::move(s), 1.5 * M_PI};
}

struct Point {
  std::string scene, family, setting;
  double dt = 0;
  long steps = 0;
  double seconds = 0;     // wall clock of the stepping loop, the fastest repetition's
                          // (projected when skipped)
  int repetitions = 1;    // how many times the loop ran
  double error = NAN;     // trajectory error at the end time
  double drift = NAN;     // (E(T) - E(0)) / max kinetic energy of the reference
  double iterations = 0;  // mean solver iterations per step
  std::string status;     // ok, diverged, skipped
};

struct Reference {
  ReferenceSolution solution;
  double seconds = 0;
};

/// Steps a copy of the scene to its end time with the integrator make() returns at dt (adjusted to
/// divide the end time); fills a Point. A finished run whose loop took less than min_time [s] is
/// repeated (a new copy of the scene, a new integrator) until its loops add up to min_time; its
/// seconds are the fastest loop's.
template <class Make>
Point run(const Scene& scene, const Reference& ref, const Make& make, double dt,
          const std::string& family, const std::string& setting, double budget, double min_time) {
  Point p;
  p.scene = scene.name;
  p.family = family;
  p.setting = setting;
  const long steps = std::max(1L, long(std::llround(std::ceil(scene.end_time / dt - 1e-9))));
  p.dt = scene.end_time / double(steps);
  System s = scene.system;
  auto integrator = make();
  integrator.precompute(s, p.dt);
  const long probe = std::min(steps, std::max(3L, steps / 50));
  long iterations = 0;
  long done = 0;
  bool ok = true;
  const auto t0 = Clock::now();
  for (; done < steps; ++done) {
    if (done == probe) {
      const double projected = seconds_since(t0) * double(steps) / double(done);
      if (projected > budget) {
        p.seconds = projected;
        p.steps = steps;
        p.status = "skipped";
        return p;
      }
    }
    const StepReport r = integrator.step(s);
    iterations += r.iterations;
    if (!r.ok()) {
      ok = false;
      ++done;
      break;
    }
  }
  p.seconds = seconds_since(t0);
  p.steps = done;
  p.iterations = double(iterations) / double(done);
  if (!ok) {
    p.status = "diverged";
    return p;
  }
  p.error = trajectory_error(s.positions(), ref.solution.positions, ref.solution.diagonal);
  p.drift = energy_drift(double(total_energy(s)), ref.solution.initial_energy,
                         std::max(ref.solution.kinetic_max, 1e-300));
  // An RMS error beyond the scene's own size is no solution: the run blew up (explicit methods
  // past their limit grow by orders of magnitude without overflowing).
  p.status = p.error <= 1 ? "ok" : "diverged";
  if (p.status != "ok") return p;
  double total = p.seconds;
  while (total < min_time && p.repetitions < 10000) {
    System again = scene.system;
    auto repeated = make();
    repeated.precompute(again, p.dt);
    const auto t1 = Clock::now();
    long k = 0;
    while (k < steps && repeated.step(again).ok()) ++k;
    const double seconds = seconds_since(t1);
    if (k < steps) break;  // a loop cut short is no time for the whole run
    total += seconds;
    p.seconds = std::min(p.seconds, seconds);
    ++p.repetitions;
  }
  return p;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

/// The list of runs of one scene, each a closure, with a work estimate for the progress line.
struct Job {
  std::string label;
  double work;
  std::function<Point()> run;
};

std::vector<Job> jobs_for(const Scene& scene, const Reference& ref, double budget, double min_time,
                          bool quick) {
  std::vector<Job> jobs;
  const double T = scene.end_time;
  const int n = scene.system.num_points();
  // The implicit solvers' sweep: 1/30 s halved down to 1/480 (1/120 in quick mode).
  std::vector<double> implicit_dts;
  for (int j = 0; j <= (quick ? 2 : 4); ++j) implicit_dts.push_back(1.0 / (30 << j));
  // Work estimate for the ETA: steps x points x a rough cost per point and step, in units of
  // one force evaluation (orders of magnitude, not exact).
  auto weight = [](const std::string& family, const std::string& setting) {
    if (family == "RK4") return 4.0;
    if (family == "BackwardEuler") return setting == "newton" ? 300.0 : 80.0;
    if (family == "LocalGlobal") {
      if (setting.rfind("it=", 0) == 0) return 2.0 * std::atof(setting.c_str() + 3);
      return setting.rfind("tol", 0) == 0 ? 60.0 : 25.0;
    }
    return 1.0;
  };
  auto add = [&](const std::string& family, const std::string& setting, double dt, auto make) {
    const double steps = std::ceil(T / dt);
    jobs.push_back({scene.name + " " + family + " " + setting + " dt=" + fmt("%.3g", dt),
                    steps * n * weight(family, setting), [=, &scene, &ref]() {
                      return run(scene, ref, make, dt, family, setting, budget, min_time);
                    }});
  };
  // Explicit methods: 0.9x their stability_limit (the edge; stable_time_step is half of it),
  // then halvings. ForwardEuler has no stable step without damping; it runs at symplectic Euler's.
  const double se_bound = stability_limit(scene.system, ExplicitMethod::SymplecticEuler);
  const double rk_bound = stability_limit(scene.system, ExplicitMethod::RK4);
  auto explicit_dts = [&](double bound) {
    std::vector<double> d;
    double h = std::min(0.9 * bound, 1.0 / 30);
    for (int j = 0; j < (quick ? 2 : 6); ++j, h /= 2) d.push_back(h);
    return d;
  };
  for (double dt : explicit_dts(se_bound)) {
    add("ForwardEuler", "-", dt, [] { return ForwardEuler<System>(); });
    add("SymplecticEuler", "-", dt, [] { return SymplecticEuler<System>(); });
  }
  for (double dt : explicit_dts(rk_bound)) add("RK4", "-", dt, [] { return RK4<System>(); });
  for (double dt : implicit_dts) {
    add("BackwardEuler", "linearized", dt, [] {
      BackwardEulerOptions<double> o;
      o.mode = BackwardEulerMode::Linearized;
      return BackwardEuler<System>(o);
    });
    add("BackwardEuler", "newton", dt, [] { return BackwardEuler<System>(); });
    for (int it : {1, 3, 10, 30, 100}) {
      if (quick && it > 10) continue;
      add("LocalGlobal", "it=" + std::to_string(it), dt, [it] {
        auto o = FastMassSpringOptions<double>::reference();
        o.iterations = it;
        return FastMassSpring<System>(o);
      });
    }
    for (double tol : {1e-3, 1e-6}) {
      add("LocalGlobal", "tol=" + fmt("%g", tol), dt, [tol] {
        auto o = FastMassSpringOptions<double>::reference();
        o.iterations = 1000;
        o.tolerance = tol;
        return FastMassSpring<System>(o);
      });
    }
    add("LocalGlobal", "chebyshev it=10", dt, [] {
      auto o = FastMassSpringOptions<double>::reference();
      o.iterations = 10;
      o.acceleration = Acceleration::Chebyshev;
      return FastMassSpring<System>(o);
    });
  }
  return jobs;
}

// ---- Liu 2013's table ---------------------------------------------------------------------

struct LiuRow {
  std::string method;
  int iterations;
  double error;    // (E(x_k) - E*) / (E(x^t) - E*)
  double seconds;  // one step, min over repetitions
};

template <class Integrator>
LiuRow liu_row(const System& start, Integrator integrator, double h, const std::string& method,
               double e_start, double e_star, int repetitions) {
  integrator.precompute(start, h);
  LiuRow row{method, 0, NAN, 1e300};
  for (int r = 0; r < repetitions; ++r) {
    System s = start;
    const auto t0 = Clock::now();
    const StepReport report = integrator.step(s);
    row.seconds = std::min(row.seconds, seconds_since(t0));
    row.iterations = report.iterations;
    const double e =
        incremental_potential(s, s.positions(), start.positions(), start.velocities(), h);
    row.error = step_error(e, e_start, e_star);
  }
  return row;
}

std::vector<LiuRow> liu_table(int n, bool quick, std::string& description) {
  Scene scene = cloth_scene(n, 1000);  // stiff, as in Liu 2013: local-global converges slowly
  const double h = 1.0 / 30;
  // The frame: the cloth after 10 frames of converged backward Euler from rest, mid-swing.
  System start = scene.system;
  {
    BackwardEuler<System> be;
    be.precompute(start, h);
    for (int f = 0; f < 10; ++f) be.step(start);
  }
  description = scene.description + "; the frame after 10 frames (dt = 1/30 s) of backward Euler";
  BackwardEulerOptions<double> exact;
  exact.tolerance = 1e-14;
  exact.iterations = 100;
  System converged = start;
  BackwardEuler<System> newton(exact);
  newton.precompute(converged, h);
  newton.step(converged);
  const double e_star = incremental_potential(converged, converged.positions(), start.positions(),
                                              start.velocities(), h);
  const double e_start =
      incremental_potential(start, start.positions(), start.positions(), start.velocities(), h);
  std::vector<LiuRow> rows;
  for (int it : {1, 10, 100, 1000}) {
    if (quick && it > 10) continue;
    auto o = FastMassSpringOptions<double>::reference();
    o.iterations = it;
    rows.push_back(liu_row(start, FastMassSpring<System>(o), h, "local-global", e_start, e_star,
                           it <= 100 ? 5 : 1));
  }
  {
    auto o = FastMassSpringOptions<double>::reference();
    o.iterations = quick ? 10 : 100;
    o.acceleration = Acceleration::Chebyshev;
    rows.push_back(liu_row(start, FastMassSpring<System>(o), h, "local-global, Chebyshev", e_start,
                           e_star, 3));
  }
  BackwardEulerOptions<double> one;
  one.iterations = 1;
  rows.push_back(liu_row(start, BackwardEuler<System>(one), h, "Newton", e_start, e_star, 3));
  rows.push_back(
      liu_row(start, BackwardEuler<System>(exact), h, "Newton, converged", e_start, e_star, 1));
  BackwardEulerOptions<double> linearized;
  linearized.mode = BackwardEulerMode::Linearized;
  rows.push_back(liu_row(start, BackwardEuler<System>(linearized), h, "linearized backward Euler",
                         e_start, e_star, 3));
  return rows;
}

// The scenes, in the order they run; the cloths only in the full benchmark (not --quick).
const std::vector<std::string> kScenes = {"chain", "net", "orbit", "cloth32", "cloth64"};
bool full_only(const std::string& name) { return name.rfind("cloth", 0) == 0; }

// The scenes to run for --scenes `list` (comma-separated; empty: every scene), in kScenes's
// order. Throws std::invalid_argument naming the unknown names and the known ones, or when
// nothing is left to run; prints to stderr the named scenes --quick leaves out.
std::vector<std::string> scene_names(const std::string& list, bool quick) {
  std::vector<std::string> asked, unknown, dropped, out;
  std::stringstream in(list);
  for (std::string name; std::getline(in, name, ',');)
    if (!name.empty()) asked.push_back(name);
  std::string known;
  for (const std::string& name : kScenes) known += (known.empty() ? "" : ", ") + name;
  for (const std::string& name : asked)
    if (std::find(kScenes.begin(), kScenes.end(), name) == kScenes.end()) unknown.push_back(name);
  auto joined = [](const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
  };
  if (!unknown.empty())
    throw std::invalid_argument("--scenes: unknown scene" +
                                std::string(unknown.size() > 1 ? "s " : " ") + joined(unknown) +
                                " (the scenes: " + known + ")");
  if (!list.empty() && asked.empty())
    throw std::invalid_argument("--scenes: no scene named (the scenes: " + known + ")");
  for (const std::string& name : kScenes) {
    const bool wanted = asked.empty() || std::find(asked.begin(), asked.end(), name) != asked.end();
    if (!wanted) continue;
    if (quick && full_only(name)) {
      if (!asked.empty()) dropped.push_back(name);
      continue;
    }
    out.push_back(name);
  }
  if (!dropped.empty())
    std::fprintf(stderr,
                 "pareto: --quick leaves out %s (the cloths run in the full benchmark only)\n",
                 joined(dropped).c_str());
  if (out.empty())
    throw std::invalid_argument("--scenes " + list + " with --quick: no scene left to run");
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out = "out/pareto", cache = "out/reference", only;
  double budget = 60, min_time = -1;  // min_time < 0: the default, 0.2 s (0 with --quick)
  bool quick = false, references_only = false;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    auto value = [&]() -> std::string {
      if (a + 1 >= argc) {
        std::fprintf(stderr, "pareto: %s needs a value\n", arg.c_str());
        std::exit(2);
      }
      return argv[++a];
    };
    if (arg == "--out") {
      out = value();
    } else if (arg == "--cache") {
      cache = value();
    } else if (arg == "--budget") {
      budget = std::atof(value().c_str());
    } else if (arg == "--min-time") {
      min_time = std::atof(value().c_str());
      if (!(min_time >= 0)) {
        std::fprintf(stderr, "pareto: --min-time must be >= 0\n");
        return 2;
      }
    } else if (arg == "--scenes") {
      only = value();
    } else if (arg == "--quick") {
      quick = true;
    } else if (arg == "--references-only") {
      references_only = true;
    } else {
      std::fprintf(stderr,
                   "usage: pareto [--out DIR] [--cache DIR] [--budget SECONDS] [--min-time "
                   "SECONDS] [--scenes "
                   "chain,net,cloth32,cloth64,orbit] [--quick] "
                   "[--references-only]\n");
      return 2;
    }
  }
  if (!(budget > 0)) {
    std::fprintf(stderr, "pareto: --budget must be > 0\n");
    return 2;
  }
  if (min_time < 0) min_time = quick ? 0 : 0.2;
  std::vector<std::string> names;
  try {
    names = scene_names(only, quick);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "pareto: %s\n", e.what());
    return 2;
  }
  std::filesystem::create_directories(out);
  std::vector<Scene> scenes;
  for (const std::string& name : names) {
    if (name == "chain") scenes.push_back(chain_scene());
    if (name == "net") scenes.push_back(net_scene());
    if (name == "orbit") scenes.push_back(orbit_scene());
    if (name == "cloth32") scenes.push_back(cloth_scene(32, 50));
    if (name == "cloth64") scenes.push_back(cloth_scene(64, 50));
  }
  if (quick)
    for (auto& s : scenes) s.end_time = std::min(s.end_time, 0.25);

  // References (cached in --cache: recomputed only when the scene or end time changes).
  std::vector<Reference> refs(scenes.size());
  std::ofstream rcsv(out + "/references.csv");
  rcsv << "scene,points,springs,end_time,dt,change,kinetic_max,initial_energy,diagonal,seconds,"
          "from_cache,se_limit_dt,rk4_limit_dt,still_error,description\n";
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    const Scene& sc = scenes[k];
    ReferenceOptions o;
    o.cache_directory = cache;
    o.key = sc.name;
    bench::Progress progress("reference " + sc.name, 1.0, 10.0);
    double printed = 0;
    o.progress = [&](double dt, double fraction) {
      if (progress.seconds() - printed < 10) return;  // a line every 10 s at most
      printed = progress.seconds();
      std::fprintf(stderr, "[reference %s] RK4 dt=%.3g s: %3.0f%% of this run, elapsed %.0f s\n",
                   sc.name.c_str(), dt, 100 * fraction, progress.seconds());
    };
    const auto t0 = Clock::now();
    refs[k].solution = reference_solution(sc.system, sc.end_time, o);
    refs[k].seconds = seconds_since(t0);
    std::fprintf(stderr, "[reference %s] dt=%.3g s, change on halving %.2g, %s in %.1f s\n",
                 sc.name.c_str(), refs[k].solution.dt, refs[k].solution.change,
                 refs[k].solution.from_cache ? "from the cache" : "computed", refs[k].seconds);
    rcsv << sc.name << ',' << sc.system.num_points() << ',' << sc.system.num_springs() << ','
         << sc.end_time << ',' << refs[k].solution.dt << ',' << refs[k].solution.change << ','
         << refs[k].solution.kinetic_max << ',' << refs[k].solution.initial_energy << ','
         << refs[k].solution.diagonal << ',' << refs[k].seconds << ','
         << (refs[k].solution.from_cache ? 1 : 0) << ','
         << stability_limit(sc.system, ExplicitMethod::SymplecticEuler) << ','
         << stability_limit(sc.system, ExplicitMethod::RK4)
         << ','
         // The error of not moving at all: the level below which a solver says something.
         << trajectory_error(sc.system.positions(), refs[k].solution.positions,
                             refs[k].solution.diagonal)
         << ",\"" << sc.description << "\"\n";
  }
  rcsv.close();
  if (references_only) return 0;

  std::vector<Job> jobs;
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    auto j = jobs_for(scenes[k], refs[k], budget, min_time, quick);
    jobs.insert(jobs.end(), j.begin(), j.end());
  }
  double total = 0;
  for (const auto& j : jobs) total += j.work;
  bench::Progress progress("pareto", total);
  std::ofstream csv(out + "/pareto.csv");
  csv << "scene,family,setting,dt,steps,seconds,cost,error,energy_drift,iterations,status,"
         "repetitions\n";
  csv.precision(6);
  for (const auto& job : jobs) {
    const Point p = job.run();
    const double simulated = p.dt * double(p.steps);
    csv << p.scene << ',' << p.family << ',' << p.setting << ',' << p.dt << ',' << p.steps << ','
        << p.seconds << ',' << (simulated > 0 ? p.seconds / simulated : NAN) << ',' << p.error
        << ',' << p.drift << ',' << p.iterations << ',' << p.status << ',' << p.repetitions << '\n';
    csv.flush();
    progress.advance(job.work, job.label + " -> " + p.status +
                                   (p.status == "ok" ? " error " + fmt("%.2e", p.error) : ""));
  }
  csv.close();

  // Liu 2013's table on the 64x64 cloth (16x16 in quick mode).
  std::string description;
  const auto rows = liu_table(quick ? 16 : 64, quick, description);
  std::ofstream liu(out + "/liu_table.csv");
  liu << "method,iterations,step_error,seconds,\"" << description << "\"\n";
  for (const auto& r : rows)
    liu << '"' << r.method << "\"," << r.iterations << ',' << r.error << ',' << r.seconds << ",\n";
  std::fprintf(stderr, "[pareto] done in %.0f s; wrote %s/{pareto,references,liu_table}.csv\n",
               progress.seconds(), out.c_str());
  return 0;
}
