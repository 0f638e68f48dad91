#pragma once
/// @file
/// @brief Placing a generated scene (make_cloth(), make_chain(), make_net()): each builds its
/// points with point 0 at the origin, then moves them rigidly to the `origin` or `center` its
/// options ask for.

#include <optional>
#include <string>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/scene/scene_description.hpp"
#include "massspring/types.hpp"

namespace massspring::detail {

/// @brief Translates every vertex of `s` so that point 0 lies at `origin` [m], or so that the
/// centre of the vertices' bounding box ((min + max) / 2 per axis) lies at `center` [m]; neither:
/// unchanged.
/// @throws Error "<who>: ..." when both are given or one is not finite.
inline void place(SceneDescription<double>& s, const std::optional<Vector3<double>>& origin,
                  const std::optional<Vector3<double>>& center, const char* who) {
  if (origin && center)
    throw Error(message(who,
                        ": give origin (where point 0 goes) or center (where the middle "
                        "goes), not both"));
  const char* name = origin ? "origin" : "center";
  const std::optional<Vector3<double>>& at = origin ? origin : center;
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
