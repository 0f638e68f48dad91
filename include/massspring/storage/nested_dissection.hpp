#pragma once
/// @file
/// @brief Geometric nested dissection: a fill-reducing elimination order for a sparse symmetric
/// matrix whose unknowns have positions in space (the points of a mass-spring network), and the
/// symbolic count of the Cholesky factor's nonzeros for any order.
///
/// Nested dissection (George 1973) splits the graph by a small vertex separator, orders the two
/// halves first (recursively) and the separator last, so that fill stays inside the halves and the
/// separators. Here the split is geometric: the points are cut at the median of their projection
/// on one of nine directions (the three axes and the six diagonals of the coordinate planes), and
/// the separator is one side's boundary (its vertices with a neighbour on the other side), the
/// direction with the smallest separator winning. On large cloth grids this fills less than Eigen's
/// AMD, on small grids and irregular meshes AMD fills less (docs/performance.md): FastMassSpring
/// counts both and takes the smaller (FastMassSpringOptions::ordering).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <vector>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"

namespace massspring {

/// @brief An undirected graph in compressed form: the neighbours of vertex v are
/// `neighbours[start[v]]` to `neighbours[start[v + 1] - 1]` (no self-loops, each edge listed at
/// both of its ends).
struct Graph {
  std::vector<int> start{0};
  std::vector<int> neighbours;
  [[nodiscard]] int size() const { return int(start.size()) - 1; }
};

/// @brief The graph of a square sparse matrix's off-diagonal pattern, made symmetric (an entry at
/// (i, j) or (j, i) joins i and j; explicit zeros count as entries).
template <class SparseMatrix>
Graph graph_of(const SparseMatrix& a) {
  const int n = int(a.rows());
  if (a.cols() != a.rows())
    throw Error(
        detail::message("graph_of: the matrix must be square, got ", a.rows(), " x ", a.cols()));
  std::vector<int> degree(std::size_t(n) + 1, 0);
  for (int j = 0; j < int(a.outerSize()); ++j)
    for (typename SparseMatrix::InnerIterator it(a, j); it; ++it)
      if (int(it.row()) != int(it.col())) {
        ++degree[std::size_t(it.row())];
        ++degree[std::size_t(it.col())];
      }
  Graph g;
  g.start.assign(std::size_t(n) + 1, 0);
  for (int v = 0; v < n; ++v)
    g.start[std::size_t(v) + 1] = g.start[std::size_t(v)] + degree[std::size_t(v)];
  g.neighbours.resize(std::size_t(g.start.back()));
  std::vector<int> fill(g.start.begin(), g.start.end() - 1);
  for (int j = 0; j < int(a.outerSize()); ++j)
    for (typename SparseMatrix::InnerIterator it(a, j); it; ++it) {
      const int r = int(it.row()), c = int(it.col());
      if (r == c) continue;
      g.neighbours[std::size_t(fill[std::size_t(r)]++)] = c;
      g.neighbours[std::size_t(fill[std::size_t(c)]++)] = r;
    }
  // Sort and drop duplicates (an entry stored at both (i, j) and (j, i)).
  std::vector<int> start(std::size_t(n) + 1, 0);
  std::size_t out = 0;
  for (int v = 0; v < n; ++v) {
    const auto first = g.neighbours.begin() + g.start[std::size_t(v)];
    const auto last = g.neighbours.begin() + g.start[std::size_t(v) + 1];
    std::sort(first, last);
    const auto end = std::unique(first, last);
    for (auto it = first; it != end; ++it) g.neighbours[out++] = *it;
    start[std::size_t(v) + 1] = int(out);
  }
  g.neighbours.resize(out);
  g.start = std::move(start);
  return g;
}

/// @brief Nonzeros of the Cholesky factor L (diagonal included) of a symmetric positive definite
/// matrix with graph g when its unknowns are eliminated in `order` (order[k]: the vertex
/// eliminated k-th), by the elimination tree and row subtrees, in time proportional to the count.
/// @throws Error when `order` is not a permutation of g's vertices.
inline std::size_t cholesky_nonzeros(const Graph& g, const std::vector<int>& order);

/// @brief Options of nested_dissection().
struct NestedDissectionOptions {
  /// @brief Parts of at most this many vertices are not split further; their vertices keep their
  /// relative order (>= 1, default 8).
  int leaf_size = 8;
};

/// @brief Elimination order of g's vertices by geometric nested dissection (see the file's
/// description).
/// @param coordinates n x 3 positions of the vertices, row v for vertex v (any unit: each axis is
/// measured in the median length of the edges along it); points at one place are split by index
/// @param nonzeros when not null, receives cholesky_nonzeros(g, order) of the order returned
/// (counted anyway, to choose between two variants)
/// @return order[k]: the vertex eliminated k-th, a permutation of 0 .. n - 1
/// @throws Error when the sizes disagree, a coordinate is not finite or leaf_size < 1.
template <class Derived>
std::vector<int> nested_dissection(const Eigen::MatrixBase<Derived>& coordinates, const Graph& g,
                                   const NestedDissectionOptions& options = {},
                                   std::size_t* nonzeros = nullptr);

namespace detail {

inline std::vector<int> inverse_order(const std::vector<int>& order, int n, const char* who) {
  if (int(order.size()) != n)
    throw Error(message(who, ": the order has ", order.size(), " entries for ", n, " unknowns"));
  std::vector<int> position(std::size_t(n), -1);
  for (int k = 0; k < n; ++k) {
    const int v = order[std::size_t(k)];
    if (v < 0 || v >= n || position[std::size_t(v)] >= 0)
      throw Error(message(who, ": the order is not a permutation of 0 .. ", n - 1, " (entry ", k,
                          " is ", v, ")"));
    position[std::size_t(v)] = k;
  }
  return position;
}

// The recursive dissection, over a working array of vertices: each call orders its slice.
class NestedDissection {
 public:
  NestedDissection(const std::vector<std::array<double, 3>>& xyz, const Graph& g, int leaf,
                   bool balance)
      : xyz_(xyz),
        g_(g),
        leaf_(leaf),
        balance_(balance),
        part_(std::size_t(g.size()), 0),
        side_(std::size_t(g.size()), 0),
        key_(std::size_t(g.size()), 0.0) {}

