/// \file springs.hpp
/// \brief Lab 2: mass-spring networks (ropes, cloth, soft bodies) and implicit integration.
///
/// A network is a particle system whose internal forces are the lecture's damped springs. Its
/// state has Lab 1's layout, \f$X = [x_1 \dots x_n,\ v_1 \dots v_n]\f$ (world frame, m and m/s),
/// so Lab 1's integrators, positions() and velocities() apply unchanged. A mass of +infinity pins
/// a particle.
#pragma once

#include <string>
#include <vector>

#include "physlab/math.hpp"
#include "physlab/system.hpp"

namespace physlab {

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
/// Penalty force of the ground on a particle at `x` moving with `v` [N] (see Ground).
/// Handout: Lab 2, section 4.
Vec3 groundForce(const Ground& ground, const Vec3& x, const Vec3& v);
///@}

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
  /// Total energy [J]: kinetic, spring potential \f$\sum \frac12 k_s(|l|-r)^2\f$, gravitational
  /// \f$-\sum m\,g \cdot x\f$ and ground \f$\sum \frac12 k\,d^2\f$, over free particles.
  double energy(const VecX& X) const;
  /// Largest spring stretch \f$\max |(|l| - r)| / r\f$ over springs with r > 0 (a health check).
  double maxStrain(const VecX& X) const;

 protected:
  void computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const override;
  void computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const override;

 private:
  SpringNetwork network_;
  VecX inverse_masses_;
};

/// The sparse linear solver inside the implicit step.
enum class LinearSolver {
  ConjugateGradient,  ///< Eigen::ConjugateGradient with a diagonal (Jacobi) preconditioner
  LDLT                ///< Eigen::SimplicialLDLT, a direct sparse Cholesky factorisation
};

/// Settings of implicitEulerStep().
struct ImplicitSettings {
  LinearSolver solver = LinearSolver::ConjugateGradient;  ///< which solver
  double cg_tolerance = 1e-10;  ///< CG stops at this relative residual
  int cg_max_iterations = 2000;  ///< CG gives up (NumericalFailure) after this many iterations
};

/// What one implicit step did.
struct ImplicitStats {
  int iterations = 0;   ///< CG iterations (0 for LDLT)
  double residual = 0;  ///< relative residual \f$|A\Delta v - b|/|b|\f$ of the solve
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
/// (no Jacobian). Called by implicitEulerStep() on validated input; throws NumericalFailure when
/// the solver fails.
ImplicitStats implicitEulerUpdate(const SpringSystem& sys, VecX& X, double h,
                                  const ImplicitSettings& settings);

/// Validates `h` (positive, finite), `X` (size, finite) and `settings`, then takes one
/// implicitEulerUpdate() step in place.
ImplicitStats implicitEulerStep(const SpringSystem& sys, VecX& X, double h,
                                const ImplicitSettings& settings = {});

}  // namespace physlab
