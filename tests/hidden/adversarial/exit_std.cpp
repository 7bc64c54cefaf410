// adversarial: std::exit(0) and std::quick_exit(0) from the code under test instead of _exit
// mode: append
#include <cstdlib>

namespace {
int leave() {
  std::quick_exit(0);
}
const int ended = (std::atexit([] {}), std::exit(0), leave());
}  // namespace
