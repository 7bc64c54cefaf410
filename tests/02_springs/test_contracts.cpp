// Lab 2 graded tests of the implicit step's whole contract: one step against the linearised
// system assembled here (damping, drag, unequal masses, pinned particles, stretched and
// compressed springs), the solver's failure, and the statistics the step reports.
#include <Eigen/Cholesky>

#include <set>
#include <utility>

#include "physlab/error.hpp"
#include "physlab/springs.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

// A 5 x 5 cloth pinned at two corners, with unequal random masses, spring damping and air drag,
// perturbed so that some springs are stretched and others compressed, moving in every direction.
// With `ground`, a penalty ground at the cloth's height, so that about half the particles are in
// contact.
struct Scene {
  SpringNetwork net;
  VecX X;
};

Scene randomCloth(bool ground = false) {
  Scene s;
  s.net = makeCloth(5, 5, 1.0, 1.0, 1.0, uniform(200.0, 1000.0), uniform(0.5, 2.0));
  for (Index i = 0; i < s.net.masses.size(); ++i) s.net.masses[i] = uniform(0.02, 0.08);
  s.net.masses[0] = s.net.masses[4] = std::numeric_limits<double>::infinity();
  s.net.drag = uniform(0.05, 0.2);
  const Index n = s.net.masses.size();
  s.X = VecX::Zero(6 * n);
  for (Index i = 0; i < n; ++i) {
    s.X.segment<3>(3 * i) = s.net.rest_positions.col(i) + randomVec3(0.05);
    if (i != 0 && i != 4) s.X.segment<3>(3 * n + 3 * i) = randomVec3(1.0);
  }
  if (ground) s.net.ground = {1.0, uniform(200.0, 2000.0), uniform(0.5, 2.0)};
  return s;
}

// The linear system of the implicit step, A dv = b, assembled densely here from the lecture's
// formulas (not the student's): A = M + h d 1 - h df/dv - h^2 df/dx with the definite spring
// Jacobian, b = h (f + h df/dx v), pinned rows and columns the identity with b = 0. The ground's
// penalty force (k d - c v_z) z for depth d > 0 enters f only: it has no Jacobian in A.
struct Linearised {
  MatX A;
  VecX b;
};

Linearised linearise(const SpringNetwork& net, const VecX& X, double h) {
  const Index n = net.masses.size(), N = 3 * n;
  const ConstPoints x = positions(X), v = velocities(X);
  MatX K = MatX::Zero(N, N), D = MatX::Zero(N, N);
  VecX f = VecX::Zero(N);
  for (const Spring& s : net.springs) {
    const Vec3 l = x.col(s.a) - x.col(s.b), l_dot = v.col(s.a) - v.col(s.b);
    const Vec3 u = l.normalized();
    const Mat3 uuT = u * u.transpose(), P = Mat3::Identity() - uuT;
    const double stretch = l.norm() - s.rest;
    const Vec3 fa = -(s.ks * stretch + s.kd * l_dot.dot(u)) * u;
    const Mat3 Kaa = -(s.ks * uuT + std::max(0.0, s.ks * stretch) / l.norm() * P);
    const Mat3 Daa = -s.kd * uuT;
    f.segment<3>(3 * s.a) += fa;
    f.segment<3>(3 * s.b) -= fa;
    for (const auto& [r, rs] : {std::pair{s.a, 1.0}, std::pair{s.b, -1.0}}) {
      for (const auto& [c, cs] : {std::pair{s.a, 1.0}, std::pair{s.b, -1.0}}) {
        K.block<3, 3>(3 * r, 3 * c) += rs * cs * Kaa;
        D.block<3, 3>(3 * r, 3 * c) += rs * cs * Daa;
      }
    }
  }
  MatX A = -h * D - h * h * K;
  VecX b = h * (f + h * K * v.reshaped());
  for (Index i = 0; i < n; ++i) {
    if (std::isinf(net.masses[i])) {
      A.middleRows<3>(3 * i).setZero();
      A.middleCols<3>(3 * i).setZero();
      A.block<3, 3>(3 * i, 3 * i).setIdentity();
      b.segment<3>(3 * i).setZero();
    } else {
      A.block<3, 3>(3 * i, 3 * i) += (net.masses[i] + h * net.drag) * Mat3::Identity();
      b.segment<3>(3 * i) += h * (net.masses[i] * net.gravity - net.drag * v.col(i));
      const double depth = net.ground.height - x(2, i);
      if (net.ground.stiffness > 0.0 && depth > 0.0) {
        b[3 * i + 2] += h * (net.ground.stiffness * depth - net.ground.damping * v(2, i));
      }
    }
  }
  return {A, b};
}

