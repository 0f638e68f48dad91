#pragma once
/// @file
/// @brief detail::FosssimReader: the state of one read of a FOSSSim scene (file name, line
/// lookup, attribute checks and numbers with messages naming the file, line and element).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <pugixml.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/io/obj.hpp"

namespace massspring::io {

namespace detail {

/// @brief The state of one read: the file's name and text, line lookup, message helpers.
class FosssimReader {
 public:
  FosssimReader(std::string name, const std::string& text) : name_(std::move(name)) {
    line_starts_.push_back(0);
    for (std::size_t k = 0; k < text.size(); ++k)
      if (text[k] == '\n') line_starts_.push_back(k + 1);
  }

  /// @brief 1-based line of a byte offset (1 for an unknown offset).
  [[nodiscard]] int line_of(std::ptrdiff_t offset) const {
    if (offset < 0) return 1;
    const auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), std::size_t(offset));
    return int(it - line_starts_.begin());
  }
  [[nodiscard]] int line(const pugi::xml_node& node) const { return line_of(node.offset_debug()); }

  /// @brief Error "<file>:<line>: <what...>".
  template <class... Parts>
  [[nodiscard]] Error error(int line, const Parts&... parts) const {
    return Error(message(name_, ':', line, ": ", parts...));
  }

  /// @brief "<particle> 3" style label of the k-th element of its kind.
  static std::string label(const pugi::xml_node& node, int k) {
    return message('<', node.name(), "> ", k);
  }

  /// @brief Refuses attributes outside `allowed` and missing ones from `required`.
  void check_attributes(const pugi::xml_node& node, const std::string& item,
                        std::initializer_list<const char*> required,
                        std::initializer_list<const char*> optional) const {
    for (const pugi::xml_attribute& a : node.attributes()) {
      const std::string_view n = a.name();
      const auto is = [&](const char* s) { return n == s; };
      if (std::none_of(required.begin(), required.end(), is) &&
          std::none_of(optional.begin(), optional.end(), is)) {
        std::string expected;
        for (const auto* list : {&required, &optional})
          for (const char* s : *list) expected += message(expected.empty() ? "" : ", ", s);
        throw error(line(node), item, ": unknown attribute \"", n, "\" (expected ", expected, ")");
      }
    }
    for (const char* r : required)
      if (!node.attribute(r))
        throw error(line(node), item, ": missing required attribute \"", r, '"');
  }

  /// @brief The attribute as a finite number (surrounding blanks allowed, as FOSSSim's streams
  /// allow them); `fallback` when absent and not required.
  [[nodiscard]] double number(const pugi::xml_node& node, const std::string& item,
                              const char* attribute, std::optional<double> fallback = {}) const {
    const pugi::xml_attribute a = node.attribute(attribute);
    if (!a) {
      if (fallback) return *fallback;
      throw error(line(node), item, ": missing required attribute \"", attribute, '"');
    }
    const std::string_view text = trimmed(a.value());
    double x = 0;
    switch (parse_number(text, x)) {
      case NumberStatus::Ok:
        break;
      case NumberStatus::OutOfRange:
        throw error(line(node), item, ": ", attribute, " = \"", a.value(),
                    "\" is out of the range of double");
      case NumberStatus::NotANumber:
        throw error(line(node), item, ": ", attribute, " = \"", a.value(), "\" is not a number");
    }
    if (!std::isfinite(x))
      throw error(line(node), item, ": ", attribute, " = \"", a.value(), "\" must be finite");
    return x;
  }

  /// @brief number() and a bound: > 0 when strict, else >= 0.
  [[nodiscard]] double nonnegative(const pugi::xml_node& node, const std::string& item,
                                   const char* attribute, bool strict,
                                   std::optional<double> fallback = {}) const {
    const double x = number(node, item, attribute, fallback);
    if (strict ? !(x > 0) : !(x >= 0))
      throw error(line(node), item, ": ", attribute, " = ",
                  trimmed(node.attribute(attribute).value()), " must be ", strict ? "> 0" : ">= 0");
    return x;
  }

  /// @brief A required whole-number attribute in [0, bound) (bound < 0: no upper bound yet).
  [[nodiscard]] int index(const pugi::xml_node& node, const std::string& item,
                          const char* attribute, int bound, const char* of) const {
    const pugi::xml_attribute a = node.attribute(attribute);
    if (!a) throw error(line(node), item, ": missing required attribute \"", attribute, '"');
    long long i = 0;
    if (parse_number(trimmed(a.value()), i) != NumberStatus::Ok)
      throw error(line(node), item, ": ", attribute, " = \"", a.value(),
                  "\" is not a whole number");
    if (i < 0 || (bound >= 0 && i >= bound))
      throw error(line(node), item, ": ", attribute, " = ", i, " is out of range: the scene has ",
                  bound, ' ', of, bound == 1 ? "" : "s");
    return int(i);
  }

  static std::string_view trimmed(std::string_view s) {
    constexpr std::string_view blanks = " \t\r\n";
    const auto first = s.find_first_not_of(blanks);
    if (first == std::string_view::npos) return {};
    return s.substr(first, s.find_last_not_of(blanks) - first + 1);
  }

  [[nodiscard]] const std::string& name() const { return name_; }

 private:
  std::string name_;
  std::vector<std::size_t> line_starts_;
};

/// @brief Elements drawn by FOSSSim's viewer only: accepted with any attributes, ignored.
inline bool fosssim_rendering_only(std::string_view name) {
  for (const char* s : {"particlecolor", "edgecolor", "particlepath", "backgroundcolor", "viewport",
                        "maxsimfreq", "halfplanecolor"})
    if (name == s) return true;
  return false;
}

}  // namespace detail

}  // namespace massspring::io
