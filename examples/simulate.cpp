// massspring-simulate: runs a scene (a JSON+OBJ file, a FOSSSim XML file or a generated one),
// writes OBJ frames and a CSV trajectory, and prints the time per step.
//
//   massspring-simulate examples/scenes/flag.json --frames 300 --out frames --csv traj.csv
//   massspring-simulate --generate cloth:60x50 --gravity 0,-9.8,0
//   massspring-simulate flag.json --gravity 0,0,0 --force 0,-9.8,0 --pins penalty
//       (the assignment's conventions, for its own scenes)
//   massspring-simulate examples/scenes_xml/orbit.xml --integrator forward-euler --every 10 --out f
//       (an XML scene runs with the integrator it names, its dt, for its duration, unless the
//        options say otherwise)
//
// Exit status: 0 on success, 1 for invalid input, 2 when a step diverged (the frames written so
// far are kept), 130 when interrupted by SIGINT or SIGTERM (the current step is finished and its
// frame written, the CSV closed). Every output file is written to <file>.tmp and renamed into
// place, so no reader ever sees a truncated frame or CSV.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <massspring/io.hpp>
#include <massspring/massspring.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace {

namespace fs = std::filesystem;
using massspring::Edges;
using massspring::Error;

// Set by SIGINT and SIGTERM; the step loop stops after the step in progress.
volatile std::sig_atomic_t g_interrupted = 0;  // NOLINT: written by a signal handler

extern "C" void on_interrupt(int) { g_interrupted = 1; }

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  // writes in progress continue; a second signal ends the program at once (the files already
  // renamed into place are whole; a .tmp file may be left)
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

constexpr int kExitInterrupted = 130;  // 128 + SIGINT, as shells report it

struct Config {
  std::string scene;     // a .json or .xml scene file, or empty
  std::string generate;  // cloth[:CxR], chain[:N], net[:CxR], or empty
  int frames = 300;      // XML scenes: ceil(duration / dt) unless given
  bool frames_given = false;
  double dt = 1.0 / 30;  // XML scenes: the scene's unless given
  bool dt_given = false;
  std::string integrator;  // empty: the XML scene's, else fast-mass-spring
  double shrink = 0;       // rest lengths l0(t) = l0(0) exp(-shrink t)
  int iterations = 50;
  double tolerance = 0;
  std::string pins = "exact";
  double penalty_weight = 1e10;
  std::vector<double> force{0, 0, 0};
  std::vector<double> gravity{0, -9.8, 0};
  std::string storage = "sparse";
  std::string precision = "double";
  std::string out;  // folder for frame_NNNNN.obj
  std::string csv;  // trajectory file
  int every = 1;
  bool quiet = false;
  double guard_growth = 100;  // DivergenceGuard growth; 0: no energy check
};

// "cloth:60x50" -> the generator's scene.
massspring::SceneDescription<double> generated(const std::string& spec) {
  const auto colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  const std::string size = colon == std::string::npos ? "" : spec.substr(colon + 1);
  int a = 0, b = 0;
  auto parse_size = [&](bool two) {
    if (size.empty()) return false;
    char x = 0, extra = 0;
    std::istringstream in(size);
    const bool ok = two ? bool(in >> a >> x >> b) && x == 'x' && !(in >> extra)
                        : bool(in >> a) && !(in >> extra);
    if (!ok)
      throw Error("--generate " + spec + ": expected " + kind +
                  (two ? ":COLUMNSxROWS" : ":POINTS") + " with whole numbers");
    return true;
  };
  if (kind == "cloth") {
    massspring::ClothOptions o;
    if (parse_size(true)) o.columns = a, o.rows = b;
    return massspring::make_cloth(o);
  }
  if (kind == "chain") {
    massspring::ChainOptions o;
    if (parse_size(false)) o.points = a;
    return massspring::make_chain(o);
  }
  if (kind == "net") {
    massspring::NetOptions o;
    if (parse_size(true)) o.columns = a, o.rows = b;
    return massspring::make_net(o);
  }
  throw Error("--generate " + spec + ": unknown generator \"" + kind +
              "\" (expected cloth, chain or net)");
}

