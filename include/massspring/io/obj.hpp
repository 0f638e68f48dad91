#pragma once
/// @file
/// @brief read_obj() and write_obj(): a strict reader and an exact writer of Wavefront OBJ meshes
/// whose faces may have 2 vertices (the JSON+OBJ scenes' springs, `f i j`) or more (polygons).
///
/// Why not tinyobjloader: it silently drops 2-vertex faces, which is all the JSON+OBJ scenes'
/// chain, net and spring files hold, and reads malformed numbers such as `x` or `nan` as 0. This
/// reader refuses anything it does not understand, naming the file and line.

#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/io/detail/text_file.hpp"
#include "massspring/types.hpp"

namespace massspring::io {

/// @brief What an OBJ file holds, in the shapes the library uses (all indices 0-based).
template <class Scalar = double>
struct ObjMesh {
  /// @brief #V by 3 vertex positions (`v x y z`; a weight w is read and dropped).
  Points<Scalar> vertices = Points<Scalar>(0, 3);
  /// @brief Polygons: the `f` lines with 3 or more vertices, in file order.
  std::vector<std::vector<int>> faces;
  /// @brief #E by 2 segments: the `f i j` lines and the consecutive pairs of each `l` polyline, in
  /// file order.
  Edges edges = Edges(0, 2);
  /// @brief The line (1-based) of each vertex's `v` statement: #V entries.
  std::vector<std::size_t> vertex_lines;
  /// @brief The line (1-based) of each polygon's `f` statement: one entry per face.
  std::vector<std::size_t> face_lines;
};

namespace detail {

/// @brief Outcome of parsing one number.
enum class NumberStatus { Ok, NotANumber, OutOfRange };

/// @brief Parses the whole of `s` as a number of type T (locale-independent, std::from_chars);
/// a leading '+' is allowed.
template <class T>
NumberStatus parse_number(std::string_view s, T& value) {
  if (s.size() > 1 && s[0] == '+' && s[1] != '+' && s[1] != '-') s.remove_prefix(1);
  const char* const first = s.data();
  const char* const last = s.data() + s.size();
  const auto [end, ec] = std::from_chars(first, last, value);
  if (ec == std::errc::result_out_of_range && end == last) return NumberStatus::OutOfRange;
  if (ec != std::errc() || end != last || s.empty()) return NumberStatus::NotANumber;
  return NumberStatus::Ok;
}

/// @brief Whitespace-separated tokens of a line (space, tab, vertical tab, form feed).
inline void split_tokens(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  constexpr std::string_view blanks = " \t\v\f\r";
  std::size_t pos = 0;
  while (true) {
    pos = line.find_first_not_of(blanks, pos);
    if (pos == std::string_view::npos) return;
    const std::size_t end = line.find_first_of(blanks, pos);
    tokens.push_back(
        line.substr(pos, end == std::string_view::npos ? line.size() - pos : end - pos));
    if (end == std::string_view::npos) return;
    pos = end;
  }
}

/// @brief The strict OBJ parser behind read_obj(); `name` prefixes every message.
template <class Scalar>
ObjMesh<Scalar> parse_obj(std::string_view text, const std::string& name) {
  static_assert(std::is_floating_point_v<Scalar>,
                "read_obj<Scalar>: Scalar must be float or double");
  std::size_t line_number = 0;
  // `throw error(...)`: an Error whose message starts with "<name>:<line>: ".
  auto error = [&](const auto&... parts) {
    return Error(message(name, ':', line_number, ": ", parts...));
  };

  std::vector<Scalar> coordinates;
  std::vector<std::size_t> vertex_lines, face_lines;
  std::vector<std::vector<int>> faces;
  std::vector<std::array<int, 2>> edges;
  // Positive indices may refer to vertices defined later in the file: their range is checked at
  // the end, against the line that holds them.
  struct Reference {
    std::size_t line;
    int index;  // 0-based
  };
  std::vector<Reference> forward;
  std::vector<std::string_view> tokens;
  std::vector<int> polygon;

  // Parses "i", "i/t", "i//n", "i/t/n" (or, for polylines, "i" and "i/t") into a 0-based index.
  auto vertex_reference = [&](std::string_view token, const char* element, std::size_t position,
                              bool polyline) -> int {
    std::string_view parts[3];
    std::size_t count = 0;
    bool malformed = false;
    for (std::size_t start = 0;;) {
      const std::size_t slash = token.find('/', start);
      if (count == 3) {
        malformed = true;
        break;
      }
      parts[count++] =
          token.substr(start, slash == std::string_view::npos ? token.npos : slash - start);
      if (slash == std::string_view::npos) break;
      start = slash + 1;
    }
    if (!malformed) {
      if (parts[0].empty()) malformed = true;
      if (count == 2 && parts[1].empty()) malformed = true;  // "i/"
      if (count == 3 && parts[2].empty()) malformed = true;  // "i/t/" or "i//"
      if (polyline && count == 3) malformed = true;          // l takes i or i/t
    }
    if (malformed)
      throw error(element, " vertex ", position, " is malformed: \"", token, "\" (expected ",
                  polyline ? "i or i/t" : "i, i/t, i//n or i/t/n", ")");
    // texture and normal indices are not used, but they must be nonzero integers
    for (std::size_t p = 1; p < count; ++p) {
      if (parts[p].empty()) continue;
      long long other = 0;
      if (parse_number(parts[p], other) != NumberStatus::Ok || other == 0)
        throw error(element, " vertex ", position, ": ", p == 1 ? "texture" : "normal",
                    " index is not a nonzero integer: \"", token, "\"");
    }
    long long written = 0;
    switch (parse_number(parts[0], written)) {
      case NumberStatus::NotANumber:
        throw error(element, " vertex ", position, ": vertex index is not an integer: \"", token,
                    "\"");
      case NumberStatus::OutOfRange:
        throw error(element, " vertex ", position, ": vertex index is out of range: \"", token,
                    "\"");
      case NumberStatus::Ok:
        break;
    }
    if (written == 0)
      throw error(element, " vertex ", position,
                  ": vertex index 0 is invalid (OBJ indices start at 1)");
    const long long defined = static_cast<long long>(coordinates.size() / 3);
    if (written < 0) {
      if (defined + written < 0)
        throw error(element, " vertex ", position, ": vertex index ", written,
                    " refers before the first vertex (", defined,
                    " vertices are defined above it)");
      return static_cast<int>(defined + written);
    }
    if (written > std::numeric_limits<int>::max())
      throw error(element, " vertex ", position, ": vertex index ", written, " is out of range");
    const int index = static_cast<int>(written - 1);
    if (written > defined) forward.push_back({line_number, index});
    return index;
  };

  std::size_t pos = 0;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") pos = 3;  // UTF-8 byte order mark
  while (pos < text.size()) {
    ++line_number;
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos)
      line = line.substr(0, hash);
    split_tokens(line, tokens);
    if (tokens.empty()) continue;
    const std::string_view keyword = tokens[0];
    const std::size_t args = tokens.size() - 1;

    if (keyword == "v") {
      if (args != 3 && args != 4)
        throw error("a vertex needs 3 coordinates and an optional weight (v x y z [w]), got ", args,
                    " values");
      for (std::size_t c = 1; c <= args; ++c) {
        Scalar x = 0;
        switch (parse_number(tokens[c], x)) {
          case NumberStatus::NotANumber:
            throw error("vertex coordinate ", c, " is not a number: \"", tokens[c], "\"");
            break;
          case NumberStatus::OutOfRange:
            throw error("vertex coordinate ", c, " is out of range for ",
                        std::is_same_v<Scalar, float> ? "float" : "double", ": \"", tokens[c],
                        "\"");
            break;
          case NumberStatus::Ok:
            if (!std::isfinite(x))
              throw error("vertex coordinate ", c, " is not finite: \"", tokens[c], "\"");
            break;
        }
        if (c <= 3) coordinates.push_back(x);
      }
      vertex_lines.push_back(line_number);
    } else if (keyword == "f") {
      if (args < 2)
        throw error(
            "a face needs at least 2 vertices (f i j for a spring, 3 or more for a polygon), got ",
            args);
      polygon.clear();
      for (std::size_t a = 1; a <= args; ++a) {
        const int v = vertex_reference(tokens[a], "face", a, false);
        for (std::size_t b = 0; b < polygon.size(); ++b)
          if (polygon[b] == v)
            throw error("face vertices ", b + 1, " and ", a, " are the same vertex ", v + 1,
                        ": a face may not repeat a vertex");
        polygon.push_back(v);
      }
      if (polygon.size() == 2)
        edges.push_back({polygon[0], polygon[1]});
      else {
        faces.push_back(polygon);
        face_lines.push_back(line_number);
      }
    } else if (keyword == "l") {
      if (args < 2) throw error("a polyline needs at least 2 vertices (l i j ...), got ", args);
      int previous = -1;
      for (std::size_t a = 1; a <= args; ++a) {
        const int v = vertex_reference(tokens[a], "polyline", a, true);
        if (a > 1) {
          if (v == previous)
            throw error("polyline vertices ", a - 1, " and ", a,
                        " are the same vertex: a segment must join two vertices");
          edges.push_back({previous, v});
        }
        previous = v;
      }
    } else if (keyword == "vt" || keyword == "vn" || keyword == "vp" || keyword == "o" ||
               keyword == "g" || keyword == "s" || keyword == "usemtl" || keyword == "mtllib") {
      // texture coordinates, normals, names, groups, smoothing and materials: not used
    } else {
      throw error("unsupported OBJ statement \"", keyword,
                  "\" (expected v, f or l; vt, vn, vp, o, g, s, usemtl and mtllib are ignored)");
    }
  }

