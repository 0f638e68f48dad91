#pragma once
/// @file
/// @brief voronoi_masses(): lumped per-vertex areas of a polygon mesh (mixed Voronoi, Meyer et al.
/// 2003), the masses the JSON+OBJ scenes' scenes get when they give none.

#include <Eigen/Geometry>
#include <vector>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief Lumped mixed-Voronoi area of each vertex [m^2] (= mass [kg] at density 1 kg/m^2).
///
/// Each polygon (f0, f1, ..., fk) is fan-triangulated into (f0, f_i, f_{i+1}). A triangle gives
/// each corner its Voronoi area, (|PR|^2 cot Q + |PQ|^2 cot R) / 8 at corner P, when no angle is
/// obtuse; when one is, half its area goes to the obtuse corner and a quarter to each other one.
/// The areas sum to the surface area. Matches libigl's `massmatrix(V, F, MASSMATRIX_TYPE_VORONOI)`.
/// @param[in] vertices #V by 3 positions
/// @param[in] faces    polygons, 0-based, 3 or more vertices each
template <class Scalar>
Vector<Scalar> voronoi_masses(const Points<Scalar>& vertices,
                              const std::vector<std::vector<int>>& faces) {
  const Eigen::Index n = vertices.rows();
  Vector<Scalar> area = Vector<Scalar>::Zero(n);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& face = faces[f];
    if (face.size() < 3)
      throw Error(
          detail::message("face ", f, ": a polygon needs 3 or more vertices, got ", face.size()));
    for (int v : face)
      if (v < 0 || v >= n)
        throw Error(
            detail::message("face ", f, ": vertex index ", v, " out of range [0, ", n, ")"));
    for (std::size_t t = 1; t + 1 < face.size(); ++t) {
      const int c[3] = {face[0], face[t], face[t + 1]};
      // e[a]: edge opposite corner a; l2[a] its squared length.
      Vector3<Scalar> e[3];
      Scalar l2[3];
      for (int a = 0; a < 3; ++a) {
        e[a] = (vertices.row(c[(a + 2) % 3]) - vertices.row(c[(a + 1) % 3])).transpose();
        l2[a] = e[a].squaredNorm();
      }
      const Scalar double_area = e[1].cross(e[2]).norm();
      if (!(double_area > 0)) continue;  // a degenerate triangle has no area to share
      const Scalar tri = double_area / 2;
      int obtuse = -1;
      for (int a = 0; a < 3; ++a)
        if (l2[a] > l2[(a + 1) % 3] + l2[(a + 2) % 3]) obtuse = a;
      if (obtuse >= 0) {
        for (int a = 0; a < 3; ++a) area(c[a]) += a == obtuse ? tri / 2 : tri / 4;
        continue;
      }
      // cot of the angle at corner a = (l2[b] + l2[c] - l2[a]) / (2 * double_area)
      Scalar cot[3];
      for (int a = 0; a < 3; ++a)
        cot[a] = (l2[(a + 1) % 3] + l2[(a + 2) % 3] - l2[a]) / (2 * double_area);
      for (int a = 0; a < 3; ++a) {
        const int b = (a + 1) % 3, d = (a + 2) % 3;
        // corner a touches edges e[b] (opposite b) and e[d] (opposite d)
        area(c[a]) += (l2[b] * cot[b] + l2[d] * cot[d]) / 8;
      }
    }
  }
  return area;
}

}  // namespace massspring
