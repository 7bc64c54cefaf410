// adversarial: every test sleeps just under the time limit, to run past the platform's budget
// mode: append
// grade: --timeout 10 --deadline 40
// quick
#include <unistd.h>

namespace {
const int slept = [] {
  sleep(9);
  return 0;
}();
}  // namespace
