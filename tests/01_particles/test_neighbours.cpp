// Lab 1 graded tests of section 5: the grid neighbour search against brute force written here
// (pairs, their order, the distance checks the documented grid makes), and the cut-off
// Lennard-Jones force against its formula, its potential and its continuity at the cut-off.
#include "physlab/error.hpp"
#include "physlab/neighbours.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

// Every pair i < j with |x_i - x_j|^2 <= r^2, by the header's own expression, in (i, j) order.
std::vector<NeighbourPair> nbBrute(const Mat3X& x, double r) {
  std::vector<NeighbourPair> pairs;
  for (Index i = 0; i < x.cols(); ++i) {
    for (Index j = i + 1; j < x.cols(); ++j) {
      if ((x.col(i) - x.col(j)).squaredNorm() <= r * r) pairs.push_back({i, j});
    }
  }
  return pairs;
}

std::vector<NeighbourPair> nbSearch(const Mat3X& x, double r, NeighbourStats& stats) {
  std::vector<NeighbourPair> pairs{{7, 9}};  // stale content: the search must clear it
  NeighbourGrid grid;
  neighbourPairs(ConstPoints(x.data(), 3, x.cols()), r, pairs, grid, stats);
  return pairs;
}

// The first difference between two pair lists, for the failure message.
std::string nbFirstDifference(const std::vector<NeighbourPair>& got, const std::vector<NeighbourPair>& want) {
  for (std::size_t k = 0; k < std::max(got.size(), want.size()); ++k) {
    const auto show = [&](const std::vector<NeighbourPair>& v) {
      return k < v.size() ? "(" + std::to_string(v[k].i) + ", " + std::to_string(v[k].j) + ")" : std::string("none");
    };
    if (k >= got.size() || k >= want.size() || got[k] != want[k]) {
      return "entry " + std::to_string(k) + ": got " + show(got) + ", brute force " + show(want);
    }
  }
  return "none";
}

// The grid of NeighbourGrid's documented layout, computed here: cell edge and cell of each point.
struct NbLayout {
  double h;
  Eigen::Matrix<Index, 3, Eigen::Dynamic> cell;
  Index cells;
};

NbLayout nbLayout(const Mat3X& x, double r) {
  const Vec3 lo = x.rowwise().minCoeff();
  const Vec3 extent = x.rowwise().maxCoeff() - lo;
  NbLayout layout{r, {}, 0};
  Vec3 dims;
  for (;;) {
    for (int a = 0; a < 3; ++a) dims[a] = std::floor(extent[a] / layout.h) + 1.0;
    if (dims.prod() <= 8.0 * static_cast<double>(x.cols())) break;
    layout.h *= 2.0;
  }
  layout.cells = static_cast<Index>(dims.prod());
  layout.cell.resize(3, x.cols());
  for (Index i = 0; i < x.cols(); ++i) {
    for (int a = 0; a < 3; ++a) layout.cell(a, i) = static_cast<Index>(std::floor((x(a, i) - lo[a]) / layout.h));
  }
  return layout;
}

// Candidate pairs i < j of the layout: cells at most one apart along every axis.
long nbCandidates(const NbLayout& layout) {
  long count = 0;
  for (Index i = 0; i < layout.cell.cols(); ++i) {
    for (Index j = i + 1; j < layout.cell.cols(); ++j) {
      count += (layout.cell.col(i) - layout.cell.col(j)).cwiseAbs().maxCoeff() <= 1 ? 1 : 0;
    }
  }
  return count;
}

// Pairs of `pairs` at a distance of exactly r (squared distance equal to r^2).
long nbExactlyAt(const Mat3X& x, double r, const std::vector<NeighbourPair>& pairs) {
  long count = 0;
  for (const NeighbourPair& p : pairs) count += (x.col(p.i) - x.col(p.j)).squaredNorm() == r * r ? 1 : 0;
  return count;
}

// The cut-off Lennard-Jones pair terms, written here: phi, and -phi'(r) / r (the force on i per
// unit of x_i - x_j).
double nbPhi(double eps, double sigma, double r) {
  return 4.0 * eps * (std::pow(sigma / r, 12) - std::pow(sigma / r, 6));
}
double nbMinusSlope(double eps, double sigma, double r) {
  return 24.0 * eps * (2.0 * std::pow(sigma / r, 12) - std::pow(sigma / r, 6)) / r;
}

}  // namespace

