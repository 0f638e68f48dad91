#pragma once
// massspring-simulate's output files: checked before the first step, written so that nothing is
// lost. The rules (docs/errors.md, "massspring-simulate"):
// - every target is checked before anything is written: it is not a directory, not a file the
//   run reads (the scene, its OBJ), not another target; its folder is writable, or, when the
//   folder is missing, the nearest folder above it that exists is writable, and the missing
//   folders are created once every check has passed (the same for every output: --out, --csv,
//   --html, --pc2, --vtk, --save-state);
// - a file that exists is never replaced unless --overwrite; a `<file>.tmp` left by a killed run is
//   named and refused unless --overwrite;
// - an --out folder holding frame_NNNNN.obj files of an earlier run is refused, or (--overwrite)
//   emptied of them before the first step, so frames of two runs are never mixed;
// - files are written to `<file>.tmp` and renamed into place; when that rename fails, the .tmp is
//   kept and the message says where.

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <massspring/error.hpp>
#include <regex>
#include <string>
#include <system_error>
#include <vector>

namespace simulate {

namespace fs = std::filesystem;
using massspring::Error;

/// True when `name` is a frame file this tool writes (or its temporary file).
inline bool is_frame_file(const std::string& name) {
  static const std::regex pattern(R"(frame_\d{5,}\.obj(\.tmp)?)");
  return std::regex_match(name, pattern);
}

/// The same file or folder: equivalent when both exist, else the same normalised absolute path.
inline bool same_path(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    const bool same = fs::equivalent(a, b, ec);
    if (!ec) return same;
  }
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

/// The folder a file will be written in ("." for a bare name).
inline fs::path folder_of(const fs::path& file) {
  return file.parent_path().empty() ? fs::path(".") : file.parent_path();
}

/// Refuses a folder that does not exist, is not a folder or cannot be written into.
inline void check_writable_folder(const std::string& option, const fs::path& target,
                                  const fs::path& folder) {
  std::error_code ec;
  const auto status = fs::status(folder, ec);
  if (!fs::exists(status))
    throw Error(option + " " + target.string() + ": the folder " + folder.string() +
                " does not exist");
  if (!fs::is_directory(status))
    throw Error(option + " " + target.string() + ": " + folder.string() + " is not a folder");
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    throw Error(option + " " + target.string() + ": cannot write in the folder " + folder.string() +
                ": " + std::strerror(errno));
}

/// `folder` when it exists, else the nearest folder above it that exists (or whatever exists
/// there: a file stops the walk), "." above a relative path's first component.
inline fs::path nearest_existing(const fs::path& folder) {
  std::error_code ec;
  fs::path at = folder;
  while (!at.empty() && !fs::exists(fs::status(at, ec)) && at != at.root_path())
    at = at.parent_path();
  return at.empty() ? fs::path(".") : at;
}

/// Refuses a folder an output cannot be written in: the folder itself when it exists, else the
/// nearest existing folder above it (the missing ones are created after every check passed) must
/// be a folder and writable.
inline void check_output_parent(const std::string& option, const fs::path& target,
                                const fs::path& folder) {
  check_writable_folder(option, target, nearest_existing(folder));
}

/// Creates the missing folders of an output's folder (after every check passed).
inline void create_folders(const std::string& option, const fs::path& target,
                           const fs::path& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec)
    throw Error(option + " " + target.string() + ": cannot create the folder " + folder.string() +
                ": " + ec.message());
}

/// One output file (--csv, --save-state): checked, never written here.
/// @param inputs  every file the run reads
/// @param others  the other output files (must differ)
inline void check_output_file(const std::string& option, const fs::path& file,
                              const std::vector<fs::path>& inputs,
                              const std::vector<fs::path>& others, bool overwrite) {
  if (file.empty()) return;
  for (const fs::path& input : inputs)
    if (same_path(file, input))
      throw Error(option + " " + file.string() + ": is " + input.string() +
                  ", a file this run reads; choose another name");
  for (const fs::path& other : others)
    if (!other.empty() && same_path(file, other))
      throw Error(option + " " + file.string() + ": another output of this run is " +
                  other.string() + "; give each output its own file");
  std::error_code ec;
  const auto status = fs::status(file, ec);
  if (fs::is_directory(status))
    throw Error(option + " " + file.string() + ": is a directory; give a file name");
  if (fs::exists(status) && !overwrite)
    throw Error(option + " " + file.string() +
                ": exists; give --overwrite to replace it, or choose another name");
  fs::path tmp = file;
  tmp += ".tmp";
  if (fs::exists(fs::symlink_status(tmp, ec)) && !overwrite)
    throw Error(option + " " + file.string() + ": " + tmp.string() +
                " exists, left by an earlier run that did not finish (killed?); it may hold "
                "its output: move or delete it, or give --overwrite to replace it");
  check_output_parent(option, file, folder_of(file));
}

