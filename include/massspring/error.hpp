#pragma once
/// @file
/// @brief massspring::Error, the one exception type the library throws.

#include <stdexcept>
#include <string>

namespace massspring {

/// @brief Raised for invalid input: the message names the item (point, spring, pin, file and line)
/// and says what was expected. Numerical failure during a step is not an exception: an integrator's
/// step() reports it in its StepReport (a failed factorization, a result that is not finite, an
/// energy blow-up) and leaves the system's state as it was; step() throws only for invalid input
/// (bad options, a step before precompute()).
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace massspring
