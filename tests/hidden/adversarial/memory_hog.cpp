// adversarial: allocate and touch 4 GiB
// mode: append
#include <cstdlib>
#include <cstring>

namespace {
const int hogged = [] {
  for (int i = 0; i < 64; ++i) {
    void* block = std::malloc(64u << 20);
    if (block) std::memset(block, 1, 64u << 20);
  }
  return 0;
}();
}  // namespace
