#pragma once
// The project's own 2D scenes in FOSSSim's XML format, written by massspring-make-scenes into
// examples/scenes_xml and run by scripts/examples.sh. Every number here is ours (none is copied
// from FOSSSim's scenes).

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "massspring/io/fosssim_scene.hpp"

namespace massspring::examples {

namespace detail {

/// @brief A scene with no particles yet: its description, integrator, time step dt [s] and
/// duration [s].
inline io::FosssimScene new_scene(std::string description, io::FosssimIntegrator integrator,
                                  double dt, double duration) {
  io::FosssimScene s;
  s.description = std::move(description);
  s.integrator = integrator;
  s.dt = dt;
  s.duration = duration;
  return s;
}

/// @brief Appends a particle (z = 0); returns its index.
inline int add_particle(io::FosssimScene& s, double m, double x, double y, double vx = 0,
                        double vy = 0, bool fixed = false) {
  const Eigen::Index n = s.positions.rows();
  s.positions.conservativeResize(n + 1, 3);
  s.velocities.conservativeResize(n + 1, 3);
  s.masses.conservativeResize(n + 1);
  s.positions.row(n) << x, y, 0;
  s.velocities.row(n) << vx, vy, 0;
  s.masses(n) = m;
  if (fixed) s.fixed.push_back(int(n));
  return int(n);
}

/// @brief Appends an edge (i, j) with a spring k, b and rest length l0 (< 0: the current
/// distance).
inline void add_spring(io::FosssimScene& s, int i, int j, double k, double b, double l0 = -1) {
  const Eigen::Index e = s.edges.rows();
  s.edges.conservativeResize(e + 1, 2);
  s.edges.row(e) << i, j;
  const double rest = l0 >= 0 ? l0 : (s.positions.row(i) - s.positions.row(j)).norm();
  s.springs.push_back({int(e), k, rest, b});
}

}  // namespace detail

/// @brief (file stem, scene) of every XML scene in examples/scenes_xml.
inline std::vector<std::pair<std::string, io::FosssimScene>> project_fosssim_scenes() {
  using detail::add_particle;
  using detail::add_spring;
  using detail::new_scene;
  using io::FosssimIntegrator;
  std::vector<std::pair<std::string, io::FosssimScene>> scenes;

  {  // A planet on an ellipse around a fixed sun: G M = 1, released at r = 1 with speed 0.8
     // across, so a = 1 / (2 - 0.64) = 0.735, e = 0.36, period 2 pi a^1.5 = 3.96 s.
    io::FosssimScene s = new_scene(
        "A planet on an ellipse (a = 0.735, e = 0.36) around a fixed sun. Run it with "
        "--integrator forward-euler to watch explicit Euler spiral out.",
        FosssimIntegrator::SymplecticEuler, 0.01, 20);
    add_particle(s, 1, 0, 0, 0, 0, true);
    add_particle(s, 1, 1, 0, 0, 0.8);
    s.attractions.push_back({0, 1, 1.0});
    scenes.emplace_back("orbit", s);
  }

  {  // A cantilever truss, 2 m by 0.2 m, 11 x 2 particles, clamped at its left end, under gravity.
    // dt = 0.5 ms, explicit: below 2 / omega_max, omega_max^2 <= 5 * 2 k / m = 2e6 s^-2
    io::FosssimScene s = new_scene(
        "A truss cantilever clamped at its left end, sagging under gravity; drag and spring "
        "damping settle it.",
        FosssimIntegrator::SymplecticEuler, 0.0005, 6);
    const int columns = 11;
    const double spacing = 0.2, height = 0.2, k = 20000, b = 5, m = 0.1;
    for (int c = 0; c < columns; ++c)
      for (int r = 0; r < 2; ++r) add_particle(s, m, c * spacing, r * height, 0, 0, c == 0);
    auto id = [](int c, int r) { return 2 * c + r; };
    for (int c = 0; c < columns; ++c) {
      add_spring(s, id(c, 0), id(c, 1), k, b);
      if (c + 1 == columns) continue;
      add_spring(s, id(c, 0), id(c + 1, 0), k, b);
      add_spring(s, id(c, 1), id(c + 1, 1), k, b);
      add_spring(s, id(c, 0), id(c + 1, 1), k, b);
      add_spring(s, id(c, 1), id(c + 1, 0), k, b);
    }
    s.gravity = Vector3<double>(0, -9.81, 0);
    s.drag = 0.1;  // with m = 0.1: the swing decays as e^{-t}
    scenes.emplace_back("cantilever", s);
  }

  {  // A chain of 16 links of rest length 0.3 m (4.8 m) hanging between two fixed ends 3 m apart,
     // starting on a circular arc of that length, at rest. Run with --shrink RATE to pull it up.
    io::FosssimScene s = new_scene(
        "A chain hanging between two fixed ends. With massspring-simulate --shrink RATE its rest "
        "lengths shrink as exp(-RATE t) and pull it taut.",
        FosssimIntegrator::LinearizedImplicitEuler, 0.01, 10);
    const int links = 16;
    const double span = 3.0, rest = 0.3, k = 500, b = 0.5, m = 0.05;
    // The arc of length L = links * rest over the chord c = span: c / L = sin(a) / a with a the
    // half angle; solved by bisection (sin(a) / a decreases on (0, pi)).
    const double L = links * rest;
    double lo = 1e-9, hi = 3.14159265358979;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (std::sin(mid) / mid > span / L ? lo : hi) = mid;
    }
    const double a = 0.5 * (lo + hi), R = L / (2 * a);
    for (int p = 0; p <= links; ++p) {
      const double phi = -a + 2 * a * p / links;  // angle from the downward vertical
      const double x = p == 0 ? 0 : p == links ? span : span / 2 + R * std::sin(phi);
      const double y = p == 0 || p == links ? 0 : R * (std::cos(a) - std::cos(phi));
      add_particle(s, m, x, y, 0, 0, p == 0 || p == links);
    }
    for (int p = 0; p < links; ++p) add_spring(s, p, p + 1, k, b, rest);
    s.gravity = Vector3<double>(0, -9.81, 0);
    s.drag = 0.02;
    scenes.emplace_back("shrinking_chain", s);
  }

