#pragma once
// massspring-simulate's "did you mean": for an option the parser did not expect, the option it
// most likely stands for (a prefix of one option, or within 2 edits of one).

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

namespace simulate {

/// The edit distance (insertions, deletions, substitutions) between a and b.
inline std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

/// " (did you mean --iterations?)" for the first argument of the form --NAME or --NAME=VALUE that
/// names no option of `app` and is a prefix of exactly one option name, or nearest to exactly one
/// within 2 edits (1 for a NAME of up to 5 letters); "" when there is none.
inline std::string did_you_mean(const CLI::App& app, int argc, const char* const* argv) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options())
    for (const std::string& name : o->get_lnames()) names.push_back("--" + name);
  for (int k = 1; k < argc; ++k) {
    std::string given = argv[k];
    if (given.rfind("--", 0) != 0 || given.size() < 3) continue;
    given = given.substr(0, given.find('='));
    if (std::find(names.begin(), names.end(), given) != names.end()) continue;
    std::vector<std::string> prefixed;
    for (const std::string& name : names)
      if (name.rfind(given, 0) == 0) prefixed.push_back(name);
    if (prefixed.size() == 1) return " (did you mean " + prefixed.front() + "?)";
    // at most 2 edits, and 1 for a name of up to 5 letters ("--dtt": --dt)
    const std::size_t limit = given.size() - 2 > 5 ? 2 : 1;
    std::size_t best = limit + 1;
    std::vector<std::string> nearest;
    for (const std::string& name : names) {
      const std::size_t d = edit_distance(given, name);
      if (d > limit) continue;
      if (d < best) nearest.clear(), best = d;
      if (d == best) nearest.push_back(name);
    }
    if (nearest.size() == 1) return " (did you mean " + nearest.front() + "?)";
  }
  return "";
}

}  // namespace simulate
