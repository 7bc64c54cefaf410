// Lab 6 graded tests: the exact solvers (pivoting, section 3; Lemke, section 4) on redundant
// contacts, as a box pyramid makes them: a box resting on the ground on its four bottom corners
// (three constraints: A is singular) with one corner counted twice, and a box on a box on the
// ground (two such faces). A = J M^-1 J^T is built here by hand, apart from contactMatrix(), and
// b = J v is the bodies' velocity after a step of gravity (the velocity level, no Baumgarte). The
// answer's w and the generalized impulse J^T f are unique; f is not. The oracle is the enumeration
// of complementary bases (lcp_support), apart from any pivoting rule.
#include <cmath>
#include <vector>

#include <Eigen/LU>

#include "lcp_support.hpp"

using namespace physlab;
using namespace physlab::test;

// (a namespace of its own: the unity build compiles this file with the other LCP tests)
namespace lcp_redundant {

using LcpSolver = LcpSolution (*)(const MatX&, const VecX&, const LcpOptions&);

LcpSolution pivoting(const MatX& A, const VecX& b, const LcpOptions& options) { return solveLcpPivoting(A, b, options); }
LcpSolution lemke(const MatX& A, const VecX& b, const LcpOptions& options) { return solveLcpLemke(A, b, options); }

struct RedundantLcp {
  MatX J, A;  // J: one row per contact, 6 columns per moving body (v, omega); A = J M^-1 J^T
  VecX b;
};

// One contact row: the point r (relative to the body's centre) pushed along n = +z, on body k
// (+1) and, when `below` >= 0, against body `below` (-1, its point r_below).
void addRow(MatX& J, Index row, int k, const Vec3& r, int below, const Vec3& r_below) {
  const Vec3 n = Vec3::UnitZ();
  J.block<1, 3>(row, 6 * k) = n.transpose();
  J.block<1, 3>(row, 6 * k + 3) = r.cross(n).transpose();
  if (below >= 0) {
    J.block<1, 3>(row, 6 * below) = -n.transpose();
    J.block<1, 3>(row, 6 * below + 3) = -r_below.cross(n).transpose();
  }
}

// `boxes` cubes of edge 2 a and masses m(k) stacked on the ground, box 0 at the bottom, each
// touching the one below (or the ground) at its four bottom corners, and corner 0 of the bottom
// face counted twice. Each body moves at v = (0, 0, -g h) with spin `spin` about x (rad/s), so
// b = J v tips the boxes: the corners on one side press more than the other's.
RedundantLcp stackedBoxes(int boxes, double a, const VecX& m, double g, double h, double spin) {
  const Index n = 4 * boxes + 1;
  RedundantLcp p;
  p.J = MatX::Zero(n, 6 * boxes);
  const double corners[4][2] = {{-a, -a}, {a, -a}, {a, a}, {-a, a}};
  Index row = 0;
  for (int k = 0; k < boxes; ++k) {
    for (const auto& c : corners) {
      addRow(p.J, row++, k, Vec3(c[0], c[1], -a), k - 1, Vec3(c[0], c[1], a));
    }
  }
  addRow(p.J, row, 0, Vec3(-a, -a, -a), -1, Vec3::Zero());  // the twin of row 0
  VecX m_inv(6 * boxes), v(6 * boxes);
  for (int k = 0; k < boxes; ++k) {
    const double inertia = m(k) * (2.0 * a) * (2.0 * a) / 6.0;  // a cube's, about any centre axis
    m_inv.segment<6>(6 * k) << Vec3::Constant(1.0 / m(k)), Vec3::Constant(1.0 / inertia);
    v.segment<6>(6 * k) << 0.0, 0.0, -g * h, spin, 0.0, 0.0;
  }
  p.A = p.J * m_inv.asDiagonal() * p.J.transpose();
  p.A = 0.5 * (p.A + p.A.transpose());  // symmetric to the last bit
  p.b = p.J * v;
  return p;
}

// Solved by `solve`: f >= 0, w = A f + b >= 0 and complementary, and w and J^T f equal to every
// answer of the oracle (the complementary bases with an independent clamped set).
void checkRedundant(LcpSolver solve, const RedundantLcp& p, double impulse) {
  const Index n = p.b.size();
  // Singular A_SS are skipped by the oracle; a feasible basis is feasible by far more than 1e-9
  // on impulses of size m g h ~ 0.1
  const std::vector<VecX> oracle = complementarySolutions(p.A, p.b, 1e-9);
  REQUIRE(!oracle.empty());
  INFO("n " << n << " contacts, rank of A " << Eigen::FullPivLU<MatX>(p.A).rank() << ", weight impulse m g h = " << impulse
            << ", the oracle's w = (" << (p.A * oracle.front() + p.b).transpose() << ")");
  const LcpSolution s = solve(p.A, p.b, {});
  INFO("pivots " << s.iterations);
  REQUIRE(s.f.size() == n);
  REQUIRE(s.w.size() == n);
  CHECK(s.f.minCoeff() >= 0.0);  // the contract clamps round-off
  // Entries of A are O(1 / m), impulses O(m g h): round-off of a few dozen operations, with the
  // clamped blocks' condition (about 10 here) as margin
  const double tol = 1e-12 * std::max(1.0, impulse);
  CHECK((s.w - (p.A * s.f + p.b)).cwiseAbs().maxCoeff() <= tol);
  CHECK(s.w.minCoeff() >= -tol);
  CHECK(complementarity(p.A, p.b, s.f) <= tol);
  CHECK(s.residual == Approx(complementarity(p.A, p.b, s.f)).epsilon(1e-9).margin(1e-300));
  for (const VecX& f : oracle) {
    // The oracle's own QR solve of blocks with condition ~10: far below a wrong answer's O(0.1)
    CHECK((s.w - (p.A * f + p.b)).cwiseAbs().maxCoeff() <= 1e-9);
    CHECK((p.J.transpose() * (s.f - f)).cwiseAbs().maxCoeff() <= 1e-9 * std::max(1.0, impulse));
  }
  // Each contact is taken once and at most a few others change set per drive: within the
  // contract's limit 10 n by far; 3 n holds for both methods here
  CHECK(s.iterations >= 1);
  CHECK(s.iterations <= 3 * n);
}

void checkBoxOnGround(LcpSolver solve) {
  // Fixed: a 1 kg cube of 0.2 m edge, falling at g h after one step at 60 Hz, no spin: w = 0
  // everywhere (it stops), and J^T f = (0, 0, m g h, 0, 0, 0): the weight, no torque
  const double g = 9.81, h = 1.0 / 60.0;
  const RedundantLcp fixed = stackedBoxes(1, 0.1, VecX::Constant(1, 1.0), g, h, 0.0);
  checkRedundant(solve, fixed, g * h);
  const LcpSolution s = solve(fixed.A, fixed.b, {});
  VecX generalized = VecX::Zero(6);
  generalized(2) = g * h;  // m = 1
  CHECK((fixed.J.transpose() * s.f - generalized).cwiseAbs().maxCoeff() <= 1e-14);  // sums of 0.16: ulps
  CHECK(s.w.cwiseAbs().maxCoeff() <= 1e-14);
  // Seeded: masses, sizes and a spin that lifts one edge (two corners free, w > 0 there)
  for (int trial = 0; trial < 10; ++trial) {
    const double m = uniform(0.5, 5.0), spin = uniform(-2.0, 2.0);
    checkRedundant(solve, stackedBoxes(1, uniform(0.05, 0.5), VecX::Constant(1, m), g, h, spin), m * g * h);
  }
}

void checkStackedBoxes(LcpSolver solve) {
  // Fixed: a 1 kg cube on a 1 kg cube: both stop, the lower face carries both weights, the
  // upper one (b = 0 there: degenerate at the start) the top cube's
  const double g = 9.81, h = 1.0 / 60.0;
  const RedundantLcp fixed = stackedBoxes(2, 0.1, VecX::Constant(2, 1.0), g, h, 0.0);
  checkRedundant(solve, fixed, 2.0 * g * h);
  const LcpSolution s = solve(fixed.A, fixed.b, {});
  CHECK(std::abs(s.f.head(4).sum() + s.f(8) - 2.0 * g * h) <= 1e-14);  // ground: both weights
  CHECK(std::abs(s.f.segment(4, 4).sum() - g * h) <= 1e-14);           // between: the top one's
  // Seeded: mass ratios up to 10 either way and spins
  for (int trial = 0; trial < 10; ++trial) {
    const VecX m = (VecX(2) << uniform(0.5, 5.0), uniform(0.5, 5.0)).finished();
    checkRedundant(solve, stackedBoxes(2, uniform(0.05, 0.5), m, g, h, uniform(-2.0, 2.0)), m.sum() * g * h);
  }
}

// A two-dimensional pyramid as cubePyramid() stands: `rows` cubes of edge 2 a on the ground,
// one fewer on each row above, `pitch` apart; each upper cube rests on the two below it, on the
// four corners of each overlap of its bottom face with their tops (redundant: three constraints
// per face), each bottom cube on the ground's four. Cube k has mass m(k); every cube moves at
// v = (0, 0, -g h), b = J v.
RedundantLcp cubePyramidLcp(int rows, double a, double pitch, const VecX& m, double g, double h) {
  const int cubes = rows * (rows + 1) / 2;
  RedundantLcp p;
  p.J = MatX::Zero(4 * rows + 8 * (cubes - rows), 6 * cubes);
  std::vector<int> first(static_cast<std::size_t>(rows));  // index of each row's first cube
  for (int r = 1; r < rows; ++r) first[static_cast<std::size_t>(r)] = first[static_cast<std::size_t>(r - 1)] + rows - r + 1;
  Index row = 0;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < rows - r; ++c) {
      const int k = first[static_cast<std::size_t>(r)] + c;
      if (r == 0) {
        for (const double x : {-a, a}) {
          for (const double y : {-a, a}) addRow(p.J, row++, k, Vec3(x, y, -a), -1, Vec3::Zero());
        }
        continue;
      }
      for (int side = 0; side < 2; ++side) {
        // The cube below, its centre `shift` along x from ours; the overlap spans [lo, hi]
        const int below = first[static_cast<std::size_t>(r - 1)] + c + side;
        const double shift = side == 0 ? -0.5 * pitch : 0.5 * pitch;
        const double lo = side == 0 ? -a : shift - a, hi = side == 0 ? shift + a : a;
        for (const double x : {lo, hi}) {
          for (const double y : {-a, a}) addRow(p.J, row++, k, Vec3(x, y, -a), below, Vec3(x - shift, y, a));
        }
      }
    }
  }
  VecX m_inv(6 * cubes), v(6 * cubes);
  for (int k = 0; k < cubes; ++k) {
    const double inertia = m(k) * (2.0 * a) * (2.0 * a) / 6.0;
    m_inv.segment<6>(6 * k) << Vec3::Constant(1.0 / m(k)), Vec3::Constant(1.0 / inertia);
    v.segment<6>(6 * k) << 0.0, 0.0, -g * h, 0.0, 0.0, 0.0;
  }
  p.A = p.J * m_inv.asDiagonal() * p.J.transpose();
  p.A = 0.5 * (p.A + p.A.transpose());
  p.b = p.J * v;
  return p;
}

