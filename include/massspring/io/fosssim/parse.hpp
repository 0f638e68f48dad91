#pragma once
/// @file
/// @brief parse_fosssim_scene() and read_fosssim_scene(): a FOSSSim XML scene, read strictly
/// with pugixml (the schema: io/fosssim_scene.hpp and docs/scenes.md).

#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <pugixml.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/integrators/integrator_kind.hpp"
#include "massspring/io/detail/text_file.hpp"
#include "massspring/io/fosssim/reader.hpp"
#include "massspring/io/fosssim/scene.hpp"
#include "massspring/io/fosssim/theme2.hpp"

namespace massspring::io {

namespace detail {

/// @brief One element of a list the scene numbers (`<particle>`, `<edge>`, ...): its node and
/// its index among the elements of its name, from 0.
struct FosssimItem {
  pugi::xml_node node;
  int k;
};

/// @brief The children of `<scene>`, sorted by name in file order; the elements read later, when
/// what they refer to is known.
struct FosssimElements {
  std::vector<FosssimItem> particles, edges, springs, attractions, halfplanes, vortices;
  pugi::xml_node duration, integrator, collision, detection;
};

/// @brief The document's one root element, `<scene>`.
/// @throws Error for a second root element, none, or one that is not `<scene>`.
inline pugi::xml_node fosssim_root(const FosssimReader& r, const pugi::xml_document& doc) {
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
  return root;
}

/// @brief `<simplegravity fx fy/>`: adds (fx, fy, 0) to the scene's gravity [m/s^2].
/// @throws Error for a bad attribute or a sum that is not finite.
inline void read_fosssim_gravity(const FosssimReader& r, const pugi::xml_node& node,
                                 FosssimScene& scene) {
  r.check_attributes(node, "<simplegravity>", {"fx", "fy"}, {});
  const Vector3<double> g(r.number(node, "<simplegravity>", "fx"),
                          r.number(node, "<simplegravity>", "fy"), 0.0);
  scene.gravity = scene.gravity ? Vector3<double>(*scene.gravity + g) : g;
  if (!scene.gravity->allFinite())
    throw r.error(r.line(node), "<simplegravity>: the accelerations so far add up to ",
                  massspring::detail::format_row(*scene.gravity), ", which is not finite");
}

/// @brief `<dragdamping b/>`: adds b >= 0 to the scene's drag coefficient [kg/s].
/// @throws Error for a bad attribute or a sum that is not finite.
inline void read_fosssim_drag(const FosssimReader& r, const pugi::xml_node& node,
                              FosssimScene& scene) {
  r.check_attributes(node, "<dragdamping>", {"b"}, {});
  const double b = r.nonnegative(node, "<dragdamping>", "b", false);
  scene.drag = scene.drag.value_or(0.0) + b;
  if (!std::isfinite(*scene.drag))
    throw r.error(r.line(node), "<dragdamping>: the coefficients so far add up to ", *scene.drag,
                  ", which is not finite");
}

/// @brief Sorts the children of `<scene>` into `FosssimElements`, and reads at once the elements
/// that refer to nothing: `<simplegravity>`, `<dragdamping>`, `<description>`, `<scenetag>`.
/// Rendering elements are skipped.
/// @throws Error for a repeated `<duration>`, `<integrator>`, `<collision>` or
/// `<collisiondetection>`, an unknown element, or a bad element read here.
inline FosssimElements sort_fosssim_elements(const FosssimReader& r, const pugi::xml_node& root,
                                             FosssimScene& scene) {
  FosssimElements e;
  for (const pugi::xml_node& node : root.children()) {
    if (node.type() != pugi::node_element) continue;
    const std::string_view tag = node.name();
    if (tag == "particle") {
      e.particles.push_back({node, int(e.particles.size())});
    } else if (tag == "edge") {
      e.edges.push_back({node, int(e.edges.size())});
    } else if (tag == "springforce") {
      e.springs.push_back({node, int(e.springs.size())});
    } else if (tag == "gravitationalforce") {
      e.attractions.push_back({node, int(e.attractions.size())});
    } else if (tag == "halfplane") {
      e.halfplanes.push_back({node, int(e.halfplanes.size())});
    } else if (tag == "vortexforce") {
      e.vortices.push_back({node, int(e.vortices.size())});
    } else if (tag == "duration" || tag == "integrator" || tag == "collision" ||
               tag == "collisiondetection") {
      pugi::xml_node& slot = tag == "duration"     ? e.duration
                             : tag == "integrator" ? e.integrator
                             : tag == "collision"  ? e.collision
                                                   : e.detection;
      if (slot)
        throw r.error(r.line(node), '<', tag, "> appears twice (first on line ", r.line(slot), ')');
      slot = node;
    } else if (tag == "simplegravity") {
      read_fosssim_gravity(r, node, scene);
    } else if (tag == "dragdamping") {
      read_fosssim_drag(r, node, scene);
    } else if (tag == "description") {
      r.check_attributes(node, "<description>", {"text"}, {});
      scene.description = node.attribute("text").value();
    } else if (tag == "scenetag") {
      r.check_attributes(node, "<scenetag>", {"tag"}, {});
      scene.tags.emplace_back(node.attribute("tag").value());
    } else if (!fosssim_rendering_only(tag)) {
      throw r.error(r.line(node), "unknown element <", tag,
                    "> (massspring reads particle, edge, halfplane, springforce, simplegravity, "
                    "gravitationalforce, dragdamping, vortexforce, collision, collisiondetection, "
                    "integrator, duration, and ignores the rendering elements)");
    }
  }
  return e;
}

/// @brief `<duration time/>` and `<integrator type dt/>`, both required: the scene's duration
/// [s] (>= 0), integrator and time step [s] (> 0).
/// @throws Error for a missing element, a bad attribute or an unknown integrator type.
inline void read_fosssim_timing(const FosssimReader& r, const pugi::xml_node& root,
                                const FosssimElements& e, FosssimScene& scene) {
  if (!e.duration) throw r.error(r.line(root), "<scene> has no <duration time=\"...\"/>");
  if (!e.integrator)
    throw r.error(r.line(root), "<scene> has no <integrator type=\"...\" dt=\"...\"/>");
  r.check_attributes(e.duration, "<duration>", {"time"}, {});
  scene.duration = r.nonnegative(e.duration, "<duration>", "time", false);
  r.check_attributes(e.integrator, "<integrator>", {"type", "dt"}, {});
  const std::string_view type = FosssimReader::trimmed(e.integrator.attribute("type").value());
  const std::optional<IntegratorKind> kind = find_integrator(type, IntegratorNaming::Fosssim);
  if (!kind)
    throw r.error(r.line(e.integrator), "<integrator>: unknown type \"",
                  e.integrator.attribute("type").value(), "\" (expected ",
                  integrator_name_list(IntegratorNaming::Fosssim), ")");
  // IntegratorNaming::Fosssim names only the four kinds FosssimIntegrator holds
  scene.integrator = FosssimIntegrator(int(*kind));
  scene.dt = r.nonnegative(e.integrator, "<integrator>", "dt", true);
}

/// @brief `<particle m px py vx vy fixed [radius] [tag]/>`, at least one: masses (> 0),
/// positions, velocities, radii and the fixed particles, in file order.
/// @throws Error for none, a bad attribute, or fixed other than 0 or 1.
inline void read_fosssim_particles(const FosssimReader& r, const pugi::xml_node& root,
                                   const std::vector<FosssimItem>& particles, FosssimScene& scene) {
  const int n = int(particles.size());
  if (n == 0)
    throw r.error(r.line(root), "<scene> has no <particle>: a scene needs at least one particle");
  scene.positions.setZero(n, 3);
  scene.velocities.setZero(n, 3);
  scene.masses.resize(n);
  for (const FosssimItem& p : particles) {
    const std::string item = FosssimReader::label(p.node, p.k);
    r.check_attributes(p.node, item, {"m", "px", "py", "vx", "vy", "fixed"}, {"radius", "tag"});
    scene.masses(p.k) = r.nonnegative(p.node, item, "m", true);
    scene.positions(p.k, 0) = r.number(p.node, item, "px");
    scene.positions(p.k, 1) = r.number(p.node, item, "py");
    scene.velocities(p.k, 0) = r.number(p.node, item, "vx");
    scene.velocities(p.k, 1) = r.number(p.node, item, "vy");
    scene.radii.push_back(
        r.nonnegative(p.node, item, "radius", false, FosssimScene::kDefaultRadius));
    const std::string_view fixed = FosssimReader::trimmed(p.node.attribute("fixed").value());
    if (fixed == "1")
      scene.fixed.push_back(p.k);
    else if (fixed != "0")
      throw r.error(r.line(p.node), item, ": fixed = \"", p.node.attribute("fixed").value(),
                    "\" must be 0 or 1");
  }
}

/// @brief `<edge i j [radius]/>`: the edges (between two particles of the n read) and their
/// radii, in file order.
/// @throws Error for a bad attribute, an index out of range, or an edge from a particle to itself.
inline void read_fosssim_edges(const FosssimReader& r, const std::vector<FosssimItem>& edges, int n,
                               FosssimScene& scene) {
  scene.edges.resize(Eigen::Index(edges.size()), 2);
  for (const FosssimItem& e : edges) {
    const std::string item = FosssimReader::label(e.node, e.k);
    r.check_attributes(e.node, item, {"i", "j"}, {"radius"});
    const int i = r.index(e.node, item, "i", n, "particle");
    const int j = r.index(e.node, item, "j", n, "particle");
    if (i == j) throw r.error(r.line(e.node), item, " joins particle ", i, " to itself");
    scene.edge_radii.push_back(
        r.nonnegative(e.node, item, "radius", false, FosssimScene::kDefaultEdgeRadius));
    scene.edges.row(e.k) << i, j;
  }
}

/// @brief `<springforce edge k l0 [b]/>`: a spring on an edge read before, stiffness k,
/// rest length l0 and damping b (all >= 0); at most one per edge and one per pair of particles.
/// @throws Error for a bad attribute, an edge out of range, or a second spring on an edge or on
/// a pair (naming the first and its line).
inline void read_fosssim_springs(const FosssimReader& r, const std::vector<FosssimItem>& springs,
                                 FosssimScene& scene) {
  const int edges = int(scene.edges.rows());
  std::map<int, int> spring_of_edge;                  // edge -> springforce
  std::map<std::pair<int, int>, int> spring_of_pair;  // (min, max) particle -> springforce
  for (const FosssimItem& s : springs) {
    const std::string item = FosssimReader::label(s.node, s.k);
    r.check_attributes(s.node, item, {"edge", "k", "l0"}, {"b"});
    FosssimScene::SpringForce f;
    f.edge = r.index(s.node, item, "edge", edges, "edge");
    f.k = r.nonnegative(s.node, item, "k", false);
    f.l0 = r.nonnegative(s.node, item, "l0", false);
    f.b = r.nonnegative(s.node, item, "b", false, 0.0);
    if (const auto it = spring_of_edge.find(f.edge); it != spring_of_edge.end())
      throw r.error(r.line(s.node), item, ": edge ", f.edge, " already has a spring (",
                    FosssimReader::label(s.node, it->second), " on line ",
                    r.line(springs[std::size_t(it->second)].node), "); one <springforce> per edge");
    const int a = scene.edges(f.edge, 0), b = scene.edges(f.edge, 1);
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    if (const auto it = spring_of_pair.find(key); it != spring_of_pair.end())
      throw r.error(r.line(s.node), item, ": particles ", key.first, " and ", key.second,
                    " are already joined by ", FosssimReader::label(s.node, it->second),
                    " on line ", r.line(springs[std::size_t(it->second)].node),
                    " (through another edge); one spring per pair");
    spring_of_edge.emplace(f.edge, s.k);
    spring_of_pair.emplace(key, s.k);
    scene.springs.push_back(f);
  }
}

/// @brief `<gravitationalforce i j G/>`: an attraction between two different particles of the n
/// read, constant G >= 0.
/// @throws Error for a bad attribute, an index out of range, or a particle paired with itself.
inline void read_fosssim_attractions(const FosssimReader& r,
                                     const std::vector<FosssimItem>& attractions, int n,
                                     FosssimScene& scene) {
  for (const FosssimItem& g : attractions) {
    const std::string item = FosssimReader::label(g.node, g.k);
    r.check_attributes(g.node, item, {"i", "j", "G"}, {});
    FosssimScene::Attraction a;
    a.i = r.index(g.node, item, "i", n, "particle");
    a.j = r.index(g.node, item, "j", n, "particle");
    if (a.i == a.j) throw r.error(r.line(g.node), item, " attracts particle ", a.i, " to itself");
    a.G = r.nonnegative(g.node, item, "G", false);
    scene.attractions.push_back(a);
  }
}

/// @brief `<halfplane px py nx ny/>`: a half-plane through (px, py) with the normal (nx, ny),
/// not zero.
/// @throws Error for a bad attribute or a normal that is zero (or whose square is not finite).
inline void read_fosssim_halfplanes(const FosssimReader& r,
                                    const std::vector<FosssimItem>& halfplanes,
                                    FosssimScene& scene) {
  for (const FosssimItem& h : halfplanes) {
    const std::string item = FosssimReader::label(h.node, h.k);
    r.check_attributes(h.node, item, {"px", "py", "nx", "ny"}, {});
    FosssimScene::Halfplane plane;
    // Read into locals first: a throw inside Eigen's comma initializer would leave it unfinished.
    const double px = r.number(h.node, item, "px"), py = r.number(h.node, item, "py");
    const double nx = r.number(h.node, item, "nx"), ny = r.number(h.node, item, "ny");
    plane.point = Vector3<double>(px, py, 0);
    plane.normal = Vector3<double>(nx, ny, 0);
    if (!(plane.normal.squaredNorm() > 0) || !std::isfinite(plane.normal.squaredNorm()))
      throw r.error(r.line(h.node), item, ": the normal (nx, ny) = (",
                    h.node.attribute("nx").value(), ", ", h.node.attribute("ny").value(),
                    ") must be non-zero (and its square finite)");
    scene.halfplanes.push_back(plane);
  }
}

/// @brief `<vortexforce i j kbs kvc/>`: a vortex force between two different particles of the n
/// read.
/// @throws Error for a bad attribute, an index out of range, or a particle paired with itself.
inline void read_fosssim_vortices(const FosssimReader& r, const std::vector<FosssimItem>& vortices,
                                  int n, FosssimScene& scene) {
  for (const FosssimItem& v : vortices) {
    const std::string item = FosssimReader::label(v.node, v.k);
    r.check_attributes(v.node, item, {"i", "j", "kbs", "kvc"}, {});
    FosssimScene::Vortex f;
    f.i = r.index(v.node, item, "i", n, "particle");
    f.j = r.index(v.node, item, "j", n, "particle");
    if (f.i == f.j)
      throw r.error(r.line(v.node), item, " acts between particle ", f.i, " and itself");
    f.kbs = r.number(v.node, item, "kbs");
    f.kvc = r.number(v.node, item, "kvc");
    scene.vortices.push_back(f);
  }
}

}  // namespace detail

/// @brief Parses a FOSSSim scene held in memory; `name` is the file name used in messages. The
/// elements are read in this order, so that of two faults the first reported is the same on
/// every run: the root, the children of `<scene>` in file order (the ones that refer to nothing
/// read at once), the duration and integrator, the particles, edges, springs, attractions, the
/// Theme 2 collision elements, the half-planes and the vortices.
/// @throws Error as read_fosssim_scene() does.
inline FosssimScene parse_fosssim_scene(const std::string& text, const std::string& name) {
  // rapidxml (FOSSSim's parser) reads `a="1"b="2"`; separate such attributes first (no
  // line moves, so every line number below is the file's)
  const std::string separated = detail::separate_attributes(text);
  detail::FosssimReader r(name, separated);
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed =
      doc.load_buffer(separated.data(), separated.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!parsed)
    throw r.error(r.line_of(parsed.offset), "not well-formed XML: ", parsed.description());
  const pugi::xml_node root = detail::fosssim_root(r, doc);

  FosssimScene scene;
  const detail::FosssimElements e = detail::sort_fosssim_elements(r, root, scene);
  detail::read_fosssim_timing(r, root, e, scene);
  detail::read_fosssim_particles(r, root, e.particles, scene);
  const int n = int(e.particles.size());
  detail::read_fosssim_edges(r, e.edges, n, scene);
  detail::read_fosssim_springs(r, e.springs, scene);
  detail::read_fosssim_attractions(r, e.attractions, n, scene);
  detail::parse_fosssim_theme2(r, scene, e.collision, e.detection);
  detail::read_fosssim_halfplanes(r, e.halfplanes, scene);
  detail::read_fosssim_vortices(r, e.vortices, n, scene);
  return scene;
}
/// @brief Reads a FOSSSim XML scene (schema: io/fosssim_scene.hpp and docs/scenes.md), strictly.
/// @param[in] path  the .xml file
/// @return the scene, particles and edges in file order
/// @throws Error whose message starts with `<path>:<line>: ` and names the element (`<particle>
/// 3` is the fourth particle) for: XML that is not well-formed; a root other than one `<scene>`;
/// an unknown element or attribute; a missing or repeated `<duration>` or `<integrator>`, a
/// repeated `<collision>` or `<collisiondetection>`, an unknown integrator, collision or detection
/// type, an attribute of `<collision>` its type does not read, COR outside [0, 1], maxiters not a
/// whole number >= 0, a half-plane normal of zero; a missing required attribute; a value that is
/// not a number or not finite; m <= 0, dt <= 0, a negative duration, k, l0, b, G or radius; fixed
/// other than 0 or 1; an index that is not a whole number or out of range; an edge or pair from a
/// particle to itself; two `<springforce>` on one edge or on one pair of particles. Naming the
/// path when the file cannot be read.
inline FosssimScene read_fosssim_scene(const std::filesystem::path& path) {
  const std::string text = detail::read_text_file(path, "FOSSSim scene");
  return parse_fosssim_scene(text, path.string());
}

}  // namespace massspring::io
