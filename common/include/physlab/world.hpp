/// \file world.hpp
/// \brief Lab 5: impulse-based collision response, and the World that steps rigid bodies with it.
///
/// The lecture's model of a collision: when two bodies touch at a point \f$p\f$ with normal
/// \f$\hat n\f$ (from B to A) and approach each other, an impulse \f$J = j \hat n\f$ changes their
/// velocities instantly so that the relative normal velocity of the touching points flips and
/// shrinks by the coefficient of restitution \f$\epsilon\f$:
/// \f[ v_{rel}^+ = -\epsilon\, v_{rel}^-, \qquad v_{rel} = \hat n \cdot (\dot p_A - \dot p_B), \qquad
///     \dot p_A = v_A + \omega_A \times r_A,\ r_A = p - x_A. \f]
/// The magnitude that achieves it is
/// \f[ j = \frac{-(1 + \epsilon)\, v_{rel}^-}{m_A^{-1} + m_B^{-1}
///        + \hat n \cdot (I_A^{-1} (r_A \times \hat n)) \times r_A
///        + \hat n \cdot (I_B^{-1} (r_B \times \hat n)) \times r_B}, \qquad I^{-1} = R\, I_{body}^{-1} R^T, \f]
/// and applying it changes the momenta by \f$\Delta P_A = J,\ \Delta L_A = r_A \times J\f$ and
/// \f$\Delta P_B = -J,\ \Delta L_B = -r_B \times J\f$. A fixed body has \f$m^{-1} = 0\f$ and
/// \f$I^{-1} = 0\f$, so the same formulas leave it at rest.
///
/// Glossary (the lecture's symbols, used as names in the code):
/// | symbol | code | meaning |
/// |---|---|---|
/// | \f$v_{rel}\f$ | `v_rel` | relative normal velocity at a point, < 0 approaching [m/s] |
/// | \f$j\f$ | `j` | normal impulse magnitude [N s] |
/// | \f$\epsilon\f$ | `epsilon` | coefficient of restitution, in [0, 1] |
/// | \f$\mu\f$ | `mu` | Coulomb friction coefficient, >= 0 |
/// | \f$r_A, r_B\f$ | `r_a`, `r_b` | contact point relative to each centre of mass, world frame [m] |
/// | \f$I^{-1}\f$ | `I_inv_world` | world inverse inertia \f$R I_{body}^{-1} R^T\f$ [1/(kg m^2)] |
/// | \f$K\f$ | `K` | inverse effective mass along a direction (the denominator of j) [1/kg] |
///
/// A step of World runs the phases of the lecture's pipeline, one call each: broad phase ->
/// narrow phase (manifolds) -> classify contacts by \f$v_{rel}\f$ (colliding, resting,
/// separating) -> apply forces -> respond -> integrate -> correct positions -> diagnostics.
/// Contacts are classified with the velocities that brought the bodies together, before this
/// step's gravity: that approach speed decides whether a point bounces, so a body resting under
/// gravity does not (its approach is 0, not \f$g h\f$), and a bounce never returns the speed gravity
/// added during the step of the impact (the energy it would gain). Impulses
/// fix velocities only, so overlap left by a step would stay for ever; the position correction
/// moves and turns the bodies until each point's overlap beyond Settings::slop has shrunk by
/// Settings::position_correction, with Settings::correction_sweeps Gauss-Seidel sweeps over the
/// points (Box2D's position solver, linearised; see the Lab 5 handout, section 8). It changes
/// positions and orientations only: no velocity, so no kinetic energy.
/// A step sees only where bodies are at its start and end, so a body fast against its size can
/// pass through another between two steps (tunnelling). With Settings::continuous the integrate
/// phase first sweeps each fast body over the step (its points may move, against another body's,
/// more than the two inner radii combined) against the bodies it is fast against with Lab 4's
/// conservative advancement, and moves it only
/// until just into the first one it would hit (continuousAdvance(), section 10): the next step
/// finds that contact and answers it. Slow bodies cost one comparison each.
/// The respond phase solves each contact island (the moving bodies joined through contacts) on its
/// own, Settings::islands; with Settings::sleeping an island whose bodies have all been still for
/// a while (sleepTimer()) sleeps until an awake body touches it (section 12).
/// Given a RestingContactSolver (Lab 6), the respond phase hands it the points that are not
/// colliding (every point, when the solver bounces() itself); without one (Lab 5) the impulse
/// solver handles them too, with \f$\epsilon = 0\f$.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "physlab/broadphase.hpp"
#include "physlab/collision.hpp"
#include "physlab/math.hpp"

namespace physlab {

// ---------------------------------------------------------------------------------------------
/// \name Description, state and settings
///@{

/// The constant description of one body of a World.
struct BodyDescription {
  Shape shape = Sphere(1.0);         ///< the shape, body frame (a Plane is world frame and must be fixed)
  double mass = 1.0;                 ///< m [kg] (ignored when fixed)
  Mat3 inertia_body = Mat3::Identity();  ///< \f$I_{body}\f$, body frame, about the centre of mass [kg m^2]
  double epsilon = 0.5;              ///< coefficient of restitution, in [0, 1]
  double mu = 0.0;                   ///< Coulomb friction coefficient, >= 0
  bool fixed = false;                ///< a fixed body never moves: \f$m^{-1} = 0\f$, \f$I^{-1} = 0\f$

