// adversarial: a signal handler that ends a crashing test with status 0, and a thread racing the harness
// mode: append
#include <csignal>
#include <cstdlib>
#include <thread>

namespace {
void pass(int) { std::_Exit(0); }
int arm() {
  std::signal(SIGSEGV, pass);
  std::signal(SIGABRT, pass);
  std::thread([] {}).detach();
  return 0;
}
const int armed = arm();
}  // namespace