  const Eigen::Index n = Eigen::Index(coordinates.size() / 3);
  for (const Reference& r : forward)
    if (r.index >= n) {
      line_number = r.line;
      throw error("vertex index ", static_cast<long long>(r.index) + 1,
                  " is out of range: the file has ", n, " vertices");
    }

  ObjMesh<Scalar> mesh;
  mesh.vertices = Eigen::Map<const Points<Scalar>>(coordinates.data(), n, 3);
  mesh.faces = std::move(faces);
  mesh.vertex_lines = std::move(vertex_lines);
  mesh.face_lines = std::move(face_lines);
  mesh.edges.resize(Eigen::Index(edges.size()), 2);
  for (std::size_t e = 0; e < edges.size(); ++e)
    mesh.edges.row(Eigen::Index(e)) << edges[e][0], edges[e][1];
  return mesh;
}

/// @brief Appends the shortest decimal text that reads back as exactly `x` (std::to_chars).
template <class Scalar>
void append_number(std::string& out, Scalar x) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  (void)ec;  // 64 characters hold any float or double
  out.append(buffer, end);
}

inline void append_index(std::string& out, int i) {
  char buffer[16];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, i);
  (void)ec;
  out.append(buffer, end);
}

}  // namespace detail

/// @brief Reads an OBJ mesh, strictly.
///
/// Understands `v x y z [w]`, `f` with `i`, `i/t`, `i//n`, `i/t/n` and negative (relative)
/// indices, and `l` polylines. A 2-vertex face `f i j` and each segment of a polyline become an
/// edge; a face of 3 or more vertices a polygon. Comments, blank lines and `vt vn vp o g s usemtl
/// mtllib` lines are skipped; CRLF line ends and a missing final newline are fine.
///
/// @tparam Scalar float or double: coordinates are parsed directly in this type (std::from_chars,
/// locale-independent, correctly rounded).
/// @param[in] path  the .obj file
/// @return the mesh, indices 0-based, with the line of each vertex and polygon (for messages)
/// @throws Error whose message starts with `<path>:<line>: ` and says what was expected, for any
/// other statement, a malformed or non-finite number, a wrong count of coordinates, an index of
/// 0, an index out of range (reported as written, 1-based), a face of fewer than 2 vertices or one
/// that repeats a vertex, a polyline segment from a vertex to itself; or naming the path when the
/// file cannot be read.
template <class Scalar = double>
ObjMesh<Scalar> read_obj(const std::filesystem::path& path) {
  const std::string text = detail::read_text_file(path, "OBJ file");
  return detail::parse_obj<Scalar>(text, path.string());
}

