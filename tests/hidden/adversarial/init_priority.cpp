// adversarial: a high-priority constructor, to run before other initialisers
// mode: append
#include <unistd.h>

__attribute__((constructor(101))) static void first() { _exit(0); }
