// massspring-make-scenes: writes the project's own scenes: JSON + OBJ into one folder, FOSSSim
// XML into another.
//
//   massspring-make-scenes [folder [xml_folder]]   (default: examples/scenes examples/scenes_xml)

#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

#include "fosssim_scenes.hpp"
#include "massspring/io.hpp"
#include "project_scenes.hpp"

int main(int argc, char** argv) {
  if (argc > 3 ||
      (argc == 2 && (std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help"))) {
    std::cerr
        << "usage: massspring-make-scenes [folder [xml_folder]]\n"
           "  (default: examples/scenes examples/scenes_xml)\n"
           "Writes chain, net, flag, curtain, drape, table, tilted, pole, mesh, clothesline,\n"
           "ribbon_pile and two_cloths (.json + .obj) into folder and orbit,\n"
           "cantilever, shrinking_chain and damping_series (.xml) into xml_folder.\n";
    return argc > 3 ? 2 : 0;
  }
  const std::filesystem::path folder = argc >= 2 ? argv[1] : "examples/scenes";
  const std::filesystem::path xml_folder = argc == 3 ? argv[2] : "examples/scenes_xml";
  try {
    std::filesystem::create_directories(folder);
    for (const auto& [stem, scene] : massspring::examples::project_scenes()) {
      const std::filesystem::path json = folder / (stem + ".json");
      massspring::io::write_json_scene(json, scene);
      std::cout
          << json.string() << ": " << scene.vertices.rows() << " points, "
          << massspring::face_springs(int(scene.vertices.rows()), scene.faces, scene.edges).rows()
          << " springs, " << scene.pinned.size() << " pinned, " << scene.colliders.size()
          << " colliders\n";
    }
    std::filesystem::create_directories(xml_folder);
    for (const auto& [stem, scene] : massspring::examples::project_fosssim_scenes()) {
      const std::filesystem::path xml = xml_folder / (stem + ".xml");
      massspring::io::write_fosssim_scene(xml, scene);
      std::cout << xml.string() << ": " << scene.num_particles() << " particles, "
                << scene.springs.size() << " springs, " << scene.fixed.size() << " fixed, "
                << scene.steps() << " steps of " << scene.dt << " s\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "massspring-make-scenes: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
