#pragma once
/// @file
/// @brief FosssimScene: what a FOSSSim XML scene says (Themes 1 and 2 of Columbia's "Animation
/// and CGI Motion" course), and the names of its integrators and collision types.

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "massspring/integrators/integrator_kind.hpp"
#include "massspring/types.hpp"

namespace massspring::io {

/// @brief The integrator a FOSSSim scene asks for (its `<integrator type>`): the four Euler
/// methods of IntegratorKind, whose FOSSSim names (IntegratorNaming::Fosssim) the scene uses.
enum class FosssimIntegrator {
  ExplicitEuler = int(IntegratorKind::ForwardEuler),  ///< "explicit-euler": ForwardEuler
  /// "symplectic-euler" (Theme 2: "forward-backward-euler"): SymplecticEuler
  SymplecticEuler = int(IntegratorKind::SymplecticEuler),
  /// "linearized-implicit-euler": BackwardEuler, Linearized mode
  LinearizedImplicitEuler = int(IntegratorKind::LinearizedBackwardEuler),
  ImplicitEuler = int(IntegratorKind::BackwardEuler),  ///< "implicit-euler": BackwardEuler, Newton
};

/// @brief The IntegratorKind a FOSSSim integrator is.
constexpr IntegratorKind integrator_kind(FosssimIntegrator integrator) {
  return IntegratorKind(int(integrator));
}

/// @brief The XML name of an integrator ("explicit-euler", ...).
inline const char* to_string(FosssimIntegrator integrator) {
  return to_string(integrator_kind(integrator), IntegratorNaming::Fosssim);
}

/// @brief The collision response a FOSSSim scene asks for (its `<collision type>`).
enum class FosssimCollision {
  None,            ///< "none"
  Simple,          ///< "simple": contact::SimpleCollisionHandler
  Penalty,         ///< "penalty": contact::PenaltyForce
  ContinuousTime,  ///< "continuous-time": contact::ContinuousTimeCollisionHandler
  Hybrid,          ///< "hybrid": contact::HybridCollisionHandler and contact::PenaltyForce
};

/// @brief The XML name of a collision type ("simple", ...).
inline const char* to_string(FosssimCollision type) {
  switch (type) {
    case FosssimCollision::None:
      return "none";
    case FosssimCollision::Simple:
      return "simple";
    case FosssimCollision::Penalty:
      return "penalty";
    case FosssimCollision::ContinuousTime:
      return "continuous-time";
    case FosssimCollision::Hybrid:
      return "hybrid";
  }
  return "?";
}

/// @brief What a FOSSSim scene file says, in SI units, indices 0-based. Positions and velocities
/// are 3D with z = 0 (the format is 2D).
struct FosssimScene {
  /// @brief A `<springforce>`: a Hooke spring on the endpoints of edges.row(edge).
  struct SpringForce {
    int edge = 0;   ///< index into edges
    double k = 0;   ///< stiffness [N/m], >= 0
    double l0 = 0;  ///< rest length [m], >= 0
    double b = 0;   ///< damping along the spring [N s/m], >= 0
  };
  /// @brief A `<gravitationalforce>`: attraction between particles i and j.
  struct Attraction {
    int i = 0, j = 0;
    double G = 0;  ///< [N m^2 / kg^2], >= 0
  };

  /// @brief #particles by 3 initial positions [m] (z = 0).
  Points<double> positions = Points<double>(0, 3);
  /// @brief #particles by 3 initial velocities [m/s] (z = 0).
  Points<double> velocities = Points<double>(0, 3);
  /// @brief #particles masses [kg], > 0.
  Vector<double> masses;
  /// @brief Fixed particles (`fixed="1"`), ascending.
  std::vector<int> fixed;
  /// @brief #edges by 2 particle indices: every `<edge>`, also those without a spring (drawing).
  Edges edges = Edges(0, 2);
  /// @brief The `<springforce>` elements, in file order (at most one per edge).
  std::vector<SpringForce> springs;
  /// @brief The sum of the `<simplegravity>` accelerations [m/s^2], when there is one.
  std::optional<Vector3<double>> gravity;
  /// @brief The `<gravitationalforce>` pairs, in file order.
  std::vector<Attraction> attractions;
  /// @brief The sum of the `<dragdamping b>` coefficients [N s/m], when there is one.
  std::optional<double> drag;
  /// @brief The integrator the scene names.
  FosssimIntegrator integrator = FosssimIntegrator::SymplecticEuler;
  /// @brief Time step [s], > 0.
  double dt = 0.01;
  /// @brief Simulated time [s], >= 0.
  double duration = 0;
  /// @brief `<description text>` (empty when absent).
  std::string description;
  /// @brief `<scenetag tag>` values, in file order.
  std::vector<std::string> tags;

