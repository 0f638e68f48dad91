#pragma once
// massspring-simulate's exports for other programs: --html (a page that plays the run, see
// html_page.hpp), --pc2 (a Blender point cache and its rest mesh) and --vtk (ParaView frames and
// their time series). Checked before the first step with the same rules as every other output
// (outputs.hpp); written frame by frame with the frames the run writes (--every, and the last).
//
// - --html FILE: written at the end, through FILE.tmp.
// - --pc2 FILE.pc2: samples through FILE.pc2.tmp, renamed at the end; start frame = the first
//   frame written, sample rate = --every (the last sample is the run's last frame, which may be
//   closer); the rest mesh (the first frame's positions, the scene's faces and edges) is FILE.obj.
// - --vtk DIR: DIR/frame_NNNNN.vtu per frame (numbered by step, like --out) and DIR/run.pvd, the
//   time series [s]; a DIR holding files of an earlier run is refused, or (--overwrite) emptied of
//   them before the first step.

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <massspring/diagnostics/strain.hpp>
#include <massspring/error.hpp>
#include <massspring/io/obj.hpp>
#include <massspring/io/pc2.hpp>
#include <massspring/io/vtk.hpp>
#include <optional>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "simulate/config.hpp"
#include "simulate/html_page.hpp"
#include "simulate/outputs.hpp"

