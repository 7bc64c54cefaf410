// Lab 3, section 1: inertia tensors in the body frame.
#include "physlab/error.hpp"
#include "physlab/rigid.hpp"

namespace physlab {

Mat3 boxInertia(double M, const Vec3& size) {
  // Refuse what has no inertia
  // TODO(student): InvalidInput unless M and every edge are positive and finite.
  // Square the edge lengths
  // TODO(student): size.cwiseProduct(size) gives (a^2, b^2, c^2).
  // Each axis feels the two edges across it
  // TODO(student): M/12 diag(b^2 + c^2, a^2 + c^2, a^2 + b^2).
  notImplemented("boxInertia", "Lab 3 handout, section 1", M, size);
}

Mat3 sphereInertia(double M, double radius) {
  // Refuse what has no inertia
  // TODO(student): InvalidInput unless M and radius are positive and finite.
  // Every axis through the centre is alike
  // TODO(student): 2/5 M r^2 times the identity.
  notImplemented("sphereInertia", "Lab 3 handout, section 1", M, radius);
}

Mat3 cylinderInertia(double M, double radius, double height) {
  // Refuse what has no inertia
  // TODO(student): InvalidInput unless M, radius and height are positive and finite.
  // Across the axis: a disc stack; along it: a disc
  // TODO(student): M/12 (3 r^2 + h^2) for x and y, M r^2 / 2 for z.
  notImplemented("cylinderInertia", "Lab 3 handout, section 1", M, radius, height);
}

Mat3 pointMassInertia(const VecX& m, const Mat3X& r) {
  // Refuse what has no inertia
  // TODO(student): InvalidInput when r has not m.size() columns, there is no point, a mass is not
  // positive and finite, or a position is not finite.
  // Move the centre of mass to the origin
  // TODO(student): c = sum m_i r_i / sum m_i.
  // Sum m ((r0 . r0) 1 - r0 r0^T) over the points
  // TODO(student): r0 = r_i - c for each point.
  notImplemented("pointMassInertia", "Lab 3 handout, section 1", m, r);
}

}  // namespace physlab
