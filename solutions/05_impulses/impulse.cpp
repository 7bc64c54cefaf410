// Lab 5, sections 1-3: the particle-plane impulse, the rigid impulse magnitude j, and applying it.
#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab {

Vec3 particlePlaneResponse(double m, const Vec3& v_minus, const Vec3& n, double epsilon) {
  // Refuse input without physical meaning before computing anything
  requirePositive(m, "particlePlaneResponse mass m");
  requireFinite(v_minus, "particlePlaneResponse velocity v_minus");
  requireUnit(n, "particlePlaneResponse normal n");
  requireInRange(epsilon, 0.0, 1.0, "particlePlaneResponse restitution epsilon");
  // Leave a particle that does not approach the plane alone
  const double v_n = v_minus.dot(n);
  if (v_n >= 0.0) return v_minus;
  // Reverse and scale the normal velocity with the impulse j = -(1 + epsilon) m v- . n
  const double j = -(1.0 + epsilon) * m * v_n;
  return v_minus + (j / m) * n;
}

Mat3 inverseInertiaWorld(const Mat3& I_body_inv, const Quat& q) {
  // Refuse a NaN inverse inertia and an orientation that is zero or not finite
  requireFinite(I_body_inv, "inverseInertiaWorld inverse inertia I_body_inv");
  requirePositive(q.norm(), "inverseInertiaWorld orientation q's length");
  // Rotate the body-frame inverse inertia into the world: I^-1 = R I_body^-1 R^T
  const Mat3 R = q.normalized().toRotationMatrix();
  return R * I_body_inv * R.transpose();
}

Vec3 relativeVelocity(const ContactBody& A, const ContactBody& B, const Vec3& p) {
  // Refuse a point that is not finite
  requireFinite(p, "relativeVelocity point p");
  // Velocity of each touching point: pdot = v + omega x r
  const Vec3 r_a = p - A.x, r_b = p - B.x;
  return (A.v + A.omega.cross(r_a)) - (B.v + B.omega.cross(r_b));
}

double inverseEffectiveMass(const ContactBody& A, const ContactBody& B, const Vec3& p, const Vec3& d) {
  // Refuse negative or non-finite inverse masses and a direction that is not a unit vector
  requireNonNegative(A.inv_mass, "inverseEffectiveMass body A inverse mass inv_mass");
  requireNonNegative(B.inv_mass, "inverseEffectiveMass body B inverse mass inv_mass");
  requireUnit(d, "inverseEffectiveMass direction d");
  // Add the linear and the rotational terms of both bodies
  const Vec3 r_a = p - A.x, r_b = p - B.x;
  return A.inv_mass + B.inv_mass + d.dot((A.I_inv_world * r_a.cross(d)).cross(r_a)) +
         d.dot((B.I_inv_world * r_b.cross(d)).cross(r_b));
}

double impulseMagnitude(const ContactBody& A, const ContactBody& B, const Vec3& p, const Vec3& n, double epsilon) {
  // Refuse epsilon outside [0, 1] (above 1 a bounce gains energy) and a normal that is not a unit vector
  requireInRange(epsilon, 0.0, 1.0, "impulseMagnitude restitution epsilon");
  requireUnit(n, "impulseMagnitude normal n");
  // Relative normal velocity of the touching points before the impulse
  const double v_rel = n.dot(relativeVelocity(A, B, p));
  // Divide -(1 + epsilon) v_rel by the inverse effective mass along n
  return -(1.0 + epsilon) * v_rel / inverseEffectiveMass(A, B, p, n);
}

void applyImpulse(ContactBody& A, ContactBody& B, const Vec3& p, const Vec3& J) {
  // Refuse bad input before changing either body
  requireNonNegative(A.inv_mass, "applyImpulse body A inverse mass inv_mass");
  requireNonNegative(B.inv_mass, "applyImpulse body B inverse mass inv_mass");
  requireFinite(p, "applyImpulse point p");
  requireFinite(J, "applyImpulse impulse J");
  // Change A's momenta by +J and r_a x J, B's by -J and -r_b x J (zero inverses leave a fixed body)
  const Vec3 r_a = p - A.x, r_b = p - B.x;
  A.v += A.inv_mass * J;
  A.omega += A.I_inv_world * r_a.cross(J);
  B.v -= B.inv_mass * J;
  B.omega -= B.I_inv_world * r_b.cross(J);
}

}  // namespace physlab
