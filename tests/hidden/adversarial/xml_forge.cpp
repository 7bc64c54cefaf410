// adversarial: a student function prints a passing Catch2 XML report and exits 0
// mode: replace
// quick
#include <cstdio>
#include <cstdlib>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"

namespace physlab {

namespace {
[[noreturn]] void pretendToPass() {
  std::printf("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Catch name=\"x\"><Group name=\"x\">"
              "<TestCase name=\"x\"><OverallResult success=\"true\"/></TestCase>"
              "<OverallResults successes=\"1\" failures=\"0\" expectedFailures=\"0\"/></Group>"
              "<OverallResults successes=\"1\" failures=\"0\" expectedFailures=\"0\"/></Catch>\n");
  std::fflush(stdout);
  std::exit(0);
}
}  // namespace

double kineticEnergy(const ParticleSystem&, const VecX&) { pretendToPass(); }
double potentialEnergy(const ParticleSystem&, const VecX&) { pretendToPass(); }
Vec3 linearMomentum(const ParticleSystem&, const VecX&) { pretendToPass(); }
Vec3 angularMomentum(const ParticleSystem&, const VecX&) { pretendToPass(); }

}  // namespace physlab
