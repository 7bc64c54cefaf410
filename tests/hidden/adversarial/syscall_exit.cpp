// adversarial: end the process with status 0 through a raw system call
// mode: append
#include <sys/syscall.h>
#include <unistd.h>

namespace {
const long ended = syscall(SYS_exit_group, 0);
}  // namespace