  /// A solid sphere of mass `mass` [kg] and radius `radius` [m].
  static BodyDescription sphere(double mass, double radius, double epsilon, double mu);
  /// A solid box of mass `mass` [kg] and half extents `half_extents` [m].
  static BodyDescription box(double mass, const Vec3& half_extents, double epsilon, double mu);
  /// A fixed half-space \f$\hat n \cdot p \le d\f$ (the ground is plane(Vec3::UnitZ(), 0, ...)).
  static BodyDescription plane(const Vec3& normal, double offset, double epsilon, double mu);
  /// A fixed box (a wall or the floor of a container).
  static BodyDescription fixedBox(const Vec3& half_extents, double epsilon, double mu);
};

/// The state of one body, as in Lab 3, world frame.
struct BodyState {
  Vec3 x = Vec3::Zero();      ///< centre of mass [m]
  Quat q = Quat::Identity();  ///< orientation, unit quaternion: body -> world
  Vec3 P = Vec3::Zero();      ///< linear momentum [kg m/s]
  Vec3 L = Vec3::Zero();      ///< angular momentum about the centre of mass [kg m^2/s]

  /// The state of `body` at x with orientation q moving at v [m/s] and turning at omega [rad/s]
  /// (world frame): \f$P = m v\f$, \f$L = R I_{body} R^T \omega\f$; a fixed body gets P = L = 0.
  /// InvalidInput when a vector is not finite or q is zero.
  static BodyState moving(const BodyDescription& body, const Vec3& x, const Quat& q, const Vec3& v, const Vec3& omega);
};

/// How World::step() responds to contacts.
enum class ResponseMethod {
  Sequential,    ///< one point at a time, each approaching point gets its full impulse, repeated
  Simultaneous,  ///< every point from the same velocities at once (Jacobi), accumulated and clamped
  Penalty,       ///< a spring and damper at each touching point, no impulses
};

/// "sequential", "simultaneous" or "penalty".
const char* responseMethodName(ResponseMethod method);

/// Every knob of World::step(), printed with every run (no statics anywhere).
struct Settings {
  ResponseMethod method = ResponseMethod::Sequential;  ///< how contacts are answered
  int iterations = 50;                ///< largest number of sweeps over the contact points, >= 1
  double tolerance = 1e-9;            ///< approaching means \f$v_{rel}\f$ < -tolerance; solvers stop when no velocity changes more [m/s], >= 0 (0: stop only when nothing changes)
  double restitution_threshold = 0.05;  ///< points with \f$|v_{rel}|\f$ at most this are resting: \f$\epsilon\f$ = 0 [m/s], >= 0 (0: every approach bounces)
  /// Impulse solvers and resting-contact solver: start each point from last step's impulses at
  /// the same point, found by feature id (Lab 4) or, when the ids changed (a face pair can swap
  /// its reference face from step to step), as the nearest of the pair's last points within
  /// 1 cm. The World decides it: when off, the contacts reach the solver with j = 0 and j_t = 0;
  /// the solvers apply whatever j, j_t their contacts carry and never read this flag.
  bool warm_start = true;
  Vec3 gravity = Vec3(0.0, 0.0, -9.81);  ///< uniform gravitational acceleration, world frame [m/s^2]
  double penalty_k = 1e4;             ///< penalty spring stiffness k [N/m]
  double penalty_d = 0.0;             ///< penalty damping d [N s/m]
  bool use_broad_phase = true;        ///< Lab 4's incremental AABB tree before the narrow phase (else every pair)
  double position_correction = 0.2;   ///< impulse methods: fraction of each point's overlap beyond the slop removed per step by moving and turning the bodies, in [0, 1] (0: off)
  double slop = 0.0002;               ///< overlap the position correction leaves alone [m]
  int correction_sweeps = 8;          ///< Gauss-Seidel sweeps of the position correction over the points, alternately forward and backward, >= 1
  /// Continuous collision (section 10): a body whose points may move, against another body's,
  /// more than the two inner radii combined in a step is swept against it (not against the
  /// planes: a half-space cannot be passed through) and stopped just into the first body it
  /// would hit, continuousAdvance()
  bool continuous = true;
  /// Shock propagation (section 11): after the response, the contacts are solved once more level
  /// by level up from the fixed bodies (level 1 touches a fixed body, level 2 touches level 1, ...),
  /// each level by the same solver with the levels below held still, so that a stack or a heavy
  /// body on a light one stands on what carries it. A response the solver converged is left as
  /// it was. Not with the penalty method, nor with a resting solver that substeps().
  bool shock_propagation = true;
  /// With shock propagation on and no resting solver, the response's sweeps stop at this many
  /// (at most `iterations`) on an island that rests on a fixed body (the whole scene when islands
  /// are off and any body rests on one): the propagation solves each of its points again, level
  /// by level, from the response's impulses, so the response need not converge by itself
  /// (section 11: on the box rain of 100, 20 in place of 30 takes a sixth off the step, and the
  /// contact suite's measures all hold). Islands in flight keep `iterations`. >= 1
  int shock_response_iterations = 20;
  /// Contact islands (section 12): each step the moving bodies connected through contacts (fixed
  /// bodies and planes join none) are grouped by union-find, and the response, the resting-contact
  /// solver and the shock propagation solve each island's contacts on their own, in the order the
  /// contacts have in the scene: a Gauss-Seidel sweep of an island touches only its bodies, so the
  /// impulse solvers give the whole scene's answers (to the bit with tolerance 0 and
  /// shock_response_iterations at least iterations; within the tolerance otherwise, as each
  /// island stops when it is quiet), and an exact resting solver
  /// solves one small LCP per island. Off: the scene is one system. A resting solver that
  /// substeps() moves every body in one solve and always takes the scene as one system.
  bool islands = true;
  /// Sleeping (section 12): an island every body of which has stayed at or below sleep_linear and
  /// sleep_angular for sleep_time, by sleepTimer(), falls asleep: its velocities are set to zero
  /// and it is neither pushed by gravity, moved, nor solved, and no narrow phase runs between
  /// two sleeping bodies or a sleeping and a fixed one, until an awake body touches one of its
  /// bodies or setState() changes one (that island wakes, and only it). The broad phase gives the
  /// incremental tree only the bodies not asleep, and looks each awake moving body up among the
  /// sleepers' boxes, kept sorted along x while they sleep: a sleeping body costs nothing until an
  /// awake one comes near (the list is sorted again, and the tree rebuilt, on a step where a body
  /// falls asleep or wakes). Off by default: with it on, every World step calls the student's
  /// sleepTimer(), so an unwritten one would fail every World test of Lab 5 (the contact suite's
  /// measures all hold with it on, in Labs 5 and 6).
  bool sleeping = false;
  double sleep_linear = 0.05;   ///< a body is still at or below this speed of its centre [m/s], >= 0
  double sleep_angular = 0.05;  ///< ... and at or below this angular speed [rad/s], >= 0
  double sleep_time = 0.5;      ///< an island sleeps once all its bodies have been still this long [s], >= 0

