// adversarial: reach into Catch2's run state from the lab file
// mode: append
#include <catch2/catch.hpp>

namespace {
const int reached = [] {
  Catch::getResultCapture();
  return 0;
}();
}  // namespace