// Streams frame, point, x, y, z, vx, vy, vz rows into <path>.tmp; renamed into place at close.
class TrajectoryCsv {
 public:
  explicit TrajectoryCsv(const std::string& path) : path_(path), tmp_(path + ".tmp") {
    out_.open(tmp_);
    if (!out_) throw Error(path + ": cannot open for writing");
    out_.precision(17);
    out_ << "frame,point,x,y,z,vx,vy,vz\n";
  }
  template <class System>
  void write(int frame, const System& s) {
    for (int i = 0; i < s.num_points(); ++i) {
      out_ << frame << ',' << i;
      for (int c = 0; c < 3; ++c) out_ << ',' << double(s.positions()(i, c));
      for (int c = 0; c < 3; ++c) out_ << ',' << double(s.velocities()(i, c));
      out_ << '\n';
    }
  }
  void close() {
    out_.close();
    if (!out_) throw Error(path_.string() + ": write failed");
    fs::rename(tmp_, path_);
    closed_ = true;
  }
  // An unfinished CSV (an error while running) leaves no temporary file behind.
  ~TrajectoryCsv() {
    if (closed_) return;
    out_.close();
    std::error_code ignored;
    fs::remove(tmp_, ignored);
  }
  TrajectoryCsv(const TrajectoryCsv&) = delete;
  TrajectoryCsv& operator=(const TrajectoryCsv&) = delete;

 private:
  fs::path path_, tmp_;
  std::ofstream out_;
  bool closed_ = false;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const double at = p * double(v.size() - 1);
  const auto lo = std::size_t(at);
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (at - double(lo)) * (v[hi] - v[lo]);
}

// What a run needs besides the options: the system, what to draw, the step and the step count.
template <class System>
struct Setup {
  System system;
  std::vector<std::vector<int>> faces;  // drawn in the OBJ frames
  Edges edges;                          // drawn in the OBJ frames (XML: every edge, springs or not)
  double dt = 0;
  int steps = 0;
  std::string integrator;  // forward-euler, symplectic-euler, backward-euler, ...
  std::string name;
  bool from_xml = false;
};

const char* const kIntegrators[] = {"forward-euler", "symplectic-euler", "backward-euler",
                                    "linearized-backward-euler", "fast-mass-spring"};

// FOSSSim's integrator names -> ours.
std::string our_integrator(massspring::io::FosssimIntegrator i) {
  using massspring::io::FosssimIntegrator;
  switch (i) {
    case FosssimIntegrator::ExplicitEuler:
      return "forward-euler";
    case FosssimIntegrator::SymplecticEuler:
      return "symplectic-euler";
    case FosssimIntegrator::LinearizedImplicitEuler:
      return "linearized-backward-euler";
    case FosssimIntegrator::ImplicitEuler:
      return "backward-euler";
  }
  return "symplectic-euler";
}

// The step loop shared by every integrator: time each step, write frames, stop on divergence.
template <class System, class Solver>
int loop(const Config& c, Setup<System>& s, Solver& solver, const std::string& what) {
  using Scalar = typename System::Scalar;
  System& system = s.system;
  const auto t0 = std::chrono::steady_clock::now();
  solver.precompute(system, Scalar(s.dt));
  const double precompute_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!c.quiet)
    std::printf(
        "%s: %d points, %d springs, %d pinned, %d force terms; %s, dt %g s, %d steps (%g s); %s, "
        "%s; precompute %.2f ms\n",
        s.name.c_str(), system.num_points(), system.num_springs(), system.num_pinned(),
        system.forces().size(), what.c_str(), s.dt, s.steps, s.dt * s.steps, c.storage.c_str(),
        c.precision.c_str(), precompute_ms);

  if (!c.out.empty()) fs::create_directories(c.out);
  std::optional<TrajectoryCsv> csv;
  if (!c.csv.empty()) csv.emplace(c.csv);
  // `always`: the last frame of an interrupted run is written whatever --every says.
  int last_written = -1;
  auto write_frame = [&](int frame, bool always = false) {
    if (frame == last_written) return;
    if (frame % c.every != 0 && frame != s.steps && !always) return;
    last_written = frame;
    if (!c.out.empty()) {
      char file[32];
      std::snprintf(file, sizeof file, "frame_%05d.obj", frame);
      massspring::io::write_obj(fs::path(c.out) / file, system.positions(), s.faces, s.edges);
    }
    if (csv) csv->write(frame, system);
  };
  write_frame(0);

  const massspring::Vector<Scalar> rest = system.rest_lengths();
  std::vector<double> ms;
  ms.reserve(std::size_t(std::min(s.steps, 1 << 20)));
  long long iterations = 0;
  int diverged_at = -1;
  bool blew_up = false;
  int interrupted_at = -1;
  // The energy check (off with --guard-growth 0): a step whose total energy passes
  // E(0) + growth x scale is undone and stops the run, like a non-finite one.
  std::optional<massspring::DivergenceGuard<System>> guard;
  if (c.guard_growth > 0) guard.emplace(system, massspring::DivergenceOptions{c.guard_growth});
  for (int step = 1; step <= s.steps; ++step) {
    if (g_interrupted) {  // SIGINT or SIGTERM since the last step: keep its frame, stop
      interrupted_at = step - 1;
      write_frame(step - 1, true);
      break;
    }
    if (c.shrink > 0)  // free: rest lengths do not change any matrix
      system.set_rest_lengths(rest * Scalar(std::exp(-c.shrink * s.dt * (step - 1))));
    const auto start = std::chrono::steady_clock::now();
    const massspring::StepReport report = guard ? guard->step(solver, system) : solver.step(system);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count());
    iterations += report.iterations;
    if (!report.ok()) {
      diverged_at = step;
      blew_up = report.blew_up;
      break;
    }
    write_frame(step);
  }
  if (csv) csv->close();

  const int done = int(ms.size()) - (diverged_at > 0 ? 1 : 0);
  if (!c.quiet)
    std::printf("%d steps, %.2f iterations per step: median %.3f ms per step "
                "(mean %.3f, p10 %.3f, p90 %.3f, max %.3f)\n",
                done, ms.empty() ? 0.0 : double(iterations) / double(ms.size()),
                percentile(ms, 0.5), ms.empty() ? 0.0 : [&] {
                  double sum = 0;
                  for (double x : ms) sum += x;
                  return sum / double(ms.size());
                }(),
                percentile(ms, 0.1), percentile(ms, 0.9), percentile(ms, 1.0));
  else
    std::printf("%.3f\n", percentile(ms, 0.5));
  if (diverged_at > 0 && blew_up) {
    std::fprintf(stderr,
                 "massspring-simulate: step %d: the total energy passed the divergence limit "
                 "(%.6g J: the initial energy + %g x the scale %.6g J); stopped with the last good "
                 "state (steps 0..%d written)\n",
                 diverged_at, guard->limit(), c.guard_growth, guard->scale(), diverged_at - 1);
    return 2;
  }
  if (diverged_at > 0) {
    std::fprintf(stderr,
                 "massspring-simulate: step %d: the step produced a non-finite state; stopped "
                 "with the last finite state (steps 0..%d written)\n",
                 diverged_at, diverged_at - 1);
    return 2;
  }
  if (interrupted_at >= 0) {
    std::fprintf(stderr, "massspring-simulate: interrupted at frame %d; frames 0..%d written%s\n",
                 interrupted_at, interrupted_at,
                 c.every > 1 ? " (every --every-th and the last)" : "");
    return kExitInterrupted;
  }
  return 0;
}

