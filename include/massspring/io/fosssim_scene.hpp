#pragma once
/// @file
/// @brief read_fosssim_scene(), write_fosssim_scene() and make_fosssim_system(): the 2D XML scenes
/// of FOSSSim (Columbia's "Animation and CGI Motion" course), read strictly with pugixml.
///
/// The schema (docs/scenes.md): a root `<scene>` holding
/// - `<duration time="T"/>` and `<integrator type="..." dt="h"/>`, both required, once each;
/// - `<particle m px py vx vy fixed [radius] [tag]/>`: index = order of appearance; z = 0;
/// - `<edge i j [radius]/>`: geometry, index = order of appearance;
/// - `<springforce edge k l0 [b]/>`: a spring on the endpoints of edge #edge (b defaults to 0);
/// - `<simplegravity fx fy/>` (an acceleration), `<gravitationalforce i j G/>`,
///   `<dragdamping b/>`;
/// - `<description text/>`, `<scenetag tag/>`: kept; `<particlecolor>`, `<edgecolor>`,
///   `<particlepath>`, `<backgroundcolor>`, `<viewport>`, `<maxsimfreq>`: rendering only, ignored.
/// Anything else (e.g. `<vortexforce>`, which massspring does not implement) is refused.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <map>
#include <optional>
#include <pugixml.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/forces/gravitational_attraction.hpp"
#include "massspring/forces/gravity.hpp"
#include "massspring/forces/linear_drag.hpp"
#include "massspring/io/detail/text_file.hpp"
#include "massspring/io/obj.hpp"
#include "massspring/types.hpp"

namespace massspring::io {

/// @brief The integrator a FOSSSim scene asks for (its `<integrator type>`).
enum class FosssimIntegrator {
  ExplicitEuler,            ///< "explicit-euler": massspring::ForwardEuler
  SymplecticEuler,          ///< "symplectic-euler": massspring::SymplecticEuler
  LinearizedImplicitEuler,  ///< "linearized-implicit-euler": BackwardEuler, Linearized mode
  ImplicitEuler,            ///< "implicit-euler": BackwardEuler, Newton mode
};

/// @brief The XML name of an integrator ("explicit-euler", ...).
inline const char* to_string(FosssimIntegrator integrator) {
  switch (integrator) {
    case FosssimIntegrator::ExplicitEuler:
      return "explicit-euler";
    case FosssimIntegrator::SymplecticEuler:
      return "symplectic-euler";
    case FosssimIntegrator::LinearizedImplicitEuler:
      return "linearized-implicit-euler";
    case FosssimIntegrator::ImplicitEuler:
      return "implicit-euler";
  }
  return "?";
}

/// @brief What a FOSSSim scene file says, in SI units, indices 0-based. Positions and velocities
/// are 3D with z = 0 (the format is 2D).
struct FosssimScene {
  /// @brief A `<springforce>`: a Hooke spring on the endpoints of edges.row(edge).
  struct SpringForce {
    int edge = 0;   ///< index into edges
    double k = 0;   ///< stiffness [N/m], >= 0
    double l0 = 0;  ///< rest length [m], >= 0
    double b = 0;   ///< damping along the spring [N s/m], >= 0
  };
  /// @brief A `<gravitationalforce>`: attraction between particles i and j.
  struct Attraction {
    int i = 0, j = 0;
    double G = 0;  ///< [N m^2 / kg^2], >= 0
  };

  /// @brief #particles by 3 initial positions [m] (z = 0).
  Points<double> positions = Points<double>(0, 3);
  /// @brief #particles by 3 initial velocities [m/s] (z = 0).
  Points<double> velocities = Points<double>(0, 3);
  /// @brief #particles masses [kg], > 0.
  Vector<double> masses;
  /// @brief Fixed particles (`fixed="1"`), ascending.
  std::vector<int> fixed;
  /// @brief #edges by 2 particle indices: every `<edge>`, also those without a spring (drawing).
  Edges edges = Edges(0, 2);
  /// @brief The `<springforce>` elements, in file order (at most one per edge).
  std::vector<SpringForce> springs;
  /// @brief The sum of the `<simplegravity>` accelerations [m/s^2], when there is one.
  std::optional<Vector3<double>> gravity;
  /// @brief The `<gravitationalforce>` pairs, in file order.
  std::vector<Attraction> attractions;
  /// @brief The sum of the `<dragdamping b>` coefficients [N s/m], when there is one.
  std::optional<double> drag;
  /// @brief The integrator the scene names.
  FosssimIntegrator integrator = FosssimIntegrator::SymplecticEuler;
  /// @brief Time step [s], > 0.
  double dt = 0.01;
  /// @brief Simulated time [s], >= 0.
  double duration = 0;
  /// @brief `<description text>` (empty when absent).
  std::string description;
  /// @brief `<scenetag tag>` values, in file order.
  std::vector<std::string> tags;

