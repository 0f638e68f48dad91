#pragma once
// Force-included (before Eigen) into every test translation unit:
// - a failed eigen_assert throws, so a test reports it instead of aborting the whole run;
// - EIGEN_RUNTIME_NO_MALLOC lets CountAllocations forbid Eigen's own heap allocations, which go
//   to malloc and not through operator new.
#include <stdexcept>
#include <string>

#define EIGEN_RUNTIME_NO_MALLOC
#define eigen_assert(x)                                                                         \
  do {                                                                                          \
    if (!(x))                                                                                   \
      throw std::logic_error(std::string("Eigen assertion failed: ") + #x + " at " + __FILE__ + \
                             ":" + std::to_string(__LINE__));                                   \
  } while (false)
