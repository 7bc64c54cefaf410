/// \file neighbours.hpp
/// \brief Lab 1 sections 5 and 6: fixed-radius neighbour search on a uniform cell grid, and the
/// two forces built on it (a cut-off Lennard-Jones force and Reynolds' boids).
///
/// A pair \f$(i, j)\f$ of particles are *neighbours* at radius \f$r\f$ when \f$i < j\f$ and
/// \f$\lvert x_i - x_j\rvert \le r\f$, the end \f$r\f$ included. "Distance" means the computed
/// `(x.col(i) - x.col(j)).squaredNorm() <= r * r`, so that a search and a brute-force loop written
/// with the same expression agree on every pair, including those exactly at \f$r\f$.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "physlab/math.hpp"
#include "physlab/particles.hpp"

namespace physlab {

/// Two particle indices with \f$i < j\f$.
struct NeighbourPair {
  Index i;  ///< the smaller index
  Index j;  ///< the larger index
  /// Same two indices.
  bool operator==(const NeighbourPair& o) const { return i == o.i && j == o.j; }
  /// Not the same two indices.
  bool operator!=(const NeighbourPair& o) const { return !(*this == o); }
};

/// What one neighbour search measured.
struct NeighbourStats {
  long distance_checks = 0;  ///< squared distances compared with \f$r^2\f$ (each pair at most once)
  Index cells = 0;           ///< cells in the grid (0 for brute force)
  double cell_size = 0.0;    ///< edge of a cell [m] (0 for brute force)
};

/// A uniform grid of cubic cells over the bounding box of a point cloud: the workspace of
/// neighbourPairs(). Keep one and pass it to every search, so that once its arrays have grown to
/// the cloud's size a search allocates nothing.
///
/// Layout (built by neighbourPairs(), the contract the tests check): the lower corner `lo` is the
/// componentwise minimum of the points; the cell edge is \f$h = r\f$, unless the box would then
/// need more than \f$8N\f$ cells (a sparse cloud), in which case \f$h = 2^k r\f$ with the
/// smallest \f$k\f$ that needs at most \f$8N\f$ (memory stays \f$O(N)\f$). Point \f$i\f$ lies in
/// cell \f$c_a = \lfloor (x_{i,a} - lo_a) / h \rfloor\f$ along each axis \f$a\f$, and
/// `dims[a]` \f$= c_a^{max} + 1\f$. A cell's linear index is \f$c_x + d_x (c_y + d_y c_z)\f$.
/// A point on a cell border belongs to the upper cell. The search visits the points cell by cell
/// (so that the cells it reads stay in cache) and then copies each point's run of pairs into the
/// output in increasing index order.
struct NeighbourGrid {
  Vec3 lo = Vec3::Zero();                      ///< lower corner of the grid [m]
  double h = 0.0;                              ///< cell edge [m], at least r
  Eigen::Matrix<Index, 3, 1> dims{0, 0, 0};    ///< number of cells along x, y, z
  Eigen::Matrix<Index, 3, Eigen::Dynamic> cell;  ///< integer cell coordinates of each point, 3 x N
  std::vector<Index> start;  ///< point slots of cell c are order[start[c]] ... order[start[c+1] - 1]
  std::vector<Index> order;  ///< point indices sorted by cell, increasing index within a cell
  /// The points in the order of `order` (column k is point order[k]): a cell's points lie side by
  /// side in memory, so the search reads them without a cache miss each.
  Mat3X sorted;
  /// The pairs as the search finds them, cell by cell: point i's pairs side by side, one run per i.
  std::vector<NeighbourPair> found;
  /// Where point i's run lies in `found`: entries run[i].first to run[i].second - 1.
  std::vector<std::pair<Index, Index>> run;
};

/// \name Neighbour search (student functions, Lab 1 section 5)
///@{

/// Every pair \f$i < j\f$ with \f$\lvert x_i - x_j\rvert \le r\f$ (computed as
/// `(x.col(i) - x.col(j)).squaredNorm() <= r * r`) into `pairs` (cleared first), in increasing
/// \f$(i, j)\f$ order (by \f$i\f$, then by \f$j\f$), found by binning the points into `grid` (see
/// NeighbourGrid for its layout) and comparing each point only with the points of its own and the
/// 26 adjacent cells. `stats` gets the number of distance checks (each candidate pair
/// \f$i < j\f$ in adjacent cells is checked exactly once) and the grid's size.
/// Costs \f$O(N + \text{candidates})\f$, about \f$O(N)\f$ on a cloud of bounded density.
/// Cells at least \f$r\f$ wide put two points within \f$r\f$ in the same or adjacent cells; in
/// floating point the cell coordinates are rounded, so a pair within an ulp or so of \f$r\f$ whose
/// coordinates also lie within an ulp of cell borders could land two cells apart and be missed.
/// Coordinates and radii exact in binary (the tests' lattices) never do.
/// Throws InvalidInput, naming it, when \f$r\f$ is not positive and finite or a point is not finite.
void neighbourPairs(ConstPoints x, double r, std::vector<NeighbourPair>& pairs, NeighbourGrid& grid,
                    NeighbourStats& stats);
///@}

/// The oracle and the benchmark's peer (framework code): every pair \f$i < j\f$ compared, so
/// `stats.distance_checks` \f$= N(N-1)/2\f$; same pairs, same order, same validation as
/// neighbourPairs().
void bruteForcePairs(ConstPoints x, double r, std::vector<NeighbourPair>& pairs, NeighbourStats& stats);

/// Lennard-Jones cut off at \f$r_c\f$ with the force shifted so that both the force and the
/// potential are continuous there. With \f$\phi(r) = 4\varepsilon[(\sigma/r)^{12} - (\sigma/r)^6]\f$
/// and \f$\phi'(r) = -\frac{24\varepsilon}{r}[2(\sigma/r)^{12} - (\sigma/r)^6]\f$, each neighbour
/// pair (\f$r = \lvert x_i - x_j\rvert \le r_c\f$, found with neighbourPairs()) has
/// \f[ U_{ij} = \phi(r) - \phi(r_c) - (r - r_c)\,\phi'(r_c), \qquad
///     f_i = -\big[\phi'(r) - \phi'(r_c)\big]\,\frac{x_i - x_j}{r}, \quad f_j = -f_i, \f]
/// and pairs farther apart contribute nothing. \f$U_{ij}\f$ and \f$f_i\f$ are both 0 at
/// \f$r = r_c\f$, and \f$f_i = -\partial U/\partial x_i\f$ for every \f$r < r_c\f$.
class CutoffLennardJones final : public Force {
 public:
  /// \param epsilon well depth \f$\varepsilon > 0\f$ [J]
  /// \param sigma zero crossing of \f$\phi\f$, \f$\sigma > 0\f$ [m]
  /// \param cutoff \f$r_c > 0\f$ [m], typically \f$2.5\sigma\f$
  CutoffLennardJones(double epsilon, double sigma, double cutoff);
  std::string name() const override { return "cut-off Lennard-Jones"; }
  void accumulate(const ParticleView& s, Points F) const override;
  double potential(const ParticleView& s) const override;
  const double epsilon;  ///< well depth [J]
  const double sigma;    ///< zero-crossing distance [m]
  const double cutoff;   ///< cut-off radius r_c [m]

