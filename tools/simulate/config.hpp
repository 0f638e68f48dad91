#pragma once
// massspring-simulate's options as read from the command line (simulate.cpp), and what a run needs
// besides them (the loaded scene).

#include <filesystem>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/local_global/option_names.hpp>
#include <massspring/io.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace simulate {

namespace fs = std::filesystem;

/// The library's default options, which the command line's defaults are.
inline const massspring::FastMassSpringOptions<double> kFastMassSpring{};
inline const massspring::BackwardEulerOptions<double> kBackwardEuler{};

/// Which option sets the length of the run.
enum class Length { Default, Steps, Frames, Duration };

struct Config {
  std::string scene;     // a .json or .xml scene file, or empty
  std::string generate;  // cloth[:CxR], chain[:N], net[:CxR], or empty
  // How long the run is: at most one of --steps, --frames, --duration; none: 300 steps (an XML
  // scene: its duration)
  Length length = Length::Default;
  long long steps = 300;  // --steps: steps to take
  long long frames = 0;   // --frames: frames written after the first; steps = frames x every
  double duration = 0;    // --duration [s]: the whole number of steps nearest duration / dt
  double progress = 10;   // --progress [s]: wall-clock seconds between progress lines; 0: none
  double dt = 1.0 / 30;
  bool dt_given = false;
  std::string integrator = "fast-mass-spring";
  bool integrator_given = false;
  double shrink = 0;  // rest lengths l0(t) = l0(0) exp(-shrink t)
  // FastMassSpringOptions, defaults the library's
  int iterations = kFastMassSpring.iterations;
  double tolerance = kFastMassSpring.tolerance;
  std::string pins = massspring::option_name(kFastMassSpring.pins);
  double penalty_weight = kFastMassSpring.penalty_weight;
  double contact_weight = kFastMassSpring.contact_weight;  // BackwardEuler's default is the same
  std::string acceleration = massspring::option_name(kFastMassSpring.acceleration);
  double chebyshev_rho = kFastMassSpring.chebyshev_rho;
  bool rho_given = false;
  double chebyshev_gamma = kFastMassSpring.chebyshev_gamma;
  int chebyshev_delay = kFastMassSpring.chebyshev_delay;
  int chebyshev_estimate = kFastMassSpring.chebyshev_estimate_iterations;
  int anderson_window = kFastMassSpring.anderson_window;
  int threads = kFastMassSpring.threads;
  std::string ordering = massspring::option_name(kFastMassSpring.ordering);
  std::string initial_guess = massspring::option_name(kFastMassSpring.initial_guess);
  // BackwardEulerOptions, defaults the library's
  int newton_iterations = kBackwardEuler.iterations;
  double newton_tolerance = kBackwardEuler.tolerance;
  std::string line_search = kBackwardEuler.line_search ? "on" : "off";
  // options given that belong to one integrator or acceleration
  std::vector<std::string> given_fast_mass_spring, given_chebyshev, given_anderson,
      given_backward_euler, given_contact;
  std::vector<double> force{0, 0, 0};
  std::vector<double> gravity{0, -9.8, 0};
  bool force_given = false, gravity_given = false;
  std::string storage = "sparse";
  std::string precision = "double";
  std::string out;         // folder for frame_NNNNN.obj
  std::string csv;         // trajectory file
  std::string save_state;  // state file
  std::string html;        // --html: the page that plays the run
  std::string pc2;         // --pc2: Blender point cache (FILE.pc2, rest mesh FILE.obj)
  std::string vtk;         // --vtk: folder for ParaView frames and run.pvd
  int save_every = 0;
  bool overwrite = false;
  int every = 1;
  bool quiet = false;
  double guard_growth = 100;  // DivergenceGuard growth; 0: no energy check
  // --self-collision: the thickness [m] (> 0), with the default friction; unset: the scene's own
  std::optional<double> self_collision;
};

// What a run needs besides the options.
template <class System>
struct Setup {
  System system;
  std::vector<std::vector<int>> faces;  // drawn in the OBJ frames
  massspring::Edges edges;              // drawn in the OBJ frames (XML: every edge)
  std::vector<fs::path> inputs;         // every file the run reads
  std::optional<massspring::io::FosssimScene> fosssim;
  std::optional<double> dt;  // a JSON+OBJ scene's "dt" [s]
  bool state = false;        // a state saved by --save-state
  nlohmann::json run_data;   // its "run" object
  std::string name;          // the scene file or "--generate SPEC"
};

}  // namespace simulate
