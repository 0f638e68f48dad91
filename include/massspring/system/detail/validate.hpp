#pragma once
/// @file
/// @brief Input checks shared by the system's setters; each throws massspring::Error naming the
/// item.

#include <Eigen/Core>
#include <cmath>
#include <sstream>
#include <string>

#include "massspring/error.hpp"

namespace massspring::detail {

/// @brief Builds a message from streamable parts: `message("point ", 3, ": mass ", m)`.
template <class... Parts>
std::string message(const Parts&... parts) {
  std::ostringstream out;
  out.precision(17);
  (out << ... << parts);
  return out.str();
}

/// @brief "(x, y, z)" of a row of three values, for messages.
template <class Row>
std::string format_row(const Row& row) {
  std::ostringstream out;
  out.precision(17);
  out << '(';
  for (Eigen::Index c = 0; c < row.size(); ++c) out << (c ? ", " : "") << row(c);
  out << ')';
  return out.str();
}

/// @brief Throws unless `rows` has `expected` rows.
inline void require_rows(const char* what, Eigen::Index rows, Eigen::Index expected,
                         const char* per) {
  if (rows != expected)
    throw Error(message(what, ": expected one value per ", per, " (", expected, "), got ", rows));
}

/// @brief Throws unless every row of an n x 3 matrix is finite; names the first bad row.
template <class Derived>
void require_finite_rows(const char* item, const char* what, const Eigen::MatrixBase<Derived>& m) {
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    if (!m.row(i).allFinite())
      throw Error(message(item, ' ', i, ": ", what, " must be finite, got ", format_row(m.row(i))));
}

/// @brief Throws unless v(i) is finite and > 0 (strict) or >= 0 (not strict); names the first bad
/// one.
template <class Derived>
void require_positive(const char* item, const char* what, const Eigen::MatrixBase<Derived>& v,
                      bool strict) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    const auto x = v(i);
    const bool ok = std::isfinite(x) && (strict ? x > 0 : x >= 0);
    if (!ok)
      throw Error(message(item, ' ', i, ": ", what, " must be finite and ", strict ? "> 0" : ">= 0",
                          ", got ", x));
  }
}

/// @brief Throws "<where>: <what> must be finite and > 0 (or >= 0), got x" unless x is.
inline void require_number(const char* where, const char* what, double x, bool strict) {
  if (!(std::isfinite(x) && (strict ? x > 0 : x >= 0)))
    throw Error(
        message(where, ": ", what, " must be finite and ", strict ? "> 0" : ">= 0", ", got ", x));
}

}  // namespace massspring::detail
