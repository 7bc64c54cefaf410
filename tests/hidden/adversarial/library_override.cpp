// adversarial: replace library functions the harness and the tests use (write, cos)
// mode: append
// quick
#include <unistd.h>

extern "C" __attribute__((weak)) ssize_t write(int, const void*, size_t n) { return static_cast<ssize_t>(n); }
extern "C" double cos(double) { return 1.0; }
