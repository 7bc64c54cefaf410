// Lab 3 scenes for the 3-D viewer (./physlab view 03): a box tumbling about its intermediate axis.
#include "physlab/integrators.hpp"
#include "physlab/replay.hpp"
#include "physlab/rigid.hpp"
#include "physlab/view.hpp"

using namespace physlab;

namespace {

// A 0.4 x 1.0 x 1.6 m box (1 kg) spun about its intermediate axis (body y) with a small
// perturbation: it flips every few seconds while L stays fixed (the Dzhanibekov effect). RK4,
// h = 0.01 s, 8 s, a frame per step.
Replay tumblingBox() {
  const Vec3 size(0.4, 1.0, 1.6);
  const RigidBody body(1.0, boxInertia(1.0, size));
  const RigidBodySystem sys(body);
  VecX X = sys.makeState(Vec3(0.0, 0.0, 1.0), Quat::Identity(), Vec3::Zero(),
                         body.inertia_body * Vec3(0.05, 3.0, 0.05));
  Replay replay;
  replay.title = "Lab 3: a box tumbling about its intermediate axis";
  replay.settings = "RK4, h = 0.01 s, I = diag(" + std::to_string(body.inertia_body(0, 0)) + ", " +
                    std::to_string(body.inertia_body(1, 1)) + ", " + std::to_string(body.inertia_body(2, 2)) +
                    ") kg m^2, omega_0 = (0.05, 3, 0.05) rad/s body frame";
  ReplayBody box;
  box.kind = ReplayShapeKind::Box;
  box.size = {0.2f, 0.5f, 0.8f, 0.0f};
  replay.bodies.push_back(box);
  Integrator rk4(Method::RK4);
  const double h = 0.01;
  for (int n = 0; n <= 800; ++n) {
    if (n > 0) rk4.step(sys, X, h);
    recordPoses(replay, n * h, {Vec3(X.head<3>())}, {orientationOf(X).normalized()}, sys.kineticEnergy(X), 0.0);
  }
  return replay;
}

}  // namespace

int main(int argc, char** argv) {
  return runView(argc, argv, {{"tumbling", "a box tumbling about its intermediate axis (Dzhanibekov), RK4", tumblingBox}});
}