// Every cube of the pyramid stops: the overlaps span each cube's whole width, so forces >= 0
// hold any loads from above without torque, and w = J v' = 0 is the unique w; then J^T f = -M v,
// each cube's weight m g h up and no torque. Lemke's answer is checked against that.
void checkPyramid(int rows, const VecX& m) {
  const double g = 9.81, h = 1.0 / 60.0;
  const RedundantLcp p = cubePyramidLcp(rows, 0.1, 0.22, m, g, h);
  const Index n = p.b.size();
  INFO("a pyramid of " << rows << " rows, n " << n << " contacts, masses (" << m.transpose()
       << ") kg: expected w = 0 and each cube's J^T f = (0, 0, m g h, 0, 0, 0)");
  const LcpSolution s = solveLcpLemke(p.A, p.b);
  INFO("pivots " << s.iterations);
  REQUIRE(s.f.size() == n);
  CHECK(s.f.minCoeff() >= 0.0);
  // Impulses of order m g h ~ 0.2 summed down the rows, entries of A of order 1 / m: the
  // reference leaves 6e-11 in 400 seeded pyramids; a wrong answer is off by O(0.1)
  const double tol = 1e-9;
  CHECK(s.w.cwiseAbs().maxCoeff() <= tol);
  CHECK(complementarity(p.A, p.b, s.f) <= tol);
  const VecX generalized = p.J.transpose() * s.f;
  for (Index k = 0; k < m.size(); ++k) {
    VecX expected = VecX::Zero(6);
    expected(2) = m(k) * g * h;
    CHECK((generalized.segment<6>(6 * k) - expected).cwiseAbs().maxCoeff() <= tol);
  }
  // Both runs' pivots: the reference needs at most 2.7 n here
  CHECK(s.iterations <= 4 * n);
}

}  // namespace lcp_redundant