TEST_CASE("neighbours: the same pairs as brute force, in (i, j) order, on seeded clouds with points on cell borders and pairs exactly at r", "[lab01][pts=2][sec=5]") {
  const double r = 0.25;  // a power of two: lattice coordinates below are exact, so are their distances
  // Cloud 1: uniform, continuous coordinates.
  Mat3X uniform_cloud = randomPoints(600, 1.0);
  // Cloud 2: on a lattice of spacing r / 4 from the origin, so that many points sit exactly on
  // cell borders and many pairs are exactly r apart along an axis; with duplicates.
  Mat3X lattice(3, 500);
  for (Index i = 0; i < lattice.cols(); ++i) {
    for (int a = 0; a < 3; ++a) lattice(a, i) = std::floor(uniform(0.0, 24.0)) * (r / 4.0);
  }
  // Cloud 3: the lattice points, each with a partner exactly r away along a random axis, and a
  // partner just beyond (by one part in 10^12), which must not be found.
  Mat3X partners(3, 300);
  for (Index i = 0; i < 100; ++i) {
    const int axis = static_cast<int>(uniform(0.0, 3.0));
    partners.col(3 * i) = lattice.col(i);
    partners.col(3 * i + 1) = lattice.col(i) + r * Vec3::Unit(axis);
    partners.col(3 * i + 2) = lattice.col(i) - r * (1.0 + 1e-12) * Vec3::Unit(axis);
  }
  for (const auto& [name, x] : {std::pair{"uniform", &uniform_cloud}, std::pair{"lattice", &lattice},
                                std::pair{"exact partners", &partners}}) {
    CAPTURE(name);
    NeighbourStats stats;
    const std::vector<NeighbourPair> got = nbSearch(*x, r, stats);
    const std::vector<NeighbourPair> want = nbBrute(*x, r);
    INFO(nbFirstDifference(got, want));
    CHECK(got.size() == want.size());
    CHECK(got == want);  // the same pairs in the same order: the comparisons are the same expression
  }
  // The lattice clouds do test the inclusive end: many of their pairs are exactly r apart.
  CHECK(nbExactlyAt(lattice, r, nbBrute(lattice, r)) > 10);
  CHECK(nbExactlyAt(partners, r, nbBrute(partners, r)) >= 100);
}

TEST_CASE("neighbours: a sparse cloud widens the cells as documented and still finds every pair", "[lab01][pts=1][sec=5]") {
  // 200 points in a unit box and two far away: cells of edge r would number about 10^7, more
  // than 8N, so the edge doubles until they fit.
  Mat3X x(3, 202);
  x.leftCols(200) = randomPoints(200, 0.5);
  x.col(200) = Vec3(400.0, 0.0, 0.0) + randomVec3(1.0);
  x.col(201) = x.col(200) + Vec3(0.0, 0.1, 0.0);  // a pair out there too
  const double r = uniform(0.08, 0.12);
  NeighbourStats stats;
  const std::vector<NeighbourPair> got = nbSearch(x, r, stats);
  const std::vector<NeighbourPair> want = nbBrute(x, r);
  INFO(nbFirstDifference(got, want));
  CHECK(got == want);
  const NbLayout layout = nbLayout(x, r);
  CHECK(layout.h > r);  // the case does widen the cells
  CHECK(stats.cell_size == layout.h);  // r times a power of two: exact
  CHECK(stats.cells == layout.cells);
  CHECK(stats.distance_checks == nbCandidates(layout));
}

TEST_CASE("neighbours: on a uniform cloud the distance checks are exactly the candidate pairs of adjacent cells, far below N(N-1)/2", "[lab01][pts=2][sec=5]") {
  const Index n = 3000;
  const Mat3X x = randomPoints(n, 1.0);
  const double r = uniform(0.15, 0.25);
  NeighbourStats stats;
  const std::vector<NeighbourPair> got = nbSearch(x, r, stats);
  CHECK(got == nbBrute(x, r));
  const NbLayout layout = nbLayout(x, r);
  CHECK(stats.cell_size == r);  // a dense cloud needs no widening
  CHECK(stats.cells == layout.cells);
  // Each candidate pair (cells one apart at most along every axis) is checked once, no other.
  const long candidates = nbCandidates(layout);
  CHECK(stats.distance_checks == candidates);
  // About 27 (r/2)^3 N of the others share the 27 cells around a point (box of side 2), half of
  // them with a larger index: 27 (r/2)^3 <= 0.053 of all N (N - 1) / 2 pairs at r <= 0.25; the
  // bound leaves a factor 2 for the fluctuations of a random cloud. Brute force checks them all.
  CHECK(static_cast<double>(stats.distance_checks) < 0.11 * n * (n - 1) / 2.0);
  CHECK(stats.distance_checks >= static_cast<long>(got.size()));
}

