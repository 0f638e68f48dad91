#pragma once
/// @file
/// @brief make_net(): a rectangular net of springs along its rows and columns, lying flat, like
/// the JSON+OBJ scenes' net.

#include <cmath>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/scene/cloth.hpp"
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
/// then moved so that point 0 lies at `origin`, or the net's middle at `center` (ScenePlacement).
struct NetOptions : ScenePlacement {
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

  // The points and springs of a horizontal cloth without diagonals (make_cloth(), which lists
  // the row springs, then the column springs), pinned here.
  ClothOptions grid;
  grid.columns = o.columns;
  grid.rows = o.rows;
  grid.width = o.width;
  grid.height = o.depth;
  grid.shear = ClothShear::None;
  grid.plane = ClothPlane::Horizontal;
  grid.pins = ClothPins::None;
  grid.stiffness = o.stiffness;
  grid.mass = o.mass;
  SceneDescription<double> s = make_cloth(grid);

  const int cols = o.columns, rows = o.rows;
  auto id = [cols](int r, int c) { return r * cols + c; };
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
  detail::place(s, o, "make_net");
  return s;
}

}  // namespace massspring
