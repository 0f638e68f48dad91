#pragma once
/// @file
/// @brief Whole-file text reading and atomic writing for the scene readers and writers.

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"

namespace massspring::io::detail {

using massspring::detail::message;

/// @brief The bytes of a file.
/// @param[in] path  file to read
/// @param[in] what  what the file is, for messages ("OBJ file", "JSON scene")
/// @throws Error naming the path when it is missing, a directory or unreadable.
inline std::string read_text_file(const std::filesystem::path& path, const char* what) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status))
    throw Error(message(path.string(), ": cannot read ", what, ": no such file"));
  if (std::filesystem::is_directory(status))
    throw Error(message(path.string(), ": cannot read ", what, ": it is a directory"));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(message(path.string(), ": cannot read ", what, ": ", std::strerror(errno)));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(message(path.string(), ": cannot read ", what, ": read failed"));
  return text;
}

/// @brief Writes `text` to `path` atomically: first to `<path>.tmp`, then renamed over `path`, so
/// a reader never sees a half-written file.
/// @throws Error naming the path when the file cannot be written (the incomplete temporary file is
/// removed) or renamed: then the temporary file, which holds the whole text, is kept and the
/// message says where (nothing written is lost).
inline void write_text_file_atomically(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw Error(
          message(path.string(), ": cannot write ", tmp.string(), ": ", std::strerror(errno)));
    out.write(text.data(), std::streamsize(text.size()));
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw Error(message(path.string(), ": cannot write ", tmp.string(), ": write failed"));
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec)
    throw Error(message(path.string(), ": cannot rename ", tmp.string(), " to it (", ec.message(),
                        "); the text is kept, whole, in ", tmp.string()));
}

}  // namespace massspring::io::detail
