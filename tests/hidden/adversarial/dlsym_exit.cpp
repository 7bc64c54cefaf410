// adversarial: look up _exit at run time with dlsym and call it with status 0
// mode: append
#include <dlfcn.h>

namespace {
int leave() {
  auto end = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "_exit"));
  if (end != nullptr) end(0);
  return 0;
}
const int ended = leave();
}  // namespace
