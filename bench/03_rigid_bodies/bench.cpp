// Lab 3 benchmark: body-steps per second for 10^4 free bodies, and the energy drift of the
// Dzhanibekov body after 20 s at h = 1/60 - ours per integrator, and Bullet's per gyroscopic
// mode and MuJoCo's integrators in the same run when they are installed.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <utility>

#include "physlab/demo.hpp"
#include "physlab/integrators.hpp"
#include "physlab/rigid.hpp"

#include "../allocation_counter.hpp"

#ifdef PHYSLAB_HAVE_MUJOCO
#include <mujoco/mujoco.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#endif

#ifdef PHYSLAB_HAVE_BULLET
#include <btBulletDynamicsCommon.h>

#include <memory>
#endif

using namespace physlab;

namespace {

const Mat3 kInertia = Vec3(1.0, 2.0, 3.0).asDiagonal();
const Vec3 kOmega0(1e-3, 1.0, 0.0);
constexpr double kStep = 1.0 / 60.0;
constexpr int kSteps = 1200;  // 20 s

// Least wall time of `rounds` calls of `sweep`, after one warm-up call: the machine is shared,
// and the fastest round is the one least disturbed by other processes, for every engine alike.
template <class Sweep>
double fastest(int rounds, Sweep&& sweep) {
  sweep();
  double best = INFINITY;
  for (int r = 0; r < rounds; ++r) {
    Stopwatch clock;
    sweep();
    best = std::min(best, clock.seconds());
  }
  return best;
}
constexpr int kRounds = 5;

// Seconds per body-step for `count` free tumbling bodies sharing one description; `allocations`
// gets the heap allocations of one more sweep, per body-step.
double oursPerBodyStep(Method method, int count, int sweeps, double& allocations) {
  const RigidBodySystem sys(RigidBody(1.0, kInertia));
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  std::vector<VecX> states;
  for (int i = 0; i < count; ++i) {
    states.push_back(sys.makeState(Vec3(normal(rng), normal(rng), normal(rng)),
                                   Quat(normal(rng), normal(rng), normal(rng), normal(rng)),
                                   Vec3::Zero(), Vec3(normal(rng), normal(rng), normal(rng))));
  }
  Integrator integrator(method);
  const double seconds = fastest(kRounds, [&] {
    for (int s = 0; s < sweeps; ++s) {
      for (VecX& X : states) integrator.step(sys, X, kStep);
    }
  });
  allocations = static_cast<double>(bench::allocationsOf([&] {
                  for (VecX& X : states) integrator.step(sys, X, kStep);
                })) / count;
  return seconds / (static_cast<double>(sweeps) * count);
}

// The anchor: the same RK4 of the same free body with a fixed-size 13-number state and the
// derivative written out (no System, no checks, no heap): what a step costs with nothing but its
// arithmetic. Same formulas as the reference (omega = R I^-1 R^T L with R of q/|q|, qdot =
// 1/2 (0, omega) q, P and L constant, q renormalised after the step).
using State13 = Eigen::Matrix<double, 13, 1>;

// The anchor's RK4, written once for either state type: State13, and VecX of size 13 (the
// framework's state type) with the same arithmetic, so that the two anchors differ only in
// whether the compiler knows the size. The stages live in the workspace: no heap in a step.
template <class State>
struct AnchorRk4 {
  State k1 = State::Zero(13), k2 = State::Zero(13), k3 = State::Zero(13), k4 = State::Zero(13);
  State stage = State::Zero(13);
  double mass = 1.0;  // the benchmark's bodies
  Mat3 I_inv = kInertia.inverse();

  void derivative(const State& X, State& d) const {
    const Quat q(X[3], X[4], X[5], X[6]);
    const Mat3 R = q.normalized().toRotationMatrix();
    const Vec3 omega = R * (I_inv * (R.transpose() * X.template segment<3>(10)));
    const Quat product = Quat(0.0, omega.x(), omega.y(), omega.z()) * q;
    d.template head<3>() = X.template segment<3>(7) / mass;
    d.template segment<4>(3) << 0.5 * product.w(), 0.5 * product.x(), 0.5 * product.y(), 0.5 * product.z();
    d.template tail<6>().setZero();
  }

