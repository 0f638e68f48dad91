// integrators/integrator_kind.hpp and with_integrator.hpp: every name of every vocabulary maps to
// its kind and back, aliases are read but never written, an unknown name is refused with the list
// of the accepted ones, and with_integrator() builds the integrator (and BackwardEuler mode) the
// kind names.
#include <doctest/doctest.h>

#include <massspring/integrators/integrator_kind.hpp>
#include <massspring/integrators/with_integrator.hpp>
#include <massspring/system/mass_spring_system.hpp>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

using massspring::IntegratorKind;
using massspring::IntegratorNaming;

namespace {

constexpr IntegratorKind kAllKinds[] = {
    IntegratorKind::ForwardEuler,   IntegratorKind::SymplecticEuler,
    IntegratorKind::BackwardEuler,  IntegratorKind::LinearizedBackwardEuler,
    IntegratorKind::FastMassSpring, IntegratorKind::RK4};

// What with_integrator() hands over, as an independent record: the type and, for BackwardEuler,
// the mode.
template <class System>
std::string built(IntegratorKind kind) {
  return massspring::with_integrator<System>(kind, [](auto& integrator) -> std::string {
    using I = std::decay_t<decltype(integrator)>;
    if constexpr (std::is_same_v<I, massspring::ForwardEuler<System>>) return "ForwardEuler";
    if constexpr (std::is_same_v<I, massspring::SymplecticEuler<System>>) return "SymplecticEuler";
    if constexpr (std::is_same_v<I, massspring::FastMassSpring<System>>) return "FastMassSpring";
    if constexpr (std::is_same_v<I, massspring::RK4<System>>) return "RK4";
    if constexpr (std::is_same_v<I, massspring::BackwardEuler<System>>)
      return integrator.options.mode == massspring::BackwardEulerMode::Newton
                 ? "BackwardEuler/Newton"
                 : "BackwardEuler/Linearized";
    return "?";
  });
}

}  // namespace

TEST_CASE("integrator_kind: the written names, kind by kind, as the tools and scenes spell them") {
  using K = IntegratorKind;
  const auto cli = IntegratorNaming::Cli, xml = IntegratorNaming::Fosssim;
  const auto label = IntegratorNaming::Label;
  CHECK(std::string(to_string(K::ForwardEuler, cli)) == "forward-euler");
  CHECK(std::string(to_string(K::SymplecticEuler, cli)) == "symplectic-euler");
  CHECK(std::string(to_string(K::BackwardEuler, cli)) == "backward-euler");
  CHECK(std::string(to_string(K::LinearizedBackwardEuler, cli)) == "linearized-backward-euler");
  CHECK(std::string(to_string(K::FastMassSpring, cli)) == "fast-mass-spring");
  CHECK(to_string(K::RK4, cli) == nullptr);
  CHECK(std::string(to_string(K::ForwardEuler, xml)) == "explicit-euler");
  CHECK(std::string(to_string(K::SymplecticEuler, xml)) == "symplectic-euler");  // not the alias
  CHECK(std::string(to_string(K::LinearizedBackwardEuler, xml)) == "linearized-implicit-euler");
  CHECK(std::string(to_string(K::BackwardEuler, xml)) == "implicit-euler");
  CHECK(to_string(K::FastMassSpring, xml) == nullptr);
  CHECK(to_string(K::RK4, xml) == nullptr);
  CHECK(std::string(to_string(K::BackwardEuler, label)) == "BackwardEuler-Newton");
  CHECK(std::string(to_string(K::FastMassSpring, label)) == "LocalGlobal");
  CHECK(std::string(to_string(K::RK4, label)) == "RK4");
}

TEST_CASE("integrator_kind: every name reads back as its kind; each kind is written one way") {
  for (const auto naming :
       {IntegratorNaming::Cli, IntegratorNaming::Fosssim, IntegratorNaming::Label}) {
    CAPTURE(int(naming));
    std::set<std::string> seen;
    for (const std::string& name : integrator_names(naming)) {
      CAPTURE(name);
      CHECK(seen.insert(name).second);  // no name twice in one vocabulary
      const auto kind = massspring::find_integrator(name, naming);
      REQUIRE(kind.has_value());
      CHECK(massspring::parse_integrator(name, naming) == *kind);
      // The written name of that kind reads back as the same kind (aliases write the main name).
      const char* written = to_string(*kind, naming);
      REQUIRE(written != nullptr);
      CHECK(massspring::find_integrator(written, naming) == kind);
    }
    // Kinds with a name: to_string and find agree for each of them.
    for (const IntegratorKind kind : kAllKinds)
      if (const char* name = to_string(kind, naming))
        CHECK(massspring::find_integrator(name, naming) == kind);
  }
  // The one alias: Theme 2's forward-backward-euler is symplectic Euler, read, never written.
  CHECK(massspring::find_integrator("forward-backward-euler", IntegratorNaming::Fosssim) ==
        IntegratorKind::SymplecticEuler);
  CHECK(integrator_names(IntegratorNaming::Fosssim).size() == 5);
  CHECK(integrator_names(IntegratorNaming::Label).size() == 6);
}

TEST_CASE("integrator_kind: an unknown name is refused, naming the accepted ones") {
  CHECK_FALSE(massspring::find_integrator("Forward-Euler", IntegratorNaming::Cli).has_value());
  CHECK_FALSE(massspring::find_integrator(" forward-euler", IntegratorNaming::Cli).has_value());
  CHECK_FALSE(massspring::find_integrator("explicit-euler", IntegratorNaming::Cli).has_value());
  CHECK_FALSE(massspring::find_integrator("", IntegratorNaming::Fosssim).has_value());
  CHECK_THROWS_WITH_AS(massspring::parse_integrator("rk4", IntegratorNaming::Cli),
                       "unknown integrator \"rk4\" (expected forward-euler, symplectic-euler, "
                       "backward-euler, linearized-backward-euler or fast-mass-spring)",
                       massspring::Error);
  CHECK(massspring::integrator_name_list(IntegratorNaming::Fosssim) ==
        "explicit-euler, symplectic-euler, forward-backward-euler, linearized-implicit-euler or "
        "implicit-euler");
}

TEST_CASE("with_integrator: builds the integrator each kind names") {
  using System = massspring::MassSpringSystem<double>;
  CHECK(built<System>(IntegratorKind::ForwardEuler) == "ForwardEuler");
  CHECK(built<System>(IntegratorKind::SymplecticEuler) == "SymplecticEuler");
  CHECK(built<System>(IntegratorKind::BackwardEuler) == "BackwardEuler/Newton");
  CHECK(built<System>(IntegratorKind::LinearizedBackwardEuler) == "BackwardEuler/Linearized");
  CHECK(built<System>(IntegratorKind::FastMassSpring) == "FastMassSpring");
  CHECK(built<System>(IntegratorKind::RK4) == "RK4");
  CHECK_THROWS_AS(built<System>(static_cast<IntegratorKind>(99)), massspring::Error);
}
