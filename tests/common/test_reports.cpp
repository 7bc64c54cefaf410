// Framework test: how a failed check reports its values. The runner (tests/support/runner.cpp)
// makes Catch2 print every double and float in the shortest form that reads back as the same
// value; this checks that its overloads are the ones Catch2 calls.
#include "support.hpp"

TEST_CASE("reports: doubles and floats print in their shortest exact form", "[common]") {
  using Catch::Detail::stringify;
  CHECK(stringify(1e-12) == "1e-12");
  CHECK(stringify(2.5) == "2.5");
  CHECK(stringify(0.1) == "0.1");
  CHECK(stringify(2.0) == "2.0");
  CHECK(stringify(-3e20) == "-3e+20");
  CHECK(stringify(0.1 + 0.2) == "0.30000000000000004");
  CHECK(stringify(1e-7f) == "1e-07f");
  CHECK(stringify(Approx(1e-12)) == "Approx( 1e-12 )");
}
