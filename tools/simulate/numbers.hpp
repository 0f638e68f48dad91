#pragma once
// massspring-simulate's option values: read from the text as given, so that every message quotes
// what the user typed (never a 309-digit bound) and NaN and infinity are refused everywhere.

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <massspring/error.hpp>
#include <string>
#include <vector>

namespace simulate {

using massspring::Error;

/// An integer in [lo, hi]: "--frames: \"abc\" is not an integer".
inline long long parse_integer(const std::string& option, const std::string& text, long long lo,
                               long long hi) {
  long long value = 0;
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (!text.empty() && *begin == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec == std::errc::result_out_of_range)
    throw Error(option + ": " + text + " is out of range (" + std::to_string(lo) + " to " +
                std::to_string(hi) + ")");
  if (ec != std::errc() || ptr != end || begin == end)
    throw Error(option + ": \"" + text + "\" is not an integer");
  if (value < lo || value > hi)
    throw Error(option + ": " + text + " is out of range (" + std::to_string(lo) + " to " +
                std::to_string(hi) + ")");
  return value;
}

/// The condition a floating option must meet besides being finite.
enum class Bound { Any, NonNegative, Positive, UnitOpen, UnitHalfOpenAbove };

/// A finite number: "--dt: must be > 0, got 0"; "--shrink: must be a finite number, got nan".
inline double parse_number(const std::string& option, const std::string& text,
                           Bound bound = Bound::Any) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size() ||
      std::isspace(static_cast<unsigned char>(text[0])))
    throw Error(option + ": \"" + text + "\" is not a number");
  if (!std::isfinite(value))  // nan, inf, or beyond the range of double (1e999)
    throw Error(option + ": must be a finite number, got " + text);
  switch (bound) {
    case Bound::Any:
      break;
    case Bound::NonNegative:
      if (!(value >= 0)) throw Error(option + ": must be >= 0, got " + text);
      break;
    case Bound::Positive:
      if (!(value > 0)) throw Error(option + ": must be > 0, got " + text);
      break;
    case Bound::UnitOpen:  // [0, 1)
      if (!(value >= 0 && value < 1)) throw Error(option + ": must be in [0, 1), got " + text);
      break;
    case Bound::UnitHalfOpenAbove:  // (0, 1]
      if (!(value > 0 && value <= 1)) throw Error(option + ": must be in (0, 1], got " + text);
      break;
  }
  return value;
}

/// Three finite numbers X,Y,Z.
inline std::vector<double> parse_vector3(const std::string& option,
                                         const std::vector<std::string>& parts) {
  if (parts.size() != 3)
    throw Error(option + ": expected three numbers X,Y,Z, got " + std::to_string(parts.size()));
  std::vector<double> out;
  for (const std::string& p : parts) out.push_back(parse_number(option, p));
  return out;
}

}  // namespace simulate
