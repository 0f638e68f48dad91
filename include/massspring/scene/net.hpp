#pragma once
/// @file
/// @brief make_net(): a rectangular net of springs along its rows and columns, lying flat, like
/// the JSON+OBJ scenes' net.

#include <cmath>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/scene/placement.hpp"
#include "massspring/scene/scene_description.hpp"

namespace massspring {

/// @brief Which points of the net are pinned.
enum class NetPins {
  None,     ///< nothing pinned
  Corners,  ///< the four corners
  Border,   ///< every point on the boundary (a trampoline)
};

/// @brief Parameters of make_net(). Point (r, c) has index r * columns + c and lies in the
/// horizontal x-z plane at (c dx, 0, r dz), dx = width / (columns - 1), dz = depth / (rows - 1),
/// then moved so that point 0 lies at `origin`, or the net's middle at `center`.
struct NetOptions {
  /// @brief Points along x, >= 2.
  int columns = 8;
  /// @brief Points along z, >= 2.
  int rows = 8;
  /// @brief Extent along x [m], finite and > 0.
  double width = 1.0;
  /// @brief Extent along z [m], finite and > 0.
  double depth = 1.0;
  /// @brief Pinned points (default the four corners).
  NetPins pins = NetPins::Corners;
  /// @brief Stiffness of every spring [N/m], finite and >= 0.
  double stiffness = 300;
  /// @brief Mass of every point [kg], finite and > 0.
  double mass = 1;
  /// @brief Where point (0, 0) lies [m] (default: the origin). At most one of origin and center.
  std::optional<Vector3<double>> origin;
  /// @brief Where the middle of the net (the centre of its bounding box) lies [m]. At most one of
  /// origin and center.
  std::optional<Vector3<double>> center;
};

/// @brief A rectangular net: columns x rows points, springs between neighbours along each row
/// ((r, c)-(r, c+1)) and each column ((r, c)-(r+1, c)) as 2-vertex edges, no diagonals, no faces:
/// rows (columns - 1) + columns (rows - 1) springs.
/// @throws Error naming the first invalid option.
inline SceneDescription<double> make_net(const NetOptions& o) {
  using detail::message;
  if (o.columns < 2 || o.rows < 2)
    throw Error(
        message("make_net: columns and rows must be >= 2, got ", o.columns, " by ", o.rows));
  if (!(o.width > 0) || !(o.depth > 0) || !std::isfinite(o.width) || !std::isfinite(o.depth))
    throw Error(message("make_net: width and depth must be finite and > 0, got ", o.width, " by ",
                        o.depth));
  detail::require_number("make_net", "stiffness", o.stiffness, false);
  detail::require_number("make_net", "mass", o.mass, true);

  const int cols = o.columns, rows = o.rows;
  auto id = [cols](int r, int c) { return r * cols + c; };
  const double dx = o.width / (cols - 1), dz = o.depth / (rows - 1);

  SceneDescription<double> s;
  s.vertices.resize(rows * cols, 3);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) s.vertices.row(id(r, c)) << c * dx, 0.0, r * dz;

  s.edges.resize(rows * (cols - 1) + cols * (rows - 1), 2);
  int e = 0;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c + 1 < cols; ++c) s.edges.row(e++) << id(r, c), id(r, c + 1);
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 0; c < cols; ++c) s.edges.row(e++) << id(r, c), id(r + 1, c);

  switch (o.pins) {
    case NetPins::None:
      break;
    case NetPins::Corners:
      s.pinned = {id(0, 0), id(0, cols - 1), id(rows - 1, 0), id(rows - 1, cols - 1)};
      break;
    case NetPins::Border:
      for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
          if (r == 0 || c == 0 || r == rows - 1 || c == cols - 1) s.pinned.push_back(id(r, c));
      break;
  }
  s.stiffness = o.stiffness;
  s.mass = o.mass;
  detail::place(s, o.origin, o.center, "make_net");
  return s;
}

}  // namespace massspring