  // Directions along an axis on which every point lies at one coordinate (a flat cloth) repeat
  // others, or separate nothing: skipped.
  void flat_axes(const std::array<bool, 3>& flat) {
    for (std::size_t d = 0; d < 9; ++d)
      for (std::size_t c = 0; c < 3; ++c)
        if (flat[c] && kDirections[d][c] != 0) use_[d] = false;
  }

  std::vector<int> run() {
    std::vector<int> vertices(std::size_t(g_.size()));
    std::iota(vertices.begin(), vertices.end(), 0);
    order_.reserve(vertices.size());
    scratch_.resize(vertices.size());
    dissect(vertices.data(), int(vertices.size()));
    return std::move(order_);
  }

 private:
  // The nine cut directions: the axes and the diagonals of the coordinate planes.
  static constexpr std::array<std::array<double, 3>, 9> kDirections{{{1, 0, 0},
                                                                     {0, 1, 0},
                                                                     {0, 0, 1},
                                                                     {1, 1, 0},
                                                                     {1, -1, 0},
                                                                     {1, 0, 1},
                                                                     {1, 0, -1},
                                                                     {0, 1, 1},
                                                                     {0, 1, -1}}};

  // Splits v[0 .. count) along direction d (d = 9: by index): side_ 0 for the `half` lowest, 1
  // for the others. False when the direction does not separate the points.
  bool split(int* v, int count, int d, int half) {
    if (d < 9) {
      const auto& u = kDirections[std::size_t(d)];
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (int k = 0; k < count; ++k) {
        const auto& p = xyz_[std::size_t(v[k])];
        const double key = u[0] * p[0] + u[1] * p[1] + u[2] * p[2];
        key_[std::size_t(v[k])] = key;
        lo = std::min(lo, key);
        hi = std::max(hi, key);
      }
      if (!(hi > lo)) return false;
    } else {
      for (int k = 0; k < count; ++k) key_[std::size_t(v[k])] = double(v[k]);
    }
    int* w = scratch_.data();
    std::copy_n(v, count, w);
    std::nth_element(w, w + half, w + count, [this](int a, int b) {
      const double ka = key_[std::size_t(a)], kb = key_[std::size_t(b)];
      return ka < kb || (ka == kb && a < b);
    });
    for (int k = 0; k < count; ++k) side_[std::size_t(w[k])] = k < half ? 0 : 1;
    return true;
  }

