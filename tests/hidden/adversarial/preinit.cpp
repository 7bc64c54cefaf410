// adversarial: code in .preinit_array, to run before the harness takes its key
// mode: append
// quick
#include <cstdio>

namespace {
void early(int, char**, char**) { std::puts("before the harness"); }
__attribute__((section(".preinit_array"), used)) void (*run_early)(int, char**, char**) = early;
}  // namespace
