#pragma once
/// @file
/// @brief FosssimBroadPhase: the candidate pairs a narrow phase tests (particle-particle,
/// particle-edge, particle-plane), either every pair (FOSSSim's AllPairsDetector) or a sorted
/// uniform grid (our `contest` detector): O(m log m + k) per call for m (cell, box) entries and k
/// candidates, m = O(n) when boxes are about the median size.
///
/// A candidate's boxes enclose the motion from the start positions qs to the end positions qe
/// (straight lines stay inside the box of their end points), grown by each primitive's radius and
/// the margin, so every pair that the narrow phase of any response can report (overlap at the end,
/// overlap at some time of the step, or penalty distance within `margin`) is a candidate. The
/// narrow phase decides; the two kinds therefore give the same contacts.
///
/// Visiting order (FOSSSim's AllPairsDetector::performCollisionDetection): for each particle i
/// in turn, the pairs (i, j) with j > i, then the edges e not incident to i, then every plane h.
/// The impulse responses depend on this order (each sees the velocities the previous ones left);
/// `ordered = false` skips the sort where the order does not matter (sums of forces).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "massspring/contact/fosssim/geometry.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief Which pairs a broad phase returns (the scene's `<collisiondetection type>`).
enum class BroadPhaseKind {
  AllPairs,  ///< "allpairs": every pair, O(n^2 + n E + n H) per call
  Grid,      ///< "contest": boxes in a uniform grid sorted by cell, O(m log m + k + n H)
};

/// @brief The kind of a candidate pair: (particle, particle), (particle, edge), (particle, plane).
enum class ParticlePairKind { PointPoint, PointEdge, PointPlane };

/// @brief Finds candidate pairs; holds its work arrays, so calls after the first allocate only
/// when the number of candidates grows.
template <class Scalar>
class FosssimBroadPhase {
 public:
  explicit FosssimBroadPhase(BroadPhaseKind kind = BroadPhaseKind::AllPairs) : kind_(kind) {}

  [[nodiscard]] BroadPhaseKind kind() const { return kind_; }
  void set_kind(BroadPhaseKind kind) {
    kind_ = kind;
    cached_ = false;
  }

  /// @brief Calls `visit(ParticlePairKind, i, j)` for every candidate: (PointPoint, i, j) with i <
  /// j, (PointEdge, i, e) with e not incident to i, (PointPlane, i, h).
  /// @param[in] g       the primitives (radii, edges, planes)
  /// @param[in] qs, qe  #particles by 3 positions at the start and at the end of the motion [m]
  ///                    (pass the same array twice for a static test)
  /// @param[in] margin  distance added to every radius [m], >= 0 (a penalty force's thickness)
  /// @param[in] ordered visit in FOSSSim's order (see the file's documentation)
  template <class Visitor>
  void visit(const ContactGeometry<Scalar>& g, const Points<Scalar>& qs, const Points<Scalar>& qe,
             Scalar margin, Visitor&& visit, bool ordered = true) {
    const int n = g.num_particles();
    const int E = g.num_edges(), H = g.num_planes();
    if (kind_ == BroadPhaseKind::AllPairs) {
      for (int i = 0; i < n; ++i) {
        for (int j = i + 1; j < n; ++j) visit(ParticlePairKind::PointPoint, i, j);
        for (int e = 0; e < E; ++e)
          if (g.edges(e, 0) != i && g.edges(e, 1) != i) visit(ParticlePairKind::PointEdge, i, e);
        for (int h = 0; h < H; ++h) visit(ParticlePairKind::PointPlane, i, h);
      }
      return;
    }
    // a static query at the positions of the previous one (a force, then the energy at the same
    // state) reuses its candidates
    const bool still = &qs == &qe;
    const bool reuse = still && cached_ && margin == cached_margin_ &&
                       (cached_ordered_ || !ordered) && qs.rows() == cached_x_.rows() &&
                       (qs.array() == cached_x_.array()).all();
    if (!reuse) {
      sweep(g, qs, qe, margin, ordered);
      cached_ = still;
      if (still) {
        cached_x_ = qs;
        cached_margin_ = margin;
        cached_ordered_ = ordered;
      }
    }
    if (!ordered) {
      for (const auto& p : pp_) visit(ParticlePairKind::PointPoint, p.first, p.second);
      for (const auto& p : pe_) visit(ParticlePairKind::PointEdge, p.first, p.second);
      for (int i = 0; i < n; ++i)
        for (int h = 0; h < H; ++h) visit(ParticlePairKind::PointPlane, i, h);
      return;
    }
    std::size_t a = 0, b = 0;
    for (int i = 0; i < n; ++i) {
      for (; a < pp_.size() && pp_[a].first == i; ++a)
        visit(ParticlePairKind::PointPoint, i, pp_[a].second);
      for (; b < pe_.size() && pe_[b].first == i; ++b)
        visit(ParticlePairKind::PointEdge, i, pe_[b].second);
      for (int h = 0; h < H; ++h) visit(ParticlePairKind::PointPlane, i, h);
    }
  }

