// io/pc2.hpp: the PC2 layout byte by byte (little-endian header, float32 samples), the writer's
// round trip through read_pc2(), and what the reader refuses.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <massspring/io/pc2.hpp>
#include <string>

#include "io/test_files.hpp"

namespace {

using massspring::Error;
using massspring::io::Pc2Writer;
using massspring::io::read_pc2;
using massspring::test::read_bytes;
using massspring::test::TempDir;

std::uint32_t u32_at(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (int b = 3; b >= 0; --b) v = v << 8 | std::uint8_t(bytes[at + std::size_t(b)]);
  return v;
}
float f32_at(const std::string& bytes, std::size_t at) {
  const std::uint32_t v = u32_at(bytes, at);
  float f = 0;
  std::memcpy(&f, &v, 4);
  return f;
}

}  // namespace

TEST_CASE("pc2: header and samples, byte by byte, and the round trip") {
  TempDir dir;
  const auto file = dir / "run.pc2";
  massspring::Points<double> x(2, 3);
  x << 0.1, -2.5, 3.0, 1e-3, 0.0, 7.25;
  {
    Pc2Writer writer(file, 2, 10.0f, 4.0f);
    writer.write(x);
    writer.write(x * 2.0);
    writer.write(x * 3.0);
    CHECK(writer.samples() == 3);
    writer.close();
  }
  const std::string bytes = read_bytes(file);
  REQUIRE(bytes.size() == 32 + 3 * 2 * 12);
  CHECK(std::memcmp(bytes.data(), "POINTCACHE2\0", 12) == 0);
  CHECK(u32_at(bytes, 12) == 1);   // version
  CHECK(u32_at(bytes, 16) == 2);   // points
  CHECK(f32_at(bytes, 20) == 10);  // start frame
  CHECK(f32_at(bytes, 24) == 4);   // sample rate
  CHECK(u32_at(bytes, 28) == 3);   // samples
  for (int s = 0; s < 3; ++s)
    for (int i = 0; i < 2; ++i)
      for (int c = 0; c < 3; ++c) {
        CAPTURE(s);
        CAPTURE(i);
        CAPTURE(c);
        CHECK(f32_at(bytes, std::size_t(32 + 12 * (2 * s + i) + 4 * c)) ==
              float(x(i, c) * double(s + 1)));
      }
  const auto cache = read_pc2(file);
  CHECK(cache.points == 2);
  CHECK(cache.start_frame == 10);
  CHECK(cache.sample_rate == 4);
  REQUIRE(cache.frames.size() == 3);
  CHECK(cache.frames[2] == (x * 3.0).cast<float>());
}

TEST_CASE("pc2: the writer refuses a frame of another size, the reader a file not PC2 or cut") {
  TempDir dir;
  Pc2Writer writer(dir / "a.pc2", 3, 0.0f, 1.0f);
  CHECK_THROWS_AS(writer.write(massspring::Points<double>(2, 3)), Error);
  CHECK_THROWS_AS(Pc2Writer(dir / "b.pc2", 0, 0.0f, 1.0f), Error);
  CHECK_THROWS_AS(Pc2Writer(dir / "c.pc2", 1, 0.0f, 0.0f), Error);
  CHECK_THROWS_WITH_AS(read_pc2(dir.write("x.pc2", "POINTCACHE3")),
                       massspring::test::contains("not a PC2 point cache"), Error);
  {
    Pc2Writer one(dir / "d.pc2", 1, 0.0f, 1.0f);
    one.write(massspring::Points<double>::Zero(1, 3));
    one.close();
  }
  const std::string whole = read_bytes(dir / "d.pc2");
  CHECK_THROWS_WITH_AS(read_pc2(dir.write("cut.pc2", whole.substr(0, whole.size() - 1))),
                       massspring::test::contains("expected 44"), Error);
}
