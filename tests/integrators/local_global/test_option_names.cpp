// integrators/local_global/option_names.hpp: every value of each option enumeration has one name
// that reads back to it, an unknown name is refused naming the option and the expected names.
#include <doctest/doctest.h>

#include <massspring/error.hpp>
#include <massspring/integrators/local_global/option_names.hpp>
#include <set>
#include <string>
#include <vector>

namespace {

// Each row's name reads back to its value, names are distinct, and option_names lists them.
template <class Enum>
void check_round_trip(std::size_t values) {
  const auto& table = massspring::OptionNames<Enum>::table;
  CHECK(table.size() == values);
  std::set<std::string> seen;
  for (const auto& row : table) {
    CAPTURE(row.name);
    CHECK(massspring::parse_option<Enum>(row.name) == row.value);
    CHECK(std::string(massspring::option_name(row.value)) == row.name);
    CHECK(seen.insert(row.name).second);
  }
  CHECK(massspring::option_names<Enum>().size() == values);
}

}  // namespace

TEST_CASE("option names: every value of every option enumeration reads back") {
  check_round_trip<massspring::PinMode>(2);
  check_round_trip<massspring::InitialGuess>(2);
  check_round_trip<massspring::Acceleration>(3);
  check_round_trip<massspring::FillOrdering>(3);
  CHECK(massspring::option_names<massspring::FillOrdering>() ==
        std::vector<std::string>{"auto", "solver", "nested-dissection"});
  CHECK(std::string(massspring::option_name(massspring::Acceleration::Chebyshev)) == "chebyshev");
}

TEST_CASE("option names: an unknown name is refused with the option and the names it takes") {
  CHECK_THROWS_WITH_AS(massspring::parse_option<massspring::Acceleration>("Chebyshev"),
                       "acceleration: unknown value \"Chebyshev\" (expected none, chebyshev or "
                       "anderson)",
                       massspring::Error);
  CHECK_THROWS_WITH_AS(massspring::parse_option<massspring::PinMode>(""),
                       "pins: unknown value \"\" (expected exact or penalty)", massspring::Error);
  CHECK_THROWS_WITH_AS(massspring::parse_option<massspring::FillOrdering>("nested dissection"),
                       "ordering: unknown value \"nested dissection\" (expected auto, solver or "
                       "nested-dissection)",
                       massspring::Error);
}
