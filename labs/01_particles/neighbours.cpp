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
  // TODO(student): requirePositive(r, ...) and requireFinite(x, ...) name what was wrong; then clear pairs and stats.
  // Lay the grid over the bounding box: cell edge r, doubled while the box needs more than 8N cells
  // TODO(student): lo = componentwise minimum; dims[a] = floor(extent[a] / h) + 1 (see NeighbourGrid).
  // Bin the points: count per cell, prefix sums, then place each index (a stable counting sort)
  // TODO(student): grid.cell(a, i) = floor((x(a, i) - lo[a]) / h); start[c] .. start[c + 1] index order;
  // TODO(student): copy each point into grid.sorted beside its index in order (the search reads it there).
  // The placing loop advanced each start to the next cell's: shift back by one cell
  // TODO(student): only if your placing loop moved the starts; stats.cells and stats.cell_size too.
  // Visit the points cell by cell (neighbouring cells then stay in cache); for each point i check
  // every j > i in its own and the 26 adjacent cells, keeping i's pairs as one run
  // TODO(student): count each check in stats.distance_checks; keep pairs with squaredNorm() <= r * r in
  // TODO(student): grid.found, and note where i's run starts and ends in grid.run[i].
  // Copy the runs out in increasing i, each sorted by j
  // TODO(student): pairs gets run 0, run 1, ...; std::sort each run by j.
  notImplemented("neighbourPairs", "Lab 1 handout, section 5", x, r, pairs, grid, stats);
}

// ---- cut-off Lennard-Jones ------------------------------------------------------------------

void CutoffLennardJones::accumulate(const ParticleView& s, Points F) const {
  // Find the pairs within the cut-off
  // TODO(student): neighbourPairs(s.x, cutoff, pairs_, grid_, stats) reuses the force's workspace.
  // Shift the force so that it vanishes at r_c: f_i = -(phi'(r) - phi'(r_c)) (x_i - x_j) / r
  // TODO(student): add f to i and -f to j for each pair.
  notImplemented("CutoffLennardJones::accumulate", "Lab 1 handout, section 5", s, F);
}

double CutoffLennardJones::potential(const ParticleView& s) const {
  // Find the pairs within the cut-off
  // TODO(student): as in accumulate().
  // Sum phi(r) - phi(r_c) - (r - r_c) phi'(r_c) over them
  // TODO(student): phi(r) = 4 eps ((s/r)^12 - (s/r)^6), phi'(r) = -(24 eps / r) (2 (s/r)^12 - (s/r)^6).
  notImplemented("CutoffLennardJones::potential", "Lab 1 handout, section 5", s);
}

}  // namespace physlab
