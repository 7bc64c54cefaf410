// Lab 5, sections 5-6: many contact points, sequentially (Gauss-Seidel) and simultaneously
// (Jacobi), with accumulated impulses, clamping and warm starting.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab {

namespace {

// The part of an accumulated friction impulse inside the cone |j_t| <= j_max.
Vec3 clampToCone(const Vec3& j_t, double j_max) {
  const double length2 = j_t.squaredNorm();
  return length2 > j_max * j_max ? Vec3(j_t * (j_max / std::sqrt(length2))) : j_t;
}

constexpr double kUnlimited = std::numeric_limits<double>::infinity();

// InvalidInput naming what is wrong with an element of a solver's input, built only on failure.
[[noreturn, gnu::cold, gnu::noinline]] void refuse(const char* solver, const char* element, std::size_t index,
                                                   const char* what) {
  throw InvalidInput(std::string(solver) + " " + element + " " + std::to_string(index) + " " + what);
}

// Every check the sweeps' functions would make, once and before any body changes, so that a
// refused input leaves bodies and contacts as they were: O(bodies + contacts), no strings.
void requireSolvable(const std::vector<ContactBody>& bodies, const std::vector<Contact>& contacts, const char* solver) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!(bodies[i].inv_mass >= 0.0 && bodies[i].inv_mass < kUnlimited)) {
      refuse(solver, "body", i, "inverse mass inv_mass must be non-negative and finite");
    }
  }
  const int count = static_cast<int>(bodies.size());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    if (c.a < 0 || c.a >= count) refuse(solver, "contact", k, "body index a is not a body");
    if (c.b < 0 || c.b >= count) refuse(solver, "contact", k, "body index b is not a body");
    if (!(std::abs(c.n.norm() - 1.0) <= 1e-9)) refuse(solver, "contact", k, "normal n must be a finite unit vector");
    if (firstNonFinite(c.p) >= 0) refuse(solver, "contact", k, "point p must be finite");
    if (!(c.epsilon >= 0.0 && c.epsilon <= 1.0)) refuse(solver, "contact", k, "restitution epsilon must be in [0, 1]");
    if (!(c.mu >= 0.0 && c.mu < kUnlimited)) refuse(solver, "contact", k, "friction mu must be non-negative and finite");
    if (!std::isfinite(c.v_rel_minus)) refuse(solver, "contact", k, "v_rel_minus must be finite");
    if (!(c.j >= 0.0 && c.j < kUnlimited)) refuse(solver, "contact", k, "impulse j must be non-negative and finite");
    if (firstNonFinite(c.j_t) >= 0) refuse(solver, "contact", k, "friction impulse j_t must be finite");
  }
}

// The point's lever arms and its inverse effective mass matrix, fixed while the velocities change:
// an impulse J at p changes the relative velocity of the touching points by K J, with
// K = (m_A^-1 + m_B^-1) 1 - [r_A]x I_A^-1 [r_A]x - [r_B]x I_B^-1 [r_B]x ([r]x y = r x y).
void prepare(const ContactBody& A, const ContactBody& B, Contact& c) {
  c.r_a = c.p - A.x;
  c.r_b = c.p - B.x;
  const auto cross = [](const Vec3& r) {
    Mat3 m;
    m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
    return m;
  };
  const Mat3 ra = cross(c.r_a), rb = cross(c.r_b);
  c.K_matrix = (A.inv_mass + B.inv_mass) * Mat3::Identity() - ra * A.I_inv_world * ra - rb * B.I_inv_world * rb;
}

// relativeVelocity() with the prepared lever arms.
Vec3 relativeVelocityAt(const ContactBody& A, const ContactBody& B, const Contact& c) {
  return (A.v + A.omega.cross(c.r_a)) - (B.v + B.omega.cross(c.r_b));
}

// applyImpulse() with the prepared lever arms (the input was checked before the first change).
void applyAt(ContactBody& A, ContactBody& B, const Contact& c, const Vec3& J) {
  A.v += A.inv_mass * J;
  A.omega += A.I_inv_world * c.r_a.cross(J);
  B.v -= B.inv_mass * J;
  B.omega -= B.I_inv_world * c.r_b.cross(J);
}

// frictionImpulse() without a bound, for the relative velocity u, with the prepared K: the
// impulse along -t that stops the sliding speed |u_t|, K_t = t . K t.
Vec3 stopSliding(const Contact& c, const Vec3& u) {
  const Vec3 u_t = u - u.dot(c.n) * c.n;
  const double speed2 = u_t.squaredNorm();
  if (speed2 == 0.0) return Vec3::Zero();
  // -(|u_t| / K_t) t with t = u_t / |u_t| and K_t = u_t . K u_t / |u_t|^2
  return -(speed2 / u_t.dot(c.K_matrix * u_t)) * u_t;
}

}  // namespace

int solveSequential(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const Settings& settings) {
  // Refuse bad bodies and contacts before anything changes
  requireSolvable(bodies, contacts, "solveSequential");
  // Prepare once per solve what no sweep changes: each point's lever arms and K matrix
  for (Contact& c : contacts) prepare(bodies[c.a], bodies[c.b], c);
  // Warm start: apply the impulses carried over from the last step
  for (const Contact& c : contacts) applyAt(bodies[c.a], bodies[c.b], c, c.j * c.n + c.j_t);
  int sweeps = 0;
  while (sweeps < settings.iterations) {
    ++sweeps;
    double largest = 0.0;
    for (Contact& c : contacts) {
      ContactBody &A = bodies[c.a], &B = bodies[c.b];
      // Aim at v_rel+ = -epsilon v_rel-, decided before the solve (resting points aim at 0), and
      // clamp the accumulated total, not the correction: j >= 0, so a sweep may take some back
      const double v_target = c.v_rel_minus < -settings.restitution_threshold ? -c.epsilon * c.v_rel_minus : 0.0;
      const Vec3 u = relativeVelocityAt(A, B, c);
      const Vec3 Kn = c.K_matrix * c.n;
      const double K = c.n.dot(Kn);
      const double j = std::max(0.0, c.j + (v_target - c.n.dot(u)) / K);
      const double dj = j - c.j;
      double change = K * std::abs(dj);
      c.j = j;
      Vec3 J = dj * c.n;
      // Stop the sliding left after this change (u + K n dj: the bodies move only once, below),
      // keeping the accumulated friction inside the cone |j_t| <= mu j of the normal impulse just
      // found (a cone of radius 0 takes everything back)
      if (c.mu > 0.0) {
        const Vec3 j_t = c.j > 0.0 ? clampToCone(c.j_t + stopSliding(c, u + dj * Kn), c.mu * c.j) : Vec3::Zero();
        const Vec3 dj_t = j_t - c.j_t;
        J += dj_t;
        c.j_t = j_t;
        const double size = dj_t.norm();
        if (size > 0.0) change = std::max(change, dj_t.dot(c.K_matrix * dj_t) / size);
      }
      // Apply the point's normal and friction changes together
      applyAt(A, B, c, J);
      largest = std::max(largest, change);
    }
    // Converged when no point's velocity changed by more than the tolerance in a whole sweep
    if (largest <= settings.tolerance) break;
  }
  return sweeps;
}

int solveSimultaneous(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const Settings& settings) {
  // Refuse bad bodies and contacts before anything changes
  requireSolvable(bodies, contacts, "solveSimultaneous");
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
