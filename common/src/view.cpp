// The main of the per-lab view programs (physlab/view.hpp).
#include "physlab/view.hpp"

#include <exception>
#include <iostream>
#include <string_view>

#include "physlab/error.hpp"

namespace physlab {
namespace {

void listScenes(std::ostream& out, const std::vector<ViewScene>& scenes) {
  for (const ViewScene& scene : scenes) out << "  " << scene.name << "  " << scene.what << "\n";
}

}  // namespace

int runView(int argc, char** argv, const std::vector<ViewScene>& scenes) {
  std::string name = scenes.empty() ? "" : scenes.front().name, out;
  for (int k = 1; k < argc; ++k) {
    const std::string_view arg = argv[k];
    if (arg == "--list") {
      listScenes(std::cout, scenes);
      return 0;
    }
    if ((arg == "--scene" || arg == "--out") && k + 1 < argc) {
      (arg == "--scene" ? name : out) = argv[++k];
    } else {
      std::cerr << "usage: " << argv[0] << " [--scene NAME] [--out FILE] [--list]\n";
      return 2;
    }
  }
  const ViewScene* scene = nullptr;
  for (const ViewScene& s : scenes) {
    if (s.name == name) scene = &s;
  }
  if (scene == nullptr) {
    std::cerr << "no scene '" << name << "'; the scenes of this lab:\n";
    listScenes(std::cerr, scenes);
    return 2;
  }
  if (out.empty()) out = scene->name + ".replay";
  try {
    writeReplay(scene->record(), out);
  } catch (const NotImplemented& e) {
    std::cerr << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "scene " << scene->name << ": " << e.what() << "\n";
    return 1;
  }
  std::cout << out << "\n";
  return 0;
}

}  // namespace physlab
