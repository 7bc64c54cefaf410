// adversarial: the lab file adds its own TEST_CASE worth 1000 points
// mode: append
#include <catch2/catch.hpp>

TEST_CASE("free points", "[lab01][pts=1000]") { CHECK(1 == 1); }
