#pragma once
// massspring-simulate's run: resolves what the scene and the options ask for, checks every output
// before the first step, steps, writes frames, the CSV and the saved state.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <massspring/integrators/with_integrator.hpp>
#include <massspring/io.hpp>
#include <massspring/io/state_scene.hpp>
#include <massspring/massspring.hpp>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "simulate/config.hpp"
#include "simulate/exports.hpp"
#include "simulate/outputs.hpp"
#include "simulate/progress.hpp"
#include "simulate/stability_hint.hpp"

namespace simulate {

constexpr int kExitBadInput = 1;  // invalid input or options; an output that cannot be written
constexpr int kExitDiverged = 2;  // a step diverged; the last good state is kept

// The signal (SIGINT or SIGTERM) received since the run started, or 0; the step loop stops after
// the step in progress and the program exits 128 + the signal.
inline volatile std::sig_atomic_t g_signal = 0;  // NOLINT: written by a signal handler

inline void on_signal(int signal) { g_signal = signal; }

inline void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  // writes in progress continue; a second signal ends the program at once (the files already
  // renamed into place are whole; a .tmp file may be left, and the next run names it)
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const double at = p * double(v.size() - 1);
  const auto lo = std::size_t(at);
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (at - double(lo)) * (v[hi] - v[lo]);
}

// The steps --duration asks for: the whole number of steps of h [s] nearest `time` [s] >= 0 (a
// half rounded up), at least one when time > 0, so that the run ends within h / 2 of `time`
// (1.5 s at h = 0.0333333 s: 45 steps, 1.4999985 s); saturates at the largest long long.
inline long long steps_for_duration(double time, double h) {
  const double q = time / h;
  if (!(q < 9.2e18)) return std::numeric_limits<long long>::max();
  const auto nearest = static_cast<long long>(std::floor(q + 0.5));
  return time > 0 ? std::max(1LL, nearest) : nearest;
}

// What the run resolved from the scene and the options.
struct Plan {
  double dt = 0;
  int steps = 0;
  long long first_frame = 0;  // a saved state's frame; 0 otherwise
  std::string integrator;     // its name (IntegratorNaming::Cli)
  massspring::IntegratorKind kind = massspring::IntegratorKind::FastMassSpring;
  std::optional<double> saved_rho;               // a saved state's Chebyshev rho
  const nlohmann::json* saved_duals = nullptr;   // a saved state's contact dual variables
  std::optional<std::vector<double>> rest_at_0;  // --shrink: rest lengths at frame 0
  StabilityHint hint;                            // explicit integrators: their stable step
};

// A saved state's "run" entry, type-checked.
inline const nlohmann::json* run_entry(const Config& c, const nlohmann::json& run, const char* key,
                                       bool (nlohmann::json::*is)() const noexcept) {
  if (!run.is_object()) return nullptr;
  const auto it = run.find(key);
  if (it == run.end()) return nullptr;
  if (!((*it).*is)())
    throw Error(c.scene + ": key \"run\": \"" + key + "\" has the wrong type: " + it->dump());
  return &*it;
}

