// Lab 5, sections 1-3: the particle-plane impulse, the rigid impulse magnitude j, and applying it.
#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab {

Vec3 particlePlaneResponse(double m, const Vec3& v_minus, const Vec3& n, double epsilon) {
  // Refuse input without physical meaning before computing anything
  // TODO(student): requirePositive(m, ...), requireFinite(v_minus, ...), requireUnit(n, ...) and
  // TODO(student): requireInRange(epsilon, 0, 1, ...) from physlab/error.hpp, each naming its argument ("mass m", ...).
  // Leave a particle that does not approach the plane alone
  // TODO(student): v_n = v_minus.dot(n); when v_n >= 0 return v_minus unchanged.
  // Reverse and scale the normal velocity with the impulse j = -(1 + epsilon) m v- . n
  // TODO(student): j = -(1 + epsilon) * m * v_n; return v_minus + (j / m) * n.
  notImplemented("particlePlaneResponse", "Lab 5 handout, section 1", m, v_minus, n, epsilon);
}

Mat3 inverseInertiaWorld(const Mat3& I_body_inv, const Quat& q) {
  // Refuse a NaN inverse inertia and an orientation that is zero or not finite
  // TODO(student): requireFinite(I_body_inv, ...) and requirePositive(q.norm(), ...), naming "I_body_inv" and "orientation q".
  // Rotate the body-frame inverse inertia into the world: I^-1 = R I_body^-1 R^T
  // TODO(student): R = q.normalized().toRotationMatrix(); return R * I_body_inv * R.transpose().
  notImplemented("inverseInertiaWorld", "Lab 5 handout, section 2", I_body_inv, q);
}

Vec3 relativeVelocity(const ContactBody& A, const ContactBody& B, const Vec3& p) {
  // Refuse a point that is not finite
  // TODO(student): requireFinite(p, "... point p").
  // Velocity of each touching point: pdot = v + omega x r
  // TODO(student): r_a = p - A.x, r_b = p - B.x; return (A.v + A.omega x r_a) - (B.v + B.omega x r_b).
  notImplemented("relativeVelocity", "Lab 5 handout, section 2", A, B, p);
}

double inverseEffectiveMass(const ContactBody& A, const ContactBody& B, const Vec3& p, const Vec3& d) {
  // Refuse negative or non-finite inverse masses and a direction that is not a unit vector
  // TODO(student): requireNonNegative(A.inv_mass, "... body A inverse mass ..."), the same for B; requireUnit(d, "... direction d").
  // Add the linear and the rotational terms of both bodies
  // TODO(student): A.inv_mass + B.inv_mass + d . ((A.I_inv_world (r_a x d)) x r_a) + the same for B.
  notImplemented("inverseEffectiveMass", "Lab 5 handout, section 2", A, B, p, d);
}

double impulseMagnitude(const ContactBody& A, const ContactBody& B, const Vec3& p, const Vec3& n, double epsilon) {
  // Refuse epsilon outside [0, 1] (above 1 a bounce gains energy) and a normal that is not a unit vector
  // TODO(student): requireInRange(epsilon, 0, 1, "... restitution epsilon") and requireUnit(n, "... normal n").
  // Relative normal velocity of the touching points before the impulse
  // TODO(student): v_rel = n . relativeVelocity(A, B, p).
  // Divide -(1 + epsilon) v_rel by the inverse effective mass along n
  // TODO(student): return -(1 + epsilon) * v_rel / inverseEffectiveMass(A, B, p, n); no sign test here.
  notImplemented("impulseMagnitude", "Lab 5 handout, section 2", A, B, p, n, epsilon);
}

void applyImpulse(ContactBody& A, ContactBody& B, const Vec3& p, const Vec3& J) {
  // Refuse bad input before changing either body
  // TODO(student): inverse masses of A and B >= 0 and finite, p and J finite; all checked before the first +=.
  // Change A's momenta by +J and r_a x J, B's by -J and -r_b x J (zero inverses leave a fixed body)
  // TODO(student): A.v += A.inv_mass J, A.omega += A.I_inv_world (r_a x J); B.v -= ..., B.omega -= I_inv_B (r_b x J).
  notImplemented("applyImpulse", "Lab 5 handout, section 3", A, B, p, J);
}

}  // namespace physlab
