#pragma once
/// @file
/// @brief write_vtu() and write_pvd(): frames for ParaView (and any VTK reader) as XML
/// UnstructuredGrid files, and the .pvd collection that makes them a time series.
///
/// A .vtu frame holds
/// - the points [m] (Float64: a double position is written exactly),
/// - point data "velocity" [m/s] (Float64, 3 components) and "pinned" (UInt8, 1 for a pinned
///   point),
/// - cells: every spring as a VTK_LINE (type 3), then every face as a VTK_TRIANGLE (5) or
///   VTK_POLYGON (7),
/// - cell data "strain" (Float64): |l / l0 - 1| for a spring, the mean over its boundary springs
///   for a face (diagnostics/strain.hpp), and "kind" (UInt8: 0 spring, 1 face).
/// The arrays are stored raw (binary, little-endian) in the file's AppendedData block, each
/// preceded by its size in bytes as a UInt64 (header_type="UInt64").

#include <Eigen/Core>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring::io {

/// @brief What one .vtu frame shows besides its positions; all arrays indexed as the system's.
struct VtkFrameData {
  Edges springs = Edges(0, 2);          ///< #springs by 2 point indices
  std::vector<std::vector<int>> faces;  ///< polygons (3 or more point indices each)
  std::vector<int> pinned;              ///< pinned point indices
  Eigen::VectorXd spring_strain;        ///< #springs
  Eigen::VectorXd face_strain;          ///< #faces
};

namespace detail {

/// @brief Little-endian bytes of a value (the file's byte_order).
template <class T>
void append_le(std::string& out, T value) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  const std::uint16_t probe = 1;
  unsigned char first = 0;
  std::memcpy(&first, &probe, 1);
  if (first != 1)  // big-endian host
    for (std::size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(b[k], b[sizeof(T) - 1 - k]);
  out.append(reinterpret_cast<const char*>(b), sizeof(T));
}

/// @brief Collects the appended arrays and the XML that refers to them.
class VtuBlocks {
 public:
  /// @brief Starts an array; its values follow with value().
  template <class T>
  std::string begin(const char* type, const char* name, int components, std::size_t count) {
    const std::uint64_t bytes = std::uint64_t(count) * sizeof(T);
    std::string xml = std::string("<DataArray type=\"") + type + "\" Name=\"" + name + "\"";
    if (components > 1) xml += " NumberOfComponents=\"" + std::to_string(components) + "\"";
    xml += " format=\"appended\" offset=\"" + std::to_string(data_.size()) + "\"/>\n";
    append_le<std::uint64_t>(data_, bytes);
    return xml;
  }
  template <class T>
  void value(T v) {
    append_le<T>(data_, v);
  }
  [[nodiscard]] const std::string& data() const { return data_; }

 private:
  std::string data_;
};

}  // namespace detail

