// Helpers of the Lab 5 tests: random colliding pairs, and momenta and energies computed here,
// apart from the student's code.
#pragma once

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

}  // namespace physlab::test
