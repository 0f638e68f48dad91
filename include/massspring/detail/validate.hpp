#pragma once
/// @file
/// @brief Input checks shared by the system's setters; each throws massspring::Error naming the
/// item.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>

#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring::detail {

/// @brief Appends a number as the shortest text that reads back to the same double ("-0.3", not
/// "-0.29999999999999999"; the JSON loader quotes the same text), in fixed notation for decimal
/// exponents -4 to 16 ("10000000000") and scientific outside ("1e-05", "1.5e+20"), as
/// `std::ostream` at precision 17 chooses; "nan", "inf". One function, not a template: every
/// message shares it.
inline void append_message_number(std::string& out, double x) {
  if (!std::isfinite(x)) {
    out += std::isnan(x) ? (std::signbit(x) ? "-nan" : "nan") : (x < 0 ? "-inf" : "inf");
    return;
  }
  char buffer[64];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::scientific);
  (void)ec;  // 64 characters hold any double
  *end = '\0';
  const std::string_view scientific(buffer, std::size_t(end - buffer));
  const int exponent = std::atoi(buffer + scientific.find('e') + 1);
  if (x != 0 && (exponent < -4 || exponent >= 17)) {
    out += scientific;
    return;
  }
  end = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::fixed).ptr;
  out.append(buffer, end);
}

/// @brief Appends one part of a message: text as it is, a character, a number (integers exactly,
/// floating point as append_message_number), anything else as its `operator<<` writes it.
template <class T>
void append_part(std::string& out, const T& part) {
  if constexpr (std::is_convertible_v<const T&, std::string_view>) {
    out += std::string_view(part);
  } else if constexpr (std::is_same_v<T, char> || std::is_same_v<T, signed char> ||
                       std::is_same_v<T, unsigned char>) {
    out += char(part);
  } else if constexpr (std::is_same_v<T, bool>) {
    out += part ? '1' : '0';
  } else if constexpr (std::is_integral_v<T>) {
    out += std::to_string(part);
  } else if constexpr (std::is_floating_point_v<T>) {
    append_message_number(out, double(part));
  } else {
    std::ostringstream text;
    text.precision(17);
    text << part;
    out += text.str();
  }
}

/// @brief Builds a message from streamable parts: `message("point ", 3, ": mass ", m)`, numbers as
/// append_message_number() writes them.
template <class... Parts>
std::string message(const Parts&... parts) {
  std::string out;
  (append_part(out, parts), ...);
  return out;
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

/// @brief What is wrong with the surface triangle (a, b, c) of points with these rest positions
/// (#points by 3), or an empty string when nothing is: "point index p out of range [0, n)",
/// "repeats a point", or "zero area at the rest positions" (relative to its longest side:
/// collinear or coincident corners).
template <class Scalar>
std::string surface_triangle_problem(int a, int b, int c, const Points<Scalar>& rest_positions) {
  using V3 = Vector3<Scalar>;
  const int n = int(rest_positions.rows());
  for (const int p : {a, b, c})
    if (p < 0 || p >= n) return message("point index ", p, " out of range [0, ", n, ")");
  if (a == b || b == c || a == c) return "repeats a point";
  const V3 u = (rest_positions.row(b) - rest_positions.row(a)).transpose();
  const V3 w = (rest_positions.row(c) - rest_positions.row(a)).transpose();
  const Scalar longest = std::max({u.squaredNorm(), w.squaredNorm(), (w - u).squaredNorm()});
  if (!(u.cross(w).norm() > Scalar(64) * std::numeric_limits<Scalar>::epsilon() * longest))
    return "zero area at the rest positions";
  return {};
}

/// @brief Checks surface triangles (#triangles by 3 point indices) against the rest positions
/// (#points by 3): Error "surface triangle t = (a, b, c): <what>" (0-based) for the first
/// triangle surface_triangle_problem() finds wrong.
template <class Scalar>
void require_surface(const Triangles& triangles, const Points<Scalar>& rest_positions) {
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const int a = triangles(t, 0), b = triangles(t, 1), c = triangles(t, 2);
    const std::string problem = surface_triangle_problem(a, b, c, rest_positions);
    if (!problem.empty())
      throw Error(message("surface triangle ", t, " = (", a, ", ", b, ", ", c, "): ", problem));
  }
}

}  // namespace massspring::detail
