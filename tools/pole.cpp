// massspring-pole: a flag wound onto a turning pole. The flag's top edge is fixed to the pole, and
// those pins turn with it (set_pin_target every step); the rest of the cloth meets the pole as a
// capsule collider turning at the same rate, whose friction carries the wound layers round.
//
//   massspring-pole [--out DIR] [--frames N] [--every K] [--dt S] [--turns-per-second F]
//                   [--integrator NAME] [--iterations N] [--acceleration NAME]
//                   [--contact-weight W] [--min-wound F]
//
// Prints the ms per step, the deepest point inside the pole over the run (never more than 1e-9 of
// the scene's diagonal: exit status 1 otherwise) and how much cloth is wound: the rows whose
// points all lie on the pole's surface, against the closed form of an inextensible cloth wound
// without slip, hanging straight down: (r + thickness) (angle - pi) / dy rows. The pins start
// at the front and go down, under and up the back, with the cloth hanging free below them; it
// first touches the pole when they pass the back, and from then on leaves it at the back, where
// a vertical line is tangent, so the first half turn winds nothing. Frames (frame_NNNNN.obj) and
// the starting scene (pole.json) go to --out, for scripts/render.py.
// No self-collision: the wound layers lie on each other at the same radius.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "massspring/io.hpp"
#include "massspring/massspring.hpp"

namespace ms = massspring;
using System = ms::MassSpringSystem<double, ms::Sparse>;
using V3 = ms::Vector3<double>;

