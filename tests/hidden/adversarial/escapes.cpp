// adversarial: invalid UTF-8 and terminal escape sequences in the output of a failing test
// mode: append
// quick
#include <cstdio>

namespace {
const int escaped = [] {
  std::printf("\x1b[2J\x1b[31mall passed\x1b[0m \xff\xfe\xc3\x28 \x07\x08\n");
  return 0;
}();
}  // namespace
