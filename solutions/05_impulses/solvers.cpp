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

// [r]x, the matrix of y -> r x y.
Mat3 crossMatrix(const Vec3& r) {
  Mat3 m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

// The point's lever arms and its inverse effective mass matrix, fixed while the velocities change:
// an impulse J at p changes the relative velocity of the touching points by K J, with
// K = (m_A^-1 + m_B^-1) 1 - [r_A]x I_A^-1 [r_A]x - [r_B]x I_B^-1 [r_B]x ([r]x y = r x y).
void prepare(const ContactBody& A, const ContactBody& B, Contact& c) {
  c.r_a = c.p - A.x;
  c.r_b = c.p - B.x;
  const Mat3 ra = crossMatrix(c.r_a), rb = crossMatrix(c.r_b);
  c.K_matrix = (A.inv_mass + B.inv_mass) * Mat3::Identity() - ra * A.I_inv_world * ra - rb * B.I_inv_world * rb;
}

// One point as the sweeps read it, built once per solve from the prepared contact and packed
// together (as Bullet's solver rows and Box2D's contact points are): everything a sweep needs and
// nothing it does not, so that it reads no Contact and no ContactBody but the velocities.
struct SweepPoint {
  int a = 0, b = 0;                           // the bodies
  bool a_moves = false, b_moves = false;      // has mass or inertia: a fixed body takes no impulse
  double v_target = 0.0;                      // -epsilon v_rel-, or 0 at and above -threshold [m/s]
  double mu = 0.0;
  double j = 0.0;                             // accumulated normal impulse [N s]
  Vec3 j_t = Vec3::Zero();                    // accumulated friction impulse [N s]
  Vec3 n = Vec3::UnitZ();
  Vec3 r_a = Vec3::Zero(), r_b = Vec3::Zero();
  double K_nn = 0.0;                          // n . K n [1/kg]
  double normal_mass = 0.0;                   // 1 / (n . K n) [kg]
  Vec3 K_n = Vec3::Zero();                    // K n: u's change per unit normal impulse
  Mat3 K = Mat3::Zero();                      // the contact's K_matrix
  double inv_mass_a = 0.0, inv_mass_b = 0.0;  // [1/kg]
  Mat3 turn_a = Mat3::Zero(), turn_b = Mat3::Zero();  // I^-1 [r]x: an impulse J turns A by turn_a J
  Vec3 u_fixed = Vec3::Zero();                // the point velocity of B when B cannot move

  SweepPoint(const ContactBody& A, const ContactBody& B, const Contact& c, const Settings& settings)
      : a(c.a), b(c.b), a_moves(moves(A)), b_moves(moves(B)),
        v_target(c.v_rel_minus < -settings.restitution_threshold ? -c.epsilon * c.v_rel_minus : 0.0), mu(c.mu),
        j(c.j), j_t(c.j_t), n(c.n), r_a(c.r_a), r_b(c.r_b), K_n(c.K_matrix * c.n), K(c.K_matrix),
        inv_mass_a(A.inv_mass), inv_mass_b(B.inv_mass), turn_a(A.I_inv_world * crossMatrix(c.r_a)),
        turn_b(B.I_inv_world * crossMatrix(c.r_b)) {
    K_nn = n.dot(K_n);
    normal_mass = 1.0 / K_nn;
    if (!b_moves) u_fixed = B.v + B.omega.cross(r_b);
  }

  static bool moves(const ContactBody& body) { return body.inv_mass > 0.0 || !body.I_inv_world.isZero(0.0); }

  // u = p_A' - p_B', the relative velocity of the touching points
  Vec3 relativeVelocity(const std::vector<ContactBody>& bodies) const {
    const ContactBody &A = bodies[a], &B = bodies[b];
    if (!b_moves) return (A.v + A.omega.cross(r_a)) - u_fixed;
    return (A.v + A.omega.cross(r_a)) - (B.v + B.omega.cross(r_b));
  }

  // J at the point on A, -J on B: applyImpulse() with the prepared turns
  void apply(std::vector<ContactBody>& bodies, const Vec3& J) const {
    if (a_moves) {
      bodies[a].v += inv_mass_a * J;
      bodies[a].omega += turn_a * J;
    }
    if (b_moves) {
      bodies[b].v -= inv_mass_b * J;
      bodies[b].omega -= turn_b * J;
    }
  }
};

}  // namespace

