/// \file springs.hpp
/// \brief Lab 2: mass-spring networks (ropes, cloth, soft bodies) and implicit integration.
///
/// A network is a particle system whose internal forces are the lecture's damped springs. Its
/// state has Lab 1's layout, \f$X = [x_1 \dots x_n,\ v_1 \dots v_n]\f$ (world frame, m and m/s),
/// so Lab 1's integrators, positions() and velocities() apply unchanged. A mass of +infinity pins
/// a particle.
#pragma once

#include <Eigen/SparseCholesky>

#include <memory>
#include <string>
#include <vector>

#include "physlab/math.hpp"
#include "physlab/system.hpp"

namespace physlab {

namespace remote {
template <int>
struct Access;  // the grader's wire (tests/support/remote): what crosses to a grading worker
}  // namespace remote

/// One damped spring between particles \f$a\f$ and \f$b\f$ (see DampedSpring for the formula).
struct Spring {
  Index a;      ///< first particle
  Index b;      ///< second particle
  double rest;  ///< rest length r [m], non-negative
  double ks;    ///< stiffness [N/m], non-negative
  double kd;    ///< damping along the spring [N s/m], non-negative
};

/// The ground: the half-space \f$z < \text{height}\f$ pushes a particle out with a penalty spring,
/// \f$f = (k\,d - c\,v_z)\,\hat z\f$ for depth \f$d = \text{height} - z > 0\f$ (0 above the ground).
struct Ground {
  double height = 0.0;     ///< plane z = height [m]
  double stiffness = 0.0;  ///< penalty stiffness k [N/m]; 0 switches the ground off
  double damping = 0.0;    ///< penalty damping c [N s/m], acts only while in contact
};

/// The description of a spring network: constant, separate from its state.
struct SpringNetwork {
  VecX masses;                    ///< one per particle [kg]; +infinity pins a particle
  std::vector<Spring> springs;    ///< internal springs
  Vec3 gravity = Vec3::Zero();    ///< uniform gravitational acceleration, world frame [m/s^2]
  double drag = 0.0;              ///< viscous air drag d on every particle, \f$f = -d\,v\f$ [N s/m]
  Ground ground;                  ///< ground contact (off while its stiffness is 0)
  Mat3X rest_positions;           ///< positions the network was built in, 3 x n [m]
};

/// Throws InvalidInput naming the problem: a non-positive mass, a negative stiffness, damping or
/// rest length, a spring joining a particle to itself, or a particle index out of range.
void validate(const SpringNetwork& network);

/// A rope of `n` particles hanging down from the first, spacing `length / (n - 1)`, the first
/// pinned. Total mass `mass` spread evenly over the free particles.
SpringNetwork makeRope(Index n, double length, double mass, double ks, double kd);
/// A square cloth of `nx` x `ny` particles in the plane z = `height`, side `size`, with
/// structural (grid), shear (diagonal) and bending (two apart) springs at rest in that plane.
SpringNetwork makeCloth(Index nx, Index ny, double size, double height, double mass, double ks,
                        double kd);
/// A soft cube ("jelly") of `n`^3 particles, side `size`, lowest face at z = `height`, each
/// particle joined to its 26 grid neighbours.
SpringNetwork makeJelly(Index n, double size, double height, double mass, double ks, double kd);

/// The Jacobians of one spring's force on its first particle, \f$f_a\f$. The force on \f$b\f$ is
/// \f$-f_a\f$, so the four 3x3 blocks of the network Jacobian are \f$\pm\f$ these.
struct SpringJacobian {
  Mat3 dfa_dxa;  ///< \f$\partial f_a / \partial x_a\f$ [N/m] (= \f$\partial f_a/\partial l\f$)
  Mat3 dfa_dva;  ///< \f$\partial f_a / \partial v_a\f$ [N s/m] (= \f$\partial f_a/\partial \dot l\f$)
};

/// Which form of the spring Jacobian to return.
enum class JacobianForm {
  Exact,    ///< the true derivative, damping terms included (not symmetric in general)
  Definite  ///< Baraff-Witkin's approximation: symmetric and negative semi-definite (see springJacobian)
};

/// \name Student functions (Lab 2)
///@{

/// Force of one spring on its first particle: with \f$l = x_a - x_b\f$, \f$\dot l = v_a - v_b\f$,
/// \f$f_a = -[k_s(|l| - r) + k_d\,\dot l \cdot l / |l|]\; l / |l|\f$ [N]. Handout: Lab 2, section 1.
Vec3 springForce(const Spring& spring, const Vec3& xa, const Vec3& xb, const Vec3& va,
                 const Vec3& vb);
/// Jacobians of springForce(). With \f$u = l/|l|\f$, \f$P = \mathbb 1 - u u^T\f$ and
/// \f$s = k_s(|l| - r) + k_d\,\dot l \cdot u\f$, the exact form is
/// \f$\partial f_a/\partial x_a = -[k_s u u^T + \frac{k_d}{|l|} u \dot l^T P + \frac{s}{|l|} P]\f$,
/// \f$\partial f_a/\partial v_a = -k_d u u^T\f$. The definite form drops the damping part of
/// \f$\partial f_a/\partial x_a\f$ and keeps the \f$P\f$ term only while the spring is stretched:
/// \f$-[k_s u u^T + \frac{\max(0,\ k_s(|l| - r))}{|l|} P]\f$. Handout: Lab 2, section 2.
SpringJacobian springJacobian(const Spring& spring, const Vec3& xa, const Vec3& xb,
                              const Vec3& va, const Vec3& vb, JacobianForm form);
/// Penalty force of the ground on a particle at `x` moving with `v` [N] (see Ground): zero unless
/// the particle is strictly below the plane (depth d > 0; a particle exactly at z = height only
/// touches it), and zero whatever the depth while the ground is off (stiffness 0: its damper is
/// off too). Handout: Lab 2, section 4.
Vec3 groundForce(const Ground& ground, const Vec3& x, const Vec3& v);
///@}

/// What a block conjugate-gradient solve did (SpringMatrix::solveCG()).
struct CGResult {
  int iterations = 0;      ///< iterations taken (0 when the starting guess already satisfied it)
  bool converged = false;  ///< whether the relative residual reached the tolerance
};

/// The matrix of an implicit step on a spring network: symmetric, made of 3x3 blocks, one on the
/// diagonal per particle and one off the diagonal per spring's pair of particles (a, b) (the
/// block (b, a) is its transpose and is not stored). The pattern is built once from the network;
/// each step refills the values in place (setZero(), addDiagonal(), addSpring()) and solves with
/// solveCG(), which allocates nothing, or solveLDLT(), which analyses the pattern on its first
/// call only and then just factorises (Eigen's factorisation and solve still make two temporary
/// allocations per call). Springs that join the same pair share one block.
///
/// A particle's row and column hold what was added to them: for the identity rows of pinned
/// particles, add the identity on the diagonal and nothing off it.
class SpringMatrix {
 public:
  /// The pattern of `network` (validated: see validate()), all blocks zero.
  explicit SpringMatrix(const SpringNetwork& network);
  SpringMatrix(const SpringMatrix&) = delete;
  SpringMatrix& operator=(const SpringMatrix&) = delete;

