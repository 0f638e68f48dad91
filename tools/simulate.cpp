// massspring-simulate: runs a scene (a JSON+OBJ file, a FOSSSim XML file, a state file it saved,
// or a generated scene), writes OBJ frames and a CSV trajectory, and prints the time per step;
// optionally a page that plays the run in a browser, a Blender point cache and ParaView frames.
//
//   massspring-simulate examples/scenes/flag.json --duration 10 --every 3 --out frames
//       (10 s at dt 1/30: 300 steps, a frame written every 3rd: frames 0, 3, ..., 300)
//   massspring-simulate --generate cloth:60x50 --acceleration chebyshev --iterations 10
//   massspring-simulate flag.json --gravity 0,0,0 --force 0,-9.8,0 --pins penalty
//       (the JSON+OBJ scenes' conventions, for those scenes)
//   massspring-simulate examples/scenes_xml/orbit.xml --integrator forward-euler --every 10 --out f
//       (an XML scene runs with the integrator it names, its dt, for its duration, unless the
//        options say otherwise)
//   massspring-simulate flag.json --steps 10 --save-state s.json
//   massspring-simulate s.json --steps 10        (continues bit for bit: frames 11..20)
//   massspring-simulate examples/scenes/drape.json --duration 1.5 --every 6 --html drape.html
//       (open drape.html in a browser: orbit, zoom, play, scrub; strain as colour)
//   massspring-simulate examples/scenes/drape.json --self-collision 0.005
//       (self-collision of the cloth's surface, 5 mm thick; needs a scene with polygons)
//
// Exit status (docs/errors.md): 0 on success; 1 for invalid input or options, or an output that
// cannot be written (refused before the first step whenever it can be known then); 2 when a step
// diverged (the frames written so far are kept); 128 + the signal on SIGINT (130) or SIGTERM (143):
// the current step is finished and its frame written, the CSV closed, the state saved.
// Every message starts with "massspring-simulate: ". Outputs: see simulate/outputs.hpp
// and simulate/exports.hpp.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <massspring/io.hpp>
#include <massspring/io/state_scene.hpp>
#include <massspring/massspring.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "simulate/did_you_mean.hpp"
#include "simulate/numbers.hpp"
#include "simulate/run.hpp"

namespace {

namespace fs = std::filesystem;
using massspring::Error;
using simulate::Bound;
using simulate::Config;

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
  try {
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
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind("--generate", 0) == 0) throw;
    throw Error("--generate " + spec + ": " + what);
  }
  throw Error("--generate " + spec + ": unknown generator \"" + kind +
              "\" (expected cloth, chain or net)");
}

template <class System>
int run_scene(const Config& c) {
  simulate::Setup<System> s{};
  if (c.scene.empty()) {
    s.name = "--generate " + c.generate;
    const massspring::SceneDescription<double> scene = generated(c.generate);
    try {
      s.system = massspring::make_system<System>(scene);
    } catch (const Error& e) {
      throw Error(s.name + ": " + e.what());
    }
    s.faces = scene.faces;
    s.edges = scene.edges;
  } else {
    s.name = c.scene;
    massspring::io::LoadedScene<System> loaded = massspring::io::load_scene_file<System>(c.scene);
    s.system = std::move(loaded.system);
    s.faces = std::move(loaded.faces);
    s.edges = std::move(loaded.edges);
    s.inputs = std::move(loaded.files);
    s.fosssim = std::move(loaded.fosssim);
    s.state = loaded.state;
    s.run_data = std::move(loaded.run);
    s.dt = loaded.dt;
  }
  return simulate::run(c, s);
}

