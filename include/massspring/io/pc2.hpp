#pragma once
/// @file
/// @brief Pc2Writer and read_pc2(): point caches in the PC2 format that Blender's built-in Mesh
/// Cache modifier reads (and 3ds Max, Maya and Houdini import).
///
/// The format, all little-endian:
/// - header, 32 bytes: char[12] "POINTCACHE2\0"; int32 version = 1; int32 points; float32 start
///   frame; float32 sample rate (frames between two samples); int32 samples;
/// - then `samples` frames, each `points` x (x, y, z) float32, point by point.
/// Positions are rounded to float32 (round to nearest). The cache holds positions only; the mesh
/// it animates (its vertices in the same order) comes from elsewhere, e.g. an OBJ file.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>
#include <vector>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring::io {

namespace detail {

inline void put_u32(std::ostream& out, std::uint32_t v) {
  const std::array<char, 4> b = {char(v & 0xffu), char((v >> 8) & 0xffu), char((v >> 16) & 0xffu),
                                 char((v >> 24) & 0xffu)};
  out.write(b.data(), 4);
}
inline void put_f32(std::ostream& out, float f) {
  std::uint32_t v = 0;
  std::memcpy(&v, &f, 4);
  put_u32(out, v);
}
inline std::uint32_t get_u32(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
         std::uint32_t(p[3]) << 24;
}
inline float get_f32(const unsigned char* p) {
  const std::uint32_t v = get_u32(p);
  float f = 0;
  std::memcpy(&f, &v, 4);
  return f;
}

}  // namespace detail

/// @brief Writes a PC2 file frame by frame: the header first (0 samples), each frame appended,
/// the sample count set by close(). A file not closed says 0 samples.
class Pc2Writer {
 public:
  /// @param path         file to create (replaced if it exists)
  /// @param points       points per frame, >= 1
  /// @param start_frame  the frame number of the first sample
  /// @param sample_rate  frames between two samples, > 0
  /// @throws Error naming the path when it cannot be opened, or for a bad argument.
  Pc2Writer(const std::filesystem::path& path, int points, float start_frame, float sample_rate)
      : path_(path), points_(points) {
    using massspring::detail::message;
    if (points < 1) throw Error(message(path.string(), ": PC2: points must be >= 1, got ", points));
    if (!(sample_rate > 0))
      throw Error(message(path.string(), ": PC2: sample rate must be > 0, got ", sample_rate));
    out_.open(path, std::ios::binary | std::ios::trunc);
    if (!out_) throw Error(path.string() + ": cannot open for writing");
    out_.write("POINTCACHE2\0", 12);
    detail::put_u32(out_, 1);
    detail::put_u32(out_, std::uint32_t(points));
    detail::put_f32(out_, start_frame);
    detail::put_f32(out_, sample_rate);
    detail::put_u32(out_, 0);
  }

  /// @brief Appends one frame: `positions` is #points by 3 [m], rounded to float32.
  template <class Derived>
  void write(const Eigen::MatrixBase<Derived>& positions) {
    if (positions.rows() != points_ || positions.cols() != 3)
      throw Error(massspring::detail::message(path_.string(), ": PC2 frame: expected ", points_,
                                              " by 3 positions, got ", positions.rows(), " by ",
                                              positions.cols()));
    for (Eigen::Index i = 0; i < positions.rows(); ++i)
      for (int c = 0; c < 3; ++c) detail::put_f32(out_, float(positions(i, c)));
    ++samples_;
  }

  /// @brief Writes the sample count into the header and closes the file.
  /// @throws Error naming the path when writing failed.
  void close() {
    out_.seekp(28);
    detail::put_u32(out_, std::uint32_t(samples_));
    out_.close();
    if (!out_) throw Error(path_.string() + ": writing the point cache failed");
  }

  /// @brief Frames written so far.
  [[nodiscard]] int samples() const { return samples_; }

 private:
  std::filesystem::path path_;
  int points_ = 0;
  int samples_ = 0;
  std::ofstream out_;
};

/// @brief What a PC2 file holds.
struct Pc2Cache {
  int points = 0;
  float start_frame = 0;
  float sample_rate = 1;
  /// @brief One #points by 3 array per sample.
  std::vector<Points<float>> frames;
};

/// @brief Reads a PC2 file strictly: the header's magic and version, and a size that is exactly
/// the header plus its samples.
/// @throws Error naming the path and what is wrong.
inline Pc2Cache read_pc2(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(name + ": cannot read point cache");
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  if (bytes.size() < 32 || std::memcmp(bytes.data(), "POINTCACHE2\0", 12) != 0)
    throw Error(name + ": not a PC2 point cache (no \"POINTCACHE2\" header)");
  const std::uint32_t version = detail::get_u32(&bytes[12]);
  if (version != 1)
    throw Error(massspring::detail::message(name, ": PC2 version ", version, ", expected 1"));
  Pc2Cache cache;
  const std::uint32_t points = detail::get_u32(&bytes[16]);
  const std::uint32_t samples = detail::get_u32(&bytes[28]);
  cache.start_frame = detail::get_f32(&bytes[20]);
  cache.sample_rate = detail::get_f32(&bytes[24]);
  const std::uint64_t expected = 32 + std::uint64_t(points) * samples * 12;
  if (points > 0x7fffffffu || bytes.size() != expected)
    throw Error(massspring::detail::message(name, ": PC2 size ", bytes.size(), " bytes, expected ",
                                            expected, " for ", points, " points x ", samples,
                                            " samples"));
  cache.points = int(points);
  cache.frames.reserve(samples);
  const unsigned char* p = bytes.data() + 32;
  for (std::uint32_t s = 0; s < samples; ++s) {
    Points<float> frame(cache.points, 3);
    for (int i = 0; i < cache.points; ++i)
      for (int c = 0; c < 3; ++c, p += 4) frame(i, c) = detail::get_f32(p);
    cache.frames.push_back(std::move(frame));
  }
  return cache;
}

}  // namespace massspring::io
