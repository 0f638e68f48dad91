#pragma once
/// @file
/// @brief The parts of the FOSSSim reader that Theme 2 (collisions) adds: `<collision>`,
/// `<collisiondetection>`, and the attribute separation FOSSSim's parser (rapidxml) allows.

#include <cctype>
#include <climits>
#include <cstddef>
#include <initializer_list>
#include <pugixml.hpp>
#include <string>
#include <string_view>

#include "massspring/io/fosssim/reader.hpp"
#include "massspring/io/fosssim/scene.hpp"
#include "massspring/io/obj.hpp"

namespace massspring::io::detail {

/// @brief `text` with a blank inserted wherever an attribute's closing quote is followed at once
/// by the next attribute's name (`vx="0"vy="0"`), which XML forbids and rapidxml, FOSSSim's
/// parser, reads as two attributes (t2m2/ImpulsesTests/test06.xml has one). Nothing else changes:
/// comments, processing instructions, CDATA and text are copied as they are; no line moves.
inline std::string separate_attributes(const std::string& text) {
  std::string out;
  out.reserve(text.size() + 16);
  const std::size_t size = text.size();
  auto starts = [&](std::size_t at, std::string_view s) {
    return text.compare(at, s.size(), s) == 0;
  };
  auto copy_to = [&](std::size_t& k, std::string_view end) {
    const std::size_t stop = text.find(end, k);
    const std::size_t last = stop == std::string::npos ? size : stop + end.size();
    out.append(text, k, last - k);
    k = last;
  };
  std::size_t k = 0;
  while (k < size) {
    if (text[k] != '<') {
      out += text[k++];
      continue;
    }
    if (starts(k, "<!--")) {
      copy_to(k, "-->");
    } else if (starts(k, "<![CDATA[")) {
      copy_to(k, "]]>");
    } else if (starts(k, "<?")) {
      copy_to(k, "?>");
    } else if (starts(k, "<!")) {
      copy_to(k, ">");
    } else {  // a tag: copy it, separating attributes where a quote ends one and a name follows
      while (k < size && text[k] != '>') {
        const char c = text[k];
        out += c;
        ++k;
        if (c == '"' || c == '\'') {
          const std::size_t close = text.find(c, k);
          const std::size_t last = close == std::string::npos ? size : close + 1;
          out.append(text, k, last - k);
          k = last;
          if (k < size) {
            const unsigned char next = static_cast<unsigned char>(text[k]);
            if (std::isalpha(next) || next == '_' || next == ':') out += ' ';
          }
        }
      }
      if (k < size) out += text[k++];
    }
  }
  return out;
}

/// @brief Reads `<collision>` and `<collisiondetection>` (null nodes: absent) into the scene.
/// Attributes, as FOSSSim's TwoDSceneXMLParser::loadCollisionHandler reads them: type
/// (required: none, simple, penalty, continuous-time, hybrid); COR (default 1) for simple,
/// continuous-time and hybrid; k and thickness for penalty (defaults 100, 0.01) and hybrid
/// (10, 0.1); maxiters for hybrid (default 10). An attribute the type does not read is refused.
inline void parse_fosssim_theme2(const FosssimReader& r, FosssimScene& scene,
                                 const pugi::xml_node& collision, const pugi::xml_node& detection) {
  if (collision) {
    const std::string item = "<collision>";
    if (!collision.attribute("type"))
      throw r.error(r.line(collision), item, ": missing required attribute \"type\"");
    const std::string_view type = FosssimReader::trimmed(collision.attribute("type").value());
    FosssimScene::Collision c;
    bool found = false;
    for (FosssimCollision t :
         {FosssimCollision::None, FosssimCollision::Simple, FosssimCollision::Penalty,
          FosssimCollision::ContinuousTime, FosssimCollision::Hybrid})
      if (type == to_string(t)) {
        c.type = t;
        found = true;
      }
    if (!found)
      throw r.error(r.line(collision), item, ": unknown type \"",
                    collision.attribute("type").value(),
                    "\" (expected none, simple, penalty, continuous-time or hybrid)");
    const bool impulses = c.type == FosssimCollision::Simple ||
                          c.type == FosssimCollision::ContinuousTime ||
                          c.type == FosssimCollision::Hybrid;
    const bool penalty = c.type == FosssimCollision::Penalty || c.type == FosssimCollision::Hybrid;
    const bool hybrid = c.type == FosssimCollision::Hybrid;
    for (const pugi::xml_attribute& a : collision.attributes()) {
      const std::string_view n = a.name();
      const bool ok = n == "type" || (impulses && n == "COR") ||
                      (penalty && (n == "k" || n == "thickness")) || (hybrid && n == "maxiters");
      if (ok) continue;
      const bool known = n == "COR" || n == "k" || n == "thickness" || n == "maxiters";
      const char* reads = c.type == FosssimCollision::None      ? "no other attribute"
                          : c.type == FosssimCollision::Penalty ? "k and thickness"
                          : hybrid                              ? "COR, k, thickness and maxiters"
                                                                : "COR";
      if (known)
        throw r.error(r.line(collision), item, ": attribute \"", n, "\" does not apply to type \"",
                      type, "\" (it reads ", reads, ")");
      throw r.error(r.line(collision), item, ": unknown attribute \"", n, "\" (type \"", type,
                    "\" reads ", reads, ")");
    }
    if (impulses) {
      c.cor = r.number(collision, item, "COR", 1.0);
      if (!(c.cor >= 0 && c.cor <= 1))
        throw r.error(r.line(collision), item,
                      ": COR = ", FosssimReader::trimmed(collision.attribute("COR").value()),
                      " must be in [0, 1]");
    }
    if (penalty) {
      c.k = r.nonnegative(collision, item, "k", false, hybrid ? 10.0 : 100.0);
      c.thickness = r.nonnegative(collision, item, "thickness", false, hybrid ? 0.1 : 0.01);
    }
    if (hybrid && collision.attribute("maxiters")) {
      long long m = 0;
      const pugi::xml_attribute a = collision.attribute("maxiters");
      if (parse_number(FosssimReader::trimmed(a.value()), m) != NumberStatus::Ok || m < 0 ||
          m > INT_MAX)
        throw r.error(r.line(collision), item, ": maxiters = \"", a.value(),
                      "\" must be a whole number >= 0");
      c.max_iterations = int(m);
    }
    scene.collision = c;
  }
  if (detection) {
    const std::string item = "<collisiondetection>";
    r.check_attributes(detection, item, {"type"}, {});
    const std::string_view type = FosssimReader::trimmed(detection.attribute("type").value());
    if (type != "allpairs" && type != "contest")
      throw r.error(r.line(detection), item, ": unknown type \"",
                    detection.attribute("type").value(), "\" (expected allpairs or contest)");
    scene.contest = type == "contest";
  }
}

}  // namespace massspring::io::detail
