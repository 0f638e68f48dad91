#pragma once
/// @file
/// @brief The text names of FastMassSpringOptions' enumerations (PinMode, InitialGuess,
/// Acceleration, FillOrdering): one table per enumeration, read by the command line
/// (massspring-simulate), by Python and by messages, so that each name is written once.
///
/// Names are lower case with hyphens ("nested-dissection"). option_name(value) gives a value's
/// name, parse_option<Enum>(text) the value a name spells (exactly: case-sensitive, no trimming),
/// option_names<Enum>() every name in table order, and OptionNames<Enum>::option the option the
/// enumeration is the type of ("pins"), for messages.

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/integrators/local_global/options.hpp"

namespace massspring {

/// @brief One row of a name table: `name` spells `value`.
template <class Enum>
struct OptionName {
  const char* name;
  Enum value;
};

/// @brief The name table of an option enumeration; defined for PinMode, InitialGuess,
/// Acceleration and FillOrdering.
template <class Enum>
struct OptionNames;

template <>
struct OptionNames<PinMode> {
  static constexpr const char* option = "pins";
  static constexpr std::array<OptionName<PinMode>, 2> table{
      {{"exact", PinMode::Exact}, {"penalty", PinMode::Penalty}}};
};

template <>
struct OptionNames<InitialGuess> {
  static constexpr const char* option = "initial_guess";
  static constexpr std::array<OptionName<InitialGuess>, 2> table{
      {{"current", InitialGuess::Current}, {"inertial", InitialGuess::Inertial}}};
};

template <>
struct OptionNames<Acceleration> {
  static constexpr const char* option = "acceleration";
  static constexpr std::array<OptionName<Acceleration>, 3> table{
      {{"none", Acceleration::None},
       {"chebyshev", Acceleration::Chebyshev},
       {"anderson", Acceleration::Anderson}}};
};

template <>
struct OptionNames<FillOrdering> {
  static constexpr const char* option = "ordering";
  static constexpr std::array<OptionName<FillOrdering>, 3> table{
      {{"auto", FillOrdering::Auto},
       {"solver", FillOrdering::Solver},
       {"nested-dissection", FillOrdering::NestedDissection}}};
};

/// @brief The name of `value` (nullptr for a value outside the table).
template <class Enum>
constexpr const char* option_name(Enum value) {
  for (const OptionName<Enum>& row : OptionNames<Enum>::table)
    if (row.value == value) return row.name;
  return nullptr;
}

/// @brief Every name of `Enum`, in table order.
template <class Enum>
std::vector<std::string> option_names() {
  std::vector<std::string> names;
  for (const OptionName<Enum>& row : OptionNames<Enum>::table) names.emplace_back(row.name);
  return names;
}

/// @brief The value `name` spells.
/// @throws Error `acceleration: unknown value "fast" (expected none, chebyshev or anderson)`.
template <class Enum>
Enum parse_option(std::string_view name) {
  std::string expected;
  const auto& table = OptionNames<Enum>::table;
  for (std::size_t i = 0; i < table.size(); ++i) {
    if (name == table[i].name) return table[i].value;
    expected += (i == 0 ? "" : i + 1 == table.size() ? " or " : ", ") + std::string(table[i].name);
  }
  throw Error(std::string(OptionNames<Enum>::option) + ": unknown value \"" + std::string(name) +
              "\" (expected " + expected + ")");
}

}  // namespace massspring