  // How many vertices of each side (of the part `stamp`) have a neighbour on the other side; with
  // mark >= 0, those of side `mark` become the separator (side 2).
  std::array<int, 2> boundary(const int* v, int count, int stamp, int mark = -1) {
    std::array<int, 2> size{0, 0};
    for (int k = 0; k < count; ++k) {
      const int a = v[k];
      const int s = side_[std::size_t(a)];
      if (s > 1 || (mark >= 0 && s != mark)) continue;
      bool cut = false;
      for (int q = g_.start[std::size_t(a)]; q < g_.start[std::size_t(a) + 1] && !cut; ++q) {
        const int b = g_.neighbours[std::size_t(q)];
        cut = part_[std::size_t(b)] == stamp && side_[std::size_t(b)] == 1 - s;
      }
      if (cut) {
        ++size[std::size_t(s)];
        if (mark >= 0) side_[std::size_t(a)] = 2;
      }
    }
    return size;
  }

  void dissect(int* v, int count) {
    if (count <= leaf_) {
      std::sort(v, v + count);
      order_.insert(order_.end(), v, v + count);
      return;
    }
    const int stamp = ++stamps_;
    for (int k = 0; k < count; ++k) part_[std::size_t(v[k])] = stamp;
    int best = -1, best_side = 0, best_size = count + 1;
    for (int d = 0; d <= 9; ++d) {
      if (d == 9 && best >= 0) break;  // by index only when no direction separates the points
      if (d < 9 && !use_[std::size_t(d)]) continue;
      if (!split(v, count, d, count / 2)) continue;
      const std::array<int, 2> size = boundary(v, count, stamp);
      for (int s = 0; s < 2; ++s)
        if (size[std::size_t(s)] < best_size)
          best = d, best_side = s, best_size = size[std::size_t(s)];
    }
    // The cut again; with balance_, moved by half the separator so that the two parts left are
    // of one size.
    // Both sides keep at least one vertex, so that both parts left are smaller than count.
    const int half = !balance_        ? count / 2
                     : best_side == 0 ? (count + best_size) / 2
                                      : (count - best_size) / 2;
    split(v, count, best, std::clamp(half, 1, count - 1));
    best_size = boundary(v, count, stamp, best_side)[std::size_t(best_side)];
    // v = [side 0 | side 1 | separator], each in its original relative order.
    int* out = scratch_.data();
    int n = 0;
    for (int s = 0; s <= 2; ++s)
      for (int k = 0; k < count; ++k)
        if (side_[std::size_t(v[k])] == s) out[n++] = v[k];
    std::copy_n(out, count, v);
    int lower = 0, upper = 0;
    for (int k = 0; k < count; ++k) (side_[std::size_t(v[k])] == 0 ? lower : upper) += 1;
    upper -= best_size;
    dissect(v, lower);
    dissect(v + lower, upper);
    std::sort(v + lower + upper, v + count);
    order_.insert(order_.end(), v + lower + upper, v + count);
  }

