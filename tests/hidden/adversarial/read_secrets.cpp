// adversarial: print the hidden tests and the reference solutions into the test output
// mode: append
// quick
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace {
const int leaked = [] {
  namespace fs = std::filesystem;
  for (const char* folder : {"{ROOT}/tests/hidden", "{ROOT}/solutions"}) {
    std::error_code ec;
    for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
      std::ifstream file(it->path());
      std::stringstream text;
      text << file.rdbuf();
      std::cout << text.str() << std::endl;
      std::cerr << text.str() << std::endl;
    }
  }
  return 0;
}();
}  // namespace
