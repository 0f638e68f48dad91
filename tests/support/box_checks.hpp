#pragma once
// Oracles for tests of box colliders, written without the library's contact code: the twelve
// edges of a box and whether a segment meets it (a slab test).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace massspring::test {

// The twelve edges of the box [-h, h] as segments.
inline std::array<std::array<Eigen::Vector3d, 2>, 12> box_edges(const Eigen::Vector3d& h) {
  std::array<std::array<Eigen::Vector3d, 2>, 12> edges;
  int n = 0;
  for (int a = 0; a < 3; ++a)
    for (int sb = -1; sb <= 1; sb += 2)
      for (int sc = -1; sc <= 1; sc += 2) {
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        Eigen::Vector3d e0, e1;
        e0(a) = -h(a);
        e1(a) = h(a);
        e0(b) = e1(b) = sb * h(b);
        e0(c) = e1(c) = sc * h(c);
        edges[std::size_t(n++)] = {e0, e1};
      }
  return edges;
}

// Whether the segment a-b meets the closed box centred at c with half extents h (axis-aligned).
inline bool segment_meets_box(Eigen::Vector3d a, Eigen::Vector3d b, const Eigen::Vector3d& c,
                              const Eigen::Vector3d& h) {
  a -= c;
  b -= c;
  double t0 = 0, t1 = 1;
  const Eigen::Vector3d d = b - a;
  for (int k = 0; k < 3; ++k) {
    if (d(k) == 0) {
      if (std::abs(a(k)) > h(k)) return false;
      continue;
    }
    double lo = (-h(k) - a(k)) / d(k), hi = (h(k) - a(k)) / d(k);
    if (lo > hi) std::swap(lo, hi);
    t0 = std::max(t0, lo);
    t1 = std::min(t1, hi);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace massspring::test