// The values of the options that take numbers or vectors, as given (read by
// simulate/numbers.hpp, whose messages quote the text); each starts as its default, written as
// numbers are in messages. The solvers' defaults are the library's (Config's, from
// FastMassSpringOptions and BackwardEulerOptions).
struct OptionText {
  explicit OptionText(const Config& c) {
    const auto text = [](auto x) { return massspring::detail::message(x); };
    iterations = text(c.iterations);
    tolerance = text(c.tolerance);
    penalty_weight = text(c.penalty_weight);
    contact_weight = text(c.contact_weight);
    rho = text(c.chebyshev_rho);
    gamma = text(c.chebyshev_gamma);
    delay = text(c.chebyshev_delay);
    estimate = text(c.chebyshev_estimate);
    window = text(c.anderson_window);
    threads = text(c.threads);
    newton_iterations = text(c.newton_iterations);
    newton_tolerance = text(c.newton_tolerance);
  }
  std::string steps = "300", frames, duration, progress = "10", dt = "0.0333333", shrink = "0",
              every = "1", guard_growth = "100", save_every = "0", self_collision;
  std::string iterations, tolerance, penalty_weight, contact_weight, rho, gamma, delay, estimate,
      window, threads, newton_iterations, newton_tolerance;
  std::vector<std::string> force{"0", "0", "0"}, gravity{"0", "-9.8", "0"};
};

// The options whose presence matters after parsing: which one set the run's length, what was
// given rather than defaulted, and the options of one integrator or one acceleration (refused
// with another: simulate/run.hpp).
struct GivenOptions {
  CLI::Option *steps = nullptr, *frames = nullptr, *duration = nullptr, *dt = nullptr,
              *integrator = nullptr, *force = nullptr, *gravity = nullptr,
              *self_collision = nullptr;
  std::vector<CLI::Option*> fast_mass_spring, chebyshev, anderson, backward_euler, contact;
};

// The scene: a file, or --generate.
void add_scene_options(CLI::App& app, Config& c) {
  app.add_option("scene", c.scene,
                 "Scene file: .json (+ .obj, the JSON+OBJ scene format; or a state saved by "
                 "--save-state) or .xml (FOSSSim's)");
  app.add_option("--generate", c.generate,
                 "Generate the scene instead: cloth[:COLSxROWS], chain[:POINTS], net[:COLSxROWS]")
      ->default_str("none");
}

// The length of the run (one of --steps, --frames, --duration; a saved state: after it), the
// step --dt, the integrator and --shrink.
void add_run_options(CLI::App& app, Config& c, OptionText& t, GivenOptions& g) {
  g.steps = app.add_option("--steps", t.steps,
                           "Steps of --dt to take (default when none of --steps, --frames, "
                           "--duration is given; an XML scene: its duration / dt)")
                ->capture_default_str();
  g.frames = app.add_option("--frames", t.frames,
                            "Frames to write after the first: takes FRAMES x --every steps")
                 ->default_str("none");
  g.duration = app.add_option("--duration", t.duration,
                              "Simulated time [s]: takes the whole number of steps "
                              "nearest duration / dt (at least one)")
                   ->default_str("none");
  g.dt = app.add_option("--dt", t.dt,
                        "Time step [s] (default: a scene's own, its \"dt\" or an XML "
                        "scene's; a saved state: its run's; else 1/30)")
             ->capture_default_str();
  g.integrator =
      app.add_option("--integrator", c.integrator,
                     "Integrator (default: an XML scene's or a saved state's; else "
                     "fast-mass-spring)")
          ->check(CLI::IsMember(massspring::integrator_names(massspring::IntegratorNaming::Cli)))
          ->default_str("fast-mass-spring");
  app.add_option("--shrink", t.shrink,
                 "Shrink every rest length as l0(t) = l0(0) exp(-RATE t) [1/s] (0: never)")
      ->capture_default_str();
}

