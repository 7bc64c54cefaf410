// adversarial: fork 300 processes that sleep for a minute
// mode: append
#include <unistd.h>

namespace {
const int forked = [] {
  for (int i = 0; i < 300; ++i) {
    if (fork() == 0) {
      sleep(60);
      _exit(0);
    }
  }
  return 0;
}();
}  // namespace