// One step of the student's implicitEulerStep against the oracle: v1 = v + dv, x1 = x + h v1.
void checkOneStep(const ImplicitSettings& settings, bool ground = false) {
  const Scene scene = randomCloth(ground);
  const SpringSystem sys(scene.net);
  const double h = uniform(0.01, 0.03);
  VecX X = scene.X;
  implicitEulerStep(sys, X, h, settings);
  const Linearised lin = linearise(scene.net, scene.X, h);
  const VecX dv = lin.A.ldlt().solve(lin.b);
  const Index N = sys.positionSize();
  const VecX v1 = scene.X.tail(N) + dv, x1 = scene.X.head(N) + h * v1;
  INFO("h = " << h << ", |dv| = " << dv.norm());
  // Both solve the same system, whose condition number is below 1e3 here, to ~1e-12 relative
  // (CG is asked for 1e-13); a missing or wrong term changes dv by 1% or more.
  CHECK((X.tail(N) - v1).norm() < 1e-9 * dv.norm());
  CHECK((X.head(N) - x1).norm() < 1e-9 * h * dv.norm());
}

// The test's dense A of a step in a SpringMatrix of `net`'s pattern: its diagonal blocks, and each
// distinct pair's block (a, b) once (springs of the same pair share one block).
void fillFromDense(const SpringNetwork& net, const MatX& A, SpringMatrix& M) {
  M.setZero();
  for (Index i = 0; i < M.count(); ++i) M.addDiagonal(i, A.block<3, 3>(3 * i, 3 * i));
  std::set<std::pair<Index, Index>> seen;
  for (std::size_t k = 0; k < net.springs.size(); ++k) {
    const Spring& s = net.springs[k];
    if (seen.insert({std::min(s.a, s.b), std::max(s.a, s.b)}).second) {
      M.addSpring(k, A.block<3, 3>(3 * s.a, 3 * s.b));
    }
  }
}

}  // namespace

TEST_CASE("implicit: one LDLT step solves the linearised system with damping, drag and pins", "[lab02][pts=1][sec=3]") {
  checkOneStep({LinearSolver::LDLT, 1e-13, 1000});
}

TEST_CASE("implicit: one CG step solves the linearised system with damping, drag and pins", "[lab02][pts=1][sec=3]") {
  checkOneStep({LinearSolver::ConjugateGradient, 1e-13, 1000});
}

TEST_CASE("implicit: the penalty ground enters the right-hand side only, not A", "[lab02][pts=1][sec=3]") {
  checkOneStep({LinearSolver::LDLT, 1e-13, 1000}, true);
}

TEST_CASE("implicit: CG that runs out of iterations throws NumericalFailure", "[lab02][pts=1][sec=3]") {
  const Scene scene = randomCloth();
  INFO("a cloth of " << scene.X.size() << " state numbers, h = 0.02: 1000 CG iterations must reach a relative residual "
                        "of 1e-12 without throwing, and 1 must throw");
  const SpringSystem sys(scene.net);
  VecX X = scene.X;
  implicitEulerStep(sys, X, 0.02, {LinearSolver::ConjugateGradient, 1e-12, 1000});
  // One CG iteration cannot reach a 1e-12 residual on a 75-unknown cloth: the step must say
  // so instead of taking an unconverged step. A fresh system, so that CG starts cold rather
  // than from the step just solved.
  const SpringSystem cold(scene.net);
  X = scene.X;
  CHECK_THROWS_AS(implicitEulerStep(cold, X, 0.02, {LinearSolver::ConjugateGradient, 1e-12, 1}),
                  NumericalFailure);
}

TEST_CASE("implicit: the step reports its CG iterations and relative residual", "[lab02][pts=1][sec=3]") {
  const Scene scene = randomCloth();
  const SpringSystem sys(scene.net);
  const double h = 0.02, tolerance = 1e-4;
  VecX X = scene.X;
  const ImplicitStats cg = implicitEulerStep(sys, X, h, {LinearSolver::ConjugateGradient, tolerance, 1000});
  const Index N = sys.positionSize();
  const VecX dv = X.tail(N) - scene.X.tail(N);
  const Linearised lin = linearise(scene.net, scene.X, h);
  const double residual = (lin.A * dv - lin.b).norm() / lin.b.norm();
  INFO("CG: " << cg.iterations << " iterations, reported residual " << cg.residual
              << ", recomputed " << residual);
  CHECK(cg.iterations >= 1);
  CHECK(cg.iterations <= 1000);
  // A loose tolerance stops CG well above round-off, so the residual recomputed here agrees
  // with the reported one to a few digits (dv recovered from the state loses ~1e-16 |v|).
  CHECK(cg.residual <= tolerance);
  CHECK(cg.residual == Approx(residual).epsilon(1e-6).margin(1e-12));
  X = scene.X;
  const ImplicitStats ldlt = implicitEulerStep(sys, X, h, {LinearSolver::LDLT, tolerance, 1000});
  CHECK(ldlt.iterations == 0);       // a direct solve has no iterations
  CHECK(ldlt.residual < 1e-12);      // and a residual at round-off: condition number < 1e3
}

