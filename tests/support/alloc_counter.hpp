#pragma once
// Counts heap allocations made by this thread while a CountAllocations is alive, through the
// replaced global operator new in alloc_counter.cpp: the oracle for "step() does not allocate".

#include <Eigen/Core>
#include <cstddef>

namespace massspring::test {

/// @brief Allocations counted so far on this thread (only while counting is on).
std::size_t allocation_count();
/// @brief Turns counting on or off for this thread; returns the previous setting.
bool set_counting(bool on);

/// @brief Counts the operator-new allocations made during its lifetime, and makes any Eigen heap
/// allocation (which goes to malloc) throw std::logic_error.
class CountAllocations {
 public:
  CountAllocations() : start_(allocation_count()), was_(set_counting(true)) {
    Eigen::internal::set_is_malloc_allowed(false);
  }
  ~CountAllocations() {
    Eigen::internal::set_is_malloc_allowed(true);
    set_counting(was_);
  }
  CountAllocations(const CountAllocations&) = delete;
  CountAllocations& operator=(const CountAllocations&) = delete;
  /// @brief Allocations since construction.
  [[nodiscard]] std::size_t count() const { return allocation_count() - start_; }

 private:
  std::size_t start_;
  bool was_;
};

}  // namespace massspring::test
