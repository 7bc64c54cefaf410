// Lab 2 scenes for the 3-D viewer (./physlab view 02): cloth and a rope under implicit Euler.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "physlab/particles.hpp"
#include "physlab/replay.hpp"
#include "physlab/springs.hpp"
#include "physlab/view.hpp"

using namespace physlab;

namespace {

// Records `net` from state X under implicit Euler (CG) at h for `seconds` [s], a frame every
// `every` steps, the CG iterations as the solver's counter. Springs drawn: the structural ones
// (rest length within 20% of the shortest), not the shear and bending springs over them.
Replay film(const SpringNetwork& net, VecX X, const std::string& title, double h, double seconds, int every) {
  const SpringSystem sys(net);
  Replay replay;
  replay.title = title;
  replay.settings = "implicit Euler (Baraff-Witkin, CG), h = " + std::to_string(h) + " s";
  replay.particle_count = static_cast<std::uint32_t>(sys.count());
  double shortest = INFINITY;
  for (const Spring& s : net.springs) shortest = std::min(shortest, s.rest);
  for (const Spring& s : net.springs) {
    if (s.rest <= 1.2 * shortest) {
      replay.springs.push_back(static_cast<std::uint32_t>(s.a));
      replay.springs.push_back(static_cast<std::uint32_t>(s.b));
    }
  }
  const int steps = static_cast<int>(seconds / h + 0.5);
  for (int n = 0; n <= steps; ++n) {
    int iterations = 0;
    if (n > 0) iterations = implicitEulerStep(sys, X, h).iterations;
    if (n % every != 0) continue;
    // Kinetic energy of the free particles; the rest of energy() is potential
    double kinetic = 0.0;
    const ConstPoints v = velocities(X);
    for (Index i = 0; i < sys.count(); ++i) {
      if (std::isfinite(net.masses[i])) kinetic += 0.5 * net.masses[i] * v.col(i).squaredNorm();
    }
    recordParticles(replay, n * h, positions(X), kinetic, sys.energy(X) - kinetic);
    replay.frames.back().iterations = static_cast<std::uint32_t>(iterations);
  }
  return replay;
}

// A 15 x 15 cloth, 1 m square at 1 m, pinned by two corners, falling under gravity.
Replay cloth() {
  SpringNetwork net = makeCloth(15, 15, 1.0, 1.0, 0.3, 500.0, 0.5);
  net.gravity = Vec3(0.0, 0.0, -9.81);
  net.masses[0] = INFINITY;
  net.masses[14] = INFINITY;
  const SpringSystem sys(net);
  return film(net, sys.restState(), "Lab 2: a cloth hanging from two corners", 1.0 / 120, 4.0, 2);
}

// A rope of 20 particles, 1 m, pinned at its first, released level (turned a quarter turn up from
// hanging about the pin): it swings down and whips.
Replay rope() {
  SpringNetwork net = makeRope(20, 1.0, 0.2, 2000.0, 0.2);
  net.gravity = Vec3(0.0, 0.0, -9.81);
  const SpringSystem sys(net);
  VecX X = sys.restState();
  const Vec3 pin = positions(X).col(0);
  for (Index i = 0; i < sys.count(); ++i) {
    const Vec3 r = X.segment<3>(3 * i) - pin;  // hanging: r along -z
    X.segment<3>(3 * i) = pin + Vec3(-r.z(), r.y(), 0.0);
  }
  return film(net, X, "Lab 2: a rope released level from its pin", 1.0 / 240, 4.0, 4);
}

}  // namespace

int main(int argc, char** argv) {
  return runView(argc, argv,
                 {{"cloth", "a 15 x 15 cloth hanging from two corners (implicit Euler)", cloth},
                  {"rope", "a rope of 20 particles released level from its pin (implicit Euler)", rope}});
}