TEST_CASE("pivoting: a box resting on four corners and a twin corner (singular A) gets the unique w and J^T f", "[lab06][pts=1][sec=3]") {
  lcp_redundant::checkBoxOnGround(lcp_redundant::pivoting);
}

TEST_CASE("lemke: a box resting on four corners and a twin corner (singular A) gets the unique w and J^T f", "[lab06][pts=1][sec=4]") {
  lcp_redundant::checkBoxOnGround(lcp_redundant::lemke);
}

TEST_CASE("pivoting: two stacked boxes on redundant corners get the unique w and J^T f, each face its load", "[lab06][pts=1][sec=3]") {
  lcp_redundant::checkStackedBoxes(lcp_redundant::pivoting);
}

TEST_CASE("lemke: two stacked boxes on redundant corners get the unique w and J^T f, each face its load", "[lab06][pts=1][sec=4]") {
  lcp_redundant::checkStackedBoxes(lcp_redundant::lemke);
}

TEST_CASE("lemke: a 15-cube pyramid on redundant faces, where ties broken lexicographically lose accuracy, stops every cube", "[lab06][pts=1][sec=4]") {
  // Fixed: 5 rows of 1 kg cubes (n = 100). The lexicographic run gives a tie to a degenerate
  // row whose entry is round-off (zero in exact arithmetic: its corner repeats the face's other
  // three) and loses accuracy after 184 pivots; the run with ties to the largest entry solves it
  lcp_redundant::checkPyramid(5, VecX::Ones(15));
  // Seeded: 5 or 6 rows, masses from 0.5 to 2 kg
  for (int trial = 0; trial < 4; ++trial) {
    const int rows = uniform(0.0, 1.0) < 0.5 ? 5 : 6;
    VecX m(rows * (rows + 1) / 2);
    for (Index k = 0; k < m.size(); ++k) m(k) = uniform(0.5, 2.0);
    lcp_redundant::checkPyramid(rows, m);
  }
}