template <class System>
Plan resolve(const Config& c, const Setup<System>& s) {
  Plan p;
  const bool xml = s.fosssim.has_value();
  if ((c.gravity_given || c.force_given) && (xml || s.state))
    throw Error(std::string(c.gravity_given ? "--gravity" : "--force") + ": " + s.name +
                " carries its own force terms (" + (xml ? "an XML scene" : "a saved state") +
                "); --gravity and --force apply to JSON+OBJ and generated scenes");
  using J = nlohmann::json;
  const J& run = s.run_data;
  if (const J* f = run_entry(c, run, "frame", &J::is_number_unsigned))
    p.first_frame = f->get<long long>();
  const J* saved_dt = run_entry(c, run, "dt", &J::is_number);
  const J* saved_integrator = run_entry(c, run, "integrator", &J::is_string);
  if (const J* r = run_entry(c, run, "chebyshev_rho", &J::is_number))
    p.saved_rho = r->get<double>();
  p.saved_duals = run_entry(c, run, "contact_duals", &J::is_array);
  p.dt = c.dt_given ? c.dt
         : xml      ? s.fosssim->dt
         : saved_dt ? saved_dt->get<double>()
         : s.dt     ? *s.dt
                    : c.dt;
  if (!(std::isfinite(p.dt) && p.dt > 0))
    throw Error(s.name + ": key \"run\": \"dt\" must be > 0, got " + std::to_string(p.dt));
  using massspring::IntegratorNaming;
  p.integrator = c.integrator_given ? c.integrator
                 : xml
                     ? massspring::to_string(massspring::io::integrator_kind(s.fosssim->integrator),
                                             IntegratorNaming::Cli)
                 : saved_integrator ? saved_integrator->get<std::string>()
                                    : "fast-mass-spring";
  const std::optional<massspring::IntegratorKind> kind =
      massspring::find_integrator(p.integrator, IntegratorNaming::Cli);
  if (!kind) throw Error(s.name + ": key \"run\": unknown integrator \"" + p.integrator + "\"");
  p.kind = *kind;
  long long steps = c.steps;
  std::string length = "--steps " + std::to_string(c.steps) + " =";  // what set it, for messages
  switch (c.length) {
    case Length::Default:
      if (xml) {
        steps = s.fosssim->steps_for(p.dt);
        length = s.name + ": its duration / dt =";
      } else {
        length = "the default =";
      }
      break;
    case Length::Steps:
      break;
    case Length::Frames:
      steps = c.frames * c.every;
      length =
          "--frames " + std::to_string(c.frames) + " x --every " + std::to_string(c.every) + " =";
      break;
    case Length::Duration:
      steps = steps_for_duration(c.duration, p.dt);
      length = "--duration " + massspring::detail::message(c.duration) + " s / dt " +
               massspring::detail::message(p.dt) + " s =";
      break;
  }
  if (steps > 100000000)
    throw Error(length + " " + std::to_string(steps) +
                " steps: more than 10^8; ask for fewer, or a larger --dt");
  if (p.first_frame + steps > 2000000000)
    throw Error(length + " " + std::to_string(steps) +
                " steps: frame numbers would pass "
                "2000000000 (" +
                s.name + " starts at frame " + std::to_string(p.first_frame) + ")");
  p.steps = int(steps);

  auto refuse = [&](const std::vector<std::string>& given, const std::string& needs, bool applies) {
    if (!given.empty() && !applies)
      throw Error(given.front() + ": applies to " + needs + " only (this run: " + p.integrator +
                  (p.kind == massspring::IntegratorKind::FastMassSpring
                       ? ", --acceleration " + c.acceleration
                       : "") +
                  ")");
  };
  const bool fms = p.kind == massspring::IntegratorKind::FastMassSpring;
  refuse(c.given_fast_mass_spring, "--integrator fast-mass-spring", fms);
  refuse(c.given_chebyshev, "--acceleration chebyshev", fms && c.acceleration == "chebyshev");
  refuse(c.given_anderson, "--acceleration anderson", fms && c.acceleration == "anderson");
  refuse(c.given_backward_euler, "--integrator backward-euler",
         p.kind == massspring::IntegratorKind::BackwardEuler);
  refuse(c.given_contact,
         "--integrator fast-mass-spring, backward-euler or linearized-backward-euler",
         fms || p.kind == massspring::IntegratorKind::BackwardEuler ||
             p.kind == massspring::IntegratorKind::LinearizedBackwardEuler);

  if (c.shrink > 0) {
    const auto m = std::size_t(s.system.num_springs());
    if (!s.state) {
      p.rest_at_0.emplace(m);
      for (std::size_t e = 0; e < m; ++e)
        (*p.rest_at_0)[e] = double(s.system.rest_lengths()(Eigen::Index(e)));
    } else {
      const J* saved_shrink = run_entry(c, run, "shrink", &J::is_number);
      const J* rest = run_entry(c, run, "rest_lengths_at_frame_0", &J::is_array);
      if (!saved_shrink || saved_shrink->get<double>() != c.shrink || !rest || rest->size() != m)
        throw Error("--shrink: " + s.name +
                    " was not saved by a run with the same --shrink, so the rest lengths at "
                    "frame 0 are not known");
      p.rest_at_0.emplace();
      for (const J& r : *rest) {
        if (!r.is_number()) throw Error(s.name + ": key \"run\": a rest length is not a number");
        p.rest_at_0->push_back(r.get<double>());
      }
    }
  }
  return p;
}