  Index count() const { return static_cast<Index>(diagonal_.size()); }  ///< particles n (3n unknowns)
  /// Sets every block to zero, keeping the pattern.
  void setZero();
  /// Adds `block` to the diagonal block of particle `i`; keep the diagonal blocks symmetric.
  /// Throws InvalidInput when `i` is not a particle.
  void addDiagonal(Index i, const Mat3& block);
  /// Adds `block` to the off-diagonal block (a, b) of spring `k` of the network, and so its
  /// transpose to (b, a). Throws InvalidInput when `k` is not a spring.
  void addSpring(std::size_t k, const Mat3& block);
  /// \f$y = A x\f$ over the blocks; `x` has length 3n, `y` is resized to it and must not be `x`.
  void multiply(const VecX& x, VecX& y) const;
  /// The whole matrix, dense (3n x 3n), for tests and small examples.
  MatX toDense() const;

  /// Solves \f$A x = b\f$ by conjugate gradients preconditioned with the inverses of the 3x3
  /// diagonal blocks (block Jacobi), starting from the `x` passed in (a warm start; length 3n).
  /// Stops when \f$|b - A x| \le\f$ `tolerance` \f$|b|\f$ (x = 0 when b = 0) or after
  /// `max_iterations`. A must be symmetric positive definite. Throws NumericalFailure naming the
  /// particle whose diagonal block cannot be inverted.
  CGResult solveCG(const VecX& b, VecX& x, double tolerance, int max_iterations);
  /// Solves \f$A x = b\f$ with Eigen::SimplicialLDLT, the pattern analysed on the first call only.
  /// Returns false when the factorisation fails (A not positive definite), leaving `x` unchanged.
  bool solveLDLT(const VecX& b, VecX& x);

