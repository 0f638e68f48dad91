#pragma once
/// @file
/// @brief write_fosssim_scene(): a FOSSSim XML scene that read_fosssim_scene() reads back exactly.

#include <filesystem>
#include <initializer_list>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/io/detail/text_file.hpp"
#include "massspring/io/fosssim/scene.hpp"
#include "massspring/io/obj.hpp"

namespace massspring::io {

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
  // ` name="x"`: an integer x as an index, any other as the shortest decimal of the double.
  auto attribute = [&out](const char* name, auto x) {
    out += ' ';
    out += name;
    out += "=\"";
    if constexpr (std::is_integral_v<decltype(x)>)
      append_index(out, int(x));
    else
      append_number(out, double(x));
    out += '"';
  };
  // A line `  <tag i="..." x="..."/>`: the index attributes in order, then the numbers.
  using Indices = std::initializer_list<std::pair<const char*, int>>;
  using Numbers = std::initializer_list<std::pair<const char*, double>>;
  auto element = [&](const char* tag, Indices indices, Numbers numbers) {
    out += "  <";
    out += tag;
    for (const auto& [name, i] : indices) attribute(name, i);
    for (const auto& [name, x] : numbers) attribute(name, x);
    out += "/>\n";
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
  if (!scene.radii.empty() && int(scene.radii.size()) != n)
    throw Error(detail::message(path.string(), ": scene has ", n, " particles but ",
                                scene.radii.size(), " radii"));
  if (!scene.edge_radii.empty() && Eigen::Index(scene.edge_radii.size()) != scene.edges.rows())
    throw Error(detail::message(path.string(), ": scene has ", scene.edges.rows(), " edges but ",
                                scene.edge_radii.size(), " edge radii"));
  if (scene.collision) {
    const auto& c = *scene.collision;
    out += "  <collision type=\"";
    out += to_string(c.type);
    out += '"';
    const bool impulses = c.type == FosssimCollision::Simple ||
                          c.type == FosssimCollision::ContinuousTime ||
                          c.type == FosssimCollision::Hybrid;
    const bool penalty = c.type == FosssimCollision::Penalty || c.type == FosssimCollision::Hybrid;
    if (impulses) attribute("COR", c.cor);
    if (penalty) {
      attribute("k", c.k);
      attribute("thickness", c.thickness);
    }
    if (c.type == FosssimCollision::Hybrid) {
      attribute("maxiters", c.max_iterations);
    }
    out += "/>\n";
  }
  if (scene.contest)
    out += *scene.contest ? "  <collisiondetection type=\"contest\"/>\n"
                          : "  <collisiondetection type=\"allpairs\"/>\n";
  for (int i = 0; i < n; ++i) {
    out += "  <particle";
    attribute("m", scene.masses(i));
    attribute("px", scene.positions(i, 0));
    attribute("py", scene.positions(i, 1));
    attribute("vx", scene.velocities(i, 0));
    attribute("vy", scene.velocities(i, 1));
    out += fixed[std::size_t(i)] ? " fixed=\"1\"" : " fixed=\"0\"";
    if (scene.radius(i) != FosssimScene::kDefaultRadius) attribute("radius", scene.radius(i));
    out += "/>\n";
  }
  for (Eigen::Index e = 0; e < scene.edges.rows(); ++e) {
    out += "  <edge";
    attribute("i", scene.edges(e, 0));
    attribute("j", scene.edges(e, 1));
    if (scene.edge_radius(int(e)) != FosssimScene::kDefaultEdgeRadius)
      attribute("radius", scene.edge_radius(int(e)));
    out += "/>\n";
  }
  for (const auto& h : scene.halfplanes)
    element("halfplane", {},
            {{"px", h.point(0)}, {"py", h.point(1)}, {"nx", h.normal(0)}, {"ny", h.normal(1)}});
  for (const auto& s : scene.springs)
    element("springforce", {{"edge", s.edge}}, {{"k", s.k}, {"l0", s.l0}, {"b", s.b}});
  if (scene.gravity)
    element("simplegravity", {}, {{"fx", (*scene.gravity)(0)}, {"fy", (*scene.gravity)(1)}});
  for (const auto& a : scene.attractions)
    element("gravitationalforce", {{"i", a.i}, {"j", a.j}}, {{"G", a.G}});
  for (const auto& v : scene.vortices)
    element("vortexforce", {{"i", v.i}, {"j", v.j}}, {{"kbs", v.kbs}, {"kvc", v.kvc}});
  if (scene.drag) element("dragdamping", {}, {{"b", *scene.drag}});
  out += "</scene>\n";
  detail::write_text_file_atomically(path, out);
}

}  // namespace massspring::io
