#pragma once
/// @file
/// @brief BroadPhase: the candidate pairs a narrow phase tests (particle-particle, particle-edge,
/// particle-plane), either every pair (the course's AllPairsDetector) or a sort-and-sweep on the
/// axis of largest spread (our `contest` detector), O(n log n + k) per call for k candidates.
///
/// A candidate's boxes enclose the motion from the start positions qs to the end positions qe
/// (straight lines stay inside the box of their end points), grown by each primitive's radius and
/// the margin, so every pair that the narrow phase of any response can report (overlap at the end,
/// overlap at some time of the step, or penalty distance within `margin`) is a candidate. The
/// narrow phase decides; the two kinds therefore give the same contacts.
///
/// Visiting order (the course's AllPairsDetector::performCollisionDetection): for each particle i
/// in turn, the pairs (i, j) with j > i, then the edges e not incident to i, then every plane h.
/// The impulse responses depend on this order (each sees the velocities the previous ones left);
/// `ordered = false` skips the sort where the order does not matter (sums of forces).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "massspring/contact/geometry.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief Which pairs a broad phase returns (the scene's `<collisiondetection type>`).
enum class BroadPhaseKind {
  AllPairs,      ///< "allpairs": every pair, O(n^2 + n E + n H) per call
  SortAndSweep,  ///< "contest": boxes sorted on one axis, O((n + E) log(n + E) + k + n H)
};

/// @brief The kind of a candidate pair: (particle, particle), (particle, edge), (particle, plane).
enum class PairKind { PointPoint, PointEdge, PointPlane };

/// @brief Finds candidate pairs; holds its work arrays, so calls after the first allocate only
/// when the number of candidates grows.
template <class Scalar>
class BroadPhase {
 public:
  explicit BroadPhase(BroadPhaseKind kind = BroadPhaseKind::AllPairs) : kind_(kind) {}

  [[nodiscard]] BroadPhaseKind kind() const { return kind_; }
  void set_kind(BroadPhaseKind kind) { kind_ = kind; }

  /// @brief Calls `visit(PairKind, i, j)` for every candidate: (PointPoint, i, j) with i < j,
  /// (PointEdge, i, e) with e not incident to i, (PointPlane, i, h).
  /// @param[in] g       the primitives (radii, edges, planes)
  /// @param[in] qs, qe  #particles by 3 positions at the start and at the end of the motion [m]
  ///                    (pass the same array twice for a static test)
  /// @param[in] margin  distance added to every radius [m], >= 0 (a penalty force's thickness)
  /// @param[in] ordered visit in the course's order (see the file's documentation)
  template <class Visitor>
  void visit(const ContactGeometry<Scalar>& g, const Points<Scalar>& qs, const Points<Scalar>& qe,
             Scalar margin, Visitor&& visit, bool ordered = true) {
    const int n = g.num_particles();
    const int E = g.num_edges(), H = g.num_planes();
    if (kind_ == BroadPhaseKind::AllPairs) {
      for (int i = 0; i < n; ++i) {
        for (int j = i + 1; j < n; ++j) visit(PairKind::PointPoint, i, j);
        for (int e = 0; e < E; ++e)
          if (g.edges(e, 0) != i && g.edges(e, 1) != i) visit(PairKind::PointEdge, i, e);
        for (int h = 0; h < H; ++h) visit(PairKind::PointPlane, i, h);
      }
      return;
    }
    sweep(g, qs, qe, margin, ordered);
    if (!ordered) {
      for (const auto& p : pp_) visit(PairKind::PointPoint, p.first, p.second);
      for (const auto& p : pe_) visit(PairKind::PointEdge, p.first, p.second);
      for (int i = 0; i < n; ++i)
        for (int h = 0; h < H; ++h) visit(PairKind::PointPlane, i, h);
      return;
    }
    std::size_t a = 0, b = 0;
    for (int i = 0; i < n; ++i) {
      for (; a < pp_.size() && pp_[a].first == i; ++a)
        visit(PairKind::PointPoint, i, pp_[a].second);
      for (; b < pe_.size() && pe_[b].first == i; ++b) visit(PairKind::PointEdge, i, pe_[b].second);
      for (int h = 0; h < H; ++h) visit(PairKind::PointPlane, i, h);
    }
  }

  /// @brief The particle-particle candidates of the last SortAndSweep visit, (i, j) with i < j.
  [[nodiscard]] const std::vector<std::pair<int, int>>& point_point() const { return pp_; }
  /// @brief The particle-edge candidates of the last SortAndSweep visit, (i, e).
  [[nodiscard]] const std::vector<std::pair<int, int>>& point_edge() const { return pe_; }

 private:
  /// @brief Boxes of the particles (items 0..n-1) and edges (n..n+E-1), sorted by their lower
  /// bound on the axis of largest spread; each item is tested against the following ones until
  /// their lower bound passes its upper bound.
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
    // the axis along which the box centres spread most
    int axis = 0;
    Scalar best = -1;
    for (int c = 0; c < 3; ++c) {
      Scalar mn = std::numeric_limits<Scalar>::infinity(), mx = -mn;
      for (int k = 0; k < N; ++k) {
        const Scalar m = lo_[std::size_t(k)][c] + hi_[std::size_t(k)][c];
        mn = std::min(mn, m);
        mx = std::max(mx, m);
      }
      if (N > 0 && mx - mn > best) {
        best = mx - mn;
        axis = c;
      }
    }
    order_.resize(std::size_t(N));
    for (int k = 0; k < N; ++k) order_[std::size_t(k)] = {lo_[std::size_t(k)][axis], k};
    std::sort(order_.begin(), order_.end());
    pp_.clear();
    pe_.clear();
    const int o1 = (axis + 1) % 3, o2 = (axis + 2) % 3;
    for (int s = 0; s < N; ++s) {
      const int k = order_[std::size_t(s)].second;
      const Box& hk = hi_[std::size_t(k)];
      const Box& lk = lo_[std::size_t(k)];
      for (int t = s + 1; t < N && order_[std::size_t(t)].first <= hk[axis]; ++t) {
        const int m = order_[std::size_t(t)].second;
        if (k >= n && m >= n) continue;  // edge-edge: not a pair kind of the model
        const Box& lm = lo_[std::size_t(m)];
        const Box& hm = hi_[std::size_t(m)];
        if (lm[o1] > hk[o1] || lk[o1] > hm[o1] || lm[o2] > hk[o2] || lk[o2] > hm[o2]) continue;
        if (k < n && m < n) {
          pp_.emplace_back(std::min(k, m), std::max(k, m));
        } else {
          const int p = k < n ? k : m;
          const int e = (k < n ? m : k) - n;
          if (g.edges(e, 0) != p && g.edges(e, 1) != p) pe_.emplace_back(p, e);
        }
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
  std::vector<std::pair<Scalar, int>> order_;
  std::vector<std::pair<int, int>> pp_, pe_;
};

}  // namespace massspring::contact