  void step(State& X, double h) {
    derivative(X, k1);
    stage = X + (0.5 * h) * k1;
    derivative(stage, k2);
    stage = X + (0.5 * h) * k2;
    derivative(stage, k3);
    stage = X + h * k3;
    derivative(stage, k4);
    X += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    X.template segment<4>(3).normalize();
  }
};

// Seconds per body-step of the fixed-size anchor, the dynamic-size anchor and our RK4
struct PairedCosts {
  double fixed_size, dynamic_size, ours;
};

// Seconds per body-step of the two anchors and of our RK4 on the bodies oursPerBodyStep() draws,
// timed in alternating rounds after a warm-up of each, so that all three see the same periods of a
// shared machine's load; `difference` gets the largest difference of our states from the
// fixed-size anchor's after the same steps (the same work: round-off at most).
PairedCosts anchorsAndOursPerBodyStep(int count, int sweeps, double& difference) {
  const RigidBodySystem sys(RigidBody(1.0, kInertia));
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  std::vector<State13> states;
  std::vector<VecX> ours, dynamic;
  for (int i = 0; i < count; ++i) {
    ours.push_back(sys.makeState(Vec3(normal(rng), normal(rng), normal(rng)),
                                 Quat(normal(rng), normal(rng), normal(rng), normal(rng)), Vec3::Zero(),
                                 Vec3(normal(rng), normal(rng), normal(rng))));
    states.push_back(ours.back());
  }
  dynamic = ours;
  AnchorRk4<State13> fixed_anchor;
  AnchorRk4<VecX> dynamic_anchor;
  Integrator integrator(Method::RK4);
  const auto fixed_sweeps = [&] {
    for (int s = 0; s < sweeps; ++s) {
      for (State13& X : states) fixed_anchor.step(X, kStep);
    }
  };
  const auto dynamic_sweeps = [&] {
    for (int s = 0; s < sweeps; ++s) {
      for (VecX& X : dynamic) dynamic_anchor.step(X, kStep);
    }
  };
  const auto our_sweeps = [&] {
    for (int s = 0; s < sweeps; ++s) {
      for (VecX& X : ours) integrator.step(sys, X, kStep);
    }
  };
  const auto seconds = [](const auto& sweep) {
    Stopwatch clock;
    sweep();
    return clock.seconds();
  };
  fixed_sweeps();
  dynamic_sweeps();
  our_sweeps();
  PairedCosts best{INFINITY, INFINITY, INFINITY};
  for (int r = 0; r < kRounds; ++r) {
    best.fixed_size = std::min(best.fixed_size, seconds(fixed_sweeps));
    best.dynamic_size = std::min(best.dynamic_size, seconds(dynamic_sweeps));
    best.ours = std::min(best.ours, seconds(our_sweeps));
  }
  difference = 0.0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    difference = std::max(difference, (ours[i] - states[i]).cwiseAbs().maxCoeff());
    difference = std::max(difference, (dynamic[i] - states[i]).cwiseAbs().maxCoeff());
  }
  const double body_steps = static_cast<double>(sweeps) * count;
  return {best.fixed_size / body_steps, best.dynamic_size / body_steps, best.ours / body_steps};
}

double oursDrift(Method method) {
  const RigidBodySystem sys(RigidBody(1.0, kInertia));
  VecX X = sys.makeState(Vec3::Zero(), Quat::Identity(), Vec3::Zero(), kInertia * kOmega0);
  const double E0 = sys.kineticEnergy(X);
  Integrator integrator(method);
  for (int n = 0; n < kSteps; ++n) integrator.step(sys, X, kStep);
  return std::abs(sys.kineticEnergy(X) - E0) / E0;
}

#ifdef PHYSLAB_HAVE_BULLET
struct BulletWorld {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  btSphereShape shape{0.1};
  std::vector<std::unique_ptr<btDefaultMotionState>> motions;
  std::vector<std::unique_ptr<btRigidBody>> bodies;

  BulletWorld() { world.setGravity(btVector3(0, 0, 0)); }
  ~BulletWorld() {
    for (auto& b : bodies) world.removeRigidBody(b.get());
  }
  btRigidBody* add(const btVector3& position, const btVector3& omega, int gyroscopic_flags) {
    motions.push_back(std::make_unique<btDefaultMotionState>(btTransform(btQuaternion::getIdentity(), position)));
    btRigidBody::btRigidBodyConstructionInfo info(1.0, motions.back().get(), &shape, btVector3(1, 2, 3));
    bodies.push_back(std::make_unique<btRigidBody>(info));
    btRigidBody* body = bodies.back().get();
    body->setFlags(gyroscopic_flags);
    body->setDamping(0, 0);
    body->setSleepingThresholds(0, 0);
    body->setActivationState(DISABLE_DEACTIVATION);
    body->setAngularVelocity(omega);
    world.addRigidBody(body);
    return body;
  }
};

