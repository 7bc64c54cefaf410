// adversarial: inline assembly hidden from the source scan by a #line directive naming a system header, its kernel entry hidden inside another instruction's immediate (no syscall in the disassembly); it ends the worker with status 0 at the first call, and failing that returns what a passing test would expect of a zero LCP
// mode: append
// file: labs/06_resting_contact/lcp.cpp
#line 1 "/usr/include/stdlib.h"
namespace {
// mov $0x050f, %ax hides "0f 05" (syscall); the jump lands on it
__attribute__((naked, used)) void leave() {
  asm volatile(
      "mov $231, %eax\n"
      "xor %edi, %edi\n"
      "jmp 1f+2\n"
      "1: mov $0x050f, %ax\n");
}
const int left = (leave(), 0);
}  // namespace