namespace simulate {

/// True when `name` is a file --vtk writes (or its temporary file).
inline bool is_vtk_file(const std::string& name) {
  static const std::regex pattern(R"((frame_\d{5,}\.vtu|run\.pvd)(\.tmp)?)");
  return std::regex_match(name, pattern);
}

/// The files of an earlier --vtk run in `folder` (sorted).
inline std::vector<fs::path> vtk_files(const fs::path& folder) {
  std::vector<fs::path> out;
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return out;
  for (const auto& entry : fs::directory_iterator(folder, ec))
    if (is_vtk_file(entry.path().filename().string())) out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

/// The rest mesh written beside a --pc2 file: FILE.pc2 -> FILE.obj.
inline fs::path rest_mesh_of(const fs::path& pc2) {
  fs::path obj = pc2;
  obj.replace_extension(".obj");
  return obj;
}

/// Checks --html, --pc2 (and its rest mesh) and --vtk before the run; throws Error naming the
/// option. `inputs`: every file the run reads.
inline void check_exports(const Config& c, const std::vector<fs::path>& inputs) {
  const std::vector<fs::path> files = {c.csv, c.save_state, c.html, c.pc2};
  auto others = [&](const std::string& self) {
    std::vector<fs::path> out;
    for (const fs::path& f : files)
      if (f.string() != self) out.push_back(f);
    return out;
  };
  if (!c.html.empty()) {
    check_output_file("--html", c.html, inputs, others(c.html), c.overwrite);
    check_three_js("--html " + c.html);
  }
  if (!c.pc2.empty()) {
    if (fs::path(c.pc2).extension() != ".pc2")
      throw Error("--pc2 " + c.pc2 +
                  ": expected a file name ending in .pc2 (its rest mesh is written beside it, "
                  "as .obj)");
    check_output_file("--pc2", c.pc2, inputs, others(c.pc2), c.overwrite);
    check_output_file("--pc2 " + c.pc2 + ": its rest mesh", rest_mesh_of(c.pc2), inputs, others(""),
                      c.overwrite);
  }
  if (!c.vtk.empty()) {
    const fs::path folder = c.vtk;
    const std::string option = "--vtk " + c.vtk;
    for (const fs::path& f : files)
      if (!f.empty() && same_path(f, folder))
        throw Error(option + ": is also the file of another output");
    if (!c.pc2.empty() && same_path(rest_mesh_of(c.pc2), folder))
      throw Error(option + ": is also the file of another output");
    if (!c.out.empty() && same_path(c.out, folder))
      throw Error(option + ": is also the --out folder; give each its own folder");
    std::error_code ec;
    const auto status = fs::status(folder, ec);
    if (fs::exists(status) && !fs::is_directory(status))
      throw Error(option + ": exists and is not a folder");
    check_output_parent("--vtk", folder, folder);
    if (!fs::exists(status)) return;
    const std::vector<fs::path> old = vtk_files(folder);
    if (!old.empty() && !c.overwrite)
      throw Error(option + ": holds " + std::to_string(old.size()) + " files of an earlier run (" +
                  old.front().filename().string() +
                  (old.size() > 1 ? " ... " + old.back().filename().string() : "") +
                  "); give --overwrite to delete them first, or choose an empty folder");
  }
}

/// The exports of one run: created once every check has passed, fed every written frame, closed
/// at the end (also after a divergence or an interruption: the frames written so far).
template <class System>
class Exports {
 public:
  Exports(const Config& c, const Setup<System>& s, double dt, long long first_frame)
      : c_(c), s_(s), dt_(dt) {
    if (!c.html.empty()) html_.emplace(s.name, s.system, s.faces, s.fosssim);
    if (!c.pc2.empty()) {
      pc2_.emplace(fs::path(c.pc2 + ".tmp"), s.system.num_points(), float(first_frame),
                   float(c.every));
      massspring::io::write_obj(rest_mesh_of(c.pc2), s.system.positions(), s.faces, s.edges);
    }
    if (!c.vtk.empty()) {
      const fs::path folder = c.vtk;
      if (c.overwrite)
        for (const fs::path& old : vtk_files(folder)) {
          std::error_code ec;
          fs::remove(old, ec);
          if (ec)
            throw Error("--vtk " + c.vtk + ": cannot delete " + old.string() + ": " + ec.message());
        }
      create_folders("--vtk", folder, folder);
      vtk_.springs = s.system.springs();
      vtk_.faces = s.faces;
      vtk_.pinned = s.system.pinned();
      boundary_ = massspring::face_boundary_springs(s.faces, s.system.springs());
    }
  }

  /// Adds the system's current state as frame `frame`.
  void write(long long frame) {
    const System& system = s_.system;
    const double time = double(frame) * dt_;
    if (html_) html_->add(frame, time, system);
    if (pc2_) pc2_->write(system.positions());
    if (!c_.vtk.empty()) {
      vtk_.spring_strain =
          massspring::spring_strain(system.positions(), system.springs(), system.rest_lengths());
      vtk_.face_strain = massspring::face_strain(boundary_, vtk_.spring_strain);
      char name[40];
      std::snprintf(name, sizeof name, "frame_%05lld.vtu", frame);
      const fs::path file = fs::path(c_.vtk) / name;
      fs::path tmp = file;
      tmp += ".tmp";
      massspring::io::write_vtu(tmp, system.positions(), system.velocities(), vtk_);
      rename_into_place(tmp, file, "VTK frame");
      series_.emplace_back(time, name);
    }
  }

  /// Writes what is written at the end: the page, the point cache's count, the time series.
  /// Returns the message of each that failed (the others are written all the same).
  std::vector<std::string> close() {
    std::vector<std::string> failures;
    auto attempt = [&](auto&& write) {
      try {
        write();
      } catch (const std::exception& e) {
        failures.push_back(e.what());
      }
    };
    if (html_)
      attempt([&] {
        const fs::path file = c_.html, tmp = c_.html + ".tmp";
        html_->write(tmp);
        rename_into_place(tmp, file, "page");
      });
    if (pc2_)
      attempt([&] {
        pc2_->close();
        rename_into_place(c_.pc2 + ".tmp", c_.pc2, "point cache");
      });
    if (!c_.vtk.empty())
      attempt([&] {
        const fs::path file = fs::path(c_.vtk) / "run.pvd";
        fs::path tmp = file;
        tmp += ".tmp";
        massspring::io::write_pvd(tmp, series_);
        rename_into_place(tmp, file, "time series");
      });
    return failures;
  }

 private:
  const Config& c_;
  const Setup<System>& s_;
  double dt_ = 0;
  std::optional<HtmlPage> html_;
  std::optional<massspring::io::Pc2Writer> pc2_;
  massspring::io::VtkFrameData vtk_;
  std::vector<std::vector<int>> boundary_;
  std::vector<std::pair<double, std::string>> series_;
};

}  // namespace simulate