/// @brief Writes an OBJ mesh that read_obj() reads back exactly: every coordinate as the shortest
/// decimal that parses to the same bits (std::to_chars), indices 1-based, polygons as `f a b c
/// ...`, edges as 2-vertex faces `f i j` (the JSON+OBJ scenes' convention for springs). The file is
/// written to `<path>.tmp` and then renamed over `path`.
/// @param[in] path       the .obj file to write (its folder must exist)
/// @param[in] positions  #V by 3 vertex positions, finite
/// @param[in] faces      polygons, 3 or more distinct vertices each, 0-based
/// @param[in] edges      #E by 2 segments, 0-based, two distinct vertices each
/// @throws Error naming the path and the item for a non-finite position or an invalid face or
/// edge (nothing is written), or when the file cannot be written.
template <class Scalar>
void write_obj(const std::filesystem::path& path, const Points<Scalar>& positions,
               const std::vector<std::vector<int>>& faces, const Edges& edges) {
  using massspring::detail::message;
  const Eigen::Index n = positions.rows();
  const std::string name = path.string();
  for (Eigen::Index i = 0; i < n; ++i)
    if (!positions.row(i).allFinite())
      throw Error(message(name, ": vertex ", i, ": position must be finite, got ",
                          massspring::detail::format_row(positions.row(i))));
  auto check_index = [&](const char* what, std::size_t item, long long v) {
    if (v < 0 || v >= n)
      throw Error(
          message(name, ": ", what, ' ', item, ": vertex index ", v, " out of range [0, ", n, ")"));
  };
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (faces[f].size() < 3)
      throw Error(message(name, ": face ", f, " has ", faces[f].size(),
                          " vertices: a polygon needs 3 or more (2-vertex springs go in edges)"));
    for (std::size_t a = 0; a < faces[f].size(); ++a) {
      check_index("face", f, faces[f][a]);
      for (std::size_t b = 0; b < a; ++b)
        if (faces[f][a] == faces[f][b])
          throw Error(message(name, ": face ", f, ": vertex ", faces[f][a], " appears twice"));
    }
  }
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    check_index("edge", std::size_t(e), edges(e, 0));
    check_index("edge", std::size_t(e), edges(e, 1));
    if (edges(e, 0) == edges(e, 1))
      throw Error(message(name, ": edge ", e, " joins vertex ", edges(e, 0), " to itself"));
  }

  std::string out;
  out.reserve(std::size_t(n) * 40 + faces.size() * 24 + std::size_t(edges.rows()) * 16 + 64);
  out += message("# massspring: ", n, " vertices, ", faces.size(), " polygons, ", edges.rows(),
                 " 2-vertex springs\n");
  for (Eigen::Index i = 0; i < n; ++i) {
    out += 'v';
    for (int c = 0; c < 3; ++c) {
      out += ' ';
      detail::append_number(out, positions(i, c));
    }
    out += '\n';
  }
  for (const auto& face : faces) {
    out += 'f';
    for (int v : face) {
      out += ' ';
      detail::append_index(out, v + 1);
    }
    out += '\n';
  }
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    out += "f ";
    detail::append_index(out, edges(e, 0) + 1);
    out += ' ';
    detail::append_index(out, edges(e, 1) + 1);
    out += '\n';
  }
  detail::write_text_file_atomically(path, out);
}

/// @brief Writes an ObjMesh; see write_obj(path, positions, faces, edges).
template <class Scalar>
void write_obj(const std::filesystem::path& path, const ObjMesh<Scalar>& mesh) {
  write_obj(path, mesh.vertices, mesh.faces, mesh.edges);
}

}  // namespace massspring::io
