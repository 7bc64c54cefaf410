// adversarial: code before main prints a pass and leaves with exit code 0
// mode: append
// quick
#include <cstdio>
#include <unistd.h>

namespace {
const int forged = [] {
  std::printf("<Catch><OverallResult success=\"true\"/></Catch>\nAll tests passed\n");
  std::fflush(stdout);
  _exit(0);
  return 0;
}();
}  // namespace