// The solvers with a contact term inside their solve (--contact-weight), whose dual variables a
// saved state holds.
template <class System, class Solver>
inline constexpr bool has_contact_term =
    std::is_same_v<Solver, massspring::FastMassSpring<System>> ||
    std::is_same_v<Solver, massspring::BackwardEuler<System>>;

// The solver, configured from the options.
template <class System>
void configure(const Config& c, const Plan& p, massspring::FastMassSpring<System>& solver) {
  using Scalar = typename System::Scalar;
  auto& o = solver.options;
  o.iterations = c.iterations;
  o.tolerance = Scalar(c.tolerance);
  o.pins = massspring::parse_option<massspring::PinMode>(c.pins);
  o.penalty_weight = Scalar(c.penalty_weight);
  o.contact_weight = Scalar(c.contact_weight);
  o.acceleration = massspring::parse_option<massspring::Acceleration>(c.acceleration);
  // A resumed run uses the rho its first run estimated: estimating again, from another state,
  // would give another rho and another trajectory.
  o.chebyshev_rho = Scalar(!c.rho_given && p.saved_rho ? *p.saved_rho : c.chebyshev_rho);
  o.chebyshev_gamma = Scalar(c.chebyshev_gamma);
  o.chebyshev_delay = c.chebyshev_delay;
  o.chebyshev_estimate_iterations = c.chebyshev_estimate;
  o.anderson_window = c.anderson_window;
  o.threads = c.threads;
  o.ordering = massspring::parse_option<massspring::FillOrdering>(c.ordering);
  o.initial_guess = massspring::parse_option<massspring::InitialGuess>(c.initial_guess);
  o.energy_growth = c.guard_growth;  // the solver's own bound, the guard's limit
  if (std::is_same_v<Scalar, float> && o.pins == massspring::PinMode::Penalty)
    throw Error(
        massspring::detail::message("--pins penalty with --precision float: w = ", c.penalty_weight,
                                    " swamps the rest of Q in float; use --pins exact"));
}

// (with_integrator() has set options.mode from the kind.)
template <class System>
void configure(const Config& c, const Plan&, massspring::BackwardEuler<System>& solver) {
  solver.options.iterations = c.newton_iterations;
  solver.options.tolerance = typename System::Scalar(c.newton_tolerance);
  solver.options.line_search = c.line_search == "on";
  solver.options.contact_weight = typename System::Scalar(c.contact_weight);
  solver.options.energy_growth = c.guard_growth;
}

// The explicit integrators: the energy bound only.
template <class System, class Solver>
void configure(const Config& c, const Plan&, Solver& solver) {
  solver.set_energy_growth(c.guard_growth);
}

// What the run is, as the first line prints it: the integrator's name, and FastMassSpring's pins,
// iterations and acceleration.
template <class System, class Solver>
std::string describe(const Config& c, const Solver&, std::string what) {
  if constexpr (std::is_same_v<Solver, massspring::FastMassSpring<System>>) {
    what += " (" + c.pins + " pins, " + std::to_string(c.iterations) + " iterations";
    if (c.acceleration != "none") what += ", " + c.acceleration;
    what += ")";
  }
  return what;
}