  {  // Eleven springs, identical but for their damping b = 0, 0.1, ..., 1 (N s/m): unit masses
     // pulled 0.5 m beyond a 1 m rest length, stacked 0.3 m apart (b = 0 at the top).
    io::FosssimScene s = new_scene(
        "Eleven springs stretched alike, damped with b = 0, 0.1, ..., 1 from top to bottom.",
        FosssimIntegrator::SymplecticEuler, 0.005, 12);
    for (int e = 0; e <= 10; ++e) {
      const double y = -0.3 * e;
      const int i = add_particle(s, 1, -0.75, y);
      const int j = add_particle(s, 1, 0.75, y);
      add_spring(s, i, j, 4.0, 0.1 * e, 1.0);
    }
    scenes.emplace_back("damping_series", s);
  }

  // Theme 2: the same box of balls under each collision response FOSSSim defines. A floor
  // and two walls (half-planes, one with a normal of length 2: FOSSSim does not require unit
  // normals), a fixed ramp (an edge of radius 0.05 m between two fixed particles) and 12 balls of
  // radius 0.15 m (0.5 kg) dropped onto it with a spring-joined pair (k = 200 N/m) among them;
  // gravity 9.81 m/s^2, symplectic Euler, 4 s. COR 0.7 for the impulse responses.
  for (const io::FosssimCollision type :
       {io::FosssimCollision::Simple, io::FosssimCollision::Penalty,
        io::FosssimCollision::ContinuousTime, io::FosssimCollision::Hybrid}) {
    const std::string kind = io::to_string(type);
    // The penalty response's stiff springs (k = 10^4 N/m) take dt = 0.5 ms: at 2 ms symplectic
    // Euler pumps energy into the bounces, and a softer k lets a falling ball through the floor.
    io::FosssimScene s = new_scene(
        "Twelve balls and a spring-joined pair dropped onto a fixed ramp in a box; collision "
        "response: " +
            kind + ".",
        FosssimIntegrator::SymplecticEuler, type == io::FosssimCollision::Penalty ? 0.0005 : 0.002,
        4);
    const int a = add_particle(s, 1, -1.6, 1.4, 0, 0, true);  // the ramp's ends
    const int b = add_particle(s, 1, 0.4, 0.6, 0, 0, true);
    const Eigen::Index ramp = s.edges.rows();
    s.edges.conservativeResize(ramp + 1, 2);
    s.edges.row(ramp) << a, b;
    s.radii = {0.05, 0.05};
    s.edge_radii = {0.05};
    for (int i = 0; i < 12; ++i) {
      const double x = -1.5 + 0.27 * i + 0.04 * std::sin(3.0 * i);
      const double y = 2.4 + 0.45 * (i % 3) + 0.1 * std::cos(5.0 * i);
      add_particle(s, 0.5, x, y, 0.3 * std::sin(7.0 * i), 0);
      s.radii.push_back(0.15);
    }
    const int p = add_particle(s, 0.5, 1.0, 4.0, -0.5, 0);
    const int q = add_particle(s, 0.5, 1.5, 4.2, -0.5, 0);
    s.radii.push_back(0.12);
    s.radii.push_back(0.12);
    add_spring(s, p, q, 200, 0.2);
    s.edge_radii.push_back(0.015);
    s.gravity = Vector3<double>(0, -9.81, 0);
    s.halfplanes.push_back({Vector3<double>(0, 0, 0), Vector3<double>(0, 1, 0)});   // the floor
    s.halfplanes.push_back({Vector3<double>(-2, 0, 0), Vector3<double>(2, 0, 0)});  // left wall
    s.halfplanes.push_back({Vector3<double>(2, 0, 0), Vector3<double>(-1, 0, 0)});  // right wall
    io::FosssimScene::Collision c;
    c.type = type;
    c.cor = 0.7;
    if (type == io::FosssimCollision::Penalty) {
      c.k = 10000;
      c.thickness = 0.01;
    } else if (type == io::FosssimCollision::Hybrid) {
      c.k = 1000;
      c.thickness = 0.01;
      c.max_iterations = 20;
    }
    s.collision = c;
    s.contest = true;
    scenes.emplace_back("balls_" + std::string(kind == "continuous-time" ? "continuous" : kind), s);
  }
  return scenes;
}

}  // namespace massspring::examples
