// Lab 1, section 5: fixed-radius neighbour search on a uniform grid, and a cut-off Lennard-Jones force.
#include <algorithm>
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/neighbours.hpp"

namespace physlab {

// ---- neighbour search -----------------------------------------------------------------------

void neighbourPairs(ConstPoints x, double r, std::vector<NeighbourPair>& pairs, NeighbourGrid& grid,
                    NeighbourStats& stats) {
  // Refuse a radius or points that make no sense
  requirePositive(r, "neighbourPairs radius r");
  requireFinite(x, "neighbourPairs points x");
  pairs.clear();
  stats = NeighbourStats{};
  const Index n = x.cols();
  if (n == 0) return;
  // Lay the grid over the bounding box: cell edge r, doubled while the box needs more than 8N cells
  grid.lo = x.rowwise().minCoeff();
  const Vec3 extent = x.rowwise().maxCoeff() - grid.lo;
  const double max_cells = 8.0 * static_cast<double>(n);
  grid.h = r;
  for (;;) {
    const Vec3 d = (extent / grid.h).array().floor() + 1.0;
    if (d.prod() <= max_cells) {
      grid.dims = d.cast<Index>();
      break;
    }
    grid.h *= 2.0;
  }
  // Bin the points: count per cell, prefix sums, then place each index (a stable counting sort)
  const Index cells = grid.dims.prod();
  grid.cell.resize(3, n);
  grid.start.assign(static_cast<std::size_t>(cells) + 1, 0);
  grid.order.resize(static_cast<std::size_t>(n));
  grid.sorted.resize(3, n);
  const auto linear = [&](Index cx, Index cy, Index cz) { return cx + grid.dims[0] * (cy + grid.dims[1] * cz); };
  for (Index i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) grid.cell(a, i) = static_cast<Index>(std::floor((x(a, i) - grid.lo[a]) / grid.h));
    ++grid.start[static_cast<std::size_t>(linear(grid.cell(0, i), grid.cell(1, i), grid.cell(2, i))) + 1];
  }
  for (Index c = 0; c < cells; ++c) grid.start[c + 1] += grid.start[c];
  for (Index i = 0; i < n; ++i) {
    const Index c = linear(grid.cell(0, i), grid.cell(1, i), grid.cell(2, i));
    grid.sorted.col(grid.start[c]) = x.col(i);
    grid.order[static_cast<std::size_t>(grid.start[c]++)] = i;
  }
  // The placing loop advanced each start to the next cell's: shift back by one cell
  for (Index c = cells; c > 0; --c) grid.start[c] = grid.start[c - 1];
  grid.start[0] = 0;
  stats.cells = cells;
  stats.cell_size = grid.h;
  // Visit the points cell by cell (neighbouring cells then stay in cache); for each point i check
  // every j > i in its own and the 26 adjacent cells, keeping i's pairs as one run
  const double r2 = r * r;
  grid.found.clear();
  grid.run.resize(static_cast<std::size_t>(n));
  for (Index k = 0; k < n; ++k) {
    const Index i = grid.order[static_cast<std::size_t>(k)];
    const Index cx = grid.cell(0, i), cy = grid.cell(1, i), cz = grid.cell(2, i);
    const Vec3 xi = grid.sorted.col(k);
    const std::size_t first = grid.found.size();
    for (Index z = std::max<Index>(cz - 1, 0); z <= std::min(cz + 1, grid.dims[2] - 1); ++z) {
      for (Index y = std::max<Index>(cy - 1, 0); y <= std::min(cy + 1, grid.dims[1] - 1); ++y) {
        for (Index xx = std::max<Index>(cx - 1, 0); xx <= std::min(cx + 1, grid.dims[0] - 1); ++xx) {
          const Index c = linear(xx, y, z);
          for (Index m = grid.start[c]; m < grid.start[c + 1]; ++m) {
            const Index j = grid.order[static_cast<std::size_t>(m)];
            if (j <= i) continue;
            ++stats.distance_checks;
            if ((xi - grid.sorted.col(m)).squaredNorm() <= r2) grid.found.push_back({i, j});
          }
        }
      }
    }
    grid.run[static_cast<std::size_t>(i)] = {static_cast<Index>(first), static_cast<Index>(grid.found.size())};
  }
  // Copy the runs out in increasing i, each sorted by j
  pairs.resize(grid.found.size());
  auto out = pairs.begin();
  for (Index i = 0; i < n; ++i) {
    const auto [first, last] = grid.run[static_cast<std::size_t>(i)];
    const auto end = std::copy(grid.found.begin() + first, grid.found.begin() + last, out);
    std::sort(out, end, [](const NeighbourPair& a, const NeighbourPair& b) { return a.j < b.j; });
    out = end;
  }
}

// ---- cut-off Lennard-Jones ------------------------------------------------------------------

namespace {
// phi'(r) = -(24 eps / r) (2 (s/r)^12 - (s/r)^6)
double ljSlope(double epsilon, double sigma, double r) {
  const double sr6 = std::pow(sigma / r, 6);
  return -24.0 * epsilon * (2.0 * sr6 * sr6 - sr6) / r;
}
// phi(r) = 4 eps ((s/r)^12 - (s/r)^6)
double ljValue(double epsilon, double sigma, double r) {
  const double sr6 = std::pow(sigma / r, 6);
  return 4.0 * epsilon * (sr6 * sr6 - sr6);
}
}  // namespace

void CutoffLennardJones::accumulate(const ParticleView& s, Points F) const {
  // Find the pairs within the cut-off
  NeighbourStats stats;
  neighbourPairs(s.x, cutoff, pairs_, grid_, stats);
  // Shift the force so that it vanishes at r_c: f_i = -(phi'(r) - phi'(r_c)) (x_i - x_j) / r
  const double slope_c = ljSlope(epsilon, sigma, cutoff);
  for (const NeighbourPair& p : pairs_) {
    const Vec3 d = s.x.col(p.i) - s.x.col(p.j);
    const double r = d.norm();
    const Vec3 f = (-(ljSlope(epsilon, sigma, r) - slope_c) / r) * d;
    F.col(p.i) += f;
    F.col(p.j) -= f;
  }
}

double CutoffLennardJones::potential(const ParticleView& s) const {
  // Find the pairs within the cut-off
  NeighbourStats stats;
  neighbourPairs(s.x, cutoff, pairs_, grid_, stats);
  // Sum phi(r) - phi(r_c) - (r - r_c) phi'(r_c) over them
  const double value_c = ljValue(epsilon, sigma, cutoff), slope_c = ljSlope(epsilon, sigma, cutoff);
  double U = 0.0;
  for (const NeighbourPair& p : pairs_) {
    const double r = (s.x.col(p.i) - s.x.col(p.j)).norm();
    U += ljValue(epsilon, sigma, r) - value_c - (r - cutoff) * slope_c;
  }
  return U;
}

}  // namespace physlab