  /// @brief Number of particles.
  [[nodiscard]] int num_particles() const { return int(positions.rows()); }
  /// @brief Steps to simulate: ceil(duration / dt), as FOSSSim counts them; a quotient within
  /// 1e-9 (relative) of a whole number counts as that number, so 4.0 / 0.01 gives 400 whatever
  /// the rounding of 0.01.
  [[nodiscard]] long long steps() const { return steps_for(dt); }
  /// @brief ceil(duration / h) with the same rounding rule, for another step h > 0 (saturating
  /// at the largest long long).
  [[nodiscard]] long long steps_for(double h) const {
    const double q = duration / h;
    // saturate rather than overflow (an absurd duration / h is still a number of steps)
    if (!(q < 9.2e18)) return std::numeric_limits<long long>::max();
    const double nearest = std::round(q);
    if (std::abs(q - nearest) <= 1e-9 * std::max(1.0, nearest))
      return static_cast<long long>(nearest);
    return static_cast<long long>(std::ceil(q));
  }
};

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
  for (const char* s :
       {"particlecolor", "edgecolor", "particlepath", "backgroundcolor", "viewport", "maxsimfreq"})
    if (name == s) return true;
  return false;
}

}  // namespace detail

/// @brief Parses a FOSSSim scene held in memory; `name` is the file name used in messages.
/// @throws Error as read_fosssim_scene() does.
inline FosssimScene parse_fosssim_scene(const std::string& text, const std::string& name) {
  detail::FosssimReader r(name, text);
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed =
      doc.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!parsed)
    throw r.error(r.line_of(parsed.offset), "not well-formed XML: ", parsed.description());

  pugi::xml_node root;
  for (const pugi::xml_node& node : doc.children()) {
    if (node.type() != pugi::node_element) continue;
    if (root)
      throw r.error(r.line(node), "a second root element <", node.name(),
                    "> (a scene file holds one <scene>)");
    root = node;
  }
  if (!root) throw r.error(1, "no <scene> element");
  if (std::string_view(root.name()) != "scene")
    throw r.error(r.line(root), "the root element is <", root.name(), ">, expected <scene>");

  FosssimScene scene;
  struct Pending {
    pugi::xml_node node;
    int k;
  };
  std::vector<Pending> particles, edges, springs, attractions;
  pugi::xml_node duration, integrator;
  for (const pugi::xml_node& node : root.children()) {
    if (node.type() != pugi::node_element) continue;
    const std::string_view tag = node.name();
    if (tag == "particle") {
      particles.push_back({node, int(particles.size())});
    } else if (tag == "edge") {
      edges.push_back({node, int(edges.size())});
    } else if (tag == "springforce") {
      springs.push_back({node, int(springs.size())});
    } else if (tag == "gravitationalforce") {
      attractions.push_back({node, int(attractions.size())});
    } else if (tag == "duration" || tag == "integrator") {
      pugi::xml_node& slot = tag == "duration" ? duration : integrator;
      if (slot)
        throw r.error(r.line(node), '<', tag, "> appears twice (first on line ", r.line(slot), ')');
      slot = node;
    } else if (tag == "simplegravity") {
      r.check_attributes(node, "<simplegravity>", {"fx", "fy"}, {});
      const Vector3<double> g(r.number(node, "<simplegravity>", "fx"),
                              r.number(node, "<simplegravity>", "fy"), 0.0);
      scene.gravity = scene.gravity ? Vector3<double>(*scene.gravity + g) : g;
      if (!scene.gravity->allFinite())
        throw r.error(r.line(node), "<simplegravity>: the accelerations so far add up to ",
                      massspring::detail::format_row(*scene.gravity), ", which is not finite");
    } else if (tag == "dragdamping") {
      r.check_attributes(node, "<dragdamping>", {"b"}, {});
      const double b = r.nonnegative(node, "<dragdamping>", "b", false);
      scene.drag = scene.drag.value_or(0.0) + b;
      if (!std::isfinite(*scene.drag))
        throw r.error(r.line(node), "<dragdamping>: the coefficients so far add up to ",
                      *scene.drag, ", which is not finite");
    } else if (tag == "description") {
      r.check_attributes(node, "<description>", {"text"}, {});
      scene.description = node.attribute("text").value();
    } else if (tag == "scenetag") {
      r.check_attributes(node, "<scenetag>", {"tag"}, {});
      scene.tags.emplace_back(node.attribute("tag").value());
    } else if (!detail::fosssim_rendering_only(tag)) {
      throw r.error(r.line(node), "unknown element <", tag,
                    "> (massspring reads particle, edge, springforce, simplegravity, "
                    "gravitationalforce, dragdamping, integrator, duration; it does not implement "
                    "the others)");
    }
  }

  // duration and integrator
  if (!duration) throw r.error(r.line(root), "<scene> has no <duration time=\"...\"/>");
  if (!integrator)
    throw r.error(r.line(root), "<scene> has no <integrator type=\"...\" dt=\"...\"/>");
  r.check_attributes(duration, "<duration>", {"time"}, {});
  scene.duration = r.nonnegative(duration, "<duration>", "time", false);
  r.check_attributes(integrator, "<integrator>", {"type", "dt"}, {});
  {
    const std::string_view type =
        detail::FosssimReader::trimmed(integrator.attribute("type").value());
    bool found = false;
    for (FosssimIntegrator candidate :
         {FosssimIntegrator::ExplicitEuler, FosssimIntegrator::SymplecticEuler,
          FosssimIntegrator::LinearizedImplicitEuler, FosssimIntegrator::ImplicitEuler})
      if (type == to_string(candidate)) {
        scene.integrator = candidate;
        found = true;
      }
    if (!found)
      throw r.error(r.line(integrator), "<integrator>: unknown type \"",
                    integrator.attribute("type").value(),
                    "\" (expected explicit-euler, symplectic-euler, linearized-implicit-euler or "
                    "implicit-euler)");
    scene.dt = r.nonnegative(integrator, "<integrator>", "dt", true);
  }

  // particles
  const int n = int(particles.size());
  if (n == 0)
    throw r.error(r.line(root), "<scene> has no <particle>: a scene needs at least one particle");
  scene.positions.setZero(n, 3);
  scene.velocities.setZero(n, 3);
  scene.masses.resize(n);
  for (const Pending& p : particles) {
    const std::string item = detail::FosssimReader::label(p.node, p.k);
    r.check_attributes(p.node, item, {"m", "px", "py", "vx", "vy", "fixed"}, {"radius", "tag"});
    scene.masses(p.k) = r.nonnegative(p.node, item, "m", true);
    scene.positions(p.k, 0) = r.number(p.node, item, "px");
    scene.positions(p.k, 1) = r.number(p.node, item, "py");
    scene.velocities(p.k, 0) = r.number(p.node, item, "vx");
    scene.velocities(p.k, 1) = r.number(p.node, item, "vy");
    (void)r.nonnegative(p.node, item, "radius", false, 0.1);
    const std::string_view fixed =
        detail::FosssimReader::trimmed(p.node.attribute("fixed").value());
    if (fixed == "1")
      scene.fixed.push_back(p.k);
    else if (fixed != "0")
      throw r.error(r.line(p.node), item, ": fixed = \"", p.node.attribute("fixed").value(),
                    "\" must be 0 or 1");
  }

  // edges
  scene.edges.resize(Eigen::Index(edges.size()), 2);
  for (const Pending& e : edges) {
    const std::string item = detail::FosssimReader::label(e.node, e.k);
    r.check_attributes(e.node, item, {"i", "j"}, {"radius"});
    const int i = r.index(e.node, item, "i", n, "particle");
    const int j = r.index(e.node, item, "j", n, "particle");
    if (i == j) throw r.error(r.line(e.node), item, " joins particle ", i, " to itself");
    (void)r.nonnegative(e.node, item, "radius", false, 0.015);
    scene.edges.row(e.k) << i, j;
  }

  // spring forces: at most one per edge, and at most one per pair of particles
  std::map<int, int> spring_of_edge;                  // edge -> springforce
  std::map<std::pair<int, int>, int> spring_of_pair;  // (min, max) particle -> springforce
  for (const Pending& s : springs) {
    const std::string item = detail::FosssimReader::label(s.node, s.k);
    r.check_attributes(s.node, item, {"edge", "k", "l0"}, {"b"});
    FosssimScene::SpringForce f;
    f.edge = r.index(s.node, item, "edge", int(edges.size()), "edge");
    f.k = r.nonnegative(s.node, item, "k", false);
    f.l0 = r.nonnegative(s.node, item, "l0", false);
    f.b = r.nonnegative(s.node, item, "b", false, 0.0);
    if (const auto it = spring_of_edge.find(f.edge); it != spring_of_edge.end())
      throw r.error(r.line(s.node), item, ": edge ", f.edge, " already has a spring (",
                    detail::FosssimReader::label(s.node, it->second), " on line ",
                    r.line(springs[std::size_t(it->second)].node), "); one <springforce> per edge");
    const int a = scene.edges(f.edge, 0), b = scene.edges(f.edge, 1);
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    if (const auto it = spring_of_pair.find(key); it != spring_of_pair.end())
      throw r.error(r.line(s.node), item, ": particles ", key.first, " and ", key.second,
                    " are already joined by ", detail::FosssimReader::label(s.node, it->second),
                    " on line ", r.line(springs[std::size_t(it->second)].node),
                    " (through another edge); one spring per pair");
    spring_of_edge.emplace(f.edge, s.k);
    spring_of_pair.emplace(key, s.k);
    scene.springs.push_back(f);
  }

  // gravitational pairs
  for (const Pending& g : attractions) {
    const std::string item = detail::FosssimReader::label(g.node, g.k);
    r.check_attributes(g.node, item, {"i", "j", "G"}, {});
    FosssimScene::Attraction a;
    a.i = r.index(g.node, item, "i", n, "particle");
    a.j = r.index(g.node, item, "j", n, "particle");
    if (a.i == a.j) throw r.error(r.line(g.node), item, " attracts particle ", a.i, " to itself");
    a.G = r.nonnegative(g.node, item, "G", false);
    scene.attractions.push_back(a);
  }
  return scene;
}