double bulletEnergy(const btRigidBody& body) {
  const btMatrix3x3& R = body.getWorldTransform().getBasis();
  const btVector3 w = R.transpose() * body.getAngularVelocity();
  return 0.5 * (1.0 * w.x() * w.x() + 2.0 * w.y() * w.y() + 3.0 * w.z() * w.z());
}

double bulletDrift(int flags) {
  BulletWorld w;
  btRigidBody* body = w.add(btVector3(0, 0, 0), btVector3(kOmega0.x(), kOmega0.y(), kOmega0.z()), flags);
  const double E0 = bulletEnergy(*body);
  for (int n = 0; n < kSteps; ++n) w.world.stepSimulation(kStep, 0);
  return std::abs(bulletEnergy(*body) - E0) / E0;
}

double bulletPerBodyStep(int count, int sweeps) {
  BulletWorld w;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  const int side = static_cast<int>(std::ceil(std::cbrt(count)));
  for (int i = 0; i < count; ++i) {  // far apart on a grid: no contacts, only the body updates
    w.add(btVector3(i % side, (i / side) % side, i / (side * side)) * 10.0,
          btVector3(normal(rng), normal(rng), normal(rng)), BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
  }
  w.world.stepSimulation(kStep, 0);  // warm-up: Bullet's first step sets up its islands, 3-4x slower
  const double seconds = fastest(kRounds, [&] {
    for (int s = 0; s < sweeps; ++s) w.world.stepSimulation(kStep, 0);
  });
  return seconds / (static_cast<double>(sweeps) * count);
}
#endif

#ifdef PHYSLAB_HAVE_MUJOCO
// A MuJoCo model of `count` free bodies with inertia diag(1, 2, 3), no geoms (so no contacts),
// no gravity, step 1/60 s and the named integrator ("Euler" or "RK4").
struct MujocoRun {
  mjModel* model = nullptr;
  mjData* data = nullptr;
  MujocoRun(int count, const std::string& integrator) {
    std::ostringstream xml;
    xml << "<mujoco><option timestep='" << kStep << "' gravity='0 0 0' integrator='" << integrator
        << "'/><worldbody>";
    for (int i = 0; i < count; ++i) {
      xml << "<body pos='" << 10 * i << " 0 0'><freejoint/><inertial pos='0 0 0' mass='1' diaginertia='1 2 3'/></body>";
    }
    xml << "</worldbody></mujoco>";
    const std::string path = "/tmp/physlab_bench_mujoco_" + std::to_string(count) + ".xml";
    std::ofstream(path) << xml.str();
    char error[1000] = "";
    model = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
    std::remove(path.c_str());
    if (!model) throw std::runtime_error(std::string("MuJoCo could not load its model: ") + error);
    data = mj_makeData(model);
  }
  ~MujocoRun() {
    mj_deleteData(data);
    mj_deleteModel(model);
  }
  // A free joint's angular velocity (qvel 3..5 of each body) is in the body's local frame.
  double energy(int body) const {
    const mjtNum* w = data->qvel + 6 * body + 3;
    return 0.5 * (1.0 * w[0] * w[0] + 2.0 * w[1] * w[1] + 3.0 * w[2] * w[2]);
  }
};

double mujocoDrift(const std::string& integrator) {
  MujocoRun run(1, integrator);
  run.data->qvel[3] = kOmega0.x();
  run.data->qvel[4] = kOmega0.y();
  run.data->qvel[5] = kOmega0.z();
  const double E0 = run.energy(0);
  for (int n = 0; n < kSteps; ++n) mj_step(run.model, run.data);
  return std::abs(run.energy(0) - E0) / E0;
}

double mujocoPerBodyStep(int count, int sweeps) {
  MujocoRun run(count, "RK4");
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  for (int i = 0; i < count; ++i) {
    for (int k = 3; k < 6; ++k) run.data->qvel[6 * i + k] = normal(rng);
  }
  const double seconds = fastest(kRounds, [&] {
    for (int s = 0; s < sweeps; ++s) mj_step(run.model, run.data);
  });
  return seconds / (static_cast<double>(sweeps) * count);
}
#endif

}  // namespace