// solver.precompute(system, dt); the time it took [ms].
template <class System, class Solver>
double timed_precompute(Solver& solver, System& system, double dt) {
  const auto t0 = std::chrono::steady_clock::now();
  solver.precompute(system, typename System::Scalar(dt));
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The first line: the scene, the run and the precompute time (not with --quiet).
template <class System>
void print_header(const Config& c, const Setup<System>& s, const Plan& p, const std::string& what,
                  double precompute_ms) {
  if (c.quiet) return;
  const System& system = s.system;
  std::printf(
      "%s: %d points, %d springs, %d pinned, %d force terms; %s, dt %g s, %d steps (%g s)%s; "
      "%s, %s; precompute %.2f ms\n",
      s.name.c_str(), system.num_points(), system.num_springs(), system.num_pinned(),
      system.forces().size(), what.c_str(), p.dt, p.steps, p.dt * p.steps,
      p.first_frame ? (" from frame " + std::to_string(p.first_frame)).c_str() : "",
      c.storage.c_str(), c.precision.c_str(), precompute_ms);
  std::fflush(stdout);  // seen before the run, also through a pipe
}

// The files written as the run goes: the OBJ frames (--out), the CSV trajectory (--csv) and the
// exports (--html, --pc2, --vtk). Constructing it is the run's first write: every check has
// passed by then.
template <class System>
class RunFiles {
 public:
  RunFiles(const Config& c, const Setup<System>& s, const Plan& p)
      : c_(c), s_(s), out_(c.out), last_frame_(p.first_frame + p.steps) {
    if (!c.out.empty()) {
      if (c.overwrite) clear_frames(out_);
      create_folders("--out", out_, out_);
    }
    // every output file's missing folders (checked writable above them)
    for (const auto& [option, file] :
         {std::pair{"--csv", c.csv}, std::pair{"--html", c.html}, std::pair{"--pc2", c.pc2},
          std::pair{"--save-state", c.save_state}})
      if (!file.empty()) create_folders(option, file, folder_of(file));
    if (!c.csv.empty()) csv_.emplace(c.csv);
    if (!c.html.empty() || !c.pc2.empty() || !c.vtk.empty())
      exports_.emplace(c, s, p.dt, p.first_frame);
  }

  // Writes the system's state as frame `frame` to every output, once: every --every-th frame and
  // the last; any frame when `always` (the first, an interrupted run's).
  void write_frame(long long frame, bool always = false) {
    if (frame == last_written_) return;
    if (frame % c_.every != 0 && frame != last_frame_ && !always) return;
    last_written_ = frame;
    if (!c_.out.empty()) {
      char file[32];
      std::snprintf(file, sizeof file, "frame_%05lld.obj", frame);
      massspring::io::write_obj(out_ / file, s_.system.positions(), s_.faces, s_.edges);
    }
    if (csv_) csv_->write(frame, s_.system);
    if (exports_) exports_->write(frame);
  }

  // For an error message: where the trajectory so far is ("" without --csv).
  [[nodiscard]] std::string where() const {
    return csv_ ? " (the trajectory so far is in " + csv_->tmp().string() + ")" : std::string();
  }

  // Closes the CSV, then the exports; appends each failure's message to `failures`.
  void close(std::vector<std::string>& failures) {
    try {
      if (csv_) csv_->close();
    } catch (const std::exception& e) {
      failures.push_back(e.what());
    }
    if (exports_)
      for (std::string& f : exports_->close()) failures.push_back(std::move(f));
  }

 private:
  const Config& c_;
  const Setup<System>& s_;
  fs::path out_;
  long long last_frame_;
  long long last_written_ = -1;
  std::optional<TrajectoryCsv> csv_;
  std::optional<Exports<System>> exports_;
};

// --save-state: the system at frame `frame`, with what a resumed run needs in its "run" entry.
template <class System, class Solver>
void save_state(const Config& c, const Setup<System>& s, const Plan& p, const Solver& solver,
                long long frame) {
  if (c.save_state.empty()) return;
  massspring::io::StateSceneExtras extras;
  extras.faces = s.faces;
  extras.edges = s.edges;
  nlohmann::json run = {{"frame", frame},
                        {"time", double(frame) * p.dt},
                        {"dt", p.dt},
                        {"integrator", p.integrator},
                        {"scene", s.name}};
  // The rho this run used, so that a resumed run uses it too. The solver estimates it once per
  // factorization; an estimate of 0 (no acceleration: the trial iterations gave no rate in
  // (0, 1)) is saved as the smallest positive float, which accelerates nothing either (omega =
  // 2 / (2 - rho^2) is exactly 1, in float and double) but is not "estimate again".
  if constexpr (std::is_same_v<Solver, massspring::FastMassSpring<System>>)
    if (c.acceleration == "chebyshev" && frame > 0)
      run["chebyshev_rho"] = solver.chebyshev_rho() > 0 ? double(solver.chebyshev_rho())
                                                        : double(std::numeric_limits<float>::min());
  // The contact term's dual variables (--contact-weight): the iteration starts from them.
  if constexpr (has_contact_term<System, Solver>)
    if (c.contact_weight > 0) {
      const auto u = solver.contact_duals();
      nlohmann::json rows = nlohmann::json::array();
      for (Eigen::Index i = 0; i < u.rows(); ++i)
        rows.push_back({double(u(i, 0)), double(u(i, 1)), double(u(i, 2))});
      run["contact_duals"] = std::move(rows);
    }
  if (p.rest_at_0) {
    run["shrink"] = c.shrink;
    run["rest_lengths_at_frame_0"] = *p.rest_at_0;
  }
  extras.run = std::move(run);
  massspring::io::write_state(s.system, c.save_state, extras);
}

// How the steps went and how they ended.
struct Outcome {
  std::vector<double> ms;         // the time of each step taken, a diverged one included [ms]
  long long iterations = 0;       // summed over the steps
  long long frame = 0;            // the last frame reached (the last good one)
  long long diverged_at = -1;     // the step that diverged, or -1
  long long interrupted_at = -1;  // the frame at which a signal stopped the run, or -1
  int signal = 0;                 // that signal
  bool blew_up = false;           // the divergence guard stopped it (not a non-finite state)
  bool unresolved = false;        // surface contact left a crossing
  double guard_limit = 0;         // the divergence guard's limit and scale [J]
  double guard_scale = 0;
  double failed_contact_work = 0;  // the contact work of the step that failed [J]
  bool contact_refused = false;    // ... more than the integrators' contact limit allows
  int contact_work_steps = 0;      // steps whose contact response added energy
  double most_contact_work = 0;    // the most it added in one step [J], and in which
  long long most_contact_work_at = 0;
};

// The steps: each timed, --shrink's rest lengths set before it, its frame written after it (and
// the state saved every --save-every frames). Stops at a divergence (the last good state kept) or
// after the step in progress at SIGINT or SIGTERM.
template <class System, class Solver>
Outcome run_steps(const Config& c, Setup<System>& s, const Plan& p, Solver& solver,
                  RunFiles<System>& files) {
  using Scalar = typename System::Scalar;
  System& system = s.system;
  Outcome o;
  o.ms.reserve(std::size_t(std::min(p.steps, 1 << 20)));
  o.frame = p.first_frame;
  massspring::Vector<Scalar> rest(system.num_springs());
  std::optional<massspring::DivergenceGuard<System>> guard;
  files.write_frame(o.frame, true);  // the first frame, whatever --every says
  // The energy check (off with --guard-growth 0): a step whose total energy passes
  // E(0) + growth x scale is undone and stops the run, like a non-finite one.
  if (c.guard_growth > 0) guard.emplace(system, massspring::DivergenceOptions{c.guard_growth});
  Progress progress(c.quiet ? 0.0 : c.progress, p.steps, p.dt);
  for (int step = 1; step <= p.steps; ++step) {
    if (g_signal) {  // SIGINT or SIGTERM since the last step: keep its frame, stop
      o.signal = g_signal;
      o.interrupted_at = o.frame;
      files.write_frame(o.frame, true);
      break;
    }
    if (p.rest_at_0) {  // free: rest lengths do not change any matrix
      const double factor = std::exp(-c.shrink * p.dt * double(o.frame));
      for (Eigen::Index e = 0; e < rest.size(); ++e)
        rest(e) = Scalar((*p.rest_at_0)[std::size_t(e)]) * Scalar(factor);
      system.set_rest_lengths(rest);
    }
    const auto start = std::chrono::steady_clock::now();
    const massspring::StepReport report = guard ? guard->step(solver, system) : solver.step(system);
    o.ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    o.iterations += report.iterations;
    if (!report.ok()) {
      o.diverged_at = o.frame + 1;
      o.blew_up = report.blew_up;
      o.failed_contact_work = report.contact_work;
      // The integrators' own limit on it (integrators/detail/energy_bound.hpp), S the guard's
      // scale: both are taken from the state the run starts from.
      o.contact_refused =
          guard && report.contact_work >
                       massspring::detail::EnergyBound<System>::kContactShare * guard->scale();
      o.unresolved = !report.contact_resolved;
      break;
    }
    ++o.frame;
    if (report.contact_work > 0) {
      ++o.contact_work_steps;
      if (report.contact_work > o.most_contact_work) {
        o.most_contact_work = report.contact_work;
        o.most_contact_work_at = o.frame;
      }
    }
    files.write_frame(o.frame);
    if (c.save_every > 0 && o.frame % c.save_every == 0) save_state(c, s, p, solver, o.frame);
    progress.step_done(step);
  }
  if (guard) {
    o.guard_limit = guard->limit();
    o.guard_scale = guard->scale();
  }
  return o;
}

// The end's writes: the state, then the CSV and the exports; a failure of one is reported after
// the others are done. Returns the failures' messages.
template <class System, class Solver>
std::vector<std::string> finish(const Config& c, const Setup<System>& s, const Plan& p,
                                const Solver& solver, RunFiles<System>& files, long long frame) {
  std::vector<std::string> failures;
  try {
    save_state(c, s, p, solver, frame);
  } catch (const std::exception& e) {
    failures.push_back(e.what());
  }
  files.close(failures);
  return failures;
}

// The step times: a summary line, or with --quiet the median alone [ms].
inline void print_times(const Config& c, const Outcome& o) {
  const std::vector<double>& ms = o.ms;
  const int done = int(ms.size()) - (o.diverged_at > 0 ? 1 : 0);
  double mean = 0;
  for (double x : ms) mean += x / double(ms.size());
  if (!c.quiet)
    std::printf(
        "%d steps, %.2f iterations per step: median %.3f ms per step "
        "(mean %.3f, p10 %.3f, p90 %.3f, max %.3f)\n",
        done, ms.empty() ? 0.0 : double(o.iterations) / double(ms.size()), percentile(ms, 0.5),
        mean, percentile(ms, 0.1), percentile(ms, 0.9), percentile(ms, 1.0));
  else
    std::printf("%.3f\n", percentile(ms, 0.5));
  // Said when one step's response added more than a thousandth of the scene's energy scale (the
  // divergence guard's; any energy without the guard): its corrections stretched springs.
  if (!c.quiet && o.contact_work_steps > 0 && o.most_contact_work > 1e-3 * o.guard_scale)
    std::printf(
        "the contact response added energy in %d steps, at most %.3g J (step %lld; the scene's "
        "energy scale is %.3g J): StepReport::contact_work, see docs/contact.md#limits\n",
        o.contact_work_steps, o.most_contact_work, o.most_contact_work_at, o.guard_scale);
  std::fflush(stdout);
}

// Says why the run stopped early, if it did, and returns the exit status: kExitDiverged after a
// divergence (with the stable step's hint for an explicit integrator), 128 + the signal after an
// interruption, kExitBadInput when an output failed at the end, 0 otherwise.
inline int exit_status(const Config& c, const Plan& p, const Outcome& o, bool failed) {
  const std::string range = std::to_string(p.first_frame) + "..";
  const std::string hint = o.diverged_at > 0 ? p.hint.text(p.dt, p.integrator) : "";
  auto print_hint = [&] {
    if (!hint.empty()) std::fprintf(stderr, "massspring-simulate: %s\n", hint.c_str());
  };
  if (o.diverged_at > 0 && o.blew_up) {
    std::fprintf(stderr,
                 "massspring-simulate: step %lld: the total energy passed the divergence limit "
                 "(%.6g J: the initial energy + %g x the scale %.6g J), or the step gained more "
                 "than %g x the scale, the integrator's own bound; stopped with the last good "
                 "state (steps %s%lld written)\n",
                 o.diverged_at, o.guard_limit, c.guard_growth, o.guard_scale, c.guard_growth,
                 range.c_str(), o.diverged_at - 1);
    if (o.contact_refused)
      std::fprintf(stderr,
                   "massspring-simulate: in that step the contact response added %.6g J, more "
                   "than half the scale: it pushed points against the springs "
                   "(StepReport::contact_work, see docs/contact.md#limits)\n",
                   o.failed_contact_work);
    else if (p.kind == massspring::IntegratorKind::LinearizedBackwardEuler)
      std::fprintf(stderr,
                   "massspring-simulate: %s also refuses a step whose one linear solve raises the "
                   "incremental potential it linearises (its linear model failed, "
                   "StepReport::blew_up); backward-euler (Newton) or a smaller --dt holds it\n",
                   p.integrator.c_str());
    print_hint();
    return kExitDiverged;
  }
  if (o.diverged_at > 0) {
    std::fprintf(stderr,
                 "massspring-simulate: step %lld: %s; stopped with the last %s state (steps %s%lld "
                 "written)\n",
                 o.diverged_at,
                 o.unresolved ? "surface contact left a crossing its rounds could not remove"
                              : "the step produced a non-finite state",
                 o.unresolved ? "good" : "finite", range.c_str(), o.diverged_at - 1);
    print_hint();
    return kExitDiverged;
  }
  if (o.interrupted_at >= 0) {
    std::fprintf(stderr,
                 "massspring-simulate: interrupted at frame %lld; frames %s%lld written%s\n",
                 o.interrupted_at, range.c_str(), o.interrupted_at,
                 c.every > 1 ? " (every --every-th and the last)" : "");
    return 128 + o.signal;
  }
  return failed ? kExitBadInput : 0;
}

// A saved state's contact dual variables, into the solver: one [x, y, z] per point, numbers.
template <class System, class Solver>
void restore_duals(const Config& c, const Setup<System>& s, const nlohmann::json& rows,
                   Solver& solver) {
  using Points = typename Solver::PointsType;
  using Scalar = typename System::Scalar;
  if (rows.size() != std::size_t(s.system.num_points()))
    throw Error(c.scene + ": key \"run\": \"contact_duals\" has " + std::to_string(rows.size()) +
                " rows for " + std::to_string(s.system.num_points()) + " points");
  Points u(s.system.num_points(), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const nlohmann::json& row = rows[i];
    if (!row.is_array() || row.size() != 3 || !row[0].is_number() || !row[1].is_number() ||
        !row[2].is_number())
      throw Error(c.scene + ": key \"run\": \"contact_duals\" row " + std::to_string(i) +
                  " is not three numbers: " + row.dump());
    for (int k = 0; k < 3; ++k) u(Eigen::Index(i), k) = Scalar(row[std::size_t(k)].get<double>());
  }
  try {
    solver.set_contact_duals(u);
  } catch (const massspring::Error& e) {
    throw Error(c.scene + ": key \"run\": \"contact_duals\": " + e.what());
  }
}

// A run with one integrator: configure and precompute, open the outputs, step, close the
// outputs, report; returns the exit status.
template <class System, class Solver>
int loop(const Config& c, Setup<System>& s, const Plan& p, Solver& solver,
         const std::string& integrator) {
  configure<System>(c, p, solver);
  const std::string what = describe<System>(c, solver, integrator);
  const double precompute_ms = timed_precompute(solver, s.system, p.dt);
  if constexpr (has_contact_term<System, Solver>)
    if (p.saved_duals && c.contact_weight > 0) restore_duals(c, s, *p.saved_duals, solver);
  // Every check has passed: from here on files are written.
  RunFiles<System> files(c, s, p);
  print_header(c, s, p, what, precompute_ms);
  Outcome o;
  try {
    o = run_steps(c, s, p, solver, files);
  } catch (const std::exception& e) {
    throw Error(std::string(e.what()) + files.where());
  }
  const std::vector<std::string> failures = finish(c, s, p, solver, files, o.frame);
  print_times(c, o);
  for (const std::string& f : failures)
    std::fprintf(stderr, "massspring-simulate: %s\n", f.c_str());
  return exit_status(c, p, o, !failures.empty());
}

template <class System>
int run(const Config& c, Setup<System>& s) {
  using Scalar = typename System::Scalar;
  const Plan p = resolve(c, s);
  // --self-collision replaces the scene's own "self_collision" (kept when it is absent); it acts
  // on the surface, so a scene without polygons is refused before anything is written.
  if (c.self_collision) {
    if (s.system.surface().rows() == 0)
      throw Error("--self-collision: " + s.name +
                  " has no surface to collide (no polygons: chains, nets and XML scenes have "
                  "none)");
    massspring::contact::SelfCollision<Scalar> parameters;
    parameters.thickness = Scalar(*c.self_collision);
    try {
      s.system.set_self_collision(parameters);
    } catch (const Error& e) {
      throw Error(std::string("--self-collision: ") + e.what());
    }
  }

  // Outputs: checked before anything is written or a step is taken.
  check_output_file("--csv", c.csv, s.inputs, {c.save_state, c.html, c.pc2}, c.overwrite);
  check_output_file("--save-state", c.save_state, s.inputs, {c.csv, c.html, c.pc2}, c.overwrite);
  check_output_folder(
      c.out, s.inputs,
      {c.csv, c.save_state, c.html, c.pc2, c.pc2.empty() ? fs::path() : rest_mesh_of(c.pc2)},
      c.overwrite);
  check_exports(c, s.inputs);

  System& system = s.system;
  // JSON and generated scenes get --gravity and --force as force terms (an XML scene or a saved
  // state has its own). Every integrator reads them from the system; FastMassSpring treats both
  // exactly, and the divergence guard sees their energy.
  // A JSON scene with "gravity" carries its own Gravity term (make_system() added it): the
  // default --gravity is then not added, and a --gravity given is refused.
  if (!s.fosssim && !s.state) {
    const bool own_gravity =
        system.forces().template find<massspring::Gravity<Scalar>>() != nullptr;
    if (own_gravity && c.gravity_given)
      throw Error("--gravity: " + s.name +
                  " carries its own gravity (its key \"gravity\"); change it there, or leave "
                  "out --gravity");
    massspring::Vector3<Scalar> gravity, force;
    for (int k = 0; k < 3; ++k) {
      gravity(k) = Scalar(c.gravity[std::size_t(k)]);
      force(k) = Scalar(c.force[std::size_t(k)]);
    }
    if (!gravity.isZero() && !own_gravity) system.add_force(massspring::Gravity<Scalar>(gravity));
    if (!force.isZero()) system.add_force(massspring::ConstantForce<Scalar>(force));
  }
  if (!c.save_state.empty())
    for (int k = 0; k < system.forces().size(); ++k) {
      const std::string term = system.forces()[k].name;
      if (!massspring::io::state_holds_force_term(term))
        throw Error("--save-state " + c.save_state + ": " + s.name + " has a " + term +
                    " term, which a state file cannot hold (it holds " +
                    massspring::io::state_force_terms_text() + ")");
    }

  Plan plan = p;
  plan.hint = StabilityHint::at(p.kind, system);
  return massspring::with_integrator<System>(
      p.kind, [&](auto& solver) { return loop(c, s, plan, solver, p.integrator); });
}

}  // namespace simulate
