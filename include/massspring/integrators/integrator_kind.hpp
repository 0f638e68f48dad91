#pragma once
/// @file
/// @brief IntegratorKind: the integrators by name, in each vocabulary that names them (the
/// command-line tools, FOSSSim XML scenes, the benchmarks' results), in one table. Needs no
/// integrator header: with_integrator() (integrators/with_integrator.hpp) builds the integrator a
/// kind names.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "massspring/error.hpp"

namespace massspring {

/// @brief An integrator and, for BackwardEuler, its mode.
enum class IntegratorKind {
  ForwardEuler,             ///< ForwardEuler
  SymplecticEuler,          ///< SymplecticEuler
  BackwardEuler,            ///< BackwardEuler, BackwardEulerMode::Newton
  LinearizedBackwardEuler,  ///< BackwardEuler, BackwardEulerMode::Linearized
  FastMassSpring,           ///< FastMassSpring (local-global, Liu et al. 2013)
  RK4,                      ///< RK4 (the accuracy reference)
};

/// @brief A vocabulary of integrator names.
enum class IntegratorNaming {
  /// massspring-simulate's `--integrator` and a saved state's "run": "integrator":
  /// forward-euler, symplectic-euler, backward-euler, linearized-backward-euler,
  /// fast-mass-spring. RK4 has no name here (the tool does not offer it).
  Cli,
  /// A FOSSSim XML scene's `<integrator type>` (Columbia's "Animation and CGI Motion" course):
  /// explicit-euler, symplectic-euler (Theme 2 also writes forward-backward-euler),
  /// linearized-implicit-euler, implicit-euler. Only the four Euler methods have names here.
  Fosssim,
  /// The label in the benchmarks' results (the `integrator` column of stability's CSV):
  /// ForwardEuler, SymplecticEuler, BackwardEuler-Newton, BackwardEuler-linearized,
  /// LocalGlobal, RK4.
  Label,
};

/// @brief One name of a kind. A kind's first name in a vocabulary is the one written; a later
/// one (an alias) is read too.
struct IntegratorName {
  const char* name;
  IntegratorKind kind;
};

namespace detail {
// One table per vocabulary, each in the order its names are listed (help texts, errors).
inline constexpr IntegratorName kCliIntegratorNames[] = {
    {"forward-euler", IntegratorKind::ForwardEuler},
    {"symplectic-euler", IntegratorKind::SymplecticEuler},
    {"backward-euler", IntegratorKind::BackwardEuler},
    {"linearized-backward-euler", IntegratorKind::LinearizedBackwardEuler},
    {"fast-mass-spring", IntegratorKind::FastMassSpring}};
inline constexpr IntegratorName kFosssimIntegratorNames[] = {
    {"explicit-euler", IntegratorKind::ForwardEuler},
    {"symplectic-euler", IntegratorKind::SymplecticEuler},
    {"forward-backward-euler", IntegratorKind::SymplecticEuler},  // Theme 2's name
    {"linearized-implicit-euler", IntegratorKind::LinearizedBackwardEuler},
    {"implicit-euler", IntegratorKind::BackwardEuler}};
inline constexpr IntegratorName kIntegratorLabels[] = {
    {"ForwardEuler", IntegratorKind::ForwardEuler},
    {"SymplecticEuler", IntegratorKind::SymplecticEuler},
    {"RK4", IntegratorKind::RK4},
    {"BackwardEuler-linearized", IntegratorKind::LinearizedBackwardEuler},
    {"BackwardEuler-Newton", IntegratorKind::BackwardEuler},
    {"LocalGlobal", IntegratorKind::FastMassSpring}};

/// @brief The names of one vocabulary, as a range.
struct IntegratorNameRange {
  const IntegratorName* first;
  const IntegratorName* last;
  [[nodiscard]] constexpr const IntegratorName* begin() const { return first; }
  [[nodiscard]] constexpr const IntegratorName* end() const { return last; }
};

template <std::size_t N>
constexpr IntegratorNameRange range(const IntegratorName (&names)[N]) {
  return {names, names + N};
}
}  // namespace detail

/// @brief Every name of `naming`, aliases included, in listing order.
constexpr detail::IntegratorNameRange integrator_name_table(IntegratorNaming naming) {
  switch (naming) {
    case IntegratorNaming::Cli:
      return detail::range(detail::kCliIntegratorNames);
    case IntegratorNaming::Fosssim:
      return detail::range(detail::kFosssimIntegratorNames);
    case IntegratorNaming::Label:
      break;
  }
  return detail::range(detail::kIntegratorLabels);
}

/// @brief The name `kind` is written with in `naming`, or nullptr when that vocabulary has none
/// for it (see IntegratorNaming).
constexpr const char* to_string(IntegratorKind kind, IntegratorNaming naming) {
  for (const IntegratorName& n : integrator_name_table(naming))
    if (n.kind == kind) return n.name;
  return nullptr;
}

/// @brief The kind `name` spells in `naming` (exactly: no trimming, case-sensitive), or
/// std::nullopt.
inline std::optional<IntegratorKind> find_integrator(std::string_view name,
                                                     IntegratorNaming naming) {
  for (const IntegratorName& n : integrator_name_table(naming))
    if (name == n.name) return n.kind;
  return std::nullopt;
}

/// @brief Every name of `naming`, aliases included, in table order.
inline std::vector<std::string> integrator_names(IntegratorNaming naming) {
  std::vector<std::string> names;
  for (const IntegratorName& n : integrator_name_table(naming)) names.emplace_back(n.name);
  return names;
}

/// @brief The names of `naming` as a message lists them: "a, b, c or d".
inline std::string integrator_name_list(IntegratorNaming naming) {
  const std::vector<std::string> names = integrator_names(naming);
  std::string list;
  for (std::size_t i = 0; i < names.size(); ++i)
    list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return list;
}

/// @brief The kind `name` spells in `naming`.
/// @throws Error `unknown integrator "NAME" (expected a, b, ... or z)`.
inline IntegratorKind parse_integrator(std::string_view name, IntegratorNaming naming) {
  if (const std::optional<IntegratorKind> kind = find_integrator(name, naming)) return *kind;
  throw Error("unknown integrator \"" + std::string(name) + "\" (expected " +
              integrator_name_list(naming) + ")");
}

}  // namespace massspring