TEST_CASE("neighbours: a fixed hand case: six points, two pairs exactly at r, one on a cell corner", "[lab01][pts=1][sec=5]") {
  // r = 1, lower corner (0, 0, 0), 3 x 3 x 1 cells. Cells: p0, p2 in (0,0); p1 in (1,0); p3 in
  // (2,0); p4 in (0,2); p5 on the corner (1,1), so in cell (1,1).
  Mat3X x(3, 6);
  x << 0.0, 1.0, 0.5, 2.5, 0.0, 1.0,  //
      0.0, 0.0, 0.5, 0.0, 2.0, 1.0,   //
      0.0, 0.0, 0.0, 0.0, 0.0, 0.0;
  NeighbourStats stats;
  const std::vector<NeighbourPair> got = nbSearch(x, 1.0, stats);
  // |p0 p1| = 1 and |p1 p5| = 1 (exactly r), |p0 p2| = |p1 p2| = |p2 p5| = sqrt(1/2); all others > 1.
  const std::vector<NeighbourPair> want{{0, 1}, {0, 2}, {1, 2}, {1, 5}, {2, 5}};
  INFO(nbFirstDifference(got, want));
  CHECK(got == want);
  // Candidates in adjacent cells: (0,1) (0,2) (1,2) (1,3), and p5 with each of the five others.
  CHECK(stats.distance_checks == 9);
  CHECK(stats.cells == 9);
  CHECK(stats.cell_size == 1.0);
}