int main(int argc, char** argv) {
  try {
    const DemoOptions options = parseDemoOptions(
        argc, argv, "Lab 3 benchmark: free-body throughput and Dzhanibekov energy drift, with Bullet.");
    const int count = 10000, sweeps = options.quick ? 2 : 10;
    Table table({"engine", "method", "body-steps per second", "energy drift after 20 s (h = 1/60)"});
    double ours_rk4_cost = 0.0, ours_rk4_drift = 0.0;
    for (Method method : {Method::SymplecticEuler, Method::RK4}) {
      double allocations = 0.0;
      const double cost = oursPerBodyStep(method, count, sweeps, allocations), drift = oursDrift(method);
      std::cout << "PhysLab " << methodName(method) << ": heap allocations per body-step "
                << (bench::allocationsCounted() ? fmt(allocations) : std::string("not counted")) << "\n";
      if (method == Method::RK4) {
        ours_rk4_cost = cost;
        ours_rk4_drift = drift;
      }
      table.add({"PhysLab", methodName(method) + ", quaternion", fmt(1.0 / cost), fmt(drift)});
    }
    table.add({"PhysLab", "explicit Euler, quaternion", "-", fmt(oursDrift(Method::ExplicitEuler))});
    std::cout << "PhysLab RK4: " << fmt(1e9 * ours_rk4_cost) << " ns per body-step, energy drift "
              << fmt(ours_rk4_drift) << " after 20 s\n";
    double anchor_difference = 0.0;
    const PairedCosts paired = anchorsAndOursPerBodyStep(count, sweeps, anchor_difference);
    table.add({"anchor", "RK4, fixed-size 13-number state", fmt(1.0 / paired.fixed_size), "-"});
    table.add({"anchor", "RK4, the same on a VecX of 13", fmt(1.0 / paired.dynamic_size), "-"});
    // The goal: the framework's RK4 within 1.2x of the fixed-size one, same states, same rounds;
    // the dynamic-size anchor shows how much of that the framework's state type alone costs
    std::cout << "cost per body-step, alternating rounds: PhysLab RK4 / fixed-size anchor "
              << fmt(paired.ours / paired.fixed_size) << ", dynamic-size anchor / fixed-size anchor "
              << fmt(paired.dynamic_size / paired.fixed_size) << ", PhysLab RK4 / dynamic-size anchor "
              << fmt(paired.ours / paired.dynamic_size) << " (largest state difference " << fmt(anchor_difference)
              << ")\n";
#ifdef PHYSLAB_HAVE_BULLET
    const std::string bullet = "Bullet " + std::to_string(btGetVersion() / 100) + "." + std::to_string(btGetVersion() % 100);
    const double bullet_cost = bulletPerBodyStep(count, sweeps);
    const double bullet_drift = bulletDrift(BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
    table.add({bullet, "implicit body gyroscopic (default)", fmt(1.0 / bullet_cost), fmt(bullet_drift)});
    table.add({bullet, "implicit world gyroscopic", "-", fmt(bulletDrift(BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_WORLD))});
    table.add({bullet, "explicit gyroscopic", "-", fmt(bulletDrift(BT_ENABLE_GYROSCOPIC_FORCE_EXPLICIT))});
    table.add({bullet, "no gyroscopic term", "-", fmt(bulletDrift(0))});
    // The goal: at least 1000x less drift than Bullet's default at no more than 2x its cost.
    std::cout << "cost per body-step, PhysLab RK4 / Bullet default: " << fmt(ours_rk4_cost / bullet_cost) << "\n"
              << "energy drift, Bullet default / PhysLab RK4: " << fmt(bullet_drift / ours_rk4_drift) << "\n";
#else
    table.add({"Bullet", "not installed", "-", "-"});
#endif
#ifdef PHYSLAB_HAVE_MUJOCO
    const double mujoco_cost = mujocoPerBodyStep(options.quick ? 1000 : count, sweeps);
    table.add({"MuJoCo " + std::string(mj_versionString()), "RK4", fmt(1.0 / mujoco_cost), fmt(mujocoDrift("RK4"))});
    table.add({"MuJoCo " + std::string(mj_versionString()), "Euler (default)", "-", fmt(mujocoDrift("Euler"))});
    std::cout << "cost per body-step, PhysLab RK4 / MuJoCo RK4: " << fmt(ours_rk4_cost / mujoco_cost) << "\n";
#else
    table.add({"MuJoCo", "not installed", "-", "-"});
#endif
    std::cout << "Lab 3 benchmark: " << count << " free bodies, I = diag(1, 2, 3), h = 1/60 s\n";
    table.print(std::cout);
    std::cout << "wrote " << table.saveMarkdown(options.out + "/lab03_bench.md") << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "bench_03_rigid_bodies: " << e.what() << "\n";
    return 1;
  }
}
