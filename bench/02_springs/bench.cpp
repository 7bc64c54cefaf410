// Lab 2 benchmark: one implicit Euler step of a cloth at 32^2, 64^2 and 128^2 particles with CG
// and with LDLT, the scaling exponent of each, and, when Bullet is installed, Bullet's soft-body
// cloth of the same grid and step measured in the same run.
#include <cmath>
#include <iostream>

#include "physlab/demo.hpp"
#include "physlab/particles.hpp"
#include "physlab/springs.hpp"

#ifdef PHYSLAB_HAVE_BULLET
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <memory>
#endif

using namespace physlab;

namespace {

constexpr double kStep = 1.0 / 60.0;

SpringSystem clothOf(Index n, double ks) {
  SpringNetwork net = makeCloth(n, n, 1.0, 1.0, 1.0, ks, 0.01);
  net.masses[0] = net.masses[n - 1] = std::numeric_limits<double>::infinity();
  return SpringSystem(net);
}

struct Run {
  double seconds = 0.0;  // per step
  int cg_iterations = 0;  // per step
  double strain = 0.0;   // largest relative spring stretch at the end
};

// `steps` timed steps after 3 untimed ones; CG solves to 1e-6 relative residual, plenty for a
// step whose own truncation error is far larger.
Run implicitRun(const SpringSystem& sys, LinearSolver solver, int steps) {
  const ImplicitSettings settings{solver, 1e-6, 5000};
  VecX X = sys.restState();
  for (int n = 0; n < 3; ++n) implicitEulerStep(sys, X, kStep, settings);
  Run run;
  Stopwatch clock;
  long iterations = 0;
  for (int n = 0; n < steps; ++n) iterations += implicitEulerStep(sys, X, kStep, settings).iterations;
  run.seconds = clock.seconds() / steps;
  run.cg_iterations = static_cast<int>(iterations / steps);
  run.strain = sys.maxStrain(X);
  return run;
}

#ifdef PHYSLAB_HAVE_BULLET
struct BulletRun {
  double seconds = 0.0;  // per step
  double strain = 0.0;   // largest relative link stretch at the end
};

// Bullet's cloth: a patch of n x n nodes pinned at two corners, one stepSimulation per step of h,
// split into `substeps` internal steps of h / substeps (its stiffness knob; one sweep of its
// position solver each, its default).
BulletRun bulletRun(Index n, int steps, int substeps) {
  btSoftBodyRigidBodyCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
  world.setGravity(btVector3(0, 0, -9.81));
  btSoftBodyWorldInfo& info = world.getWorldInfo();
  info.m_gravity = btVector3(0, 0, -9.81);
  info.m_sparsesdf.Initialize();
  btSoftBody* cloth = btSoftBodyHelpers::CreatePatch(info, btVector3(0, 0, 1), btVector3(1, 0, 1),
                                                     btVector3(0, 1, 1), btVector3(1, 1, 1),
                                                     static_cast<int>(n), static_cast<int>(n), 1 + 2, true);
  cloth->setTotalMass(1.0);
  world.addSoftBody(cloth);
  const double substep = kStep / substeps;
  for (int i = 0; i < 3; ++i) world.stepSimulation(kStep, substeps, substep);
  Stopwatch clock;
  for (int i = 0; i < steps; ++i) world.stepSimulation(kStep, substeps, substep);
  BulletRun run;
  run.seconds = clock.seconds() / steps;
  for (int i = 0; i < cloth->m_links.size(); ++i) {
    const btSoftBody::Link& link = cloth->m_links[i];
    const double length = (link.m_n[0]->m_x - link.m_n[1]->m_x).length();
    run.strain = std::max(run.strain, std::abs(length - link.m_rl) / link.m_rl);
  }
  world.removeSoftBody(cloth);
  delete cloth;
  return run;
}

// A link stretched a thousandfold means a node has flown off: the run blew up.
bool blewUp(const BulletRun& run) { return !(run.strain < 1e3); }

// Bullet's cloth at one step per frame is far softer than ours, so the fair comparison is at
// equal stiffness: the fewest substeps (doubling up to `cap`) that hold its strain to `strain`.
// Returns a label for the substeps ("64", "> 256" when the cap does not suffice, "none, blows up
// at 16") and the last run that did not blow up.
std::pair<std::string, BulletRun> bulletAtStrain(Index n, int steps, double strain, int cap) {
  int substeps = 1;
  BulletRun run = bulletRun(n, steps, substeps);
  while (run.strain > strain && substeps < cap) {
    const BulletRun finer = bulletRun(n, steps, 2 * substeps);
    if (blewUp(finer)) return {"none, blows up at " + std::to_string(2 * substeps), run};
    substeps *= 2;
    run = finer;
  }
  return {(run.strain > strain ? "> " : "") + std::to_string(substeps), run};
}
#endif

}  // namespace