  /// One line naming every setting and its value.
  std::string toString() const;
};
/// Writes Settings::toString().
std::ostream& operator<<(std::ostream& out, const Settings& settings);
///@}

// ---------------------------------------------------------------------------------------------
/// \name Contacts
///@{

/// What the sign of \f$v_{rel}\f$ says about a contact point (lecture 002).
enum class ContactKind {
  Colliding,   ///< \f$v_{rel} < -\f$ threshold: the bodies approach, an impulse is needed
  Resting,     ///< \f$|v_{rel}| \le\f$ threshold: touching, neither approaching nor leaving
  Separating,  ///< \f$v_{rel} >\f$ threshold: the bodies move apart, nothing to do
};

/// The solver's view of one body during the response: velocities and inverse mass properties,
/// world frame. A fixed body has inv_mass = 0, I_inv_world = 0 and zero velocities.
struct ContactBody {
  Vec3 x = Vec3::Zero();                ///< centre of mass [m]
  Vec3 v = Vec3::Zero();                ///< velocity of the centre [m/s]
  Vec3 omega = Vec3::Zero();            ///< angular velocity [rad/s]
  double inv_mass = 0.0;                ///< \f$m^{-1}\f$ [1/kg], 0 when fixed
  Mat3 I_inv_world = Mat3::Zero();      ///< \f$R I_{body}^{-1} R^T\f$ [1/(kg m^2)], 0 when fixed
};

/// One contact point between bodies `a` and `b` (indices into the solver's bodies).
struct Contact {
  int a = 0;                      ///< body A (the normal points towards it)
  int b = 0;                      ///< body B
  Vec3 p = Vec3::Zero();          ///< the point (manifold midpoint), world frame [m]
  Vec3 n = Vec3::UnitZ();         ///< unit normal from B to A, world frame
  double depth = 0.0;             ///< penetration, > 0 overlapping [m]
  std::uint32_t id = 0;           ///< feature id (Lab 4), for warm starting
  double epsilon = 0.0;           ///< restitution of the pair, min of the two (solvers use 0 below the threshold)
  double mu = 0.0;                ///< friction of the pair, \f$\sqrt{\mu_A \mu_B}\f$
  double v_rel_minus = 0.0;       ///< \f$v_{rel}^-\f$ when classified: with the velocities before this step's gravity [m/s]
  ContactKind kind = ContactKind::Separating;  ///< what classify found
  double j = 0.0;                 ///< accumulated normal impulse, >= 0 [N s]
  Vec3 j_t = Vec3::Zero();        ///< accumulated friction impulse, tangent plane, \f$|j_t| \le \mu j\f$ [N s]
  /// \name Prepared by solveSequential() (section 5) before its warm start; what they hold on entry is ignored
  ///@{
  Vec3 r_a = Vec3::Zero();        ///< \f$r_A = p - x_A\f$ [m]
  Vec3 r_b = Vec3::Zero();        ///< \f$r_B = p - x_B\f$ [m]
  /// \f$\mathbf K = (m_A^{-1} + m_B^{-1})\,\mathbf 1 - [r_A]_\times I_A^{-1} [r_A]_\times - [r_B]_\times I_B^{-1} [r_B]_\times\f$:
  /// an impulse J at p changes \f$\dot p_A - \dot p_B\f$ by \f$\mathbf K J\f$, and
  /// \f$d \cdot \mathbf K d\f$ is inverseEffectiveMass() along d [1/kg]
  Mat3 K_matrix = Mat3::Zero();
  ///@}
};
///@}

// ---------------------------------------------------------------------------------------------
/// \name Student functions (Lab 5)
///@{

/// A particle of mass m hitting a fixed plane with unit normal n: when it approaches
/// (\f$v^- \cdot \hat n < 0\f$), \f$v^+ = v^- + \frac{j}{m}\hat n\f$ with
/// \f$j = -(1 + \epsilon)\, m\, v^- \cdot \hat n\f$; otherwise (grazing at \f$v^- \cdot \hat n = 0\f$
/// included) \f$v^+ = v^-\f$ [m/s]. Every \f$\epsilon\f$ in [0, 1] is allowed, both ends included
/// (0: a dead stop along n, 1: a perfect bounce). InvalidInput when m is not positive and finite,
/// v_minus is not finite, n is not a finite unit vector (its length off 1 by more than 1e-9) or
/// \f$\epsilon\f$ is outside [0, 1] or NaN. Handout: Lab 5, section 1.
Vec3 particlePlaneResponse(double m, const Vec3& v_minus, const Vec3& n, double epsilon);

/// The world inverse inertia \f$I^{-1} = R\, I_{body}^{-1} R^T\f$ with \f$R = R(q)\f$ (q normalised).
/// InvalidInput when I_body_inv is not finite or q is zero or not finite. Handout: Lab 5, section 2.
Mat3 inverseInertiaWorld(const Mat3& I_body_inv, const Quat& q);

/// The relative velocity of the touching points, \f$\dot p_A - \dot p_B\f$ with
/// \f$\dot p = v + \omega \times (p - x)\f$ [m/s]. InvalidInput when p is not finite.
/// Handout: Lab 5, section 2.
Vec3 relativeVelocity(const ContactBody& A, const ContactBody& B, const Vec3& p);

/// The inverse effective mass along the unit direction d at p, the denominator of j:
/// \f$K = m_A^{-1} + m_B^{-1} + d \cdot (I_A^{-1}(r_A \times d)) \times r_A + d \cdot (I_B^{-1}(r_B \times d)) \times r_B\f$
/// [1/kg]. InvalidInput when an inverse mass is negative or not finite, or d is not a finite unit
/// vector (its length off 1 by more than 1e-9). Handout: Lab 5, section 2.
double inverseEffectiveMass(const ContactBody& A, const ContactBody& B, const Vec3& p, const Vec3& d);

/// The lecture's impulse magnitude \f$j = -(1 + \epsilon)\, v_{rel}^- / K\f$ with
/// \f$v_{rel}^- = \hat n \cdot (\dot p_A - \dot p_B)\f$ now [N s]. (Negative when the points separate:
/// the caller decides whether to apply it.) InvalidInput when \f$\epsilon\f$ is outside [0, 1] or NaN
/// (above 1 a bounce would gain energy), n is not a finite unit vector, or as relativeVelocity() and
/// inverseEffectiveMass(). Handout: Lab 5, section 2.
double impulseMagnitude(const ContactBody& A, const ContactBody& B, const Vec3& p, const Vec3& n, double epsilon);

/// Applies the impulse J at p to A and -J to B: \f$\Delta v_A = m_A^{-1} J\f$,
/// \f$\Delta \omega_A = I_A^{-1}(r_A \times J)\f$, and the opposite for B (fixed bodies: zero
/// inverses, no change). InvalidInput, with neither body changed, when an inverse mass is negative
/// or not finite, or p or J is not finite. Handout: Lab 5, section 3.
void applyImpulse(ContactBody& A, ContactBody& B, const Vec3& p, const Vec3& J);

/// Coulomb friction at p: the impulse in the tangent plane (normal n) that stops the sliding
/// velocity \f$v_t\f$ of A relative to B, \f$-\frac{|v_t|}{K_t}\hat t\f$ with \f$\hat t = v_t / |v_t|\f$
/// and \f$K_t\f$ = inverseEffectiveMass() along \f$\hat t\f$, shortened to length `j_max` when
/// longer (sliding; \f$j_{max} = \mu j\f$), kept when shorter (sticking). Exactly zero when not
/// sliding (\f$v_t = 0\f$, so no direction \f$\hat t\f$) and when `j_max` = 0 (\f$\mu = 0\f$ or
/// \f$j = 0\f$); `j_max` may be infinite (no bound). [N s] InvalidInput when n is not a finite unit
/// vector or `j_max` is negative or NaN (+infinity is the only non-finite bound), or as
/// relativeVelocity() and inverseEffectiveMass(). Handout: Lab 5, section 4.
Vec3 frictionImpulse(const ContactBody& A, const ContactBody& B, const Vec3& p, const Vec3& n, double j_max);

/// Sequential impulses (Gauss-Seidel, as Bullet and Box2D solve contacts): first applies the
/// impulses the contacts arrive with (warm starting: \f$c.j\,\hat n + c.j_t\f$ at each point,
/// whatever settings.warm_start says). Then sweeps over the contacts in order; each point, with
/// the velocities the sweep has left so far, aims at the velocity target decided before the solve,
/// \f$v_{rel}^+ = -\epsilon\, v_{rel}^-\f$ (v_rel_minus of the contact; 0 when
/// \f$v_{rel}^- \ge\f$ -settings.restitution_threshold), with the correction
/// \f$(v_{target} - v_{rel}) / K\f$ added to its accumulated j and the *total* clamped to
/// \f$j \ge 0\f$ (a sweep may take back what earlier sweeps gave); it applies the change of j,
/// then its friction, accumulated and clamped to \f$|j_t| \le \mu j\f$ with the j just found.
/// Repeats until a whole sweep changes no velocity by more than settings.tolerance (a change
/// \f$\Delta j\f$ along d changes the velocity along d by \f$K \Delta j\f$; normal and friction changes
/// both count) or settings.iterations sweeps. Returns the sweeps made, the last (quiet) one
/// included: no contacts at all take 1.
/// InvalidInput, before any body or contact changes, when a body's inv_mass is negative or not
/// finite, or a contact names a body outside [0, bodies.size()) (as a or b), has a normal n that is
/// not a finite unit vector (length off 1 by more than 1e-9), a point p that is not finite,
/// \f$\epsilon\f$ outside [0, 1] or NaN, \f$\mu\f$ negative or not finite, a v_rel_minus that is
/// not finite, j negative or not finite, or a j_t that is not finite. The message names the contact
/// (or body) and the field. Handout: Lab 5, section 5.
int solveSequential(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const Settings& settings);

/// Simultaneous impulses (Jacobi): each sweep computes every point's correction from the same
/// velocities, aiming at \f$v_{rel}^+ = -\epsilon\, v_{rel}^-\f$ (v_rel_minus of the contact; 0 when
/// \f$v_{rel}^- \ge\f$ -settings.restitution_threshold), with
/// accumulated impulses clamped to \f$j \ge 0\f$ and \f$|j_t| \le \mu j\f$ (a point's friction sees its
/// own normal correction), then applies them all, each scaled by 1/(the largest number of contacts
/// on either of its moving bodies; a fixed body takes no correction and counts none) so that a body
/// resting on several points does not receive several full corrections. Contacts that arrive with
/// j, j_t from the last step (warm starting) apply them first, whatever settings.warm_start says.
/// Repeats until no correction exceeds settings.tolerance (as a velocity change: a correction
/// clamped away changes nothing) or settings.iterations sweeps; every sweep's corrections,
/// the last one's included, reach the bodies, so the momentum each body gained is exactly the
/// accumulated impulses at its points. Returns the sweeps, the last one included: no contacts at
/// all take 1. InvalidInput on the same input as solveSequential(), before anything changes.
/// Handout: Lab 5, section 6.
int solveSimultaneous(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const Settings& settings);

/// The penalty force on A at a touching point (lecture 001): a spring of stiffness k on the depth
/// and a damper d on the normal velocity, \f$F = \max(0,\ k\, depth - d\, v_{rel})\, \hat n\f$ (never pulling)
/// [N], for depth >= 0 and d >= 0: at depth exactly 0 (just touching) the damper alone pushes a point
/// that approaches, and with d = 0 the spring alone acts. InvalidInput when depth or d is negative
/// or not finite, v_rel is not finite, n is not a finite unit vector, or k is not positive and
/// finite. Handout: Lab 5, section 7.
Vec3 penaltyForce(double depth, double v_rel, const Vec3& n, double k, double d);

/// Continuous collision (section 10): how long a fast body moves in a step of size h [s]. `hits`
/// are the times of impact of its sweep against the other bodies (Lab 4's conservative
/// advancement; +infinity for a body it misses), each in [0, h] or +infinity. A hit at exactly 0
/// is a pair already touching, which the contact solver answers: it does not stop the body. With
/// t the earliest hit after 0, the body moves for t + overlap / speed (on into the other body by
/// about `overlap`, so that the next step finds the contact and answers it), at most h; h when no
/// hit comes after 0, or when speed is 0 (the body does not move). `speed` is the bound on how fast
/// any of its points moves [m/s], `overlap` the depth to reach [m]. InvalidInput when h is not
/// positive and finite, speed or overlap is negative or not finite, or a hit is NaN, negative,
/// or past h (naming the hit). Allocates nothing unless it throws. Handout: Lab 5, section 10.
double continuousAdvance(const std::vector<double>& hits, double h, double speed, double overlap);

/// Sleeping (section 12): a body's time spent still after a step of size h [s]. The body is still
/// when its speed \f$|v|\f$ is at most `linear` [m/s] and its angular speed \f$|\omega|\f$ at most
/// `angular` [rad/s], both ends included (a body exactly at a threshold is still); then the timer
/// grows by h, `timer + h`; otherwise it starts again at 0. An island sleeps once every body's
/// timer has reached Settings::sleep_time. InvalidInput, naming the argument, when v or omega is
/// not finite, timer or a threshold is negative or not finite, or h is not positive and finite.
/// Handout: Lab 5, section 12.
double sleepTimer(const Vec3& v, const Vec3& omega, double timer, double h, double linear, double angular);
///@}

// ---------------------------------------------------------------------------------------------
/// \name World
///@{

/// What World::step() measures after each step.
struct Diagnostics {
  double kinetic_energy = 0.0;      ///< \f$\sum \frac12 m |v|^2 + \frac12 \omega \cdot L\f$, moving bodies [J]
  double potential_energy = 0.0;    ///< \f$-\sum m\, g \cdot x\f$, moving bodies [J]
  Vec3 linear_momentum = Vec3::Zero();   ///< \f$\sum P\f$, moving bodies [kg m/s]
  Vec3 angular_momentum = Vec3::Zero();  ///< \f$\sum x \times P + L\f$ about the origin [kg m^2/s]
  double max_penetration = 0.0;     ///< largest contact depth found this step [m]
  int contacts = 0;                 ///< contact points found this step
  int colliding = 0;                ///< of which colliding
  int resting = 0;                  ///< of which resting
  int iterations = 0;               ///< solver sweeps this step (impulses, the resting solver's and the shock propagation's; of each, the most any island took)
  int levels = 0;                   ///< levels the shock propagation solved this step (0: none)
  int islands = 0;                  ///< islands with contacts this step, each solved on its own (1 with Settings::islands off and any contact)
  int largest_island = 0;           ///< contact points of the largest of them
  int asleep = 0;                   ///< bodies asleep after this step (Settings::sleeping)
};

/// Seconds spent in each phase since the World was made (or resetTimers()).
struct PhaseTimes {
  double forces = 0.0;       ///< apply forces [s]
  double broad_phase = 0.0;  ///< candidate pairs [s]
  double narrow_phase = 0.0; ///< manifolds [s]
  double classify = 0.0;     ///< v_rel and kinds [s]
  double respond = 0.0;      ///< impulses or penalty forces [s]
  double resting = 0.0;      ///< the resting-contact solver (Lab 6) [s]
  double integrate = 0.0;    ///< positions and orientations [s]
  double correct = 0.0;      ///< position correction [s]
  double diagnostics = 0.0;  ///< energies and momenta [s]
};

/// A set of bodies and their initial states (scenes below).
struct Scene {
  std::vector<BodyDescription> bodies;  ///< constant descriptions
  std::vector<BodyState> states;        ///< initial states, one per body
};

/// What World::step() hands the resting contacts to when a scene has a resting-contact solver
/// (Lab 6 provides them; Lab 5's World has none and answers resting points with impulses).
class RestingContactSolver {
 public:
  virtual ~RestingContactSolver() = default;
  /// One line naming the solver and its settings, printed with every run.
  virtual std::string describe() const = 0;
  /// True when the solver answers colliding points too, aiming each (Contact::kind Colliding) at
  /// its bounce \f$v_{rel}^+ = -\epsilon\, v_{rel}^-\f$: the World then hands it every point and runs
  /// no impulses, so that impacts and the weight they land on are solved together. False (the
  /// default): the World answers colliding points with impulses first and hands it the others.
  virtual bool bounces() const { return false; }
  /// Changes the velocities of `bodies` over the step h [s] so that the `resting` contacts (indices
  /// into `contacts`: every point that is not colliding, or every point when bounces()) neither
  /// approach nor pull. `bodies` carry the velocities after the applied
  /// forces (gravity, `gravity` [m/s^2]) of this step; `states` are the World's states at the
  /// same moment (Lab 6's acceleration-level formulation needs L). Stores each point's impulse over the step in
  /// Contact::j (and friction in Contact::j_t). Returns the solver's iterations or pivots.
  virtual int solve(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const std::vector<int>& resting,
                    const std::vector<BodyDescription>& descriptions, const std::vector<BodyState>& states,
                    const Vec3& gravity, double h) = 0;
  /// Sub-stepping solvers (Lab 6's soft step) move the bodies while they solve. World::step() calls
  /// this in the integrate phase of every step: a solver whose solve() moved the bodies in this
  /// step writes every moving body's new centre x and orientation q into `states` and returns
  /// true, and the World then integrates nothing itself; otherwise (and by default) it returns
  /// false and the World integrates the velocities.
  virtual bool placeBodies(std::vector<BodyState>& states) {
    (void)states;
    return false;
  }
  /// True when solve() moves the bodies in substeps (placeBodies() then returns true): the World
  /// runs no shock propagation after it, as the substeps have moved the bodies with their velocities.
  virtual bool substeps() const { return false; }
};

/// Rigid bodies with impulse-based collision response.
class World {
 public:
  /// Validates every description, state and setting (InvalidInput naming the body and field).
  /// With a `resting` solver, colliding points get impulses (Settings::method) and resting points
  /// go to it; a step without resting points never calls it.
  World(Scene scene, Settings settings = {}, std::shared_ptr<RestingContactSolver> resting = nullptr);
  /// One step of size h [s] (h > 0): the phases of the file's pipeline, in order.
  void step(double h);

