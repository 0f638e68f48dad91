#pragma once
/// @file
/// @brief BoxHash: a spatial hash of axis-aligned boxes, the broad phase of surface contact
/// (contact/response/surface_contact.hpp): which stored boxes may overlap a query box.
///
/// Space is cut into cubic cells of side h; a box is entered in every cell it touches, and the
/// cells are hashed into a table of 2^k buckets (a counting sort: O(entries) to build, no
/// comparison sort). A query visits the buckets of the cells its box touches and reports each
/// stored box that truly overlaps it once. Two boxes that overlap share a cell, so no overlap is
/// missed; hash collisions only cost a box test. Cost per build O(m c) for m boxes of about c
/// cells each; it grows with how far the elements sweep per step (Teschner et al. 2003,
/// "Optimized spatial hashing for collision detection of deformable objects").
///
/// Work arrays keep their capacity: after the first builds of a given size, nothing allocates.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "massspring/contact/aligned_box.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief Boxes 0..m-1 stored for overlap queries.
template <class Scalar>
class BoxHash {
 public:
  using Box = AlignedBox3<Scalar>;

  /// @brief A box that touches more cells than this (a ball's centre with its gap among the cells
  /// of a fine cloth) is not hashed: it is kept in a list every query tests; a query box that
  /// large tests every stored box. Either way the cost stays O(boxes), never O(cells).
  static constexpr double kMaxCells = 4096;

  /// @brief Stores `boxes` (kept by reference until the next build) with cells of side `cell` [m]
  /// (> 0, finite; the boxes finite). Pick the cell about the size of a typical box: a box enters
  /// every cell it touches. A box changed after build() stays in the cells of its old value (or
  /// in the large list), and query() tests the new value: change one only to tighten it, or
  /// filter it out of the visits.
  void build(const std::vector<Box>& boxes, Scalar cell) {
    boxes_ = &boxes;
    inv_cell_ = Scalar(1) / cell;
    const std::size_t m = boxes.size();
    keys_.clear();
    large_.clear();
    for (std::size_t i = 0; i < m; ++i) {
      if (too_large(boxes[i]))
        large_.push_back(int(i));
      else
        for_each_cell(boxes[i], [&](std::uint64_t key) { keys_.push_back(key); });
    }
    const std::size_t entries = keys_.size();
    std::size_t buckets = 1;
    while (buckets < entries + 1) buckets *= 2;
    mask_ = buckets - 1;
    for (std::uint64_t& key : keys_) key &= mask_;
    start_.assign(buckets + 1, 0);
    for (std::uint64_t key : keys_) ++start_[key + 1];
    for (std::size_t k = 0; k < buckets; ++k) start_[k + 1] += start_[k];
    fill_.assign(start_.begin(), start_.end() - 1);
    ids_.resize(entries);
    std::size_t next = 0, large = 0;
    for (std::size_t i = 0; i < m; ++i) {
      if (large < large_.size() && large_[large] == int(i)) {
        ++large;
        continue;
      }
      const std::size_t count = cell_count(boxes[i]);
      for (std::size_t c = 0; c < count; ++c) ids_[fill_[keys_[next++]]++] = int(i);
    }
    stamp_.assign(m, 0);
    query_ = 0;
  }

  /// @brief Makes room for builds of up to `boxes` boxes entered in up to `entries` cells in all,
  /// so that they allocate nothing.
  void reserve(std::size_t boxes, std::size_t entries) {
    keys_.reserve(entries);
    ids_.reserve(entries);
    large_.reserve(boxes);
    stamp_.reserve(boxes);
    std::size_t buckets = 1;
    while (buckets < entries + 1) buckets *= 2;
    start_.reserve(buckets + 1);
    fill_.reserve(buckets);
  }
  /// @brief Cells entered by the last build, over all its hashed boxes.
  [[nodiscard]] std::size_t entries() const { return ids_.size(); }

  /// @brief Calls visit(i) once for each stored box i > `above` that overlaps `q` (every one with
  /// the default -1). A bucket holds its boxes in ascending order and is read from its end, so
  /// the boxes at or below `above` cost nothing: querying each box of the stored set with its own
  /// index lists each overlapping pair once, at half the cost.
  template <class Visit>
  void query(const Box& q, Visit&& visit, int above = -1) {
    const auto& boxes = *boxes_;
    if (too_large(q)) {
      for (std::size_t i = std::size_t(above + 1); i < boxes.size(); ++i)
        if (boxes[i].overlaps(q)) visit(int(i));
      return;
    }
    if (++query_ == 0) {  // the stamps wrapped: clear them
      std::fill(stamp_.begin(), stamp_.end(), 0u);
      query_ = 1;
    }
    for_each_cell(q, [&](std::uint64_t key) {
      key &= mask_;
      for (std::uint32_t k = start_[key + 1]; k > start_[key];) {
        const int i = ids_[--k];
        if (i <= above) break;
        if (stamp_[std::size_t(i)] == query_) continue;
        stamp_[std::size_t(i)] = query_;
        if (boxes[std::size_t(i)].overlaps(q)) visit(i);
      }
    });
    for (int i : large_)
      if (i > above && boxes[std::size_t(i)].overlaps(q)) visit(i);
  }

 private:
  // The cells a box touches along each axis: [lo, hi] in cell coordinates.
  struct Range {
    long long lo[3], hi[3];
  };
  Range range(const Box& b) const {
    Range r;
    for (int a = 0; a < 3; ++a) {
      r.lo[a] = static_cast<long long>(std::floor(b.lo(a) * inv_cell_));
      r.hi[a] = static_cast<long long>(std::floor(b.hi(a) * inv_cell_));
    }
    return r;
  }
  // Whether b touches more than kMaxCells cells (counted in floating point: no overflow).
  bool too_large(const Box& b) const {
    double cells = 1;
    for (int a = 0; a < 3; ++a)
      cells *=
          double(std::floor(b.hi(a) * inv_cell_)) - double(std::floor(b.lo(a) * inv_cell_)) + 1;
    return !(cells <= kMaxCells);
  }
  std::size_t cell_count(const Box& b) const {
    const Range r = range(b);
    std::size_t c = 1;
    for (int a = 0; a < 3; ++a) c *= std::size_t(r.hi[a] - r.lo[a] + 1);
    return c;
  }
  template <class Fn>
  void for_each_cell(const Box& b, Fn&& fn) const {
    const Range r = range(b);
    for (long long x = r.lo[0]; x <= r.hi[0]; ++x)
      for (long long y = r.lo[1]; y <= r.hi[1]; ++y)
        for (long long z = r.lo[2]; z <= r.hi[2]; ++z) fn(hash(x, y, z));
  }
  std::uint64_t hash(long long x, long long y, long long z) const {
    const auto h = std::uint64_t(x) * 73856093ull ^ std::uint64_t(y) * 19349663ull ^
                   std::uint64_t(z) * 83492791ull;
    return h ^ (h >> 29);
  }

  const std::vector<Box>* boxes_ = nullptr;
  Scalar inv_cell_ = 1;
  std::uint64_t mask_ = 0;
  std::vector<std::uint64_t> keys_;  // build(): each box's cells' keys, in order
  std::vector<std::uint32_t> start_, fill_;
  std::vector<int> ids_;
  std::vector<int> large_;  // the boxes too large to hash, ascending
  std::vector<unsigned> stamp_;
  unsigned query_ = 0;
};

}  // namespace massspring::contact
