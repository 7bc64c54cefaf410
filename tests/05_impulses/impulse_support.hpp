// Helpers of the Lab 5 tests: random colliding pairs, and momenta and energies computed here,
// apart from the student's code.
#pragma once

#include <algorithm>

#include "physlab/world.hpp"
#include "support.hpp"

namespace physlab::test {

/// Two bodies touching at p with normal n (from B to A), approaching, with their masses and
/// world inertias kept for the oracles.
struct RandomPair {
  ContactBody A, B;
  double m_a = 1.0, m_b = 1.0;
  Mat3 I_a = Mat3::Identity(), I_b = Mat3::Identity();  // world inertia tensors (zero when fixed)
  Vec3 p = Vec3::Zero(), n = Vec3::UnitZ();
};

/// A symmetric positive definite tensor with principal moments in [0.2, 2] along random axes.
inline Mat3 randomInertiaTensor() {
  const Mat3 R = randomRotation();
  return R * Vec3(uniform(0.2, 2.0), uniform(0.2, 2.0), uniform(0.2, 2.0)).asDiagonal() * R.transpose();
}

inline void randomBody(ContactBody& body, double& m, Mat3& I) {
  m = uniform(0.2, 5.0);
  I = randomInertiaTensor();
  body.x = randomVec3(1.0);
  body.v = randomVec3(2.0);
  body.omega = randomVec3(2.0);
  body.inv_mass = 1.0 / m;
  body.I_inv_world = I.inverse();
}

/// Random masses, inertias, poses and velocities; B fixed when asked. The velocities are
/// reversed when needed so that the points approach (v_rel < 0).
inline RandomPair randomPair(bool b_fixed = false) {
  RandomPair pair;
  randomBody(pair.A, pair.m_a, pair.I_a);
  randomBody(pair.B, pair.m_b, pair.I_b);
  if (b_fixed) {
    pair.B.v = pair.B.omega = Vec3::Zero();
    pair.B.inv_mass = 0.0;
    pair.B.I_inv_world = Mat3::Zero();
    pair.m_b = 0.0;
    pair.I_b = Mat3::Zero();
  }
  pair.p = randomVec3(1.0);
  pair.n = randomVec3(1.0).normalized();
  if (pair.n.dot(pair.A.v + pair.A.omega.cross(pair.p - pair.A.x) - pair.B.v - pair.B.omega.cross(pair.p - pair.B.x)) > 0) {
    pair.A.v = -pair.A.v;
    pair.A.omega = -pair.A.omega;
    pair.B.v = -pair.B.v;
    pair.B.omega = -pair.B.omega;
  }
  return pair;
}

/// v_rel = n . (pdot_A - pdot_B), computed here.
inline double vRel(const RandomPair& s) {
  const Vec3 pdot_a = s.A.v + s.A.omega.cross(s.p - s.A.x), pdot_b = s.B.v + s.B.omega.cross(s.p - s.B.x);
  return s.n.dot(pdot_a - pdot_b);
}

inline Vec3 linearMomentum(const RandomPair& s) { return s.m_a * s.A.v + s.m_b * s.B.v; }

/// Angular momentum about the world origin: x x m v + I omega, both bodies.
inline Vec3 angularMomentum(const RandomPair& s) {
  return s.A.x.cross(s.m_a * s.A.v) + s.I_a * s.A.omega + s.B.x.cross(s.m_b * s.B.v) + s.I_b * s.B.omega;
}

inline double kineticEnergy(const RandomPair& s) {
  return 0.5 * (s.m_a * s.A.v.squaredNorm() + s.A.omega.dot(s.I_a * s.A.omega) + s.m_b * s.B.v.squaredNorm() +
                s.B.omega.dot(s.I_b * s.B.omega));
}

// ---------------------------------------------------------------------------------------------
// Oracles of the single-contact formulas, written here from world.hpp apart from the student's
// code, so that a solver's test does not trust the student's helpers.

/// pdot_A - pdot_B at p, pdot = v + omega x (p - x).
inline Vec3 oracleRelativeVelocity(const ContactBody& A, const ContactBody& B, const Vec3& p) {
  return A.v + A.omega.cross(p - A.x) - B.v - B.omega.cross(p - B.x);
}

/// K along the unit direction d: 1/m_A + 1/m_B + d . (I_A^-1 (r_A x d)) x r_A + (same for B).
inline double oracleK(const ContactBody& A, const ContactBody& B, const Vec3& p, const Vec3& d) {
  const Vec3 r_a = p - A.x, r_b = p - B.x;
  return A.inv_mass + B.inv_mass + d.dot((A.I_inv_world * r_a.cross(d)).cross(r_a)) +
         d.dot((B.I_inv_world * r_b.cross(d)).cross(r_b));
}

/// J to A and -J to B at p.
inline void oracleApply(ContactBody& A, ContactBody& B, const Vec3& p, const Vec3& J) {
  A.v += A.inv_mass * J;
  A.omega += A.I_inv_world * (p - A.x).cross(J);
  B.v -= B.inv_mass * J;
  B.omega -= B.I_inv_world * (p - B.x).cross(J);
}

/// The friction impulse that stops the slip along t = v_t / |v_t|, at most j_max long.
inline Vec3 oracleFriction(const ContactBody& A, const ContactBody& B, const Vec3& p, const Vec3& n, double j_max) {
  const Vec3 v = oracleRelativeVelocity(A, B, p), v_t = v - v.dot(n) * n;
  if (v_t.norm() == 0.0) return Vec3::Zero();
  const Vec3 t = v_t.normalized();
  return -std::min(v_t.norm() / oracleK(A, B, p, t), j_max) * t;
}

/// j_t shortened to length j_max when longer.
inline Vec3 oracleClamp(const Vec3& j_t, double j_max) {
  return j_t.norm() > j_max ? Vec3(j_t * (j_max / j_t.norm())) : j_t;
}

/// A random pair (both bodies moving) whose points approach at least at 0.3 m/s: redrawn until
/// so, so that every seed gives a collision well above the solvers' tolerance.
inline RandomPair approachingPair() {
  RandomPair s;
  do {
    s = randomPair();
  } while (vRel(s) > -0.3);
  return s;
}

/// Scales every velocity of the pair so that v_rel becomes `target` (< 0).
inline void scaleToApproach(RandomPair& s, double target) {
  const double f = target / vRel(s);
  s.A.v *= f;
  s.A.omega *= f;
  s.B.v *= f;
  s.B.omega *= f;
}

/// Distance between two bodies' velocities, |dv| + |domega|.
inline double velocityDistance(const ContactBody& X, const ContactBody& Y) {
  return (X.v - Y.v).norm() + (X.omega - Y.omega).norm();
}

}  // namespace physlab::test
