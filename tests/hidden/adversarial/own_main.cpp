// adversarial: the lab file defines its own main that reports success
// mode: append
// quick
#include <cstdio>

int main() {
  std::puts("All tests passed (1 assertion in 1 test case)");
  return 0;
}
