// adversarial: write a gigabyte to standard output
// mode: append
// quick
#include <cstdio>
#include <string>

namespace {
const int flooded = [] {
  const std::string line(1 << 20, 'x');
  for (int i = 0; i < 1024; ++i) std::fwrite(line.data(), 1, line.size(), stdout);
  return 0;
}();
}  // namespace