TEST_CASE("neighbours: coincident points, N = 0 and N = 1, and a bad radius or point refused by name", "[lab01][pts=1][sec=5]") {
  // Four copies of one point (distance 0 <= r) and one point beyond r: six pairs.
  Mat3X x(3, 5);
  const Vec3 p = randomVec3(1.0);
  for (Index i = 0; i < 4; ++i) x.col(i) = p;
  x.col(4) = p + Vec3(0.0, 0.0, 0.3);
  NeighbourStats stats;
  const std::vector<NeighbourPair> want{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  CHECK(nbSearch(x, 0.2, stats) == want);
  for (const Index n : {0, 1}) {
    CAPTURE(n);
    stats.distance_checks = 99;  // stale: the search must reset it
    CHECK(nbSearch(randomPoints(n, 1.0), 0.5, stats).empty());
    CHECK(stats.distance_checks == 0);
  }
  for (const double r : {0.0, -0.5, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    CAPTURE(r);
    CHECK_THROWS_WITH(nbSearch(x, r, stats), Catch::Contains("radius"));
  }
  x(1, 2) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(nbSearch(x, 0.2, stats), Catch::Contains("points"));
}

TEST_CASE("cut-off Lennard-Jones: the shifted force and potential written here, minus the gradient of the potential, nothing beyond r_c", "[lab01][pts=2][sec=5]") {
  const double eps = uniform(0.5, 2.0), sigma = uniform(0.8, 1.2), rc = 2.5 * sigma;
  // 60 particles at least 0.9 sigma apart in a box of 5 sigma: pairs inside and beyond r_c.
  const Index n = 60;
  Mat3X x(3, n);
  for (Index i = 0; i < n; ++i) {
    for (bool ok = false; !ok;) {
      x.col(i) = randomVec3(2.5 * sigma);
      ok = true;
      for (Index j = 0; j < i; ++j) ok &= (x.col(i) - x.col(j)).norm() > 0.9 * sigma;
    }
  }
  const Mat3X v = randomPoints(n, 1.0);
  const VecX m = VecX::Ones(n);
  const CutoffLennardJones lj(eps, sigma, rc);
  Mat3X expected = Mat3X::Zero(3, n);
  double U = 0.0;
  int beyond = 0;
  for (Index i = 0; i < n; ++i) {
    for (Index j = i + 1; j < n; ++j) {
      const Vec3 d = x.col(i) - x.col(j);
      const double r = d.norm();
      if (r > rc) {
        ++beyond;
        continue;
      }
      const Vec3 f = (nbMinusSlope(eps, sigma, r) - nbMinusSlope(eps, sigma, rc)) / r * d;
      expected.col(i) += f;
      expected.col(j) -= f;
      U += nbPhi(eps, sigma, r) - nbPhi(eps, sigma, rc) + (r - rc) * nbMinusSlope(eps, sigma, rc);
    }
  }
  REQUIRE(beyond > 100);  // the cut-off matters in this cloud
  Mat3X F = Mat3X::Zero(3, n);
  const ParticleView s{ConstPoints(x.data(), 3, n), ConstPoints(v.data(), 3, n), m};
  lj.accumulate(s, Points(F.data(), 3, n));
  // Same formula, other order: round-off relative to the largest force.
  CHECK((F - expected).norm() <= 1e-12 * expected.norm());
  CHECK(lj.potential(s) == Approx(U).epsilon(1e-12).margin(1e-12 * eps * n));
  // Minus the gradient of the potential by central differences (O(h^2) ~ 1e-9 relative at h = 1e-5
  // on forces of O(eps / sigma)); no pair is within 1e-5 of r_c, where U has a kink in curvature.
  Mat3X grad(3, n);
  Mat3X y = x;
  const double h = 1e-5;
  for (Index i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      y(a, i) = x(a, i) + h;
      const double up = lj.potential({ConstPoints(y.data(), 3, n), ConstPoints(v.data(), 3, n), m});
      y(a, i) = x(a, i) - h;
      const double down = lj.potential({ConstPoints(y.data(), 3, n), ConstPoints(v.data(), 3, n), m});
      y(a, i) = x(a, i);
      grad(a, i) = -(up - down) / (2.0 * h);
    }
  }
  CHECK((grad - expected).norm() <= 1e-6 * expected.norm());
}

TEST_CASE("cut-off Lennard-Jones: continuous at the cut-off: zero force and potential at r_c, linear and quadratic just inside, nothing just beyond", "[lab01][pts=1][sec=5]") {
  const double eps = 1.0, sigma = 1.0, rc = 2.5;  // rc exact in binary
  const CutoffLennardJones lj(eps, sigma, rc);
  const Vec3 dir = Vec3(uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(0.5, 1.0)).normalized();
  const VecX m = VecX::Ones(2);
  const Mat3X v = Mat3X::Zero(3, 2);
  // phi''(r_c) by the formula: 4 eps (156 s^12 / r^14 - 42 s^6 / r^8).
  const double curvature = 4.0 * eps * (156.0 * std::pow(sigma, 12) / std::pow(rc, 14) - 42.0 * std::pow(sigma, 6) / std::pow(rc, 8));
  for (const double r : {rc, rc - 1e-3, rc * (1.0 + 1e-9)}) {
    CAPTURE(r);
    Mat3X x(3, 2);
    x.col(0) = Vec3(0.5, 0.25, -0.75);
    x.col(1) = r == rc ? Vec3(x.col(0) + Vec3(rc, 0.0, 0.0)) : Vec3(x.col(0) + r * dir);
    const ParticleView s{ConstPoints(x.data(), 3, 2), ConstPoints(v.data(), 3, 2), m};
    Mat3X F = Mat3X::Zero(3, 2);
    lj.accumulate(s, Points(F.data(), 3, 2));
    const double U = lj.potential(s);
    if (r > rc) {
      CHECK(F.norm() == 0.0);  // not neighbours: nothing at all
      CHECK(U == 0.0);
    } else if (r == rc) {
      // phi'(r_c) - phi'(r_c): the two terms cancel to round-off of numbers of size ~0.04
      CHECK(F.norm() < 1e-15);
      CHECK(std::abs(U) < 1e-15);
    } else {
      // Taylor at r_c: |f| = phi''(r_c) (r_c - r) and U = phi''(r_c) (r_c - r)^2 / 2, to O(1e-3) relative.
      CHECK(F.col(0).norm() == Approx(std::abs(curvature) * 1e-3).epsilon(2e-2));
      CHECK(U == Approx(0.5 * curvature * 1e-6).epsilon(2e-2));
      CHECK((F.col(0) + F.col(1)).norm() < 1e-17);  // equal and opposite
    }
  }
}