template <class System>
int run(const Config& c, Setup<System>& s) {
  using Scalar = typename System::Scalar;
  System& system = s.system;
  massspring::Vector3<Scalar> gravity, force;
  for (int k = 0; k < 3; ++k) {
    gravity(k) = Scalar(c.gravity[std::size_t(k)]);
    force(k) = Scalar(c.force[std::size_t(k)]);
  }
  // Every integrator reads every force from the system: JSON and generated scenes get the
  // --gravity and --force options as force terms (an XML scene has its own). FastMassSpring
  // treats both exactly, and the divergence guard sees their energy.
  if (!s.from_xml) {
    if (!gravity.isZero()) system.add_force(massspring::Gravity<Scalar>(gravity));
    if (!force.isZero()) system.add_force(massspring::ConstantForce<Scalar>(force));
  }
  if (s.integrator == "fast-mass-spring") {
    massspring::FastMassSpring<System> solver;
    solver.options.iterations = c.iterations;
    solver.options.tolerance = Scalar(c.tolerance);
    solver.options.pins =
        c.pins == "penalty" ? massspring::PinMode::Penalty : massspring::PinMode::Exact;
    solver.options.penalty_weight = Scalar(c.penalty_weight);
    if (std::is_same_v<Scalar, float> && solver.options.pins == massspring::PinMode::Penalty)
      std::cerr << "massspring-simulate: warning: penalty pins (w = " << c.penalty_weight
                << ") in float lose the rest of Q to rounding; use --pins exact\n";
    return loop(c, s, solver, "fast-mass-spring (" + c.pins + " pins)");
  }
  if (s.integrator == "forward-euler") {
    massspring::ForwardEuler<System> solver;
    return loop(c, s, solver, s.integrator);
  }
  if (s.integrator == "symplectic-euler") {
    massspring::SymplecticEuler<System> solver;
    return loop(c, s, solver, s.integrator);
  }
  massspring::BackwardEuler<System> solver;
  solver.options.mode = s.integrator == "backward-euler"
                            ? massspring::BackwardEulerMode::Newton
                            : massspring::BackwardEulerMode::Linearized;
  return loop(c, s, solver, s.integrator);
}