/// @brief Reads a FOSSSim XML scene (schema: this file's header and docs/scenes.md), strictly.
/// @param[in] path  the .xml file
/// @return the scene, particles and edges in file order
/// @throws Error whose message starts with `<path>:<line>: ` and names the element (`<particle>
/// 3` is the fourth particle) for: XML that is not well-formed; a root other than one `<scene>`;
/// an unknown element (e.g. `<vortexforce>`) or attribute; a missing or repeated `<duration>` or
/// `<integrator>`, an unknown integrator type; a missing required attribute; a value that is not
/// a number or not finite; m <= 0, dt <= 0, a negative duration, k, l0, b, G or radius; fixed
/// other than 0 or 1; an index that is not a whole number or out of range; an edge or pair from a
/// particle to itself; two `<springforce>` on one edge or on one pair of particles. Naming the
/// path when the file cannot be read.
inline FosssimScene read_fosssim_scene(const std::filesystem::path& path) {
  const std::string text = detail::read_text_file(path, "FOSSSim scene");
  return parse_fosssim_scene(text, path.string());
}

/// @brief Writes a scene that read_fosssim_scene() reads back exactly (numbers as the shortest
/// decimal that parses to the same double), through `<path>.tmp` renamed over `path`.
/// @throws Error when a position or velocity has z != 0 (the format is 2D), or an index is out
/// of range; naming the path when it cannot be written.
inline void write_fosssim_scene(const std::filesystem::path& path, const FosssimScene& scene) {
  using detail::append_index;
  using detail::append_number;
  const int n = scene.num_particles();
  if (scene.velocities.rows() != n || scene.masses.size() != n)
    throw Error(detail::message(path.string(), ": scene has ", n, " positions but ",
                                scene.velocities.rows(), " velocities and ", scene.masses.size(),
                                " masses"));
  for (int i = 0; i < n; ++i)
    if (scene.positions(i, 2) != 0 || scene.velocities(i, 2) != 0)
      throw Error(
          detail::message(path.string(), ": particle ", i, " has z != 0: FOSSSim scenes are 2D"));
  std::string out = "<scene>\n";
  auto attribute = [&out](const char* name, double x) {
    out += ' ';
    out += name;
    out += "=\"";
    append_number(out, x);
    out += '"';
  };
  auto escaped = [](const std::string& s) {
    std::string e;
    for (char c : s) {
      if (c == '&')
        e += "&amp;";
      else if (c == '<')
        e += "&lt;";
      else if (c == '>')
        e += "&gt;";
      else if (c == '"')
        e += "&quot;";
      else
        e += c;
    }
    return e;
  };
  if (!scene.description.empty())
    out += "  <description text=\"" + escaped(scene.description) + "\"/>\n";
  for (const std::string& tag : scene.tags) out += "  <scenetag tag=\"" + escaped(tag) + "\"/>\n";
  out += "  <duration";
  attribute("time", scene.duration);
  out += "/>\n  <integrator type=\"";
  out += to_string(scene.integrator);
  out += '"';
  attribute("dt", scene.dt);
  out += "/>\n\n";
  std::vector<bool> fixed(std::size_t(n), false);
  for (int i : scene.fixed) {
    if (i < 0 || i >= n)
      throw Error(
          detail::message(path.string(), ": fixed particle ", i, " out of range [0, ", n, ")"));
    fixed[std::size_t(i)] = true;
  }
  for (int i = 0; i < n; ++i) {
    out += "  <particle";
    attribute("m", scene.masses(i));
    attribute("px", scene.positions(i, 0));
    attribute("py", scene.positions(i, 1));
    attribute("vx", scene.velocities(i, 0));
    attribute("vy", scene.velocities(i, 1));
    out += fixed[std::size_t(i)] ? " fixed=\"1\"/>\n" : " fixed=\"0\"/>\n";
  }
  for (Eigen::Index e = 0; e < scene.edges.rows(); ++e) {
    out += "  <edge i=\"";
    append_index(out, scene.edges(e, 0));
    out += "\" j=\"";
    append_index(out, scene.edges(e, 1));
    out += "\"/>\n";
  }
  for (const auto& s : scene.springs) {
    out += "  <springforce edge=\"";
    append_index(out, s.edge);
    out += '"';
    attribute("k", s.k);
    attribute("l0", s.l0);
    attribute("b", s.b);
    out += "/>\n";
  }
  if (scene.gravity) {
    out += "  <simplegravity";
    attribute("fx", (*scene.gravity)(0));
    attribute("fy", (*scene.gravity)(1));
    out += "/>\n";
  }
  for (const auto& a : scene.attractions) {
    out += "  <gravitationalforce i=\"";
    append_index(out, a.i);
    out += "\" j=\"";
    append_index(out, a.j);
    out += '"';
    attribute("G", a.G);
    out += "/>\n";
  }
  if (scene.drag) {
    out += "  <dragdamping";
    attribute("b", *scene.drag);
    out += "/>\n";
  }
  out += "</scene>\n";
  detail::write_text_file_atomically(path, out);
}