/// @brief Writes one frame as a VTK XML UnstructuredGrid (.vtu); see the file comment.
/// @param path        file to write (replaced if it exists)
/// @param positions   #points by 3 [m]
/// @param velocities  #points by 3 [m/s]
/// @param data        springs, faces, pinned points and strains
/// @throws Error naming the path when it cannot be written or the sizes disagree.
template <class DerivedX, class DerivedV>
void write_vtu(const std::filesystem::path& path, const Eigen::MatrixBase<DerivedX>& positions,
               const Eigen::MatrixBase<DerivedV>& velocities, const VtkFrameData& data) {
  using massspring::detail::message;
  const Eigen::Index n = positions.rows(), m = data.springs.rows();
  const auto faces = Eigen::Index(data.faces.size());
  if (velocities.rows() != n || data.spring_strain.size() != m || data.face_strain.size() != faces)
    throw Error(message(path.string(), ": VTK frame: sizes disagree (", n, " points, ",
                        velocities.rows(), " velocities, ", m, " springs, ",
                        data.spring_strain.size(), " spring strains, ", faces, " faces, ",
                        data.face_strain.size(), " face strains)"));
  std::size_t corners = 0;
  for (const auto& f : data.faces) corners += f.size();
  const std::size_t cells = std::size_t(m + faces);

  detail::VtuBlocks b;
  std::string xml;
  xml += "<?xml version=\"1.0\"?>\n";
  xml +=
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n<UnstructuredGrid>\n";
  xml += "<Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfCells=\"" +
         std::to_string(cells) + "\">\n";
  xml += "<PointData Vectors=\"velocity\" Scalars=\"pinned\">\n";
  xml += b.begin<double>("Float64", "velocity", 3, std::size_t(n) * 3);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) b.value<double>(double(velocities(i, c)));
  std::vector<std::uint8_t> pinned(std::size_t(n), 0);
  for (int i : data.pinned)
    if (i >= 0 && i < n) pinned[std::size_t(i)] = 1;
  xml += b.begin<std::uint8_t>("UInt8", "pinned", 1, std::size_t(n));
  for (std::uint8_t p : pinned) b.value<std::uint8_t>(p);
  xml += "</PointData>\n<CellData Scalars=\"strain\">\n";
  xml += b.begin<double>("Float64", "strain", 1, cells);
  for (Eigen::Index e = 0; e < m; ++e) b.value<double>(data.spring_strain(e));
  for (Eigen::Index f = 0; f < faces; ++f) b.value<double>(data.face_strain(f));
  xml += b.begin<std::uint8_t>("UInt8", "kind", 1, cells);
  for (Eigen::Index e = 0; e < m; ++e) b.value<std::uint8_t>(0);
  for (Eigen::Index f = 0; f < faces; ++f) b.value<std::uint8_t>(1);
  xml += "</CellData>\n<Points>\n";
  xml += b.begin<double>("Float64", "Points", 3, std::size_t(n) * 3);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) b.value<double>(double(positions(i, c)));
  xml += "</Points>\n<Cells>\n";
  xml += b.begin<std::int64_t>("Int64", "connectivity", 1, std::size_t(m) * 2 + corners);
  for (Eigen::Index e = 0; e < m; ++e)
    for (int c = 0; c < 2; ++c) b.value<std::int64_t>(data.springs(e, c));
  for (const auto& f : data.faces)
    for (int i : f) b.value<std::int64_t>(i);
  xml += b.begin<std::int64_t>("Int64", "offsets", 1, cells);
  std::int64_t offset = 0;
  for (Eigen::Index e = 0; e < m; ++e) b.value<std::int64_t>(offset += 2);
  for (const auto& f : data.faces) b.value<std::int64_t>(offset += std::int64_t(f.size()));
  xml += b.begin<std::uint8_t>("UInt8", "types", 1, cells);
  for (Eigen::Index e = 0; e < m; ++e) b.value<std::uint8_t>(3);
  for (const auto& f : data.faces) b.value<std::uint8_t>(f.size() == 3 ? 5 : 7);
  xml += "</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_";

  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw Error(path.string() + ": cannot open for writing");
  out << xml;
  out.write(b.data().data(), std::streamsize(b.data().size()));
  out << "\n</AppendedData>\n</VTKFile>\n";
  out.close();
  if (!out) throw Error(path.string() + ": writing the VTK frame failed");
}

/// @brief Writes a ParaView collection (.pvd): the time series of `frames`, each (time [s], file
/// name relative to the .pvd's folder).
/// @throws Error naming the path when it cannot be written.
inline void write_pvd(const std::filesystem::path& path,
                      const std::vector<std::pair<double, std::string>>& frames) {
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw Error(path.string() + ": cannot open for writing");
  out.precision(17);
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "<Collection>\n";
  for (const auto& [time, file] : frames)
    out << "<DataSet timestep=\"" << time << "\" group=\"\" part=\"0\" file=\"" << file << "\"/>\n";
  out << "</Collection>\n</VTKFile>\n";
  out.close();
  if (!out) throw Error(path.string() + ": writing the collection failed");
}

}  // namespace massspring::io