  const std::vector<BodyDescription>& bodies() const { return bodies_; }  ///< the descriptions
  const std::vector<BodyState>& states() const { return states_; }        ///< the states now
  const Settings& settings() const { return settings_; }                  ///< the settings
  /// Settings::toString(); with a resting-contact solver only the settings that act (gravity, broad
  /// phase, continuous, shock propagation, the position correction when on, the impulse method's
  /// when it answers the colliding points), which points the solver answers ("every point (bounces
  /// too): ..." or "colliding points: impulses, resting: ...") and its description.
  std::string describe() const;
  /// Replaces body i's state (validated); wakes its island when it sleeps.
  void setState(int i, const BodyState& state);
  /// True while body i sleeps (Settings::sleeping; fixed bodies never do). InvalidInput when i is not a body.
  bool asleep(int i) const;
  /// Velocity of body i's centre, \f$P/m\f$ (zero when fixed) [m/s]. InvalidInput when i is not a body.
  Vec3 velocity(int i) const;
  /// Angular velocity of body i, \f$I^{-1} L\f$ (zero when fixed) [rad/s]. InvalidInput when i is not a body.
  Vec3 angularVelocity(int i) const;
  /// The deepest overlap between bodies i and j among the last step's contacts (0 when they did
  /// not touch), in either order [m]. InvalidInput when i or j is not a body.
  double depth(int i, int j) const;
  /// The contacts of the last step, as the solver left them.
  const std::vector<Contact>& contacts() const { return contacts_; }
  const Diagnostics& diagnostics() const { return diagnostics_; }  ///< of the last step
  const PhaseTimes& times() const { return times_; }               ///< accumulated phase times
  void resetTimers() { times_ = PhaseTimes{}; }                    ///< zero the phase times
  double time() const { return time_; }                            ///< simulated time [s]