/// The frame files in `folder` (sorted), "" when it does not exist.
inline std::vector<fs::path> frame_files(const fs::path& folder) {
  std::vector<fs::path> out;
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return out;
  for (const auto& entry : fs::directory_iterator(folder, ec))
    if (is_frame_file(entry.path().filename().string())) out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

/// --out: a folder that does not exist (its nearest existing ancestor a writable folder), or a
/// folder without frame files, or (--overwrite) one whose frame files will be deleted; never one
/// that holds a file the run reads under a frame file's name.
inline void check_output_folder(const fs::path& folder, const std::vector<fs::path>& inputs,
                                const std::vector<fs::path>& files, bool overwrite) {
  if (folder.empty()) return;
  const std::string option = "--out";
  std::error_code ec;
  const auto status = fs::status(folder, ec);
  for (const fs::path& f : files)
    if (!f.empty() && same_path(f, folder))
      throw Error(option + " " + folder.string() + ": is also the file of another output");
  if (fs::exists(status) && !fs::is_directory(status))
    throw Error(option + " " + folder.string() + ": exists and is not a folder");
  check_output_parent(option, folder, folder);
  if (!fs::exists(status)) return;
  const std::vector<fs::path> frames = frame_files(folder);
  for (const fs::path& frame : frames)
    for (const fs::path& input : inputs)
      if (same_path(frame, input))
        throw Error(option + " " + folder.string() + ": " + input.string() +
                    " is read by this run and would be replaced by a frame; choose another "
                    "folder");
  if (!frames.empty() && !overwrite)
    throw Error(option + " " + folder.string() + ": holds " + std::to_string(frames.size()) +
                " frame files of an earlier run (" + frames.front().filename().string() +
                (frames.size() > 1 ? " ... " + frames.back().filename().string() : "") +
                "); give --overwrite to delete them first, or choose an empty folder");
}

/// Deletes the frame files an --overwrite run replaces (after every check passed).
inline void clear_frames(const fs::path& folder) {
  for (const fs::path& frame : frame_files(folder)) {
    std::error_code ec;
    fs::remove(frame, ec);
    if (ec)
      throw Error("--out " + folder.string() + ": cannot delete " + frame.string() + ": " +
                  ec.message());
  }
}

/// Renames `tmp` to `file`; on failure keeps `tmp` and says where the output is.
inline void rename_into_place(const fs::path& tmp, const fs::path& file, const char* what) {
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec)
    throw Error(file.string() + ": cannot rename " + tmp.string() + " to it (" + ec.message() +
                "); the " + what + " is kept, whole, in " + tmp.string());
}

/// Streams frame, point, x, y, z, vx, vy, vz rows into <path>.tmp; renamed into place by
/// close(). The .tmp is never deleted: a run that fails leaves its rows there, and says so.
class TrajectoryCsv {
 public:
  explicit TrajectoryCsv(const fs::path& path) : path_(path), tmp_(path.string() + ".tmp") {
    out_.open(tmp_, std::ios::trunc);
    if (!out_) throw Error(path.string() + ": cannot open " + tmp_.string() + " for writing");
    out_.precision(17);
    out_ << "frame,point,x,y,z,vx,vy,vz\n";
  }
  template <class System>
  void write(long long frame, const System& s) {
    for (int i = 0; i < s.num_points(); ++i) {
      out_ << frame << ',' << i;
      for (int c = 0; c < 3; ++c) out_ << ',' << double(s.positions()(i, c));
      for (int c = 0; c < 3; ++c) out_ << ',' << double(s.velocities()(i, c));
      out_ << '\n';
    }
  }
  void close() {
    out_.close();
    if (!out_)
      throw Error(path_.string() + ": writing " + tmp_.string() +
                  " failed; what was written is in " + tmp_.string());
    rename_into_place(tmp_, path_, "trajectory");
  }
  [[nodiscard]] const fs::path& tmp() const { return tmp_; }

 private:
  fs::path path_, tmp_;
  std::ofstream out_;
};

}  // namespace simulate
