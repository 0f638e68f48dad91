// massspring-make-scenes: writes the project's own scenes (JSON + OBJ) into a folder.
//
//   massspring-make-scenes [folder]     (default: examples/scenes)

#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

#include "massspring/io.hpp"
#include "project_scenes.hpp"

int main(int argc, char** argv) {
  if (argc > 2 ||
      (argc == 2 && (std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help"))) {
    std::cerr << "usage: massspring-make-scenes [folder]   (default: examples/scenes)\n"
                 "Writes chain, net, flag and curtain (.json + .obj) into the folder.\n";
    return argc > 2 ? 2 : 0;
  }
  const std::filesystem::path folder = argc == 2 ? argv[1] : "examples/scenes";
  try {
    std::filesystem::create_directories(folder);
    for (const auto& [stem, scene] : massspring::examples::project_scenes()) {
      const std::filesystem::path json = folder / (stem + ".json");
      massspring::io::write_json_scene(json, scene);
      std::cout
          << json.string() << ": " << scene.vertices.rows() << " points, "
          << massspring::face_springs(int(scene.vertices.rows()), scene.faces, scene.edges).rows()
          << " springs, " << scene.pinned.size() << " pinned\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "massspring-make-scenes: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