int solveSequential(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const Settings& settings) {
  // Refuse bad bodies and contacts before anything changes
  requireSolvable(bodies, contacts, "solveSequential");
  // Prepare once per solve what no sweep changes: each point's lever arms and K matrix
  std::vector<SweepPoint> points;
  points.reserve(contacts.size());
  for (Contact& c : contacts) {
    prepare(bodies[c.a], bodies[c.b], c);
    points.emplace_back(bodies[c.a], bodies[c.b], c, settings);
  }
  // Warm start: apply the impulses carried over from the last step
  for (const SweepPoint& c : points) c.apply(bodies, c.j * c.n + c.j_t);
  int sweeps = 0;
  while (sweeps < settings.iterations) {
    ++sweeps;
    double largest = 0.0, stopped2 = 0.0;  // the largest velocity change; the largest |u_t|^2 stopped
    for (SweepPoint& c : points) {
      // Aim at v_rel+ = -epsilon v_rel-, decided before the solve (resting points aim at 0), and
      // clamp the accumulated total, not the correction: j >= 0, so a sweep may take some back
      const Vec3 u = c.relativeVelocity(bodies);
      const double j = std::max(0.0, c.j + (c.v_target - c.n.dot(u)) * c.normal_mass);
      const double dj = j - c.j;
      largest = std::max(largest, c.K_nn * std::abs(dj));
      c.j = j;
      Vec3 J = dj * c.n;
      // Stop the sliding left after this change (u + K n dj: the bodies move only once, below),
      // keeping the accumulated friction inside the cone |j_t| <= mu j of the normal impulse just
      // found (a cone of radius 0 takes everything back)
      if (c.mu > 0.0) {
        Vec3 j_t = Vec3::Zero();
        bool inside = false;
        if (c.j > 0.0) {
          // -(|u_t| / K_t) t with t = u_t / |u_t| and K_t = u_t . K u_t / |u_t|^2
          const Vec3 w = u + dj * c.K_n;
          const Vec3 u_t = w - w.dot(c.n) * c.n;
          const double speed2 = u_t.squaredNorm();
          j_t = speed2 > 0.0 ? Vec3(c.j_t - (speed2 / u_t.dot(c.K * u_t)) * u_t) : c.j_t;
          const double j_max = c.mu * c.j, length2 = j_t.squaredNorm();
          if (length2 > j_max * j_max) {
            j_t *= j_max / std::sqrt(length2);
          } else {
            // Inside the cone the change stops the sliding: along itself it changes the velocity
            // by the whole |u_t|, compared once per sweep (no square root per point)
            inside = true;
            stopped2 = std::max(stopped2, speed2);
          }
        }
        const Vec3 dj_t = j_t - c.j_t;
        J += dj_t;
        c.j_t = j_t;
        // Cut by the cone, it changes the velocity along itself by dj_t . K dj_t / |dj_t|
        const double size = inside ? 0.0 : dj_t.norm();
        if (size > 0.0) largest = std::max(largest, dj_t.dot(c.K * dj_t) / size);
      }
      // Apply the point's normal and friction changes together
      c.apply(bodies, J);
    }
    // Converged when no point's velocity changed by more than the tolerance in a whole sweep
    if (std::max(largest, std::sqrt(stopped2)) <= settings.tolerance) break;
  }
  for (std::size_t k = 0; k < contacts.size(); ++k) {  // the accumulated impulses, reported
    contacts[k].j = points[k].j;
    contacts[k].j_t = points[k].j_t;
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
