// The FOSSSim scenes of ../shared/scenes/fosssim against closed forms, run with the integrator each
// scene names (explicit-euler -> ForwardEuler, symplectic-euler -> SymplecticEuler,
// linearized-implicit-euler -> BackwardEuler Linearized). Every oracle is a closed form of the
// scene's own numbers (the continuous solution, or the exact discrete solution of the scheme);
// every tolerance is either rounding or the scheme's own error term, derived in the test.
// MESSAGE lines give the worst error per scene folder.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <massspring/diagnostics/energy.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/forward_euler.hpp>
#include <massspring/integrators/symplectic_euler.hpp>
#include <massspring/io/fosssim_scene.hpp>
#include <string>
#include <vector>

#include "massspring/system/mass_spring_system.hpp"
#include "support/paths.hpp"

namespace {

namespace fs = std::filesystem;
using massspring::io::FosssimIntegrator;
using massspring::io::FosssimScene;
using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using Observer = std::function<void(const System&, long long step, double t)>;
constexpr double kEps = std::numeric_limits<double>::epsilon();
const double kPi = std::acos(-1.0);

fs::path fosssim_dir() { return massspring::test::shared_dir() / "scenes" / "fosssim"; }
bool have_fosssim() { return fs::is_directory(fosssim_dir()); }

// Every scene file of a folder kind ("SpringTests") across t1m1, t1m2, t1m3, sorted.
std::vector<fs::path> scenes_in(const std::string& folder) {
  std::vector<fs::path> files;
  for (const char* part : {"t1m1", "t1m2", "t1m3"}) {
    const fs::path dir = fosssim_dir() / part / folder;
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.path().extension() == ".xml") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

fs::path scene_path(const std::string& relative) { return fosssim_dir() / relative; }

template <class Solver>
void run_with(Solver& solver, System& system, double h, long long steps, const Observer& observe) {
  solver.precompute(system, h);
  if (observe) observe(system, 0, 0.0);
  for (long long n = 1; n <= steps; ++n) {
    REQUIRE(solver.step(system).ok());
    if (observe) observe(system, n, double(n) * h);
  }
}

// Runs `steps` steps of h with the scheme FOSSSim names; observe() after each (and at step 0).
void run(System& system, FosssimIntegrator kind, double h, long long steps,
         const Observer& observe) {
  switch (kind) {
    case FosssimIntegrator::ExplicitEuler: {
      massspring::ForwardEuler<System> s;
      run_with(s, system, h, steps, observe);
      return;
    }
    case FosssimIntegrator::SymplecticEuler: {
      massspring::SymplecticEuler<System> s;
      run_with(s, system, h, steps, observe);
      return;
    }
    case FosssimIntegrator::LinearizedImplicitEuler:
    case FosssimIntegrator::ImplicitEuler: {
      massspring::BackwardEuler<System> s;
      s.options.mode = kind == FosssimIntegrator::ImplicitEuler
                           ? massspring::BackwardEulerMode::Newton
                           : massspring::BackwardEulerMode::Linearized;
      run_with(s, system, h, steps, observe);
      return;
    }
  }
}

// Folder of a scene, "t1m2/SpringTests/test00symplectic.xml" -> "t1m2/SpringTests/test00...".
std::string short_name(const fs::path& p) {
  return fs::relative(p, fosssim_dir()).generic_string();
}

// A spring whose two particles are in no other spring, with no other force: its length obeys the
// damped oscillator mu u'' = -k u - b u' (u = l - l0, mu = m_i m_j / (m_i + m_j)) as long as the
// relative velocity stays along the spring (it starts at 0 in these scenes).
struct IsolatedSpring {
  int i, j;
  double k, b, l0, mu, u0;
  // The closed form with u(0) = u0, u'(0) = 0 (underdamped: b^2 < 4 k mu, checked).
  [[nodiscard]] double length(double t) const {
    const double gamma = b / (2 * mu);
    const double wd = std::sqrt(k / mu - gamma * gamma);
    return l0 + std::exp(-gamma * t) * (u0 * std::cos(wd * t) + u0 * gamma / wd * std::sin(wd * t));
  }
};

std::vector<IsolatedSpring> isolated_springs(const FosssimScene& s) {
  std::vector<IsolatedSpring> out;
  if (s.gravity || s.drag || !s.attractions.empty()) return out;
  std::vector<int> degree(std::size_t(s.num_particles()), 0);
  for (const auto& f : s.springs) {
    ++degree[std::size_t(s.edges(f.edge, 0))];
    ++degree[std::size_t(s.edges(f.edge, 1))];
  }
  for (const auto& f : s.springs) {
    const int i = s.edges(f.edge, 0), j = s.edges(f.edge, 1);
    if (degree[std::size_t(i)] != 1 || degree[std::size_t(j)] != 1) continue;
    if (!s.fixed.empty()) continue;
    if ((s.velocities.row(i) - s.velocities.row(j)).norm() != 0) continue;
    const double mu = s.masses(i) * s.masses(j) / (s.masses(i) + s.masses(j));
    if (f.b * f.b >= 4 * f.k * mu) continue;
    const double l = (s.positions.row(i) - s.positions.row(j)).norm();
    out.push_back({i, j, f.k, f.b, f.l0, mu, l - f.l0});
  }
  return out;
}

// Worst |l(t) - closed form| over every isolated spring and step, run with h for time T.
double worst_spring_error(const fs::path& file, double h, double T) {
  const FosssimScene scene = massspring::io::read_fosssim_scene(file);
  const auto springs = isolated_springs(scene);
  REQUIRE(int(springs.size()) == int(scene.springs.size()));  // every spring qualifies
  System system = massspring::io::make_fosssim_system<System>(scene);
  double worst = 0;
  run(system, scene.integrator, h, std::llround(T / h), [&](const System& s, long long, double t) {
    for (const auto& sp : springs) {
      const double l = (s.positions().row(sp.i) - s.positions().row(sp.j)).norm();
      worst = std::max(worst, std::abs(l - sp.length(t)));
    }
  });
  return worst;
}

// Energy and angular momentum (about the origin, z component) of particle 1 around a fixed
// particle 0 of the AccuracyTests scene.
struct Orbit {
  double energy, momentum, radius;
};
Orbit orbit_of(const System& s, double mu) {
  const Eigen::RowVector3d x = s.positions().row(1) - s.positions().row(0);
  const Eigen::RowVector3d v = s.velocities().row(1);
  const double r = x.norm();
  return {0.5 * v.squaredNorm() - mu / r, x(0) * v(1) - x(1) * v(0), r};
}

}  // namespace

TEST_CASE(
    "fosssim oracles: SpringTests/test00 follows l(t) = 1 + 0.2 cos(sqrt(2) t) to the "
    "scheme's error bound" *
    doctest::skip(!have_fosssim())) {
  // The scene: two unit masses 1.2 m apart on a spring k = 1, l0 = 1, at rest. Along the line
  // u = l - l0 obeys u'' = -w^2 u with w^2 = k / mu = 2 (mu = 1/2): l(t) = 1 + 0.2 cos(sqrt(2) t).
  const FosssimScene scene =
      massspring::io::read_fosssim_scene(scene_path("t1m2/SpringTests/test00symplectic.xml"));
  REQUIRE(scene.masses(0) == 1.0);
  REQUIRE(scene.masses(1) == 1.0);
  REQUIRE(scene.springs.size() == 1);
  REQUIRE(scene.springs[0].k == 1.0);
  REQUIRE(scene.springs[0].l0 == 1.0);
  REQUIRE((scene.positions.row(0) - scene.positions.row(1)).norm() == doctest::Approx(1.2));
  const double w = std::sqrt(2.0), u0 = 0.2, h = 1e-3, T = scene.duration;  // 50 s

  // Exact discrete solutions of each scheme on u'' = -w^2 u (u(0) = u0, u'(0) = 0):
  // - symplectic Euler: u_n = u0 cos(n th) + B sin(n th), cos th = 1 - w^2 h^2 / 2,
  //   |B| = u0 w h / (2 sqrt(1 - w^2 h^2 / 4)), th - w h in [0, (w h)^3 / 24 (1 + (w h)^2)]:
  //   |u_n - u(t)| <= |B| + u0 t w^3 h^2 / 24 (1 + (w h)^2);
  // - backward Euler: u_n = u0 r^n cos(n th), r = (1 + w^2 h^2)^(-1/2), tan th = w h:
  //   |u_n - u(t)| <= u0 (1 - r^n) + u0 n |th - w h| <= u0 (t w^2 h / 2 + t w^3 h^2 / 3);
  // - forward Euler: u_n = u0 r^n cos(n th), r = (1 + w^2 h^2)^(1/2), tan th = w h:
  //   |u_n - u(t)| <= u0 (r^n - 1) + u0 t w^3 h^2 / 3.
  // Plus rounding, 1e-12 (far below every bound: they are ~1e-4 .. 1e-2 here).
  const double wh = w * h;
  struct Case {
    const char* file;
    std::function<double(double)> bound;
  };
  const Case cases[] = {
      {"t1m2/SpringTests/test00symplectic.xml",
       [&](double t) {
         return u0 * wh / (2 * std::sqrt(1 - wh * wh / 4)) +
                u0 * t * w * w * w * h * h / 24 * (1 + wh * wh) + 1e-12;
       }},
      {"t1m3/SpringTests/test00linearizedimplicit.xml",
       [&](double t) { return u0 * (t * w * w * h / 2 + t * w * w * w * h * h / 3) + 1e-12; }},
      {"t1m2/SpringTests/test00explicit.xml",
       [&](double t) {
         return u0 * (std::pow(1 + wh * wh, t / h / 2) - 1) + u0 * t * w * w * w * h * h / 3 +
                1e-12;
       }},
  };
  for (const Case& c : cases) {
    const std::string name = c.file;
    CAPTURE(name);
    const FosssimScene s = massspring::io::read_fosssim_scene(scene_path(c.file));
    System system = massspring::io::make_fosssim_system<System>(s);
    double worst = 0, worst_ratio = 0;
    run(system, s.integrator, h, std::llround(T / h), [&](const System& sys, long long, double t) {
      const double l = (sys.positions().row(0) - sys.positions().row(1)).norm();
      const double e = std::abs(l - (1 + 0.2 * std::cos(w * t)));
      worst = std::max(worst, e);
      worst_ratio = std::max(worst_ratio, e / c.bound(t));
    });
    CHECK(worst_ratio <= 1.0);
    // The bound is tight to within a factor 4 (a bound that never bites would test nothing).
    CHECK(worst_ratio >= 0.25);
    MESSAGE("SpringTests/test00 (" << name << ") h = " << h << ", 0..50 s: worst |l - 1 - 0.2 "
                                   << "cos(sqrt 2 t)| = " << worst << " (" << worst_ratio
                                   << " of its bound)");
  }
}

TEST_CASE(
    "fosssim oracles: every spring of SpringTests and SpringDampingTests follows the damped "
    "oscillator, to first order" *
    doctest::skip(!have_fosssim())) {
  // Each spring there joins two particles found in no other spring, at rest: l(t) is the damped
  // oscillator's closed form (IsolatedSpring). Each scheme is first order, so its worst error
  // over 0..10 s halves when h halves: the ratio err(h/2) / err(h) lies within 0.5 +- 0.05 (the
  // O(h^2) remainder at h = 1e-3 is far below 10% of the O(h) term). A wrong closed form (or a
  // wrong force) would leave an error that does not shrink with h.
  for (const char* folder : {"SpringTests", "SpringDampingTests"}) {
    double worst = 0;
    std::string worst_file;
    for (const fs::path& file : scenes_in(folder)) {
      CAPTURE(short_name(file));
      const double e1 = worst_spring_error(file, 1e-3, 10.0);
      const double e2 = worst_spring_error(file, 5e-4, 10.0);
      CHECK(e2 / e1 == doctest::Approx(0.5).epsilon(0.1));
      if (e1 > worst) worst = e1, worst_file = short_name(file);
    }
    MESSAGE(std::string(folder) << ": worst |l(t) - closed form| over 0..10 s at h = 1e-3: "
                                << worst << " (" << worst_file << "); halves with h");
  }
}

TEST_CASE("fosssim oracles: SpringDampingTests/test03 decays faster with larger b" *
          doctest::skip(!have_fosssim())) {
  // Eleven identical springs (k = 1, unit masses, stretched by 0.4) with b = 0, 0.1, ..., 1. The
  // closed form's energy decays as e^{-b t / mu} on average: after 20 s each b leaves strictly
  // less energy than the smaller b before it, under each scheme at the scene's dt. b = 0 keeps it
  // (symplectic: within the scheme's O(h) oscillation of the modified energy).
  for (const char* file : {"t1m2/SpringDampingTests/test03symplectic.xml",
                           "t1m2/SpringDampingTests/test03explicit.xml",
                           "t1m3/SpringDampingTests/test03linearizedimplicit.xml"}) {
    CAPTURE(file);
    const FosssimScene scene = massspring::io::read_fosssim_scene(scene_path(file));
    System system = massspring::io::make_fosssim_system<System>(scene);
    run(system, scene.integrator, scene.dt, scene.steps(), {});
    std::vector<double> energy;
    for (int e = 0; e < system.num_springs(); ++e) {
      const int i = system.springs()(e, 0), j = system.springs()(e, 1);
      const double u =
          (system.positions().row(i) - system.positions().row(j)).norm() - system.rest_lengths()(e);
      const double ki = 0.5 * system.masses()(i) * system.velocities().row(i).squaredNorm() +
                        0.5 * system.masses()(j) * system.velocities().row(j).squaredNorm();
      energy.push_back(0.5 * system.stiffness()(e) * u * u + ki);
    }
    REQUIRE(energy.size() == 11);
    for (std::size_t e = 1; e < energy.size(); ++e) {
      CAPTURE(e);
      CHECK(system.damping()(Eigen::Index(e)) > system.damping()(Eigen::Index(e - 1)));
      CHECK(energy[e] < energy[e - 1]);
    }
    // b = 1 (mu = 1/2): the envelope e^{-2 b t} of the energy leaves ~e^{-40} of 0.08 J.
    CHECK(energy[10] < 1e-12);
    MESSAGE(std::string(file) << ": spring energy after 20 s, b = 0: " << energy[0]
                              << " J, b = 0.5: " << energy[5] << " J, b = 1: " << energy[10]
                              << " J (initial 0.08 J)");
  }
}

TEST_CASE("fosssim oracles: GravityTests/test01 is a circular orbit of period 2 pi" *
          doctest::skip(!have_fosssim())) {
  // Two unit masses at (+-1, 0) with velocities (0, -+1) and G = 4: the attraction G m m / 4 = 1
  // is the centripetal force m v^2 / 1 of a circle of radius 1 about the fixed centre of mass,
  // angular speed 1, period 2 pi. Symplectic Euler with h = 2 pi / N. Its positions are exactly
  // those of Stoermer-Verlet (second order) started from the velocities v0 + h/2 a(x0)
  // (SE^n = kick(-h/2) Verlet^n kick(h/2), and kicks leave positions alone). That radial kick
  // makes the orbit eccentric by O(h): the radius deviates from 1 to first order (ratio 0.5 +-
  // 0.05 when h halves). It changes the energy only by O(h^2) and the angular momentum not at
  // all, so the period is 2 pi + O(h^2): the bodies come back to the start to second order
  // (ratio 0.25 +- 0.025). The centre of mass stays at 0 to rounding (internal forces cancel).
  const FosssimScene scene =
      massspring::io::read_fosssim_scene(scene_path("t1m2/GravityTests/test01symplectic.xml"));
  REQUIRE(scene.attractions.size() == 1);
  REQUIRE(scene.attractions[0].G == 4.0);
  auto errors = [&](int N) {
    System system = massspring::io::make_fosssim_system<System>(scene);
    const Eigen::MatrixXd start = system.positions();
    double radius = 0, centre = 0;
    run(system, scene.integrator, 2 * kPi / N, N, [&](const System& s, long long, double) {
      const Eigen::RowVector3d c = 0.5 * (s.positions().row(0) + s.positions().row(1));
      centre = std::max(centre, c.norm());
      for (int i = 0; i < 2; ++i)
        radius = std::max(radius, std::abs((s.positions().row(i) - c).norm() - 1.0));
    });
    const double back = (Eigen::MatrixXd(system.positions()) - start).rowwise().norm().maxCoeff();
    return std::array<double, 3>{radius, back, centre};
  };
  const auto e1 = errors(6000);
  const auto e2 = errors(12000);
  CHECK(e2[0] / e1[0] == doctest::Approx(0.5).epsilon(0.1));
  CHECK(e2[1] / e1[1] == doctest::Approx(0.25).epsilon(0.1));
  CHECK(e1[2] < 1e-13);
  CHECK(e2[2] < 1e-13);
  MESSAGE(
      "GravityTests/test01, symplectic, h = 2 pi / 6000 (radius first order, return second): worst "
      "|radius - 1| = "
      << e1[0] << ", |x(2 pi) - x(0)| = " << e1[1] << "; at h / 2: " << e2[0] << ", " << e2[1]);
}

TEST_CASE(
    "fosssim oracles: AccuracyTests is an ellipse with semi-major axis 5 and eccentricity "
    "0.6" *
    doctest::skip(!have_fosssim())) {
  // A fixed sun (m = 1) and a planet (m = 1) at r0 = 8 with speed v0 = 2.236050808 across, G = 100:
  // mu = G m_sun = 100, E = v0^2 / 2 - mu / r0 = -10 (to the scene's 10 digits), so
  // a = -mu / (2 E) = 5; L = r0 v0, e = sqrt(1 + 2 E L^2 / mu^2) = 0.6; perihelion a (1 - e) = 2,
  // aphelion a (1 + e) = 8, period 2 pi sqrt(a^3 / mu).
  const FosssimScene scene =
      massspring::io::read_fosssim_scene(scene_path("t1m2/AccuracyTests/test00symplectic.xml"));
  REQUIRE(scene.fixed == std::vector<int>{0});
  const double mu = scene.attractions.at(0).G * scene.masses(0);
  const double r0 = scene.positions(1, 0), v0 = scene.velocities(1, 1);
  const double E0 = v0 * v0 / 2 - mu / r0, L0 = r0 * v0;
  const double a0 = -mu / (2 * E0), e0 = std::sqrt(1 + 2 * E0 * L0 * L0 / (mu * mu));
  CHECK(a0 == doctest::Approx(5).epsilon(1e-5));  // the scene's v0 has 10 digits
  CHECK(e0 == doctest::Approx(0.6).epsilon(1e-5));
  const double period = 2 * kPi * std::sqrt(a0 * a0 * a0 / mu);

  // Symplectic Euler keeps L = x × v exactly for a central force from a fixed centre
  // (x_{n+1} × v_{n+1} = x_n × v_{n+1} = x_n × v_n): rounding only. E, and so a and e, oscillate
  // by O(h): the worst deviations over one period halve with h (ratio 0.5 +- 0.05).
  struct Result {
    double a, e, rmin, rmax, L;
  };
  auto simulate = [&](int N) {
    System system = massspring::io::make_fosssim_system<System>(scene);
    Result r{0, 0, 1e9, 0, 0};
    run(system, FosssimIntegrator::SymplecticEuler, period / N, N,
        [&](const System& s, long long, double) {
          const Orbit o = orbit_of(s, mu);
          r.a = std::max(r.a, std::abs(-mu / (2 * o.energy) - a0));
          r.e = std::max(
              r.e,
              std::abs(std::sqrt(1 + 2 * o.energy * o.momentum * o.momentum / (mu * mu)) - e0));
          r.rmin = std::min(r.rmin, o.radius);
          r.rmax = std::max(r.rmax, o.radius);
          r.L = std::max(r.L, std::abs(o.momentum - L0) / L0);
        });
    return r;
  };
  const Result r1 = simulate(20000), r2 = simulate(40000);
  CHECK(r1.L < 1e-11);  // rounding over 20000 steps
  CHECK(r2.L < 1e-11);
  CHECK(r2.a / r1.a == doctest::Approx(0.5).epsilon(0.1));
  CHECK(r2.e / r1.e == doctest::Approx(0.5).epsilon(0.1));
  // The extreme radii a (1 -+ e) = 2 and 8: the positions are Stoermer-Verlet's (second order)
  // from velocities kicked by h/2 a(x0), radially at the aphelion: L unchanged, E changed by
  // O(h^2), so the apsides are right to second order (ratio 0.25 +- 0.025 when h halves).
  const double drmin1 = std::abs(r1.rmin - a0 * (1 - e0)),
               drmin2 = std::abs(r2.rmin - a0 * (1 - e0));
  const double drmax1 = std::abs(r1.rmax - a0 * (1 + e0)),
               drmax2 = std::abs(r2.rmax - a0 * (1 + e0));
  CHECK(drmin2 / drmin1 == doctest::Approx(0.25).epsilon(0.1));
  CHECK(drmax2 / drmax1 == doctest::Approx(0.25).epsilon(0.1));
  MESSAGE("AccuracyTests, symplectic, h = T / 20000 = "
          << period / 20000 << ": worst |a - 5| = " << r1.a << ", |e - 0.6| = " << r1.e
          << ", |r_min - 2| = " << drmin1 << ", |r_max - 8| = " << drmax1
          << "; a, e halve with h, the apsides quarter");
}

TEST_CASE(
    "fosssim oracles: orbits spiral out with explicit Euler, stay with symplectic, spiral in "
    "with implicit Euler" *
    doctest::skip(!have_fosssim())) {
  // At the scenes' own dt = 0.01 over 15 s (about 2.4 orbits) of GravityTests/test01. Explicit
  // Euler adds energy at every step on a circular orbit (E_{n+1} - E_n = h^2/2 (|F|^2/m - ...) > 0
  // at first order in the orbit's curvature), implicit Euler removes it; symplectic keeps the
  // modified energy, so E only oscillates by O(h) with no drift.
  struct Run {
    double energy_change, radius_change, worst_radius;
    bool monotone;
  };
  auto simulate = [&](const char* file) {
    const FosssimScene scene = massspring::io::read_fosssim_scene(scene_path(file));
    System system = massspring::io::make_fosssim_system<System>(scene);
    const double E0 = massspring::total_energy(system);
    double last = E0, sign = 0, worst = 0;
    bool monotone = true;
    run(system, scene.integrator, scene.dt, scene.steps(),
        [&](const System& s, long long n, double) {
          const double E = massspring::total_energy(s);
          if (n == 1) sign = E > last ? 1 : -1;
          if (n > 0 && (E - last) * sign <= 0) monotone = false;
          last = E;
          worst =
              std::max(worst, std::abs((s.positions().row(0) - s.positions().row(1)).norm() - 2));
        });
    const double r = (system.positions().row(0) - system.positions().row(1)).norm();
    return Run{last - E0, r - 2, worst, monotone};
  };
  const Run forward = simulate("t1m2/GravityTests/test01explicit.xml");
  const Run symplectic = simulate("t1m2/GravityTests/test01symplectic.xml");
  const Run backward = simulate("t1m3/GravityTests/test01linearizedimplicit.xml");
  CHECK(forward.monotone);
  CHECK(forward.energy_change > 0);
  CHECK(forward.radius_change > 0);
  CHECK(backward.monotone);
  CHECK(backward.energy_change < 0);
  CHECK(backward.radius_change < 0);
  // Symplectic: its worst radius deviation over the run is below the final drift of both others.
  CHECK(symplectic.worst_radius < 0.1 * forward.radius_change);
  CHECK(symplectic.worst_radius < 0.1 * -backward.radius_change);
  MESSAGE("GravityTests/test01 at dt = 0.01, 15 s: separation - 2 at the end: explicit "
          << forward.radius_change << ", implicit " << backward.radius_change
          << "; symplectic worst |separation - 2| " << symplectic.worst_radius);
}

TEST_CASE("fosssim oracles: LinearDragTests follow x(t) = x0 + v0 m / b (1 - e^{-b t / m})" *
          doctest::skip(!have_fosssim())) {
  // m v' = -b v: v = v0 e^{-c}, c = b t / m. Each scheme's exact discrete solution with
  // q = b h / m: forward v_n = v0 (1 - q)^n, x_n = x0 + v0 m / b (1 - (1 - q)^n); symplectic
  // x_n = x0 + v0 m / b (1 - q) (1 - (1 - q)^n); backward x_n = x0 + v0 m / b (1 - (1 + q)^-n).
  // The simulation matches these to rounding (1e-12). Against the continuous solution, with
  // s = b t / m: (1 - q)^n lies within e^{-s} s q / (2 (1 - q)) below e^{-s}, (1 + q)^-n within
  // e^{-s} (e^{s q / 2} - 1) above; the symplectic form adds at most q (1 - (1-q)^n) <= q.
  double worst = 0;
  for (const fs::path& file : scenes_in("LinearDragTests")) {
    CAPTURE(short_name(file));
    const FosssimScene scene = massspring::io::read_fosssim_scene(file);
    REQUIRE(scene.drag.has_value());
    System system = massspring::io::make_fosssim_system<System>(scene);
    const double h = scene.dt, b = *scene.drag;
    double discrete = 0, ratio = 0;
    run(system, scene.integrator, h, scene.steps(), [&](const System& s, long long n, double t) {
      for (int i = 0; i < scene.num_particles(); ++i) {
        if (s.is_pinned(i)) continue;
        const double m = scene.masses(i), q = b * h / m, sc = b * t / m;
        const double d = double(n);
        double factor = 0, bound = 0;
        switch (scene.integrator) {
          case FosssimIntegrator::ExplicitEuler:
            factor = 1 - std::pow(1 - q, d);
            bound = std::exp(-sc) * sc * q / (2 * (1 - q));
            break;
          case FosssimIntegrator::SymplecticEuler:
            factor = (1 - q) * (1 - std::pow(1 - q, d));
            bound = std::exp(-sc) * sc * q / (2 * (1 - q)) + q;
            break;
          default:
            factor = 1 - std::pow(1 + q, -d);
            bound = std::exp(-sc) * (std::exp(sc * q / 2) - 1);
            break;
        }
        for (int a = 0; a < 2; ++a) {
          const double x0 = scene.positions(i, a), v0 = scene.velocities(i, a);
          const double x = s.positions()(i, a);
          discrete = std::max(discrete, std::abs(x - (x0 + v0 * m / b * factor)));
          const double exact = x0 + v0 * m / b * (1 - std::exp(-sc));
          const double e = std::abs(x - exact);
          worst = std::max(worst, e);
          if (v0 != 0) ratio = std::max(ratio, e / (std::abs(v0) * m / b * bound + 1e-12));
        }
      }
    });
    CHECK(discrete < 1e-12);
    CHECK(ratio <= 1.0);
  }
  // LinearDragTests/test00 by name: x(t) = 1 - e^{-t}, reached within h / (2 e) at dt = 0.01.
  {
    const FosssimScene scene =
        massspring::io::read_fosssim_scene(scene_path("t1m2/LinearDragTests/test00explicit.xml"));
    CHECK(scene.positions(0, 0) == 0.0);
    CHECK(scene.velocities(0, 0) == 1.0);
    CHECK(*scene.drag == 1.0);
    CHECK(scene.masses(0) == 1.0);
  }
  MESSAGE("LinearDragTests: worst |x(t) - (x0 + v0 m / b (1 - e^{-b t / m}))| at the scenes' dt: "
          << worst << " (within each scheme's bound; exact discrete forms to 1e-12)");
}

TEST_CASE(
    "fosssim oracles: SimpleGravityTests and ProjectileRainbow fall as the schemes' exact "
    "discrete parabolas; y(2) = -19.62 to h g t / 2" *
    doctest::skip(!have_fosssim())) {
  // x(t) = x0 + v0 t + g t^2 / 2. Forward Euler gives exactly x0 + v0 t + g t (t - h) / 2,
  // symplectic and (linearised) backward Euler x0 + v0 t + g t (t + h) / 2: the error is exactly
  // |g| h t / 2 at every step, to rounding (a few ulps of |x| per step: 4 eps n (1 + |x|)).
  std::vector<fs::path> files = scenes_in("SimpleGravityTests");
  files.push_back(scene_path("t1m1/SystemTests/ProjectileRainbowExplicit.xml"));
  double worst = 0, worst_rainbow = 0;
  for (const fs::path& file : files) {
    CAPTURE(short_name(file));
    const FosssimScene scene = massspring::io::read_fosssim_scene(file);
    REQUIRE(scene.gravity.has_value());
    REQUIRE(scene.springs.empty());
    const Eigen::Vector3d g = *scene.gravity;
    System system = massspring::io::make_fosssim_system<System>(scene);
    const double h = scene.dt;
    const double side = scene.integrator == FosssimIntegrator::ExplicitEuler ? -1 : 1;
    double off = 0, order = 0;
    run(system, scene.integrator, h, scene.steps(), [&](const System& s, long long n, double t) {
      for (int i = 0; i < scene.num_particles(); ++i) {
        if (s.is_pinned(i)) {
          CHECK(s.positions().row(i) == scene.positions.row(i));
          continue;
        }
        for (int a = 0; a < 2; ++a) {
          const double x = s.positions()(i, a);
          const double base = scene.positions(i, a) + scene.velocities(i, a) * t;
          const double discrete = base + g(a) * t * (t + side * h) / 2;
          const double exact = base + g(a) * t * t / 2;
          const double tol = 4 * kEps * double(n) * (1 + std::abs(x));
          off = std::max(off, std::abs(x - discrete) / (tol + 1e-300));
          order = std::max(
              order, std::abs(std::abs(x - exact) - std::abs(g(a)) * h * t / 2) / (tol + 1e-300));
          const double e = std::abs(x - exact);
          if (file.filename().string().find("Rainbow") != std::string::npos)
            worst_rainbow = std::max(worst_rainbow, e);
          else
            worst = std::max(worst, e);
        }
      }
    });
    CHECK(off <= 1.0);
    CHECK(order <= 1.0);
  }
  // test00 by name: from rest, g = 9.81: y(2) = -19.62; forward Euler is h g t / 2 = 0.0981 above.
  for (const char* file : {"t1m1/SimpleGravityTests/test00explicit.xml",
                           "t1m2/SimpleGravityTests/test00symplectic.xml"}) {
    CAPTURE(file);
    const FosssimScene scene = massspring::io::read_fosssim_scene(scene_path(file));
    System system = massspring::io::make_fosssim_system<System>(scene);
    const double h = scene.dt;
    double y2 = 0;
    run(system, scene.integrator, h, 200,
        [&](const System& s, long long, double) { y2 = s.positions()(0, 1); });
    const double side = scene.integrator == FosssimIntegrator::ExplicitEuler ? 1 : -1;
    CHECK(y2 == doctest::Approx(-19.62 + side * 9.81 * h * 2 / 2).epsilon(1e-12));
  }
  MESSAGE("SimpleGravityTests: worst |x - (x0 + v0 t + g t^2 / 2)| = "
          << worst << " (= |g| h T / 2 at T = 4)");
  MESSAGE("SystemTests/ProjectileRainbowExplicit: worst |x - parabola| = "
          << worst_rainbow << " (= |g| h T / 2 at T = 50)");
}

TEST_CASE("fosssim oracles: InertiaTests and helloworld keep kinetic energy exactly" *
          doctest::skip(!have_fosssim())) {
  // No force: every scheme gives v_{n+1} = v_n + 0 bit for bit (backward Euler solves A dv = 0
  // and adds its exact zero), so kinetic energy is unchanged exactly. Positions x0 + v0 t to
  // rounding (4 eps n (1 + |x|)).
  std::vector<fs::path> files = scenes_in("InertiaTests");
  files.push_back(scene_path("t1m1/StarterTests/helloworld.xml"));
  double worst = 0;
  for (const fs::path& file : files) {
    CAPTURE(short_name(file));
    const FosssimScene scene = massspring::io::read_fosssim_scene(file);
    REQUIRE(scene.springs.empty());
    REQUIRE_FALSE(scene.gravity.has_value());
    System system = massspring::io::make_fosssim_system<System>(scene);
    const double K0 = massspring::kinetic_energy(system);
    bool same = true;
    double off = 0;
    run(system, scene.integrator, scene.dt, scene.steps(),
        [&](const System& s, long long n, double t) {
          const double K = massspring::kinetic_energy(s);
          same = same && K == K0;
          for (int i = 0; i < scene.num_particles(); ++i)
            for (int a = 0; a < 2; ++a) {
              const double x = s.positions()(i, a);
              const double e = std::abs(x - (scene.positions(i, a) + scene.velocities(i, a) * t));
              worst = std::max(worst, e);
              off = std::max(off, e / (4 * kEps * double(n) * (1 + std::abs(x)) + 1e-300));
            }
        });
    CHECK(same);
    CHECK(off <= 1.0);
  }
  MESSAGE(
      "InertiaTests + StarterTests/helloworld: kinetic energy exact for every scheme; "
      "worst |x - (x0 + v0 t)| = "
      << worst);
}