// The solvers' options: fast-mass-spring's (with Chebyshev's and Anderson's), contact inside the
// solve, backward Euler's; each recorded in its group of `g`.
void add_solver_options(CLI::App& app, Config& c, OptionText& t, GivenOptions& g) {
  auto& fms = g.fast_mass_spring;
  fms.push_back(app.add_option("--iterations", t.iterations,
                               "fast-mass-spring: most local-global iterations per step")
                    ->capture_default_str());
  fms.push_back(app.add_option("--tolerance", t.tolerance,
                               "fast-mass-spring: stop iterating when the relative energy "
                               "decrease is <= this (0: never)")
                    ->capture_default_str());
  fms.push_back(app.add_option("--pins", c.pins, "fast-mass-spring: how pinned points are held")
                    ->check(CLI::IsMember(massspring::option_names<massspring::PinMode>()))
                    ->capture_default_str());
  fms.push_back(app.add_option("--penalty-weight", t.penalty_weight,
                               "fast-mass-spring: penalty weight w for --pins penalty [N/m]")
                    ->capture_default_str());
  g.contact.push_back(
      app.add_option("--contact-weight", t.contact_weight,
                     "fast-mass-spring, backward-euler, linearized-backward-euler: weight "
                     "alpha of contact and friction inside the solve (0: at the end of the "
                     "step only), relative to each point's sqrt(m (m + dt^2 k)) / dt^2 (k its "
                     "springs' summed stiffness). 1 suits at dt = 1/30: backward-euler, and "
                     "fast-mass-spring with --acceleration anderson or chebyshev "
                     "--initial-guess inertial")
          ->capture_default_str());
  fms.push_back(
      app.add_option("--acceleration", c.acceleration,
                     "fast-mass-spring: none, chebyshev (Wang 2015) or anderson (Peng et al. "
                     "2018)")
          ->check(CLI::IsMember(massspring::option_names<massspring::Acceleration>()))
          ->capture_default_str());
  g.chebyshev.push_back(
      app.add_option("--chebyshev-rho", t.rho,
                     "chebyshev: spectral radius rho in [0, 1); 0: estimated (a saved "
                     "state: the estimate its run used)")
          ->capture_default_str());
  g.chebyshev.push_back(
      app.add_option("--chebyshev-gamma", t.gamma, "chebyshev: under-relaxation in (0, 1]")
          ->capture_default_str());
  g.chebyshev.push_back(
      app.add_option("--chebyshev-delay", t.delay,
                     "chebyshev: plain iterations before the acceleration starts, >= 1")
          ->capture_default_str());
  g.chebyshev.push_back(app.add_option("--chebyshev-estimate-iterations", t.estimate,
                                       "chebyshev: trial iterations to estimate rho, >= 4")
                            ->capture_default_str());
  g.anderson.push_back(app.add_option("--anderson-window", t.window,
                                      "anderson: past iterates in the fit, 1 to " +
                                          std::to_string(massspring::kMaxAndersonWindow))
                           ->capture_default_str());
  fms.push_back(app.add_option("--threads", t.threads,
                               "fast-mass-spring: threads for the substitutions (sparse storage, "
                               "OpenMP), 1 to 256; the same result bit for bit")
                    ->capture_default_str());
  fms.push_back(app.add_option("--ordering", c.ordering,
                               "fast-mass-spring: fill-reducing order of the factor: auto (the "
                               "sparser of the other two), solver (AMD), nested-dissection")
                    ->check(CLI::IsMember(massspring::option_names<massspring::FillOrdering>()))
                    ->capture_default_str());
  fms.push_back(app.add_option("--initial-guess", c.initial_guess,
                               "fast-mass-spring: where iterations start: current "
                               "(X^t) or inertial (X^t + dt V^t)")
                    ->check(CLI::IsMember(massspring::option_names<massspring::InitialGuess>()))
                    ->capture_default_str());
  auto& be = g.backward_euler;
  be.push_back(app.add_option("--newton-iterations", t.newton_iterations,
                              "backward-euler: most Newton iterations per step")
                   ->capture_default_str());
  be.push_back(app.add_option("--newton-tolerance", t.newton_tolerance,
                              "backward-euler: stop when max |dx| <= this (1 + max |x|)")
                   ->capture_default_str());
  be.push_back(app.add_option("--line-search", c.line_search,
                              "backward-euler: backtracking line search, on or off")
                   ->check(CLI::IsMember({"on", "off"}))
                   ->capture_default_str());
}