 private:
  template <int>
  friend struct remote::Access;  // a grading worker rebuilds its workspace's pattern in place
  struct Pair {
    Index i, j;  // particles, i < j: the stored block is (i, j)
  };
  // Lays out the pattern of `network` (validated), all blocks zero, replacing any earlier one.
  void build(const SpringNetwork& network);
  struct Slot {
    std::size_t pair;  // which stored block the spring's (a, b) block is
    bool transposed;   // a > b: the spring's block is the transpose of the stored one
  };
  void invertDiagonal();
  void refillCsc();

  std::vector<Mat3> diagonal_;          // block (i, i)
  std::vector<Mat3> off_diagonal_;      // block (i, j) of pairs_[k]
  std::vector<Pair> pairs_;             // distinct spring pairs
  std::vector<Slot> slots_;             // one per spring
  std::vector<Mat3> inverse_diagonal_;  // CG's preconditioner
  VecX r_, z_, p_, Ap_;                 // CG's vectors
  Eigen::SparseMatrix<double> lower_;   // lower triangle in CSC, refilled for LDLT
  std::vector<Index> diagonal_entries_;      // 6 value positions in lower_ per particle
  std::vector<Index> off_diagonal_entries_;  // 9 value positions in lower_ per pair
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
  bool analysed_ = false;
};

/// What implicitEulerUpdate() works in, sized once for a network and kept by its SpringSystem so
/// that a step allocates nothing: the matrix and the vectors of the step, each of length 3n.
struct ImplicitWorkspace {
  /// Sized for `network` (validated by the caller); the vectors are zero.
  explicit ImplicitWorkspace(const SpringNetwork& network);
  SpringMatrix A;  ///< \f$M - h\,\partial f/\partial v - h^2\,\partial f/\partial x\f$
  VecX b;          ///< right-hand side
  VecX Kv;         ///< \f$(\partial f/\partial x)\, v\f$
  VecX dv;         ///< \f$\Delta v\f$; keeps the last step's, CG's warm start for the next
  VecX Adv;        ///< room for \f$A\,\Delta v\f$ (the residual)
};

/// A spring network as a System, so that Lab 1's integrators advance it.
class SpringSystem final : public System {
 public:
  /// Validates `network` (see validate()) and keeps it.
  explicit SpringSystem(SpringNetwork network);
  Index positionSize() const override { return 3 * count(); }
  Index velocitySize() const override { return 3 * count(); }
  std::string name() const override { return "spring network"; }
  Index count() const { return network_.masses.size(); }  ///< number of particles n
  const SpringNetwork& network() const { return network_; }  ///< the description
  /// Inverse masses, length n; 0 for pinned particles.
  const VecX& inverseMasses() const { return inverse_masses_; }
  /// The state of the network at rest in its build positions with zero velocity.
  VecX restState() const;
  /// Total force on every particle, 3n [N]: springs (springForce()), gravity, drag and ground
  /// (groundForce()). Pinned particles get a force too; their zero inverse mass ignores it.
  VecX forces(const VecX& X) const;
  /// forces() into `f` (resized to 3n if needed), allocating nothing when it has that size.
  void forces(const VecX& X, VecX& f) const;
  /// Total energy [J]: kinetic, spring potential \f$\sum \frac12 k_s(|l|-r)^2\f$, gravitational
  /// \f$-\sum m\,g \cdot x\f$ and ground \f$\sum \frac12 k\,d^2\f$, over free particles.
  double energy(const VecX& X) const;
  /// Largest spring stretch \f$\max |(|l| - r)| / r\f$ over springs with r > 0 (a health check).
  double maxStrain(const VecX& X) const;
  /// The implicit step's workspace, built with the system. Mutable state behind a const system
  /// (like forceEvaluations()): one implicit step at a time per system, and the last step's
  /// \f$\Delta v\f$ seeds CG in the next, whichever state that step advances.
  ImplicitWorkspace& implicitWorkspace() const { return *workspace_; }

