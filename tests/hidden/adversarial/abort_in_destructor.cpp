// adversarial: abort in a static destructor, after the tests
// mode: append
#include <cstdlib>

namespace {
struct Bomb {
  ~Bomb() { std::abort(); }
} bomb;
}  // namespace
