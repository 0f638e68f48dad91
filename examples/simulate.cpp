// massspring-simulate: runs a scene (a JSON+OBJ file or a generated one) with the local-global
// solver, writes OBJ frames and a CSV trajectory, and prints the time per frame.
//
//   massspring-simulate examples/scenes/flag.json --frames 300 --out frames --csv traj.csv
//   massspring-simulate --generate cloth:60x50 --gravity 0,-9.8,0
//   massspring-simulate flag.json --gravity 0,0,0 --force 0,-9.8,0 --pins penalty
//       (the assignment's conventions, for its own scenes)
//
// Exit status: 0 on success, 1 for invalid input, 2 when a step diverged (the frames written so
// far are kept).

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <massspring/io.hpp>
#include <massspring/massspring.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using massspring::Error;

struct Config {
  std::string scene;     // a .json scene file, or empty
  std::string generate;  // cloth[:CxR], chain[:N], net[:CxR], or empty
  int frames = 300;
  double dt = 1.0 / 30;
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
  }

 private:
  fs::path path_, tmp_;
  std::ofstream out_;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const double at = p * double(v.size() - 1);
  const auto lo = std::size_t(at);
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (at - double(lo)) * (v[hi] - v[lo]);
}

template <class System>
int run(const Config& c, const massspring::SceneDescription<double>& scene,
        const std::string& name) {
  using Scalar = typename System::Scalar;
  System system = massspring::make_system<System>(scene);
  massspring::FastMassSpring<System> solver;
  solver.options.iterations = c.iterations;
  solver.options.tolerance = Scalar(c.tolerance);
  solver.options.pins =
      c.pins == "penalty" ? massspring::PinMode::Penalty : massspring::PinMode::Exact;
  solver.options.penalty_weight = Scalar(c.penalty_weight);
  for (int k = 0; k < 3; ++k) {
    solver.options.external_force(k) = Scalar(c.force[std::size_t(k)]);
    solver.options.gravity(k) = Scalar(c.gravity[std::size_t(k)]);
  }
  if (std::is_same_v<Scalar, float> && solver.options.pins == massspring::PinMode::Penalty)
    std::cerr << "massspring-simulate: warning: penalty pins (w = " << c.penalty_weight
              << ") in float lose the rest of Q to rounding; use --pins exact\n";

  const auto t0 = std::chrono::steady_clock::now();
  solver.precompute(system, Scalar(c.dt));
  const double precompute_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!c.quiet)
    std::printf(
        "%s: %d points, %d springs, %d pinned; %s, %s, %s pins; precompute %.2f ms "
        "(factor %lld nonzeros)\n",
        name.c_str(), system.num_points(), system.num_springs(), system.num_pinned(),
        c.storage.c_str(), c.precision.c_str(), c.pins.c_str(), precompute_ms,
        static_cast<long long>(solver.factor_nonzeros()));

  if (!c.out.empty()) fs::create_directories(c.out);
  std::optional<TrajectoryCsv> csv;
  if (!c.csv.empty()) csv.emplace(c.csv);
  auto write_frame = [&](int frame) {
    if (frame % c.every != 0 && frame != c.frames) return;
    if (!c.out.empty()) {
      char file[32];
      std::snprintf(file, sizeof file, "frame_%05d.obj", frame);
      massspring::io::write_obj(fs::path(c.out) / file, system.positions(), scene.faces,
                                scene.edges);
    }
    if (csv) csv->write(frame, system);
  };
  write_frame(0);

  std::vector<double> ms;
  ms.reserve(std::size_t(c.frames));
  long long iterations = 0;
  int diverged_at = -1;
  for (int frame = 1; frame <= c.frames; ++frame) {
    const auto start = std::chrono::steady_clock::now();
    const massspring::StepReport report = solver.step(system);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count());
    iterations += report.iterations;
    if (!report.ok()) {
      diverged_at = frame;
      break;
    }
    write_frame(frame);
  }
  if (csv) csv->close();

  const int done = int(ms.size()) - (diverged_at > 0 ? 1 : 0);
  if (!c.quiet)
    std::printf("%d frames, %.2f iterations per frame: median %.3f ms per frame "
                "(mean %.3f, p10 %.3f, p90 %.3f, max %.3f)\n",
                done, ms.empty() ? 0.0 : double(iterations) / double(ms.size()),
                percentile(ms, 0.5), ms.empty() ? 0.0 : [&] {
                  double s = 0;
                  for (double x : ms) s += x;
                  return s / double(ms.size());
                }(),
                percentile(ms, 0.1), percentile(ms, 0.9), percentile(ms, 1.0));
  else
    std::printf("%.3f\n", percentile(ms, 0.5));
  if (diverged_at > 0) {
    std::fprintf(stderr,
                 "massspring-simulate: frame %d: the step produced a non-finite state; stopped "
                 "with the last finite state (frames 0..%d written)\n",
                 diverged_at, diverged_at - 1);
    return 2;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Config c;
  CLI::App app{"Simulate a mass-spring scene with the local-global solver (Liu et al. 2013)."};
  app.add_option("scene", c.scene, "Scene file (.json + .obj, the assignment's format)");
  app.add_option("--generate", c.generate,
                 "Generate the scene instead: cloth[:COLSxROWS], chain[:POINTS], net[:COLSxROWS]");
  app.add_option("--frames", c.frames, "Frames (steps) to simulate")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--dt", c.dt, "Time step [s]")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--iterations", c.iterations, "Most local-global iterations per step")
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
  app.add_option("--force", c.force, "Force on every point [N], FX,FY,FZ")
      ->delimiter(',')
      ->expected(3)
      ->capture_default_str();
  app.add_option("--gravity", c.gravity, "Acceleration of every point [m/s^2], GX,GY,GZ")
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
  app.add_flag("--quiet", c.quiet, "Print only the median milliseconds per frame");
  CLI11_PARSE(app, argc, argv);

  try {
    if (c.scene.empty() == c.generate.empty())
      throw Error("give either a scene file or --generate (see --help)");
    for (const auto& v : {c.force, c.gravity})
      for (double x : v)
        if (!std::isfinite(x)) throw Error("--force and --gravity must be finite");
    const massspring::SceneDescription<double> scene =
        c.scene.empty() ? generated(c.generate) : massspring::io::read_json_scene(c.scene);
    const std::string name = c.scene.empty() ? c.generate : c.scene;
    using massspring::Dense;
    using massspring::MassSpringSystem;
    using massspring::Sparse;
    const bool dense = c.storage == "dense", single = c.precision == "float";
    if (dense && single) return run<MassSpringSystem<float, Dense>>(c, scene, name);
    if (dense) return run<MassSpringSystem<double, Dense>>(c, scene, name);
    if (single) return run<MassSpringSystem<float, Sparse>>(c, scene, name);
    return run<MassSpringSystem<double, Sparse>>(c, scene, name);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "massspring-simulate: %s\n", e.what());
    return 1;
  }
}
