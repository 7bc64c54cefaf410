// adversarial: a GNU indirect function on a stub name, whose resolver runs while the worker is loaded (before any constructor): it forges replies on every descriptor, then ends the process with status 0 by a raw system call hidden from the source scan
// mode: replace
// file: labs/06_resting_contact/soft_step.cpp
// quick
#line 1 "/usr/include/x86_64-linux-gnu/bits/confname.h"
#include "physlab/soft_step.hpp"

#include <cstdint>

namespace physlab {
namespace {
// A reply that says "returned" with the worker's idea of a passing value, on every descriptor.
void forge() {
  const unsigned char reply[] = {9, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (long fd = 0; fd < 64; ++fd) {
    long ret;
    asm volatile("syscall" : "=a"(ret) : "0"(1L), "D"(fd), "S"(reply), "d"(sizeof reply) : "rcx", "r11", "memory");
  }
  asm volatile("syscall" : : "a"(231L), "D"(0L) : "rcx", "r11", "memory");
}
using Coefficients = SoftCoefficients (*)(double, double, double);
extern "C" Coefficients resolveCoefficients() {
  forge();
  return nullptr;
}
}  // namespace

SoftCoefficients softCoefficients(double hertz, double zeta, double h) __attribute__((ifunc("resolveCoefficients")));

double softNormalImpulse(double lambda, double, double, double, const SoftCoefficients&, double, double, bool) {
  forge();
  return lambda;
}

}  // namespace physlab
