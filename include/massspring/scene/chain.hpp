#pragma once
/// @file
/// @brief make_chain(): points on a straight line joined by springs, like the JSON+OBJ scenes'
/// horizontal chain.

#include <cmath>
#include <optional>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/scene/placement.hpp"
#include "massspring/scene/scene_description.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief Which points of the chain are pinned.
enum class ChainPins {
  None,      ///< nothing pinned
  First,     ///< point 0
  BothEnds,  ///< point 0 and the last point
};

/// @brief Parameters of make_chain(). Point i has index i and lies at i * length / (points - 1)
/// along `direction` from point 0, which lies at `origin` (default the origin), or the chain's
/// middle at `center` (ScenePlacement).
struct ChainOptions : ScenePlacement {
  /// @brief Number of points, >= 2.
  int points = 10;
  /// @brief Distance from the first to the last point [m], finite and > 0.
  double length = 1.0;
  /// @brief Direction of the chain (normalised here), finite and nonzero; default +x.
  Vector3<double> direction = Vector3<double>::UnitX();
  /// @brief Pinned points (default both ends).
  ChainPins pins = ChainPins::BothEnds;
  /// @brief Stiffness of every spring [N/m], finite and >= 0.
  double stiffness = 500;
  /// @brief Mass of every point [kg], finite and > 0.
  double mass = 1;
};

/// @brief A straight chain: `points` points evenly spaced along `direction`, springs between
/// consecutive points as 2-vertex edges (i, i + 1), no faces. Every rest length is
/// length / (points - 1).
/// @throws Error naming the first invalid option.
inline SceneDescription<double> make_chain(const ChainOptions& o) {
  using detail::message;
  if (o.points < 2) throw Error(message("make_chain: points must be >= 2, got ", o.points));
  detail::require_number("make_chain", "length", o.length, true);
  const double norm = o.direction.norm();
  if (!o.direction.allFinite() || !(norm > 0) || !std::isfinite(norm))
    throw Error(message("make_chain: direction must be finite and nonzero, got ",
                        detail::format_row(o.direction)));
  detail::require_number("make_chain", "stiffness", o.stiffness, false);
  detail::require_number("make_chain", "mass", o.mass, true);

  const Vector3<double> unit = o.direction / norm;
  SceneDescription<double> s;
  s.vertices.resize(o.points, 3);
  for (int i = 0; i < o.points; ++i)
    s.vertices.row(i) = (unit * (o.length * i / (o.points - 1))).transpose();
  s.edges.resize(o.points - 1, 2);
  for (int i = 0; i + 1 < o.points; ++i) s.edges.row(i) << i, i + 1;
  switch (o.pins) {
    case ChainPins::None:
      break;
    case ChainPins::First:
      s.pinned = {0};
      break;
    case ChainPins::BothEnds:
      s.pinned = {0, o.points - 1};
      break;
  }
  s.stiffness = o.stiffness;
  s.mass = o.mass;
  detail::place(s, o, "make_chain");
  return s;
}

}  // namespace massspring
