#pragma once
/// @file
/// @brief make_cloth(): a rectangular cloth grid, with or without diagonals and bending springs.

#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/scene/placement.hpp"
#include "massspring/scene/scene_description.hpp"

namespace massspring {

/// @brief Diagonal (shear) springs of each grid cell.
enum class ClothShear {
  None,  ///< structural springs only (rows and columns), written as 2-vertex edges
  One,   ///< one diagonal per cell: each cell is two triangles (a, b, c), (a, c, d)
  Both,  ///< both diagonals: each cell is a quad face, whose six vertex pairs are springs
};

/// @brief Which points of the cloth are pinned. Row 0 is the "top" row.
enum class ClothPins {
  None,        ///< nothing pinned
  TopCorners,  ///< the two ends of row 0
  TopEdge,     ///< every point of row 0
};

/// @brief Where the cloth lies at rest (then moved to ClothOptions::origin or center).
enum class ClothPlane {
  Vertical,    ///< the x-y plane, rows going down: point (r, c) at (c dx, -r dy, 0)
  Horizontal,  ///< the x-z plane, rows going along +z: point (r, c) at (c dx, 0, r dy)
};

/// @brief Parameters of make_cloth(). Point (r, c) has index r * columns + c; point (0, 0) lies at
/// `origin`, or the cloth's middle at `center` (ScenePlacement).
struct ClothOptions : ScenePlacement {
  /// @brief Points along x, >= 2.
  int columns = 60;
  /// @brief Points along the other axis (y or z), >= 2.
  int rows = 50;
  /// @brief Extent along x [m], > 0.
  double width = 1.2;
  /// @brief Extent along the other axis [m], > 0.
  double height = 1.0;
  /// @brief Diagonal springs per cell (default Both, like the JSON+OBJ scenes' flag).
  ClothShear shear = ClothShear::Both;
  /// @brief Skip-one springs, (r, c)-(r, c+2) and (r, c)-(r+2, c), written as 2-vertex edges.
  bool bending = false;
  /// @brief Pinned points (default the two top corners).
  ClothPins pins = ClothPins::TopCorners;
  /// @brief Rest plane (default Vertical).
  ClothPlane plane = ClothPlane::Vertical;
  /// @brief Stiffness of every spring [N/m], >= 0.
  double stiffness = 1000;
  /// @brief Mass of every point [kg], > 0. When absent: the faces' lumped Voronoi areas (density
  /// 1 kg/m^2), or with ClothShear::None (no faces) width * height / #points for every point.
  std::optional<double> mass;
};

/// @brief A rectangular cloth grid. Springs: structural (rows, columns), the chosen diagonals and,
/// optionally, bending; see ClothOptions.
/// @throws Error naming the first invalid option.
inline SceneDescription<double> make_cloth(const ClothOptions& o) {
  if (o.columns < 2 || o.rows < 2)
    throw Error(detail::message("make_cloth: columns and rows must be >= 2, got ", o.columns,
                                " by ", o.rows));
  if (!(o.width > 0) || !(o.height > 0) || !std::isfinite(o.width) || !std::isfinite(o.height))
    throw Error(detail::message("make_cloth: width and height must be finite and > 0, got ",
                                o.width, " by ", o.height));
  detail::require_number("make_cloth", "stiffness", o.stiffness, false);
  if (o.mass) detail::require_number("make_cloth", "mass", *o.mass, true);

  const int cols = o.columns, rows = o.rows;
  auto id = [cols](int r, int c) { return r * cols + c; };
  const double dx = o.width / (cols - 1), dy = o.height / (rows - 1);

  SceneDescription<double> s;
  s.vertices.resize(rows * cols, 3);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      if (o.plane == ClothPlane::Vertical)
        s.vertices.row(id(r, c)) << c * dx, -r * dy, 0.0;
      else
        s.vertices.row(id(r, c)) << c * dx, 0.0, r * dy;
    }

  std::vector<std::array<int, 2>> edges;
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 0; c + 1 < cols; ++c) {
      const int a = id(r, c), b = id(r, c + 1), cc = id(r + 1, c + 1), d = id(r + 1, c);
      switch (o.shear) {
        case ClothShear::Both:
          s.faces.push_back({a, b, cc, d});
          break;
        case ClothShear::One:
          s.faces.push_back({a, b, cc});
          s.faces.push_back({a, cc, d});
          break;
        case ClothShear::None:
          break;
      }
    }
  if (o.shear == ClothShear::None) {
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c + 1 < cols; ++c) edges.push_back({id(r, c), id(r, c + 1)});
    for (int r = 0; r + 1 < rows; ++r)
      for (int c = 0; c < cols; ++c) edges.push_back({id(r, c), id(r + 1, c)});
  }
  if (o.bending) {
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c + 2 < cols; ++c) edges.push_back({id(r, c), id(r, c + 2)});
    for (int r = 0; r + 2 < rows; ++r)
      for (int c = 0; c < cols; ++c) edges.push_back({id(r, c), id(r + 2, c)});
  }
  s.edges.resize(Eigen::Index(edges.size()), 2);
  for (std::size_t e = 0; e < edges.size(); ++e)
    s.edges.row(Eigen::Index(e)) << edges[e][0], edges[e][1];

  switch (o.pins) {
    case ClothPins::None:
      break;
    case ClothPins::TopCorners:
      s.pinned = {id(0, 0), id(0, cols - 1)};
      break;
    case ClothPins::TopEdge:
      for (int c = 0; c < cols; ++c) s.pinned.push_back(id(0, c));
      break;
  }
  s.stiffness = o.stiffness;
  s.mass = o.mass;
  if (!s.mass && o.shear == ClothShear::None) s.mass = o.width * o.height / (rows * cols);
  detail::place(s, o, "make_cloth");
  return s;
}

}  // namespace massspring
