#pragma once
/// @file
/// @brief ContactGeometry: what collides in FOSSSim's 2D model (Theme 2): particles
/// with radii (discs, spheres in 3D), edges with radii (capsules around segments) and planes
/// (half-planes in 2D).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "massspring/contact/distance/point_plane.hpp"
#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The collision primitives of a scene. Positions come from the state at each call; this
/// holds the rest: particle radii, edges, edge radii, planes.
template <class Scalar>
struct ContactGeometry {
  /// @brief #particles radii [m], each >= 0 (FOSSSim's default is 0.1).
  Vector<Scalar> radii;
  /// @brief #edges by 2 particle indices: every collision edge (with or without a spring).
  Edges edges = Edges(0, 2);
  /// @brief #edges radii [m], each >= 0 (FOSSSim's default is 0.015).
  Vector<Scalar> edge_radii;
  /// @brief The planes (half-planes), in file order.
  std::vector<Plane<Scalar>> planes;

  [[nodiscard]] int num_particles() const { return int(radii.size()); }
  [[nodiscard]] int num_edges() const { return int(edges.rows()); }
  [[nodiscard]] int num_planes() const { return int(planes.size()); }

  /// @brief Largest particle index an edge uses, or #particles - 1.
  [[nodiscard]] int max_index() const {
    int m = num_particles() - 1;
    for (Eigen::Index e = 0; e < edges.rows(); ++e) m = std::max({m, edges(e, 0), edges(e, 1)});
    return m;
  }

  /// @brief Throws Error (prefixed by `who`) for a negative or non-finite radius, an edge index
  /// out of range or joining a particle to itself, a non-finite plane or a zero normal.
  void validate(const char* who) const {
    const int n = num_particles();
    for (int i = 0; i < n; ++i)
      if (!(radii(i) >= 0) || !std::isfinite(double(radii(i))))
        throw Error(massspring::detail::message(who, ": particle ", i,
                                                " radius must be finite and >= 0, got ", radii(i)));
    if (edge_radii.size() != edges.rows())
      throw Error(massspring::detail::message(who, ": ", edges.rows(), " edges but ",
                                              edge_radii.size(), " edge radii"));
    for (int e = 0; e < num_edges(); ++e) {
      for (int c = 0; c < 2; ++c)
        if (edges(e, c) < 0 || edges(e, c) >= n)
          throw Error(massspring::detail::message(who, ": edge ", e, " = (", edges(e, 0), ", ",
                                                  edges(e, 1),
                                                  "): particle index out of range [0, ", n, ")"));
      if (edges(e, 0) == edges(e, 1))
        throw Error(massspring::detail::message(who, ": edge ", e, " joins particle ", edges(e, 0),
                                                " to itself"));
      if (!(edge_radii(e) >= 0) || !std::isfinite(double(edge_radii(e))))
        throw Error(massspring::detail::message(
            who, ": edge ", e, " radius must be finite and >= 0, got ", edge_radii(e)));
    }
    for (int h = 0; h < num_planes(); ++h) {
      const auto& p = planes[std::size_t(h)];
      if (!p.point.allFinite() || !p.normal.allFinite() || !(p.normal.squaredNorm() > 0))
        throw Error(massspring::detail::message(
            who, ": half-plane ", h, " needs a finite point and a finite, non-zero normal"));
    }
  }
};

}  // namespace massspring::contact