 private:
  // Workspace of the neighbour search: reused between calls, never part of the result.
  mutable NeighbourGrid grid_;
  mutable std::vector<NeighbourPair> pairs_;
};

/// Reynolds' boids (1987) as a force. The neighbourhood of particle \f$i\f$ is
/// \f$\mathcal N_i = \{ j \ne i : \lvert x_i - x_j\rvert \le R \}\f$ (the pairs of
/// neighbourPairs() at radius \f$R\f$, the end included), \f$n_i = \lvert\mathcal N_i\rvert\f$.
/// When \f$n_i > 0\f$,
/// \f[ f_i = w_s \sum_{j \in \mathcal N_i,\ x_j \ne x_i} \frac{x_i - x_j}{\lvert x_i - x_j\rvert^2}
///     + w_a \Big(\frac1{n_i}\sum_{j \in \mathcal N_i} v_j - v_i\Big)
///     + w_c \Big(\frac1{n_i}\sum_{j \in \mathcal N_i} x_j - x_i\Big) \f]
/// (separation, alignment toward the neighbours' mean velocity, cohesion toward their
/// centroid); a neighbour at the very same position counts in \f$n_i\f$ and the two means but
/// adds no separation (it has no direction). \f$f_i = 0\f$ when \f$n_i = 0\f$. The force does not
/// depend on the masses, and a pinned particle is steered like any other (its infinite mass
/// keeps it still). It is not conservative: potential() is 0, and addJacobians() is the
/// default's false (no analytic Jacobian; implicit methods fall back on finite differences).
class Boids final : public Force {
 public:
  /// \param radius neighbour radius \f$R > 0\f$ [m]
  /// \param separation \f$w_s \ge 0\f$ [N m]
  /// \param alignment \f$w_a \ge 0\f$ [N s/m]
  /// \param cohesion \f$w_c \ge 0\f$ [N/m]
  Boids(double radius, double separation, double alignment, double cohesion);
  std::string name() const override { return "boids"; }
  void accumulate(const ParticleView& s, Points F) const override;
  double potential(const ParticleView& s) const override;
  const double radius;      ///< neighbour radius R [m]
  const double separation;  ///< separation weight w_s [N m]
  const double alignment;   ///< alignment weight w_a [N s/m]
  const double cohesion;    ///< cohesion weight w_c [N/m]

 private:
  // Workspace: the neighbour search and the per-particle sums, reused between calls.
  mutable NeighbourGrid grid_;
  mutable std::vector<NeighbourPair> pairs_;
  mutable Mat3X push_, velocity_sum_, position_sum_;
  mutable VecX count_;
};

/// The order parameter of a flock, \f$\phi = \big\lvert \frac1N \sum_i v_i / \lvert v_i\rvert \big\rvert\f$
/// (1: every particle heads the same way; near 0: headings at random); particles at rest are left
/// out of the sum and of \f$N\f$; 0 when none moves. Framework code (used by the demo).
double orderParameter(ConstPoints v);

}  // namespace physlab