  const std::vector<std::array<double, 3>>& xyz_;
  const Graph& g_;
  int leaf_;
  bool balance_;
  std::array<bool, 9> use_{true, true, true, true, true, true, true, true, true};
  int stamps_ = 0;
  std::vector<int> part_;    // stamp of the part being split that holds the vertex
  std::vector<int> side_;    // 0, 1: side of the current split; 2: separator
  std::vector<double> key_;  // projection on the direction being tried
  std::vector<int> scratch_, order_;
};

}  // namespace detail

inline std::size_t cholesky_nonzeros(const Graph& g, const std::vector<int>& order) {
  const int n = g.size();
  const std::vector<int> position = detail::inverse_order(order, n, "cholesky_nonzeros");
  std::vector<int> parent(std::size_t(n), -1), flag(std::size_t(n), -1);
  std::size_t count = std::size_t(n);
  for (int k = 0; k < n; ++k) {
    flag[std::size_t(k)] = k;
    const int v = order[std::size_t(k)];
    for (int q = g.start[std::size_t(v)]; q < g.start[std::size_t(v) + 1]; ++q) {
      // Row k of L: the path from each earlier neighbour up the elimination tree to row k.
      for (int i = position[std::size_t(g.neighbours[std::size_t(q)])];
           i < k && flag[std::size_t(i)] != k; i = parent[std::size_t(i)]) {
        if (parent[std::size_t(i)] < 0) parent[std::size_t(i)] = k;
        flag[std::size_t(i)] = k;
        ++count;
      }
    }
  }
  return count;
}

template <class Derived>
std::vector<int> nested_dissection(const Eigen::MatrixBase<Derived>& coordinates, const Graph& g,
                                   const NestedDissectionOptions& options, std::size_t* nonzeros) {
  const int n = g.size();
  if (int(coordinates.rows()) != n || coordinates.cols() != 3)
    throw Error(detail::message("nested_dissection: coordinates are ", coordinates.rows(), " x ",
                                coordinates.cols(), " for a graph of ", n, " vertices (need ", n,
                                " x 3)"));
  if (options.leaf_size < 1)
    throw Error(
        detail::message("nested_dissection: leaf_size must be >= 1, got ", options.leaf_size));
  std::vector<std::array<double, 3>> xyz(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v)
    for (int c = 0; c < 3; ++c) {
      const double x = double(coordinates(v, c));
      if (!std::isfinite(x))
        throw Error(
            detail::message("nested_dissection: coordinate (", v, ", ", c, ") is not finite: ", x));
      xyz[std::size_t(v)][std::size_t(c)] = x;
    }
  // Each axis in units of the median length of the edges along it, so that the diagonal
  // directions follow the diagonals of a grid whose spacing differs between its axes.
  for (int c = 0; c < 3; ++c) {
    std::vector<double> lengths;
    lengths.reserve(g.neighbours.size() / 2);
    for (int v = 0; v < n; ++v)
      for (int q = g.start[std::size_t(v)]; q < g.start[std::size_t(v) + 1]; ++q) {
        const int u = g.neighbours[std::size_t(q)];
        const double d =
            std::abs(xyz[std::size_t(u)][std::size_t(c)] - xyz[std::size_t(v)][std::size_t(c)]);
        if (u > v && d > 0) lengths.push_back(d);
      }
    if (lengths.empty()) continue;
    const auto middle = lengths.begin() + std::ptrdiff_t(lengths.size() / 2);
    std::nth_element(lengths.begin(), middle, lengths.end());
    // Rounded to 1e-6 of that length: points of one grid line stay tied after the division.
    for (auto& p : xyz) p[std::size_t(c)] = std::round(p[std::size_t(c)] / *middle * 1e6) * 1e-6;
  }
  // Two variants: the cut at the median (the separator then takes its vertices from one side),
  // and the cut moved by half the separator (two parts of one size). Neither wins everywhere
  // (the first on grids with skip-one springs, the second on plain grids); the one with the
  // smaller factor is returned.
  std::array<bool, 3> flat{};
  for (std::size_t c = 0; c < 3; ++c) {
    flat[c] = true;
    for (const auto& p : xyz) flat[c] = flat[c] && p[c] == xyz.front()[c];
  }
  detail::NestedDissection by_median(xyz, g, options.leaf_size, false);
  detail::NestedDissection by_balance(xyz, g, options.leaf_size, true);
  by_median.flat_axes(flat);
  by_balance.flat_axes(flat);
  std::vector<int> median = by_median.run();
  std::vector<int> balanced = by_balance.run();
  const std::size_t nnz_balanced = cholesky_nonzeros(g, balanced);
  const std::size_t nnz_median = cholesky_nonzeros(g, median);
  if (nonzeros) *nonzeros = std::min(nnz_balanced, nnz_median);
  return nnz_balanced < nnz_median ? balanced : median;
}

}  // namespace massspring
