// Framework tests for Lab 2's SpringMatrix (ungraded): its block pattern, its product, its
// block-Jacobi CG and its LDLT against a dense matrix assembled here.
#include <Eigen/Cholesky>

#include "physlab/error.hpp"
#include "physlab/springs.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;
using Catch::Matchers::Contains;

namespace {

// A 4 x 4 cloth with two extra springs: one stored backwards (a > b) and one doubling a pair that
// already has a spring, so that blocks are transposed and shared.
SpringNetwork network() {
  SpringNetwork net = makeCloth(4, 4, 1.0, 0.0, 1.0, 100.0, 0.0);
  net.springs.push_back({5, 1, 1.0, 100.0, 0.0});
  net.springs.push_back({0, 1, 1.0, 100.0, 0.0});
  return net;
}

VecX randomVector(Index size) {
  VecX v(size);
  for (Index k = 0; k < size; ++k) v[k] = uniform(-1.0, 1.0);
  return v;
}

Mat3 randomMat3() {
  Mat3 m;
  for (int k = 0; k < 9; ++k) m.data()[k] = uniform(-1.0, 1.0);
  return m;
}

// Random blocks in `A` and the same matrix assembled densely: off-diagonal blocks of any shape,
// symmetric diagonal blocks that dominate them (so A is symmetric positive definite), and the
// identity with nothing off the diagonal for the `pinned` particle.
MatX fillRandom(const SpringNetwork& net, SpringMatrix& A, Index pinned) {
  const Index n = net.masses.size();
  MatX dense = MatX::Zero(3 * n, 3 * n);
  A.setZero();
  for (std::size_t k = 0; k < net.springs.size(); ++k) {
    const Spring& s = net.springs[k];
    if (s.a == pinned || s.b == pinned) continue;
    const Mat3 block = randomMat3();
    A.addSpring(k, block);
    dense.block<3, 3>(3 * s.a, 3 * s.b) += block;
    dense.block<3, 3>(3 * s.b, 3 * s.a) += block.transpose();
  }
  for (Index i = 0; i < n; ++i) {
    const Mat3 r = randomMat3();
    const Mat3 block = i == pinned ? Mat3::Identity() : Mat3(r * r.transpose() + 40.0 * Mat3::Identity());
    A.addDiagonal(i, block);
    dense.block<3, 3>(3 * i, 3 * i) += block;
  }
  return dense;
}

}  // namespace

TEST_CASE("spring matrix: blocks, product, CG and LDLT agree with a dense solve", "[common]") {
  const SpringNetwork net = network();
  SpringMatrix A(net);
  REQUIRE(A.count() == 16);
  const MatX dense = fillRandom(net, A, 3);
  // The pattern holds each block where the dense assembly put it, (b, a) as the transpose.
  CHECK((A.toDense() - dense).norm() == 0.0);
  VecX x = randomVector(48), y = VecX::Zero(48);
  A.multiply(x, y);
  CHECK((y - dense * x).norm() < 1e-13 * (dense * x).norm());

  VecX b = randomVector(48);
  b.segment<3>(9).setZero();  // the pinned particle's right-hand side
  const VecX expected = dense.ldlt().solve(b);
  VecX cg = VecX::Zero(48);
  const CGResult result = A.solveCG(b, cg, 1e-12, 200);
  CHECK(result.converged);
  CHECK(result.iterations >= 1);
  // Well conditioned (diagonally dominant): a 1e-12 residual is a ~1e-11 relative error at most.
  CHECK((cg - expected).norm() < 1e-10 * expected.norm());
  CHECK(cg.segment<3>(9).norm() == 0.0);  // an identity row with b = 0 stays exactly 0
  VecX ldlt = VecX::Zero(48);
  CHECK(A.solveLDLT(b, ldlt));
  CHECK((ldlt - expected).norm() < 1e-12 * expected.norm());

  // Refilled values, same pattern: the LDLT analysed before still factorises the new matrix.
  const MatX dense2 = fillRandom(net, A, 3);
  CHECK(A.solveLDLT(b, ldlt));
  CHECK((ldlt - dense2.ldlt().solve(b)).norm() < 1e-12 * ldlt.norm());
}

TEST_CASE("spring matrix: CG starts from the guess it is given and reports failure", "[common]") {
  const SpringNetwork net = network();
  SpringMatrix A(net);
  const MatX dense = fillRandom(net, A, 3);
  VecX b = randomVector(48);
  b.segment<3>(9).setZero();
  VecX x = dense.ldlt().solve(b);
  // Started at the solution it has nothing to do.
  CHECK(A.solveCG(b, x, 1e-8, 100).iterations == 0);
  // One iteration from zero cannot reach 1e-12 on 48 unknowns; a zero right-hand side gives zero.
  x.setZero();
  const CGResult capped = A.solveCG(b, x, 1e-12, 1);
  CHECK_FALSE(capped.converged);
  CHECK(capped.iterations == 1);
  x.setOnes();
  const CGResult zero = A.solveCG(VecX::Zero(48), x, 1e-12, 1);
  CHECK(zero.converged);
  CHECK(x.norm() == 0.0);
}

TEST_CASE("spring matrix: bad sizes, indices, networks and a singular block are refused", "[common]") {
  const SpringNetwork net = network();
  SpringMatrix A(net);
  fillRandom(net, A, 3);
  VecX x = VecX::Zero(48);
  CHECK_THROWS_WITH(A.solveCG(VecX::Ones(47), x, 1e-6, 10), Contains("CG right-hand side has size 47"));
  VecX short_x = VecX::Zero(5);
  CHECK_THROWS_WITH(A.solveCG(VecX::Ones(48), short_x, 1e-6, 10), Contains("CG starting guess has size 5"));
  CHECK_THROWS_WITH(A.solveLDLT(VecX::Ones(3), x), Contains("LDLT right-hand side"));
  CHECK_THROWS_WITH(A.multiply(VecX::Ones(3), x), Contains("multiply: x has size 3"));
  CHECK_THROWS_WITH(A.multiply(x, x), Contains("y must not be x"));
  CHECK_THROWS_WITH(A.addDiagonal(16, Mat3::Identity()), Contains("particle 16 of 16"));
  CHECK_THROWS_WITH(A.addSpring(net.springs.size(), Mat3::Identity()),
                    Contains("spring " + std::to_string(net.springs.size())));
  SpringNetwork bad = net;
  bad.springs[2].b = 99;
  CHECK_THROWS_WITH(SpringMatrix(bad), Contains("spring 2 names particle 99"));
  A.addDiagonal(7, -A.toDense().block<3, 3>(21, 21));  // particle 7's block becomes zero
  CHECK_THROWS_AS(A.solveCG(VecX::Ones(48), x, 1e-6, 10), NumericalFailure);
  CHECK_THROWS_WITH(A.solveCG(VecX::Ones(48), x, 1e-6, 10), Contains("particle 7"));
}

TEST_CASE("spring matrix: a system's workspace is sized for its network", "[common]") {
  const SpringSystem sys(network());
  ImplicitWorkspace& ws = sys.implicitWorkspace();
  CHECK(ws.A.count() == 16);
  for (const VecX* v : {&ws.b, &ws.Kv, &ws.dv, &ws.Adv}) CHECK(v->size() == 48);
  CHECK(ws.dv.norm() == 0.0);  // the first step starts cold
}