  /// @brief The particle-particle candidates of the last Grid visit, (i, j) with i < j.
  [[nodiscard]] const std::vector<std::pair<int, int>>& point_point() const { return pp_; }
  /// @brief The particle-edge candidates of the last Grid visit, (i, e).
  [[nodiscard]] const std::vector<std::pair<int, int>>& point_edge() const { return pe_; }

 private:
  /// @brief Boxes of the particles (items 0..n-1) and edges (n..n+E-1) in a uniform grid of
  /// cells the size of the median box: (cell, item) entries sorted by cell, the items sharing a
  /// cell tested pairwise (a pair once, in the cell of the lower corner of its boxes'
  /// intersection); boxes wider than 4 cells are tested against every box.
  void sweep(const ContactGeometry<Scalar>& g, const Points<Scalar>& qs, const Points<Scalar>& qe,
             Scalar margin, bool ordered) {
    const int n = g.num_particles(), E = g.num_edges();
    const int N = n + E;
    lo_.resize(std::size_t(N));
    hi_.resize(std::size_t(N));
    constexpr Scalar eps = 16 * std::numeric_limits<Scalar>::epsilon();
    auto grow = [&](Box& lo, Box& hi, Scalar r) {
      for (int c = 0; c < 3; ++c) {
        // widen by the radius and by a few ulps of the coordinates, so rounding never drops a
        // pair the narrow phase would report
        const Scalar pad = r * (1 + eps) + eps * std::max(std::abs(lo[c]), std::abs(hi[c]));
        lo[c] -= pad;
        hi[c] += pad;
      }
    };
    for (int i = 0; i < n; ++i) {
      Box& lo = lo_[std::size_t(i)];
      Box& hi = hi_[std::size_t(i)];
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(qs(i, c), qe(i, c));
        hi[c] = std::max(qs(i, c), qe(i, c));
      }
      grow(lo, hi, g.radii(i) + margin);
    }
    for (int e = 0; e < E; ++e) {
      Box& lo = lo_[std::size_t(n + e)];
      Box& hi = hi_[std::size_t(n + e)];
      const int a = g.edges(e, 0), b = g.edges(e, 1);
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min({qs(a, c), qe(a, c), qs(b, c), qe(b, c)});
        hi[c] = std::max({qs(a, c), qe(a, c), qs(b, c), qe(b, c)});
      }
      grow(lo, hi, g.edge_radii(e) + margin);
    }
    // cell size: the median box extent, so that a typical box spans one or two cells per axis;
    // boxes over 4 cells wide (a long floor edge) are tested against every box instead
    ext_.resize(std::size_t(N));
    for (int k = 0; k < N; ++k) {
      Scalar e = 0;
      for (int c = 0; c < 3; ++c) e = std::max(e, hi_[std::size_t(k)][c] - lo_[std::size_t(k)][c]);
      ext_[std::size_t(k)] = e;
    }
    pp_.clear();
    pe_.clear();
    if (N == 0) return;
    scratch_ = ext_;
    std::nth_element(scratch_.begin(), scratch_.begin() + N / 2, scratch_.end());
    Scalar median = scratch_[std::size_t(N / 2)];
    if (!(median > 0) || !std::isfinite(median)) median = 1;
    const Scalar large = 8 * median;
    Scalar h = median;
    big_.clear();
    Box origin{};
    origin.fill(std::numeric_limits<Scalar>::infinity());
    Box top{};
    top.fill(-std::numeric_limits<Scalar>::infinity());
    for (int k = 0; k < N; ++k) {
      if (ext_[std::size_t(k)] > large) {
        big_.push_back(k);
        continue;
      }
      for (int c = 0; c < 3; ++c) {
        origin[c] = std::min(origin[c], lo_[std::size_t(k)][c]);
        top[c] = std::max(top[c], hi_[std::size_t(k)][c]);
      }
    }
    // at most 2^20 cells per axis (cell numbers fit 63 bits, with one bit left)
    for (int c = 0; c < 3; ++c)
      if (top[c] > origin[c]) h = std::max(h, (top[c] - origin[c]) / Scalar(1 << 20));
    auto overlap = [&](int a, int b) {
      for (int c = 0; c < 3; ++c)
        if (lo_[std::size_t(a)][c] > hi_[std::size_t(b)][c] ||
            lo_[std::size_t(b)][c] > hi_[std::size_t(a)][c])
          return false;
      return true;
    };
    auto emit = [&](int a, int b) {
      if (a < n && b < n) {
        pp_.emplace_back(std::min(a, b), std::max(a, b));
      } else {
        const int p = a < n ? a : b;
        const int e = (a < n ? b : a) - n;
        if (g.edges(e, 0) != p && g.edges(e, 1) != p) pe_.emplace_back(p, e);
      }
    };
    auto cell = [&](Scalar v, int c) { return std::int32_t(std::floor((v - origin[c]) / h)); };
    // each small box's range of cells; the grid's size
    cell_lo_.resize(std::size_t(N));
    cell_hi_.resize(std::size_t(N));
    std::array<std::int64_t, 3> dims{1, 1, 1};
    std::size_t entries = 0;
    for (int k = 0; k < N; ++k) {
      if (ext_[std::size_t(k)] > large) continue;
      std::size_t span = 1;
      for (int c = 0; c < 3; ++c) {
        cell_lo_[std::size_t(k)][c] = cell(lo_[std::size_t(k)][c], c);
        cell_hi_[std::size_t(k)][c] = cell(hi_[std::size_t(k)][c], c);
        dims[c] = std::max<std::int64_t>(dims[c], cell_hi_[std::size_t(k)][c] + 1);
        span *= std::size_t(cell_hi_[std::size_t(k)][c] - cell_lo_[std::size_t(k)][c] + 1);
      }
      entries += span;
    }
    // (cell, item) entries ordered by cell, particles before edges within a cell: a counting
    // sort when the grid has few cells for its entries, a comparison sort otherwise
    const std::int64_t total = dims[0] * dims[1] * dims[2];
    cells_.resize(entries);
    auto linear = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      return std::uint64_t((z * dims[1] + y) * dims[0] + x);
    };
    auto for_cells = [&](int k, auto&& f) {
      const auto& a = cell_lo_[std::size_t(k)];
      const auto& b = cell_hi_[std::size_t(k)];
      for (std::int64_t z = a[2]; z <= b[2]; ++z)
        for (std::int64_t y = a[1]; y <= b[1]; ++y)
          for (std::int64_t x = a[0]; x <= b[0]; ++x) f(linear(x, y, z));
    };
    if (total <= std::int64_t(4 * entries + 4096)) {
      start_.assign(std::size_t(total) + 1, 0);
      for (int k = 0; k < N; ++k)
        if (!(ext_[std::size_t(k)] > large))
          for_cells(k, [&](std::uint64_t c) { ++start_[c + 1]; });
      for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
      for (int k = 0; k < N; ++k)  // items in order: particles (k < n) land before edges
        if (!(ext_[std::size_t(k)] > large))
          for_cells(k, [&](std::uint64_t c) { cells_[start_[c]++] = {2 * c + (k >= n), k}; });
    } else {
      std::size_t at = 0;
      for (int k = 0; k < N; ++k)
        if (!(ext_[std::size_t(k)] > large))
          for_cells(k, [&](std::uint64_t c) { cells_[at++] = {2 * c + (k >= n), k}; });
      std::sort(cells_.begin(), cells_.end());
    }
    for (std::size_t r = 0; r < cells_.size();) {
      // a run: the entries of one cell, particles first (the key's last bit), then edges
      const std::uint64_t key = cells_[r].first >> 1;
      std::size_t end = r, edges_from = r;
      run_.clear();
      for (; end < cells_.size() && (cells_[end].first >> 1) == key; ++end) {
        if (!(cells_[end].first & 1)) edges_from = end + 1;
        const int k = cells_[end].second;
        run_.push_back({lo_[std::size_t(k)], hi_[std::size_t(k)], cell_lo_[std::size_t(k)], k});
      }
      const std::size_t count = end - r, particles = edges_from - r;
      for (std::size_t u = 0; u < particles; ++u) {  // particle-particle and particle-edge only
        const Entry& a = run_[u];
        for (std::size_t t = u + 1; t < count; ++t) {
          const Entry& b = run_[t];
          // one branch for the six comparisons (& not &&): most pairs fail one of them, and
          // which one is unpredictable (as ints: clang warns of & on bools)
          if (!(int(a.lo[0] <= b.hi[0]) & int(b.lo[0] <= a.hi[0]) & int(a.lo[1] <= b.hi[1]) &
                int(b.lo[1] <= a.hi[1]) & int(a.lo[2] <= b.hi[2]) & int(b.lo[2] <= a.hi[2])))
            continue;
          // report a pair once: in the cell holding the lower corner of the boxes' intersection
          if (linear(std::max(a.cell[0], b.cell[0]), std::max(a.cell[1], b.cell[1]),
                     std::max(a.cell[2], b.cell[2])) == key)
            emit(a.item, b.item);
        }
      }
      r = end;
    }
    for (std::size_t u = 0; u < big_.size(); ++u) {
      const int a = big_[u];
      for (int b = 0; b < N; ++b) {
        if (b == a || (a >= n && b >= n)) continue;
        const bool b_big = ext_[std::size_t(b)] > large;
        if (b_big && b < a) continue;  // a big pair once
        if (overlap(a, b)) emit(a, b);
      }
    }
    if (ordered) {
      std::sort(pp_.begin(), pp_.end());
      std::sort(pe_.begin(), pe_.end());
    }
  }

  using Box = std::array<Scalar, 3>;
  BroadPhaseKind kind_;
  std::vector<Box> lo_, hi_;
  std::vector<Scalar> ext_, scratch_;
  std::vector<int> big_;
  std::vector<std::pair<std::uint64_t, int>> cells_;
  using Cell = std::array<std::int32_t, 3>;
  struct Entry {
    Box lo, hi;
    Cell cell;  // the cell of lo
    int item;
  };
  std::vector<Cell> cell_lo_, cell_hi_;
  Points<Scalar> cached_x_;
  Scalar cached_margin_ = 0;
  bool cached_ = false, cached_ordered_ = false;
  std::vector<std::size_t> start_;
  std::vector<Entry> run_;
  std::vector<std::pair<int, int>> pp_, pe_;
};

}  // namespace massspring::contact
