#pragma once
/// @file
/// @brief Numbers, lists and rows as JSON text that reads back bit for bit (the state scene's and
/// the collider writers' shared pieces).

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <type_traits>

#include "massspring/io/obj.hpp"

namespace massspring::io::detail {

/// @brief x as the shortest text that reads back as the same double through nlohmann-json: -0 is
/// written "-0.0" (nlohmann reads "-0" as the integer 0, losing the sign).
inline void append_real(std::string& out, double x) {
  if (x == 0 && std::signbit(x)) {
    out += "-0.0";
    return;
  }
  append_number(out, x);
}

template <class Derived>
void append_rows(std::string& out, const Eigen::DenseBase<Derived>& m) {
  out += '[';
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    out += i ? ",\n    [" : "\n    [";
    for (Eigen::Index c = 0; c < m.cols(); ++c) {
      if (c) out += ", ";
      if constexpr (std::is_integral_v<typename Derived::Scalar>)
        append_index(out, int(m(i, c)));
      else
        append_real(out, double(m(i, c)));
    }
    out += ']';
  }
  out += m.rows() ? "\n  ]" : "]";
}

template <class Derived>
void append_list(std::string& out, const Eigen::DenseBase<Derived>& v) {
  out += '[';
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (i) out += ", ";
    append_real(out, double(v(i)));
  }
  out += ']';
}

}  // namespace massspring::io::detail
