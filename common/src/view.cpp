// The main of the per-lab view programs (physlab/view.hpp).
#include "physlab/view.hpp"

#include <charconv>
#include <cstddef>
#include <exception>
#include <iostream>
#include <string_view>
#include <system_error>

#include "physlab/error.hpp"

namespace physlab {
namespace {

void listScenes(std::ostream& out, const std::vector<ViewScene>& scenes) {
  for (const ViewScene& scene : scenes) out << "  " << scene.name << "  " << scene.what << "\n";
}

// A positive whole number of bytes into `bytes`; false for anything else.
bool parseBytes(std::string_view text, std::size_t& bytes) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), bytes);
  return error == std::errc() && end == text.data() + text.size() && bytes > 0;
}

}  // namespace

int runView(int argc, char** argv, const std::vector<ViewScene>& scenes) {
  std::string name = scenes.empty() ? "" : scenes.front().name, out;
  std::size_t max_bytes = 0;
  for (int k = 1; k < argc; ++k) {
    const std::string_view arg = argv[k];
    if (arg == "--list") {
      listScenes(std::cout, scenes);
      return 0;
    }
    if ((arg == "--scene" || arg == "--out") && k + 1 < argc) {
      (arg == "--scene" ? name : out) = argv[++k];
    } else if (arg == "--max-bytes" && k + 1 < argc) {
      if (!parseBytes(argv[++k], max_bytes)) {
        std::cerr << argv[0] << ": --max-bytes needs a positive whole number of bytes, got '" << argv[k] << "'\n";
        return 2;
      }
    } else {
      std::cerr << "usage: " << argv[0] << " [--scene NAME] [--out FILE] [--max-bytes N] [--list]\n";
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
    const Replay replay = scene->record();
    writeReplay(max_bytes > 0 ? thinReplay(replay, max_bytes) : replay, out);
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