/// @brief The system a FOSSSim scene describes, with its force terms.
///
/// - points: the particles (z = 0), their masses and initial velocities; fixed particles are
///   pinned where they start, with velocity 0;
/// - springs: one per `<springforce>` (its edge's endpoints, k, rest length l0, damping b); edges
///   without a spring are drawing only and are not in the system;
/// - `<simplegravity>` -> Gravity (an acceleration: F = m g), `<gravitationalforce>` pairs ->
///   one GravitationalAttraction, `<dragdamping>` -> LinearDrag (coefficients summed).
///
/// @tparam System a MassSpringSystem<Scalar, Storage>
/// @throws Error from MassSpringSystem for a description it refuses (e.g. one built by hand with
/// an index out of range).
template <class System>
System make_fosssim_system(const FosssimScene& scene) {
  using Scalar = typename System::Scalar;
  const Eigen::Index m = Eigen::Index(scene.springs.size());
  Edges springs(m, 2);
  Vector<Scalar> k(m), l0(m), b(m);
  for (Eigen::Index s = 0; s < m; ++s) {
    const auto& f = scene.springs[std::size_t(s)];
    if (f.edge < 0 || f.edge >= scene.edges.rows())
      throw Error(detail::message("spring force ", s, ": edge ", f.edge, " out of range [0, ",
                                  scene.edges.rows(), ")"));
    springs.row(s) = scene.edges.row(f.edge);
    k(s) = Scalar(f.k);
    l0(s) = Scalar(f.l0);
    b(s) = Scalar(f.b);
  }
  System system(scene.positions.template cast<Scalar>(), springs,
                scene.masses.template cast<Scalar>(), k);
  system.set_rest_lengths(l0);
  system.set_damping(b);
  Points<Scalar> v = scene.velocities.template cast<Scalar>();
  for (int i : scene.fixed)
    if (i >= 0 && i < v.rows()) v.row(i).setZero();
  system.set_velocities(v);
  system.pin(scene.fixed);
  if (scene.gravity) system.add_force(Gravity<Scalar>(scene.gravity->template cast<Scalar>()));
  if (!scene.attractions.empty()) {
    std::vector<typename GravitationalAttraction<Scalar>::Pair> pairs;
    for (const auto& a : scene.attractions) pairs.push_back({a.i, a.j, Scalar(a.G)});
    system.add_force(GravitationalAttraction<Scalar>(std::move(pairs)));
  }
  if (scene.drag) system.add_force(LinearDrag<Scalar>(Scalar(*scene.drag)));
  return system;
}

}  // namespace massspring::io