// What acts on the scene besides its springs: --force and --gravity (three numbers, X,Y,Z) and
// --self-collision.
void add_force_options(CLI::App& app, OptionText& t, GivenOptions& g) {
  auto add_vector3 = [&app](const char* name, std::vector<std::string>& target, const char* help) {
    return app.add_option(name, target, help)
        ->delimiter(',')
        ->expected(3)
        ->capture_default_str()
        ->type_name("X,Y,Z");
  };
  g.force = add_vector3("--force", t.force,
                        "Force on every point [N], FX,FY,FZ, added as a ConstantForce term "
                        "(not for XML scenes or saved states: they carry their own)");
  g.gravity = add_vector3("--gravity", t.gravity,
                          "Acceleration of every point [m/s^2], GX,GY,GZ, added as a "
                          "Gravity term (not for scenes that carry their own: XML scenes, "
                          "saved states, JSON scenes with \"gravity\")");
  g.self_collision =
      app.add_option("--self-collision", t.self_collision,
                     "Self-collision of the surface (the scene's polygons) with this thickness "
                     "[m], > 0, and friction 0.2; refused for a scene without polygons (default: "
                     "the scene's \"self_collision\", else off)")
          ->default_str("none");
}

// The system's storage and precision, the outputs, and how the run reports: --every,
// --progress, --guard-growth, --quiet, --version.
void add_output_options(CLI::App& app, Config& c, OptionText& t) {
  app.add_option("--storage", c.storage, "Matrix storage: sparse or dense")
      ->check(CLI::IsMember({"sparse", "dense"}))
      ->capture_default_str();
  app.add_option("--precision", c.precision, "Scalar type: double or float")
      ->check(CLI::IsMember({"double", "float"}))
      ->capture_default_str();
  app.add_option("--out", c.out, "Write frame_NNNNN.obj files into this folder")
      ->default_str("none");
  app.add_option("--csv", c.csv, "Write the trajectory (frame,point,x,y,z,vx,vy,vz) here")
      ->default_str("none");
  app.add_option("--html", c.html,
                 "Write a page that plays the run in a web browser (three.js inlined: one file "
                 "that works offline): the surface or the springs coloured by strain, colliders, "
                 "pinned points; the frames written (--every, and the last)")
      ->default_str("none");
  app.add_option("--pc2", c.pc2,
                 "Write the frames as a Blender point cache FILE.pc2 (Mesh Cache modifier; "
                 "float32, a sample every --every frames) and its rest mesh FILE.obj")
      ->default_str("none");
  app.add_option("--vtk", c.vtk,
                 "Write the frames for ParaView into this folder: frame_NNNNN.vtu (velocity, "
                 "pinned, strain per spring and face) and run.pvd, the time series")
      ->default_str("none");
  app.add_option("--save-state", c.save_state,
                 "Save the final state here (a .json scene that resumes the run bit for bit)")
      ->default_str("none");
  app.add_option("--save-every", t.save_every,
                 "Also save the state every N steps (0: at the end only)")
      ->capture_default_str();
  app.add_flag("--overwrite", c.overwrite,
               "Replace existing output files, a stale .tmp, and the frame files in --out");
  app.add_option("--every", t.every,
                 "Write a frame every N steps (and the last); frame files are numbered by step")
      ->capture_default_str();
  app.add_option("--progress", t.progress,
                 "Print a progress line (step, simulated time, time left) every this many "
                 "seconds of wall-clock time [s]; 0: never (--quiet: never)")
      ->capture_default_str();
  app.add_option("--guard-growth", t.guard_growth,
                 "Stop when the total energy passes E(0) + G x scale (DivergenceGuard; the step "
                 "times then include its energy check); 0 turns the check off")
      ->capture_default_str();
  app.add_flag("--quiet", c.quiet, "Print only the median milliseconds per frame");
  app.set_version_flag("--version",
                       std::string("massspring-simulate ") + MASSSPRING_PROJECT_VERSION,
                       "Print the version (massspring-simulate MAJOR.MINOR.PATCH) and exit");
}