 private:
  void applyForces(double h);
  void findCandidatePairs();
  void computeContacts();
  void classifyContacts();
  void respond(double h);
  void solveRestingContacts(double h);
  // Islands (section 12): union-find over the contacts; the chosen contacts ordered island by
  // island; each island's solve on copies of its bodies and contacts
  int findRoot(int i);
  void findIslands();
  void groupByIsland(const std::vector<int>& chosen);
  // The response's impulses (its sweeps limited by shock_response_iterations when the shock
  // propagation follows), the impulses with every setting as given, the resting-contact solver
  enum class Solver { Response, Impulses, Resting };
  int solveIslands(std::vector<ContactBody>& bodies, Solver solver, bool keep_impulses, double h);
  // Sleeping (section 12): waking the islands awake bodies touch, timers, falling asleep
  bool awakeMoving(int i) const { return !bodies_[i].fixed && !asleep_[i]; }
  // Whether it woke any island
  bool wakeTouchedIslands();
  void wake(int i);
  // The bodies not asleep listed for the broad phase, the sleepers' boxes sorted (sleeping on)
  void listSleepers();
  // Calls visit(body) for every sleeper whose box overlaps `box` (touching included)
  template <class Visit>
  void querySleepers(const Aabb& box, Visit&& visit) const;
  void updateSleep(double h);
  // Shock propagation (section 11): the contacts solved again level by level from the ground up
  void propagateShock(double h);
  // Whether shock propagation runs after the response: on, and neither the penalty method nor a
  // resting solver that substeps()
  bool shockPropagates() const {
    return settings_.shock_propagation && settings_.method != ResponseMethod::Penalty &&
           !(resting_solver_ && resting_solver_->substeps());
  }
  void findLevels();
  void integrate(double h);
  // Continuous collision (section 10): how long body i moves in a step of h
  double sweptStep(int i, double h);
  // Whether the narrow phase found a contact between bodies i and j this step
  bool touching(int i, int j) const;
  void correctPositions(double h);
  void computeDiagnostics();
  void loadContactBodies();
  void storeContactBodies();
  void applyPenaltyForces(const std::vector<int>& chosen, double h);
  void requireBody(int i) const;

