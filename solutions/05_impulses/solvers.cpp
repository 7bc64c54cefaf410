// Lab 5, sections 5-6: many contact points, sequentially (Gauss-Seidel) and simultaneously
// (Jacobi), with accumulated impulses, clamping and warm starting.
#include <algorithm>
#include <limits>

#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab {

namespace {

// The part of an accumulated friction impulse inside the cone |j_t| <= j_max.
Vec3 clampToCone(const Vec3& j_t, double j_max) {
  const double length = j_t.norm();
  return length > j_max ? Vec3(j_t * (j_max / length)) : j_t;
}

constexpr double kUnlimited = std::numeric_limits<double>::infinity();

}  // namespace

int solveSequential(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const Settings& settings) {
  // Warm start: apply the impulses carried over from the last step
  for (const Contact& c : contacts) applyImpulse(bodies[c.a], bodies[c.b], c.p, c.j * c.n + c.j_t);
  int sweeps = 0;
  while (sweeps < settings.iterations) {
    ++sweeps;
    double largest = 0.0;
    for (Contact& c : contacts) {
      ContactBody &A = bodies[c.a], &B = bodies[c.b];
      // Aim at v_rel+ = -epsilon v_rel-, decided before the solve (resting points aim at 0), and
      // clamp the accumulated total, not the correction: j >= 0, so a sweep may take some back
      const double v_target = c.v_rel_minus < -settings.restitution_threshold ? -c.epsilon * c.v_rel_minus : 0.0;
      const double v_rel = c.n.dot(relativeVelocity(A, B, c.p));
      const double K = inverseEffectiveMass(A, B, c.p, c.n);
      const double j = std::max(0.0, c.j + (v_target - v_rel) / K);
      applyImpulse(A, B, c.p, (j - c.j) * c.n);
      double change = K * std::abs(j - c.j);
      c.j = j;
      // Stop the sliding, keeping the accumulated friction inside the cone |j_t| <= mu j of the
      // normal impulse just found
      if (c.mu > 0.0) {
        const Vec3 j_t = clampToCone(c.j_t + frictionImpulse(A, B, c.p, c.n, kUnlimited), c.mu * c.j);
        const Vec3 dj_t = j_t - c.j_t;
        applyImpulse(A, B, c.p, dj_t);
        c.j_t = j_t;
        const double size = dj_t.norm();
        if (size > 0.0) change = std::max(change, size * inverseEffectiveMass(A, B, c.p, dj_t / size));
      }
      largest = std::max(largest, change);
    }
    // Converged when no point's velocity changed by more than the tolerance in a whole sweep
    if (largest <= settings.tolerance) break;
  }
  return sweeps;
}

int solveSimultaneous(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const Settings& settings) {
  // Count the points on each moving body, to split a body's correction between them
  std::vector<int> points_on(bodies.size(), 0);
  for (const Contact& c : contacts) {
    if (bodies[c.a].inv_mass > 0.0) ++points_on[c.a];
    if (bodies[c.b].inv_mass > 0.0) ++points_on[c.b];
  }
  // Warm start: apply the impulses carried over from the last step
  for (const Contact& c : contacts) applyImpulse(bodies[c.a], bodies[c.b], c.p, c.j * c.n + c.j_t);

  std::vector<double> delta_j(contacts.size());
  std::vector<Vec3> delta_j_t(contacts.size());
  std::vector<ContactBody> before;
  int sweeps = 0;
  while (sweeps < settings.iterations) {
    ++sweeps;
    // Every point sees the same velocities: those at the start of the sweep
    before = bodies;
    double largest = 0.0;
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      Contact& c = contacts[k];
      ContactBody A = before[c.a], B = before[c.b];
      const double share = 1.0 / std::max({1, points_on[c.a], points_on[c.b]});
      // Aim at v_rel+ = -epsilon v_rel- (resting points aim at 0), keeping the accumulated j >= 0
      const double v_target = c.v_rel_minus < -settings.restitution_threshold ? -c.epsilon * c.v_rel_minus : 0.0;
      const double v_rel = c.n.dot(relativeVelocity(A, B, c.p));
      const double K = inverseEffectiveMass(A, B, c.p, c.n);
      const double j = std::max(0.0, c.j + share * (v_target - v_rel) / K);
      delta_j[k] = j - c.j;
      c.j = j;
      // Stop the sliding, keeping the accumulated friction inside the cone |j_t| <= mu j; it
      // sees this point's own normal correction (Jacobi across points, not within one)
      delta_j_t[k] = Vec3::Zero();
      if (c.mu > 0.0) {
        applyImpulse(A, B, c.p, delta_j[k] * c.n);
        const Vec3 j_t = clampToCone(c.j_t + share * frictionImpulse(A, B, c.p, c.n, kUnlimited), c.mu * c.j);
        delta_j_t[k] = j_t - c.j_t;
        c.j_t = j_t;
      }
      largest = std::max(largest, K * (std::abs(delta_j[k]) + delta_j_t[k].norm()));
    }
    // Apply every correction at once
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const Contact& c = contacts[k];
      applyImpulse(bodies[c.a], bodies[c.b], c.p, delta_j[k] * c.n + delta_j_t[k]);
    }
    if (largest <= settings.tolerance) break;
  }
  return sweeps;
}

}  // namespace physlab