namespace {

// The oracle of CG's iteration count: the framework's block-Jacobi CG (tested against dense
// solves) on the implicit step's system assembled here, from dv = 0.
CGResult coldStartCG(const Scene& scene, double h, double tolerance) {
  const Linearised lin = linearise(scene.net, scene.X, h);
  SpringMatrix M(scene.net);
  fillFromDense(scene.net, lin.A, M);
  VecX dv = VecX::Zero(lin.b.size());
  return M.solveCG(lin.b, dv, tolerance, 1000);
}

}  // namespace

TEST_CASE("implicit: the reported CG iterations are those block-Jacobi CG needs from a cold start", "[lab02][pts=1][sec=3]") {
  const Scene scene = randomCloth();
  const SpringSystem sys(scene.net);  // fresh: its CG starts from dv = 0
  const double h = uniform(0.01, 0.03), tolerance = 1e-6;
  INFO("h = " << h << ", relative residual tolerance " << tolerance << ", at most 1000 CG iterations");
  VecX X = scene.X;
  const ImplicitStats stats = implicitEulerStep(sys, X, h, {LinearSolver::ConjugateGradient, tolerance, 1000});
  const CGResult expected = coldStartCG(scene, h, tolerance);
  REQUIRE(expected.converged);
  INFO("reported " << stats.iterations << " iterations, block-Jacobi CG from zero takes " << expected.iterations);
  // Exactly: the two matrices differ by round-off (~1e-16 relative), which moves CG's residual
  // far too little to cross the tolerance at a different iteration.
  CHECK(stats.iterations == expected.iterations);
}

TEST_CASE("implicit: CG that converges on its last allowed iteration is a success", "[lab02][pts=1][sec=3]") {
  const Scene scene = randomCloth();
  const double h = uniform(0.01, 0.03), tolerance = 1e-6;
  const CGResult needed = coldStartCG(scene, h, tolerance);
  REQUIRE(needed.converged);
  REQUIRE(needed.iterations >= 2);
  INFO("block-Jacobi CG from zero needs " << needed.iterations << " iterations");
  // Allowed exactly that many (fresh systems: cold starts), the step succeeds and reports them;
  // one fewer and it must throw.
  const SpringSystem exact(scene.net);
  VecX X = scene.X;
  ImplicitStats stats;
  REQUIRE_NOTHROW(stats = implicitEulerStep(exact, X, h, {LinearSolver::ConjugateGradient, tolerance, needed.iterations}));
  CHECK(stats.iterations == needed.iterations);
  CHECK(stats.residual <= tolerance);
  const SpringSystem short_of_one(scene.net);
  X = scene.X;
  CHECK_THROWS_AS(implicitEulerStep(short_of_one, X, h, {LinearSolver::ConjugateGradient, tolerance, needed.iterations - 1}),
                  NumericalFailure);
}

TEST_CASE("implicit: CG starts from the last step's dv, so repeating a solved step takes no iterations", "[lab02][pts=1][sec=3]") {
  const Scene scene = randomCloth();
  const SpringSystem sys(scene.net);
  const double h = uniform(0.01, 0.03);
  VecX X = scene.X;
  const ImplicitStats first = implicitEulerStep(sys, X, h, {LinearSolver::ConjugateGradient, 1e-10, 1000});
  REQUIRE(first.iterations >= 1);
  // The same state again: the same A and b, and the last dv already meets a looser tolerance
  // (its residual is ~1e-10, the tolerance 1e-6), so CG stops before its first iteration.
  VecX Y = scene.X;
  const ImplicitStats again = implicitEulerStep(sys, Y, h, {LinearSolver::ConjugateGradient, 1e-6, 1000});
  CHECK(again.iterations == 0);
  CHECK((Y - X).norm() == 0.0);  // dv untouched: the same update, bit for bit
}

TEST_CASE("implicit: a network at rest without external forces stays at rest, residual 0", "[lab02][pts=1][sec=3]") {
  SpringNetwork net = makeCloth(4, 4, 1.0, 1.0, 0.5, uniform(100.0, 1000.0), uniform(0.5, 2.0));
  net.gravity.setZero();
  net.drag = 0.1;
  net.masses[0] = net.masses[3] = std::numeric_limits<double>::infinity();
  const SpringSystem sys(net);
  for (const LinearSolver solver : {LinearSolver::ConjugateGradient, LinearSolver::LDLT}) {
    VecX X = sys.restState();
    // At the build positions every spring has exactly its rest length and nothing moves, so f,
    // (df/dx) v and b are exactly 0: dv = 0, nothing to iterate, and the residual is 0 (not 0/0).
    const ImplicitStats stats = implicitEulerStep(sys, X, 0.02, {solver, 1e-6, 1000});
    INFO(solverName(solver) << ": residual " << stats.residual << ", " << stats.iterations << " iterations");
    CHECK((X - sys.restState()).norm() == 0.0);
    CHECK(stats.iterations == 0);
    CHECK(stats.residual == 0.0);
  }
}