// --help names what each value is: INT, NUMBER or PATH (all numbers are taken as text).
void name_value_types(CLI::App& app) {
  static const std::vector<std::string> whole = {"--steps",
                                                 "--frames",
                                                 "--iterations",
                                                 "--chebyshev-delay",
                                                 "--chebyshev-estimate-iterations",
                                                 "--anderson-window",
                                                 "--threads",
                                                 "--newton-iterations",
                                                 "--every",
                                                 "--save-every"};
  static const std::vector<std::string> real = {"--dt",
                                                "--duration",
                                                "--progress",
                                                "--shrink",
                                                "--tolerance",
                                                "--penalty-weight",
                                                "--contact-weight",
                                                "--chebyshev-rho",
                                                "--chebyshev-gamma",
                                                "--newton-tolerance",
                                                "--guard-growth",
                                                "--self-collision"};
  static const std::vector<std::string> path = {"--out", "--csv", "--save-state", "--html",
                                                "--pc2", "--vtk", "scene"};
  auto in = [](const std::vector<std::string>& list, const std::string& name) {
    return std::find(list.begin(), list.end(), name) != list.end();
  };
  for (CLI::Option* o : app.get_options()) {
    const std::string name = o->get_name();
    if (in(whole, name)) o->type_name("INT");
    if (in(real, name)) o->type_name("NUMBER");
    if (in(path, name)) o->type_name("PATH");
  }
}

// Parses the command line into the options; on --help, --version or a parse error, the exit
// status (after printing the help, the version or the message), else nothing. Unexpected
// arguments are listed in the order given, with the option an unknown one most likely stands for.
std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ExtrasError&) {
    // the arguments in the order given (CLI11's own message lists them in reverse)
    const std::vector<std::string> extras = app.remaining();
    std::string listed;
    for (const std::string& a : extras) listed += (listed.empty() ? "" : " ") + a;
    std::fprintf(stderr,
                 "massspring-simulate: The following argument%s not expected: %s%s (see --help)\n",
                 extras.size() > 1 ? "s were" : " was", listed.c_str(),
                 simulate::did_you_mean(app, argc, argv).c_str());
    return simulate::kExitBadInput;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "massspring-simulate: %s (see --help)\n", e.what());
    return simulate::kExitBadInput;
  }
  return std::nullopt;
}

// Records in `c` which options were given (the length's option, --dt, --integrator, --gravity,
// --force, --chebyshev-rho, and the names of every integrator's and acceleration's options
// given). Throws Error when more than one of --steps, --frames and --duration is given.
void record_given(const GivenOptions& g, Config& c) {
  std::vector<std::string> lengths;
  for (CLI::Option* o : {g.steps, g.frames, g.duration})
    if (o->count() > 0) lengths.push_back(o->get_name());
  if (lengths.size() > 1)
    throw Error(lengths[0] + " and " + lengths[1] +
                ": give one of --steps, --frames and --duration");
  c.dt_given = g.dt->count() > 0;
  c.integrator_given = g.integrator->count() > 0;
  c.gravity_given = g.gravity->count() > 0;
  c.force_given = g.force->count() > 0;
  c.rho_given = g.chebyshev.front()->count() > 0;
  for (auto [list, names] :
       {std::pair{&g.fast_mass_spring, &c.given_fast_mass_spring},
        std::pair{&g.chebyshev, &c.given_chebyshev}, std::pair{&g.anderson, &c.given_anderson},
        std::pair{&g.backward_euler, &c.given_backward_euler},
        std::pair{&g.contact, &c.given_contact}})
    for (CLI::Option* o : *list)
      if (o->count() > 0) names->push_back(o->get_name());
}