  std::vector<BodyDescription> bodies_;
  std::vector<BodyState> states_;
  Settings settings_;
  Settings response_settings_;  // settings_ with the response's sweeps (shock_response_iterations)
  std::vector<ContactBody> contact_bodies_;
  std::vector<BoxPair> pairs_;
  std::vector<Contact> contacts_;
  // Last step's impulses in the contacts' order (a pair's points together), and the pairs' runs
  // of them sorted by (A, B) for binary search: refilled in place
  struct LastImpulse {
    std::uint32_t id;
    Vec3 p;
    double j;
    Vec3 j_t;
  };
  struct LastPair {
    std::uint64_t key;  // A in the high 32 bits, B in the low
    int begin, end;     // its points in last_impulses_
  };
  static std::uint64_t pairKey(int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
  }
  // The runs of last_pairs_ with this key: a pair may have two (lastImpulse() searches both)
  std::pair<const LastPair*, const LastPair*> lastRuns(std::uint64_t key) const;
  const LastImpulse* lastImpulse(const Contact& c, std::pair<const LastPair*, const LastPair*> runs) const;
  std::vector<LastImpulse> last_impulses_;
  std::vector<LastPair> last_pairs_;
  std::vector<int> bounded_, planes_;
  std::vector<Aabb> boxes_;
  std::unique_ptr<IncrementalBroadPhase> broad_phase_;
  std::shared_ptr<RestingContactSolver> resting_solver_;
  std::vector<int> chosen_;  // the contacts a solve takes (indices into contacts_)
  std::vector<Mat3> inv_inertia_body_;     // I_body^-1 once, 0 when fixed
  PairList found_;                         // the broad phase's pairs, refilled in place
  std::vector<int> resting_;
  // Continuous collision: each body's bounding and inner radius (0 for a plane), its motion at the
  // step's start, its time to move this step; a fast body's times of impact
  std::vector<double> radius_, inner_;
  std::vector<Motion> motions_;
  std::vector<double> advance_, hits_;
  std::vector<int> reachable_;  // the bodies a fast body's sweep may reach (broad phase ids)
  double largest_travel_ = 0.0;  // the farthest any body's point moves this step [m]
  // The position correction's points and the bodies' moves and turns, refilled in place
  struct CorrectionPoint {
    int a, b;
    Vec3 n, r_a, r_b;
    Vec3 turn_a, turn_b;  // I^-1 (r x n): the turn of each body per unit push along n
    double separation;    // n . (p_A - p_B) after the step's motion, before any correction [m]
    double target;        // the separation this step's correction reaches for [m]
    double inv_k;         // 1 / (n . K n), the push that opens the separation by 1 m [kg]
    double pushed;        // the push so far, >= 0: a later sweep may take back what an earlier overdid
  };
  std::vector<CorrectionPoint> correction_;
  // Shock propagation: each body's level (0 fixed, -1 not carried by a fixed body), the contact
  // graph (each body's neighbours from first_[i] to first_[i + 1]), the bodies and contacts by
  // level (the bodies in queue_, breadth-first; level L from *_level_start_[L] to [L + 1]), the bodies with the lower levels held
  // still, and one level's contacts as the solver takes them
  std::vector<int> level_, first_, neighbours_, queue_;
  std::vector<int> body_level_start_, contacts_by_level_, contact_level_start_;
  std::vector<ContactBody> held_;
  std::vector<int> level_points_;
  std::vector<Vec3> shift_, turn_;
  // Islands: the union-find forest over the bodies (parent, size of each root's tree), each
  // contact's island, the chosen contacts of a solve by island (island g from group_start_[g]
  // to [g + 1]), and one island's bodies and contacts as its solver takes them (local indices;
  // island_members_ the World's index of each local body, local_ the reverse, -1 outside)
  std::vector<int> parent_, tree_size_, island_of_, contact_island_, island_count_, group_next_;
  // Each island: whether it rests on a fixed body (a contact with one); the scene's the same
  std::vector<char> island_carried_;
  bool carried_ = false;
  std::vector<int> group_, group_start_;
  std::vector<int> island_members_, local_, island_points_, island_contact_index_;
  std::vector<ContactBody> island_bodies_;
  std::vector<Contact> island_contacts_;
  std::vector<BodyDescription> island_descriptions_;
  std::vector<BodyState> island_states_;
  int island_total_ = 0;  // islands this step, bodies without contacts included
  // Sleeping: each body's time still [s], whether it sleeps, and its island's label while it does
  // (the island's root when it fell asleep); the contacts of the sleeping islands, kept to warm
  // start them when they wake
  std::vector<double> still_time_;
  std::vector<char> asleep_;
  std::vector<int> sleep_label_;
  std::vector<Contact> sleeping_contacts_;
  // The broad phase's bodies, every bounded one not asleep (box k of the incremental tree is
  // listed_[k]), and the sleepers' boxes sorted by min x, each with the largest max x of it and
  // those before it: both made again (and the tree cleared) when a body falls asleep or wakes
  struct SleeperBox {
    Aabb box;
    double reach;
    int body;
  };
  std::vector<int> listed_;
  std::vector<SleeperBox> sleepers_;
  bool sleepers_changed_ = true;
  std::vector<double> island_still_;
  Diagnostics diagnostics_;
  PhaseTimes times_;
  double time_ = 0.0;
};
///@}

// ---------------------------------------------------------------------------------------------
/// \name Scenes for tests and demos
/// Ground: the plane z <= 0. Gravity comes from Settings.
///@{

/// A sphere (mass 1 kg, radius 0.1 m) whose lowest point is `height` [m] above the ground, at rest.
Scene bouncingBall(double height, double epsilon);
/// n touching spheres (1 kg, radius 0.1 m) in a row along x on no ground, epsilon 1, the first
/// moving towards the others at v0 [m/s]. (Use zero gravity.)
Scene newtonsCradle(int n, double v0);
/// A box (1 kg, 0.4 x 0.4 x 0.2 m) resting on the ground, sliding along x at v0 [m/s], with mu.
Scene slidingBox(double v0, double mu);
/// A sphere (1 kg, radius 0.1 m) touching the ground, thrown along x at v0 [m/s] without spin.
Scene thrownSphere(double v0, double mu);
/// A container (ground plus four fixed walls, 2 x 2 m) and `count` boxes and spheres above it,
/// placed on a grid without overlap with small random velocities; the same seed gives the same rain.
Scene boxRain(int count, std::uint64_t seed);
/// `scene` with every moving body's start shifted by up to `shift` [m] in x and y (uniform,
/// seeded; seed 0 returns the scene as it is). Many-body scenes are chaotic: a nanometre moves
/// where a stack sways to by centimetres, as another order of the same sums does, so one run is
/// one draw and a fair figure is a median over shifted runs. InvalidInput for a shift that is
/// negative or not finite.
Scene shakenScene(const Scene& scene, std::uint64_t seed, double shift = 1e-9);
///@}

}  // namespace physlab