int main(int argc, char** argv) {
  keepFreedMemory();
  try {
    const DemoOptions options = parseDemoOptions(
        argc, argv, "Lab 2 benchmark: implicit cloth step time, CG vs LDLT, scaling, and Bullet.");
    const std::vector<Index> sizes = options.quick ? std::vector<Index>{16, 32} : std::vector<Index>{32, 64, 128};
    const int steps = options.quick ? 3 : 10;
    Table table({"grid", "particles", "CG ms/step", "CG iterations", "LDLT ms/step", "our max strain",
                 "Bullet ms/step", "Bullet max strain", "ours (best) / Bullet", "Bullet substeps at our strain",
                 "substepped Bullet ms/step", "its max strain", "ours (best) / substepped"});
    std::vector<double> log_n, log_cg, log_ldlt;
    for (Index n : sizes) {
      const SpringSystem sys = clothOf(n, 1e4);
      const Run cg = implicitRun(sys, LinearSolver::ConjugateGradient, steps);
      const Run ldlt = implicitRun(sys, LinearSolver::LDLT, steps);
      std::string bullet = "not installed", bullet_strain = "-", ratio = "-";
      std::string substeps_needed = "-", matched = "-", matched_strain = "-", matched_ratio = "-";
#ifdef PHYSLAB_HAVE_BULLET
      const double ours = std::min(cg.seconds, ldlt.seconds);
      const BulletRun bt = bulletRun(n, steps, 1);
      bullet = fmt(1e3 * bt.seconds);
      bullet_strain = fmt(bt.strain);
      ratio = fmt(ours / bt.seconds);
      const int cap = options.quick ? 64 : 256;
      const auto [label, at_strain] = bulletAtStrain(n, steps, cg.strain, cap);
      substeps_needed = label;
      matched = fmt(1e3 * at_strain.seconds);
      matched_strain = fmt(at_strain.strain);
      matched_ratio = at_strain.strain <= cg.strain ? fmt(ours / at_strain.seconds) : "not matched";
#endif
      table.add({std::to_string(n) + "^2", std::to_string(n * n), fmt(1e3 * cg.seconds),
                 std::to_string(cg.cg_iterations), fmt(1e3 * ldlt.seconds), fmt(cg.strain), bullet,
                 bullet_strain, ratio, substeps_needed, matched, matched_strain, matched_ratio});
      log_n.push_back(std::log(static_cast<double>(n * n)));
      log_cg.push_back(std::log(cg.seconds));
      log_ldlt.push_back(std::log(ldlt.seconds));
    }
    auto slope = [&](const std::vector<double>& y) {
      return (y.back() - y.front()) / (log_n.back() - log_n.front());
    };
    std::cout << "Lab 2 benchmark: cloth pinned at two corners, k = 1e4 N/m, h = 1/60 s\n";
    table.print(std::cout);
    std::cout << "time ~ particles^p: CG p = " << fmt(slope(log_cg)) << ", LDLT p = " << fmt(slope(log_ldlt)) << "\n";
    table.add({"scaling exponent p", "", fmt(slope(log_cg)), "", fmt(slope(log_ldlt)), "", "", "", "", "", "",
               "", ""});
    std::cout << "wrote " << table.saveMarkdown(options.out + "/lab02_bench.md") << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "bench_02_springs: " << e.what() << "\n";
    return 1;
  }
}
