// adversarial: code before main at every priority (.preinit_array, constructors 101 and 65535, init_priority, a static object) and after it (a destructor, atexit), each forging a reply and ending the worker with status 0
// mode: append
// file: labs/06_resting_contact/lcp.cpp
#include <cstdlib>
#include <cstring>
#include <unistd.h>

namespace {
void forgeAndLeave() {
  const char reply[] = "\x05\x00\x00\x00\x00\x01\x02\x03\x04";
  for (int fd = 0; fd < 64; ++fd) {
    if (write(fd, reply, sizeof reply - 1) < 0) continue;
  }
  _exit(0);
}
void early() { forgeAndLeave(); }
__attribute__((section(".preinit_array"), used)) void (*const preinit)() = early;
__attribute__((constructor(101))) void first() { forgeAndLeave(); }
__attribute__((constructor(65535))) void last() { forgeAndLeave(); }
struct Static {
  Static() { std::atexit(forgeAndLeave); }
  ~Static() { forgeAndLeave(); }
};
__attribute__((init_priority(101))) Static early_object;
Static plain_object;
}  // namespace
