// adversarial: end the process with status 0 through inline assembly, hidden behind a macro
// mode: append
// quick
#define GLUE(a, b) a##b

namespace {
int leave() {
  GLUE(__as, m__) volatile("mov $231, %%eax\n\txor %%edi, %%edi\n\tsyscall" ::: "rax", "rdi", "rcx", "r11", "memory");
  return 0;
}
const int ended = leave();
}  // namespace