namespace {

/// Rotation by angle [rad] about the x axis.
Eigen::Matrix3d rotation_x(double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()).toRotationMatrix();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"massspring-pole: a flag wound onto a turning pole"};
  std::string out;
  int frames = 2500, every = 25, iterations = 10;
  double contact_weight = 0;  // unset: the integrator's default
  std::string acceleration;   // unset: FastMassSpring's default
  std::string integrator = "fast-mass-spring";
  double dt = 0.002, turns_per_second = 0.5, min_wound = 0;
  app.add_option("--out", out, "folder for frame_NNNNN.obj (none: no frames written)");
  app.add_option("--frames", frames, "steps to take")->check(CLI::PositiveNumber);
  app.add_option("--every", every, "write every K-th step")->check(CLI::PositiveNumber);
  app.add_option("--dt", dt, "time step [s]")->check(CLI::PositiveNumber);
  app.add_option("--turns-per-second", turns_per_second, "the pole's rate [1/s]")
      ->check(CLI::PositiveNumber);
  app.add_option("--integrator", integrator,
                 "fast-mass-spring, backward-euler, linearized-backward-euler or symplectic-euler")
      ->check(CLI::IsMember(
          {"fast-mass-spring", "backward-euler", "linearized-backward-euler", "symplectic-euler"}));
  CLI::Option* o_iterations =
      app.add_option("--iterations", iterations,
                     "local-global iterations per step (fast-mass-spring: default its own, 10); "
                     "most Newton or contact iterations (backward-euler: default its own, 20)")
          ->check(CLI::PositiveNumber);
  CLI::Option* o_acceleration =
      app.add_option("--acceleration", acceleration,
                     "FastMassSpringOptions::acceleration: none, chebyshev or anderson "
                     "(fast-mass-spring only; default its own, anderson)")
          ->check(CLI::IsMember(ms::option_names<ms::Acceleration>()));
  CLI::Option* o_contact_weight =
      app.add_option("--contact-weight", contact_weight,
                     "the contact_weight of FastMassSpringOptions or BackwardEulerOptions "
                     "(default the integrator's own: 1 and 0; 0: contact at the end of the step, "
                     "and fast-mass-spring then starts from the current positions; > 0: inside "
                     "the solve)")
          ->check(CLI::NonNegativeNumber);
  app.add_option("--min-wound", min_wound,
                 "exit 1 when fewer rows than this fraction of the closed form are wound")
      ->check(CLI::Range(0.0, 1.0));
  CLI11_PARSE(app, argc, argv);
  const ms::IntegratorKind kind = ms::parse_integrator(integrator, ms::IntegratorNaming::Cli);
  const bool fast = kind == ms::IntegratorKind::FastMassSpring;
  if (!fast && o_acceleration->count() > 0) {
    std::fprintf(stderr, "massspring-pole: --acceleration applies to fast-mass-spring only\n");
    return 1;
  }
  if (kind == ms::IntegratorKind::SymplecticEuler && contact_weight > 0) {
    std::fprintf(stderr,
                 "massspring-pole: --contact-weight applies to fast-mass-spring and "
                 "backward-euler only\n");
    return 1;
  }

  try {
    // A 1 m x 0.8 m flag (31 x 25 points, Voronoi masses at 1 kg/m^2, k = 1000 N/m) hanging in
    // the plane z = r + thickness, its top edge (row 0) on the front of a pole of radius r along x
    // at height 1.5 m.
    const double r = 0.05, thickness = 0.004, height = 1.5, mu = 0.8;
    ms::ClothOptions cloth;
    cloth.columns = 31;
    cloth.rows = 25;
    cloth.width = 1.0;
    cloth.height = 0.8;
    cloth.pins = ms::ClothPins::TopEdge;
    ms::SceneDescription<double> scene = ms::make_cloth(cloth);
    scene.vertices.col(0).array() -= cloth.width / 2;
    scene.vertices.col(1).array() += height;
    scene.vertices.col(2).array() += r + thickness;
    const double omega = 2 * M_PI * turns_per_second;  // [rad/s] about +x: the front goes down
    ms::ColliderDescription<double> pole;
    pole.shape = ms::contact::ColliderShape::Capsule;
    pole.a = {-0.6, height, 0};
    pole.b = {0.6, height, 0};
    pole.radius = r;
    pole.thickness = thickness;
    pole.static_friction = pole.kinetic_friction = mu;
    pole.angular_velocity = {omega, 0, 0};
    scene.colliders = {pole};
    System sys = ms::make_system<System>(scene);
    sys.add_force(ms::Gravity<double>({0, -9.8, 0}));

    ms::SymplecticEuler<System> se;
    ms::FastMassSpring<System> solver;
    // The defaults unless a flag sets an option. `--contact-weight 0` also starts the solve from
    // the current positions, FastMassSpringOptions::reference()'s start (options.hpp: the
    // inertial start pairs with the contact term).
    if (o_iterations->count() > 0) solver.options.iterations = iterations;
    if (o_acceleration->count() > 0)
      solver.options.acceleration = ms::parse_option<ms::Acceleration>(acceleration);
    if (o_contact_weight->count() > 0) {
      solver.options.contact_weight = contact_weight;
      if (contact_weight == 0) solver.options.initial_guess = ms::InitialGuess::Current;
    }
    ms::BackwardEuler<System> be;
    be.options.mode = kind == ms::IntegratorKind::LinearizedBackwardEuler
                          ? ms::BackwardEulerMode::Linearized
                          : ms::BackwardEulerMode::Newton;
    if (o_iterations->count() > 0) be.options.iterations = iterations;
    if (o_contact_weight->count() > 0) be.options.contact_weight = contact_weight;
    const auto step = [&] {
      return fast                                          ? solver.step(sys)
             : kind == ms::IntegratorKind::SymplecticEuler ? se.step(sys)
                                                           : be.step(sys);
    };
    if (fast)
      solver.precompute(sys, dt);
    else if (kind == ms::IntegratorKind::SymplecticEuler)
      se.precompute(sys, dt);
    else
      be.precompute(sys, dt);

    // The scene (cloth, pins at their start, the pole) beside the frames, for render.py --scene.
    // A folder that holds anything already is refused: nothing of another run is overwritten.
    if (!out.empty()) {
      if (std::filesystem::exists(out) && !std::filesystem::is_empty(out)) {
        std::fprintf(stderr, "massspring-pole: %s is not empty; name a new or empty folder\n",
                     out.c_str());
        return 1;
      }
      std::filesystem::create_directories(out);
      ms::io::write_json_scene(std::filesystem::path(out) / "pole.json", scene);
    }
    auto write = [&](int frame) {
      if (out.empty()) return;
      char name[32];
      std::snprintf(name, sizeof name, "frame_%05d.obj", frame);
      ms::io::write_obj(std::filesystem::path(out) / name, sys.positions(), scene.faces,
                        scene.edges);
    };
    write(0);

    // Penetration: how far a free point is inside the pole's surface pushed out by thickness,
    // measured from the pole's axis (the x axis at the pole's height; the segment is longer than
    // the flag is wide), against the diagonal of the cloth's starting bounding box.
    const ms::Points<double> rest = sys.positions();
    const double diagonal = (rest.colwise().maxCoeff() - rest.colwise().minCoeff()).norm();
    double deepest = 0;
    std::chrono::duration<double> stepping{0};
    for (int frame = 1; frame <= frames; ++frame) {
      const Eigen::Matrix3d R = rotation_x(omega * frame * dt);  // the pole's end-of-step turn
      for (int i : sys.pinned()) {
        const V3 c(rest(i, 0), height, 0);
        sys.set_pin_target(i, c + R * (rest.row(i).transpose() - c));
      }
      const auto t0 = std::chrono::steady_clock::now();
      const ms::StepReport report = step();
      stepping += std::chrono::steady_clock::now() - t0;
      if (!report.ok()) {
        std::fprintf(stderr, "massspring-pole: step %d failed (not finite or not factorized)\n",
                     frame);
        return 2;
      }
      for (int i = 0; i < sys.num_points(); ++i) {
        if (sys.is_pinned(i)) continue;
        const double d = std::hypot(sys.positions()(i, 1) - height, sys.positions()(i, 2));
        deepest = std::max(deepest, r + thickness - d);
      }
      if (frame % every == 0) write(frame);
    }

    // Wound rows: every point of the row within 1.5 thickness of the surface (r + thickness).
    int wound = 0;
    for (int row = 1; row < cloth.rows; ++row) {
      bool on = true;
      for (int c = 0; c < cloth.columns && on; ++c) {
        const int i = row * cloth.columns + c;
        const double d = std::hypot(sys.positions()(i, 1) - height, sys.positions()(i, 2));
        on = std::abs(d - (r + thickness)) <= 1.5 * thickness;
      }
      if (!on) break;
      ++wound;
    }
    const double angle = omega * frames * dt;
    const double dy = cloth.height / (cloth.rows - 1);
    const double expected =
        std::min<double>(cloth.rows - 1, std::max(0.0, (r + thickness) * (angle - M_PI) / dy));
    std::printf(
        "massspring-pole: %d points, %d steps of %g s: %.3f ms per step\n"
        "  pole turned %.2f times; wound rows %d (inextensible, no slip: %.1f)\n"
        "  deepest point inside the pole: %.3g m (%.3g of the diagonal)\n",
        sys.num_points(), frames, dt, 1e3 * stepping.count() / frames, angle / (2 * M_PI), wound,
        expected, deepest, deepest / diagonal);
    if (deepest > 1e-9 * diagonal) {
      std::fprintf(stderr, "massspring-pole: a point ended a step inside the pole\n");
      return 1;
    }
    if (wound < min_wound * expected) {
      std::fprintf(stderr, "massspring-pole: %d rows wound, fewer than %g of %.1f\n", wound,
                   min_wound, expected);
      return 1;
    }
  } catch (const ms::Error& e) {
    std::fprintf(stderr, "massspring-pole: %s\n", e.what());
    return 1;
  }
  return 0;
}