 protected:
  void computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const override;
  void computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const override;

 private:
  SpringNetwork network_;
  VecX inverse_masses_;
  std::unique_ptr<ImplicitWorkspace> workspace_;
};

/// The sparse linear solver inside the implicit step.
enum class LinearSolver {
  ConjugateGradient,  ///< SpringMatrix::solveCG(): block-Jacobi preconditioned, warm-started
  LDLT                ///< SpringMatrix::solveLDLT(): Eigen::SimplicialLDLT, a direct sparse Cholesky
};

/// Settings of implicitEulerStep().
struct ImplicitSettings {
  LinearSolver solver = LinearSolver::ConjugateGradient;  ///< which solver
  /// CG stops at this relative residual: on the benchmark's cloth 1e-3 moves the positions by 2-7 mm,
  /// well below implicit Euler's own 45-49 mm error at h = 1/60 (handout, section 3).
  double cg_tolerance = 1e-3;
  int cg_max_iterations = 2000;  ///< CG gives up (NumericalFailure) after this many iterations
};

/// What one implicit step did.
struct ImplicitStats {
  int iterations = 0;   ///< CG iterations (0 for LDLT)
  double residual = 0;  ///< relative residual \f$|A\Delta v - b|/|b|\f$ of the solve (0 when b = 0)
};

/// Display name of a linear solver ("CG", "LDLT").
std::string solverName(LinearSolver solver);

/// One step of implicit Euler as in Baraff & Witkin 1998 (student function, Lab 2 section 3).
/// Linearising the forces about the current state gives
/// \f[ \big(M - h\,\tfrac{\partial f}{\partial v} - h^2 \tfrac{\partial f}{\partial x}\big)\,\Delta v
///     = h\,\big(f + h\,\tfrac{\partial f}{\partial x}\, v\big), \f]
/// assembled sparse from the definite spring Jacobians (and the drag), with pinned particles'
/// rows and columns replaced by the identity so their \f$\Delta v = 0\f$; then
/// \f$v \leftarrow v + \Delta v\f$, \f$x \leftarrow x + h\,v\f$. The ground force enters \f$f\f$ only
/// (no Jacobian). Works in `ws` (the system's implicitWorkspace()), allocating nothing. Called by
/// implicitEulerStep() on validated input; throws NumericalFailure when the solver fails.
ImplicitStats implicitEulerUpdate(const SpringSystem& sys, VecX& X, double h,
                                  const ImplicitSettings& settings, ImplicitWorkspace& ws);

/// Validates `h` (positive, finite), `X` (size, finite) and `settings`, then takes one
/// implicitEulerUpdate() step in place.
ImplicitStats implicitEulerStep(const SpringSystem& sys, VecX& X, double h,
                                const ImplicitSettings& settings = {});

}  // namespace physlab
