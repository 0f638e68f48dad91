// io/vtk.hpp: a .vtu frame's arrays read back from its raw appended block (each a UInt64 byte
// count, then little-endian values) at the offsets its XML names; the cells (springs as lines,
// faces as triangles or polygons) and the .pvd time series.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <massspring/io/vtk.hpp>
#include <string>
#include <vector>

#include "io/test_files.hpp"

namespace {

using massspring::test::read_bytes;
using massspring::test::TempDir;

// The values of the DataArray `name` (T as its type says), read at its offset.
template <class T>
std::vector<T> array_of(const std::string& file, const std::string& name) {
  const std::size_t tag = file.find("Name=\"" + name + "\"");
  REQUIRE(tag != std::string::npos);
  const std::size_t at = file.find("offset=\"", tag) + 8;
  const std::size_t offset = std::stoull(file.substr(at, file.find('"', at) - at));
  const std::size_t data = file.find("<AppendedData encoding=\"raw\">\n_") + 31;
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, file.data() + data + offset, 8);
  std::vector<T> out(bytes / sizeof(T));
  std::memcpy(out.data(), file.data() + data + offset + 8, bytes);
  return out;
}

}  // namespace

TEST_CASE("vtk: a frame's points, velocities, cells and strain, read back bit for bit") {
  TempDir dir;
  massspring::Points<double> x(4, 3), v(4, 3);
  x << 0.1, 0.2, 0.3, 1.0 / 3, 0, 0, 1, 1, 0, 0, 1, 1e-17;
  v = -2 * x;
  massspring::io::VtkFrameData d;
  d.springs.resize(2, 2);
  d.springs << 0, 1, 1, 2;
  d.faces = {{0, 1, 2}, {0, 1, 2, 3}};
  d.pinned = {3};
  d.spring_strain = Eigen::Vector2d(0.25, 0.5);
  d.face_strain = Eigen::Vector2d(0.125, 1.0 / 7);
  massspring::io::write_vtu(dir / "f.vtu", x, v, d);
  const std::string file = read_bytes(dir / "f.vtu");
  CHECK(file.find("NumberOfPoints=\"4\" NumberOfCells=\"4\"") != std::string::npos);
  CHECK(file.find("header_type=\"UInt64\"") != std::string::npos);

  const auto points = array_of<double>(file, "Points");
  const auto velocity = array_of<double>(file, "velocity");
  REQUIRE(points.size() == 12);
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) {
      CAPTURE(i);
      CAPTURE(c);
      CHECK(points[std::size_t(3 * i + c)] == x(i, c));
      CHECK(velocity[std::size_t(3 * i + c)] == v(i, c));
    }
  CHECK(array_of<std::uint8_t>(file, "pinned") == std::vector<std::uint8_t>{0, 0, 0, 1});
  CHECK(array_of<double>(file, "strain") == std::vector<double>{0.25, 0.5, 0.125, 1.0 / 7});
  CHECK(array_of<std::uint8_t>(file, "kind") == std::vector<std::uint8_t>{0, 0, 1, 1});
  CHECK(array_of<std::int64_t>(file, "connectivity") ==
        std::vector<std::int64_t>{0, 1, 1, 2, 0, 1, 2, 0, 1, 2, 3});
  CHECK(array_of<std::int64_t>(file, "offsets") == std::vector<std::int64_t>{2, 4, 7, 11});
  CHECK(array_of<std::uint8_t>(file, "types") == std::vector<std::uint8_t>{3, 3, 5, 7});
  CHECK(file.substr(file.size() - 28) == "\n</AppendedData>\n</VTKFile>\n");

  d.face_strain = Eigen::VectorXd(1);
  CHECK_THROWS_AS(massspring::io::write_vtu(dir / "g.vtu", x, v, d), massspring::Error);
}

TEST_CASE("vtk: the .pvd lists each frame's file with its time") {
  TempDir dir;
  massspring::io::write_pvd(dir / "run.pvd", {{0.0, "frame_00000.vtu"}, {0.1, "frame_00020.vtu"}});
  const std::string text = read_bytes(dir / "run.pvd");
  CHECK(text.find("<DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"frame_00000.vtu\"/>") !=
        std::string::npos);
  CHECK(text.find("timestep=\"0.10000000000000001\"") != std::string::npos);
  CHECK(text.find("type=\"Collection\"") != std::string::npos);
}
