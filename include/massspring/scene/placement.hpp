#pragma once
/// @file
/// @brief Placing a generated scene (make_cloth(), make_chain(), make_net()): each builds its
/// points with point 0 at the origin, then moves them rigidly to the `origin` or `center` its
/// options (a ScenePlacement) ask for.

#include <optional>
#include <string>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/scene/scene_description.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief Where a generated scene lies: the base of ClothOptions, ChainOptions and NetOptions.
/// At most one of origin and center; neither: point 0 stays at the origin.
struct ScenePlacement {
  /// @brief Where point 0 lies [m] (default: the origin).
  std::optional<Vector3<double>> origin;
  /// @brief Where the middle of the scene (the centre of its vertices' bounding box) lies [m],
  /// e.g. above the ball a cloth is dropped on.
  std::optional<Vector3<double>> center;
};

}  // namespace massspring

namespace massspring::detail {

/// @brief Translates every vertex of `s` so that point 0 lies at `placement.origin` [m], or so
/// that the centre of the vertices' bounding box ((min + max) / 2 per axis) lies at
/// `placement.center` [m]; neither: unchanged.
/// @throws Error "<who>: ..." when both are given or one is not finite.
inline void place(SceneDescription<double>& s, const ScenePlacement& placement, const char* who) {
  const std::optional<Vector3<double>>& origin = placement.origin;
  if (origin && placement.center)
    throw Error(message(who,
                        ": give origin (where point 0 goes) or center (where the middle "
                        "goes), not both"));
  const char* name = origin ? "origin" : "center";
  const std::optional<Vector3<double>>& at = origin ? origin : placement.center;
  if (!at || s.vertices.rows() == 0) return;
  if (!at->allFinite())
    throw Error(message(who, ": ", name, " must be finite, got ", format_row(*at)));
  const Vector3<double> from =
      origin ? Vector3<double>(s.vertices.row(0).transpose())
             : Vector3<double>(
                   (s.vertices.colwise().minCoeff() + s.vertices.colwise().maxCoeff()).transpose() /
                   2);
  s.vertices.rowwise() += (*at - from).transpose();
}

}  // namespace massspring::detail