// Reads every number and vector given as text into `c`, each checked against its range
// (simulate/numbers.hpp: Error naming the option and quoting the text), then the checks that
// need two options: a scene file or --generate (exactly one), --save-every with --save-state.
void read_values(const OptionText& t, const GivenOptions& g, Config& c) {
  using simulate::parse_integer;
  using simulate::parse_number;
  if (g.steps->count() > 0) {
    c.length = simulate::Length::Steps;
    c.steps = parse_integer("--steps", t.steps, 0, 100000000);
  } else if (g.frames->count() > 0) {
    c.length = simulate::Length::Frames;
    c.frames = parse_integer("--frames", t.frames, 0, 100000000);
  } else if (g.duration->count() > 0) {
    c.length = simulate::Length::Duration;
    c.duration = parse_number("--duration", t.duration, Bound::NonNegative);
  }
  c.progress = parse_number("--progress", t.progress, Bound::NonNegative);
  c.dt = c.dt_given ? parse_number("--dt", t.dt, Bound::Positive) : 1.0 / 30;
  c.shrink = parse_number("--shrink", t.shrink, Bound::NonNegative);
  c.iterations = int(parse_integer("--iterations", t.iterations, 1, 1000000));
  c.tolerance = parse_number("--tolerance", t.tolerance, Bound::NonNegative);
  c.penalty_weight = parse_number("--penalty-weight", t.penalty_weight, Bound::Positive);
  c.contact_weight = parse_number("--contact-weight", t.contact_weight, Bound::NonNegative);
  c.chebyshev_rho = parse_number("--chebyshev-rho", t.rho, Bound::UnitOpen);
  c.chebyshev_gamma = parse_number("--chebyshev-gamma", t.gamma, Bound::UnitHalfOpenAbove);
  c.chebyshev_delay = int(parse_integer("--chebyshev-delay", t.delay, 1, 1000000));
  c.chebyshev_estimate =
      int(parse_integer("--chebyshev-estimate-iterations", t.estimate, 4, 1000000));
  c.anderson_window =
      int(parse_integer("--anderson-window", t.window, 1, massspring::kMaxAndersonWindow));
  c.threads = int(parse_integer("--threads", t.threads, 1, 256));
  c.newton_iterations = int(parse_integer("--newton-iterations", t.newton_iterations, 1, 1000000));
  c.newton_tolerance = parse_number("--newton-tolerance", t.newton_tolerance, Bound::NonNegative);
  c.every = int(parse_integer("--every", t.every, 1, 100000000));
  c.save_every = int(parse_integer("--save-every", t.save_every, 0, 100000000));
  c.guard_growth = parse_number("--guard-growth", t.guard_growth, Bound::NonNegative);
  c.force = simulate::parse_vector3("--force", t.force);
  c.gravity = simulate::parse_vector3("--gravity", t.gravity);
  if (g.self_collision->count() > 0)
    c.self_collision = parse_number("--self-collision", t.self_collision, Bound::Positive);
  if (c.scene.empty() == c.generate.empty())
    throw Error("give either a scene file or --generate (see --help)");
  if (c.save_every > 0 && c.save_state.empty())
    throw Error("--save-every " + t.save_every + ": needs --save-state FILE");
}

// Runs the scene with the system type --storage and --precision name; the run's exit status.
int run_with_storage(const Config& c) {
  using massspring::Dense;
  using massspring::MassSpringSystem;
  using massspring::Sparse;
  const bool dense = c.storage == "dense", single = c.precision == "float";
  if (dense && single) return run_scene<MassSpringSystem<float, Dense>>(c);
  if (dense) return run_scene<MassSpringSystem<double, Dense>>(c);
  if (single) return run_scene<MassSpringSystem<float, Sparse>>(c);
  return run_scene<MassSpringSystem<double, Sparse>>(c);
}

}  // namespace

int main(int argc, char** argv) {
  Config c;
  OptionText text(c);
  GivenOptions given;
  CLI::App app{
      "Simulate a mass-spring scene: local-global (Liu et al. 2013), forward, symplectic or "
      "backward Euler. Exit status: 0 done, 1 invalid input or output, 2 diverged, 128+signal "
      "interrupted (130 SIGINT, 143 SIGTERM)."};
  app.get_formatter()->column_width(36);
  app.footer(
      "Outputs (--out, --csv, --html, --pc2, --vtk, --save-state): every one is checked before "
      "the first step; the missing folders of its path are created once every check has passed; "
      "an existing file is replaced only with --overwrite.");
  // in the order --help lists them
  add_scene_options(app, c);
  add_run_options(app, c, text, given);
  add_solver_options(app, c, text, given);
  add_force_options(app, text, given);
  add_output_options(app, c, text);
  name_value_types(app);
  if (const std::optional<int> status = parse_command_line(app, argc, argv)) return *status;

  try {
    record_given(given, c);
    read_values(text, given, c);
    simulate::install_interrupt_handlers();
    return run_with_storage(c);
  } catch (const std::exception& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "massspring-simulate: %s\n", e.what());
    return simulate::kExitBadInput;
  }
}