  // ---- Theme 2: collisions (and Theme 1's vortex force) ----------------------------------------

  /// @brief A `<halfplane px py nx ny>`: a point on the boundary and the normal into the free side
  /// (any length > 0), z = 0.
  struct Halfplane {
    Vector3<double> point = Vector3<double>::Zero();
    Vector3<double> normal = Vector3<double>::UnitY();
  };
  /// @brief A `<vortexforce i j kbs kvc>` (forces/vortex.hpp).
  struct Vortex {
    int i = 0, j = 0;
    double kbs = 0, kvc = 0;
  };
  /// @brief The `<collision>` element: its type and parameters (FOSSSim's defaults filled in).
  struct Collision {
    FosssimCollision type = FosssimCollision::None;
    double cor = 1;           ///< COR, in [0, 1] (simple, continuous-time, hybrid)
    double k = 0;             ///< penalty stiffness [N/m] (penalty: default 100; hybrid: 10)
    double thickness = 0;     ///< penalty thickness [m] (penalty: default 0.01; hybrid: 0.1)
    int max_iterations = 10;  ///< maxiters (hybrid), >= 0
  };

  /// @brief Particle radii [m] (`<particle radius>`, default 0.1), one per particle; empty means
  /// every particle has the default.
  std::vector<double> radii;
  /// @brief Edge radii [m] (`<edge radius>`, default 0.015), one per edge; empty: the default.
  std::vector<double> edge_radii;
  /// @brief The `<halfplane>` elements, in file order.
  std::vector<Halfplane> halfplanes;
  /// @brief The `<vortexforce>` elements, in file order.
  std::vector<Vortex> vortices;
  /// @brief The `<collision>` element, when there is one.
  std::optional<Collision> collision;
  /// @brief `<collisiondetection type>`: "allpairs" (false) or "contest" (true), when present.
  std::optional<bool> contest;

  /// @brief Particle i's radius [m].
  [[nodiscard]] double radius(int i) const {
    return radii.empty() ? kDefaultRadius : radii[std::size_t(i)];
  }
  /// @brief Edge e's radius [m].
  [[nodiscard]] double edge_radius(int e) const {
    return edge_radii.empty() ? kDefaultEdgeRadius : edge_radii[std::size_t(e)];
  }
  static constexpr double kDefaultRadius = 0.1;        ///< FOSSSim's particle radius
  static constexpr double kDefaultEdgeRadius = 0.015;  ///< FOSSSim's edge radius

  /// @brief Number of particles.
  [[nodiscard]] int num_particles() const { return int(positions.rows()); }
  /// @brief Steps to simulate: ceil(duration / dt), as FOSSSim counts them; a quotient within
  /// 1e-9 (relative) of a whole number counts as that number, so 4.0 / 0.01 gives 400 whatever
  /// the rounding of 0.01.
  [[nodiscard]] long long steps() const { return steps_for(dt); }
  /// @brief ceil(duration / h) with the same rounding rule, for another step h > 0 (saturating
  /// at the largest long long).
  [[nodiscard]] long long steps_for(double h) const { return steps_of(duration, h); }
  /// @brief ceil(time / h) for a time [s] >= 0 and a step h > 0 [s], with the same rounding rule.
  [[nodiscard]] static long long steps_of(double time, double h) {
    const double q = time / h;
    // saturate rather than overflow (an absurd duration / h is still a number of steps)
    if (!(q < 9.2e18)) return std::numeric_limits<long long>::max();
    const double nearest = std::round(q);
    if (std::abs(q - nearest) <= 1e-9 * std::max(1.0, nearest))
      return static_cast<long long>(nearest);
    return static_cast<long long>(std::ceil(q));
  }
};

}  // namespace massspring::io
