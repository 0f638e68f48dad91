#pragma once
/// @file
/// @brief merge_sorted_tail(): a sorted list with new entries appended, sorted again without
/// allocating once its arrays have grown.

#include <algorithm>
#include <cstddef>
#include <functional>
#include <vector>

namespace massspring::detail {

/// @brief Sorts list[kept, end) by `less` and merges it with list[0, kept) (already sorted by
/// `less`), through `scratch`, which is swapped with `list` (std::inplace_merge may take a
/// temporary buffer on every call; the two vectors here keep their capacity). Stable: of equal
/// entries, those of the first run come first. Cost O(k log k + n) for k appended of n.
template <class T, class Less = std::less<>>
void merge_sorted_tail(std::vector<T>& list, std::size_t kept, std::vector<T>& scratch,
                       Less less = Less()) {
  if (list.size() == kept) return;
  const auto middle = list.begin() + std::ptrdiff_t(kept);
  std::sort(middle, list.end(), less);
  scratch.resize(list.size());
  std::merge(list.begin(), middle, middle, list.end(), scratch.begin(), less);
  list.swap(scratch);
}

}  // namespace massspring::detail