template <class System>
int run_scene(const Config& c) {
  Setup<System> s{};
  s.name = c.scene.empty() ? c.generate : c.scene;
  fs::path path = c.scene;
  std::string extension = path.extension().string();
  for (char& ch : extension) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  if (!c.scene.empty() && extension == ".xml") {
    const massspring::io::FosssimScene scene = massspring::io::read_fosssim_scene(path);
    s.system = massspring::io::make_fosssim_system<System>(scene);
    s.edges = scene.edges;
    s.from_xml = true;
    s.dt = c.dt_given ? c.dt : scene.dt;
    const long long steps = c.frames_given ? c.frames : scene.steps_for(s.dt);
    if (steps > 100000000) throw Error(c.scene + ": more than 10^8 steps; give --frames or --dt");
    s.steps = int(steps);
    s.integrator = c.integrator.empty() ? our_integrator(scene.integrator) : c.integrator;
  } else {
    const massspring::SceneDescription<double> scene =
        c.scene.empty() ? generated(c.generate) : massspring::io::read_json_scene(c.scene);
    s.system = massspring::make_system<System>(scene);
    s.faces = scene.faces;
    s.edges = scene.edges;
    s.dt = c.dt;
    s.steps = c.frames;
    s.integrator = c.integrator.empty() ? "fast-mass-spring" : c.integrator;
  }
  return run(c, s);
}

}  // namespace

int main(int argc, char** argv) {
  Config c;
  CLI::App app{
      "Simulate a mass-spring scene: local-global (Liu et al. 2013), forward, symplectic or "
      "backward Euler."};
  app.add_option("scene", c.scene,
                 "Scene file: .json (+ .obj, the assignment's format) or .xml (FOSSSim's)");
  app.add_option("--generate", c.generate,
                 "Generate the scene instead: cloth[:COLSxROWS], chain[:POINTS], net[:COLSxROWS]");
  auto* frames = app.add_option("--frames", c.frames,
                                "Steps to simulate (XML scenes: ceil(duration / dt) by default)")
                     ->check(CLI::NonNegativeNumber)
                     ->capture_default_str();
  auto* dt = app.add_option("--dt", c.dt, "Time step [s] (XML scenes: the scene's by default)")
                 ->check(CLI::PositiveNumber)
                 ->capture_default_str();
  app.add_option("--integrator", c.integrator,
                 "Integrator (default: the XML scene's; fast-mass-spring for other scenes)")
      ->check(CLI::IsMember(
          std::vector<std::string>(std::begin(kIntegrators), std::end(kIntegrators))));
  app.add_option("--shrink", c.shrink,
                 "Shrink every rest length as l0(t) = l0(0) exp(-RATE t) [1/s] (0: never)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--iterations", c.iterations,
                 "Most local-global iterations per step (fast-mass-spring)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--tolerance", c.tolerance,
                 "Stop iterating when the relative energy decrease is <= this (0: never)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--pins", c.pins, "How pinned points are held")
      ->check(CLI::IsMember({"exact", "penalty"}))
      ->capture_default_str();
  app.add_option("--penalty-weight", c.penalty_weight, "Penalty weight w for --pins penalty [N/m]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--force", c.force, "Force on every point [N], FX,FY,FZ (not XML scenes)")
      ->delimiter(',')
      ->expected(3)
      ->capture_default_str();
  app.add_option("--gravity", c.gravity,
                 "Acceleration of every point [m/s^2], GX,GY,GZ (XML scenes: the scene's)")
      ->delimiter(',')
      ->expected(3)
      ->capture_default_str();
  app.add_option("--storage", c.storage, "Matrix storage")
      ->check(CLI::IsMember({"sparse", "dense"}))
      ->capture_default_str();
  app.add_option("--precision", c.precision, "Scalar type")
      ->check(CLI::IsMember({"double", "float"}))
      ->capture_default_str();
  app.add_option("--out", c.out, "Write frame_NNNNN.obj files into this folder");
  app.add_option("--csv", c.csv, "Write the trajectory (frame,point,x,y,z,vx,vy,vz) here");
  app.add_option("--every", c.every, "Write every Nth frame (and the last)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--guard-growth", c.guard_growth,
                 "Stop when the total energy passes E(0) + G x scale (DivergenceGuard; the step "
                 "times then include its energy check); 0 turns the check off")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--quiet", c.quiet, "Print only the median milliseconds per frame");
  CLI11_PARSE(app, argc, argv);
  c.frames_given = frames->count() > 0;
  c.dt_given = dt->count() > 0;

  install_interrupt_handlers();
  try {
    if (c.scene.empty() == c.generate.empty())
      throw Error("give either a scene file or --generate (see --help)");
    for (const auto& v : {c.force, c.gravity})
      for (double x : v)
        if (!std::isfinite(x)) throw Error("--force and --gravity must be finite");
    using massspring::Dense;
    using massspring::MassSpringSystem;
    using massspring::Sparse;
    const bool dense = c.storage == "dense", single = c.precision == "float";
    if (dense && single) return run_scene<MassSpringSystem<float, Dense>>(c);
    if (dense) return run_scene<MassSpringSystem<double, Dense>>(c);
    if (single) return run_scene<MassSpringSystem<float, Sparse>>(c);
    return run_scene<MassSpringSystem<double, Sparse>>(c);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "massspring-simulate: %s\n", e.what());
    return 1;
  }
}
