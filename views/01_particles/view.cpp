// Lab 1 scenes for the 3-D viewer (./physlab view 01): particles under N-body gravity, and a flock.
#include <cmath>
#include <memory>
#include <random>

#include "physlab/integrators.hpp"
#include "physlab/neighbours.hpp"
#include "physlab/particles.hpp"
#include "physlab/replay.hpp"
#include "physlab/view.hpp"

using namespace physlab;

namespace {

// Steps `sys` from state X with `method` at h [s] for `steps` steps, a frame every `every` steps
// from t = 0, into a replay titled `title` with `settings` shown.
Replay film(const ParticleSystem& sys, VecX X, Method method, double h, int steps, int every, const char* title,
            const char* settings) {
  Replay replay;
  replay.title = title;
  replay.settings = settings;
  replay.particle_count = static_cast<std::uint32_t>(sys.count());
  Integrator integrator(method);
  for (int n = 0; n <= steps; ++n) {
    if (n > 0) integrator.step(sys, X, h);
    if (n % every == 0) recordParticles(replay, n * h, positions(X), kineticEnergy(sys, X), potentialEnergy(sys, X));
  }
  return replay;
}

// A sun (mass 1) and three planets (10^-3 each) on circular orbits of radius 1, 1.6 and 2.4 in the
// plane z = 0.5, G = 1 (scaled units: the inner year is 2 pi), softening 0.01. Velocity Verlet,
// h = 0.002, 20 time units, 50 frames a unit.
Replay orbits() {
  const double G = 1.0, sun = 1.0, planet = 1e-3;
  VecX masses(4);
  masses << sun, planet, planet, planet;
  ParticleSystem sys(masses);
  sys.addForce(std::make_shared<NBodyGravity>(G, 0.01));
  Mat3X x = Mat3X::Zero(3, 4), v = Mat3X::Zero(3, 4);
  x.row(2).setConstant(0.5);
  const double radii[3] = {1.0, 1.6, 2.4};
  for (int k = 0; k < 3; ++k) {
    const double angle = 2.1 * k;  // spread round the sun
    x.col(k + 1).head<2>() << radii[k] * std::cos(angle), radii[k] * std::sin(angle);
    const double speed = std::sqrt(G * sun / radii[k]);
    v.col(k + 1).head<2>() << -speed * std::sin(angle), speed * std::cos(angle);
  }
  return film(sys, sys.makeState(x, v), Method::Verlet, 0.002, 10000, 10,
              "Lab 1: three planets round a sun, N-body gravity",
              "velocity Verlet, h = 0.002, G = 1, softening 0.01, masses 1 and 3 x 0.001");
}

// 150 boids (section 6) in a 3 m cube at z in [0, 3], headings within 60 degrees of +x at 1 m/s;
// R = 1.2, w_s = 0.02, w_a = 2, w_c = 1.5; symplectic Euler, h = 0.02, 8 s, 25 frames a second.
// Boids do not propel themselves, so the flock keeps roughly its initial mean velocity.
Replay flock() {
  const Index n = 150;
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> coordinate(-1.5, 1.5), angle(-M_PI / 3.0, M_PI / 3.0);
  Mat3X x(3, n), v(3, n);
  for (Index i = 0; i < n; ++i) {
    x.col(i) << coordinate(rng), coordinate(rng), 1.5 + coordinate(rng);
    const double a = angle(rng), b = 0.5 * angle(rng);
    v.col(i) << std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b);
  }
  ParticleSystem sys(VecX::Ones(n));
  sys.addForce(std::make_shared<Boids>(1.2, 0.02, 2.0, 1.5));
  return film(sys, sys.makeState(x, v), Method::SymplecticEuler, 0.02, 400, 2, "Lab 1: a flock of 150 boids",
              "symplectic Euler, h = 0.02, R = 1.2, w_s = 0.02, w_a = 2, w_c = 1.5");
}

}  // namespace

int main(int argc, char** argv) {
  return runView(argc, argv, {{"orbits", "three planets round a sun (N-body gravity, velocity Verlet)", orbits},
                              {"flock", "150 boids aligning (section 6, symplectic Euler)", flock}});
}
