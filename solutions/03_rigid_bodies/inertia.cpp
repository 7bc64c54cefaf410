// Lab 3, section 1: inertia tensors in the body frame.
#include "physlab/error.hpp"
#include "physlab/rigid.hpp"

namespace physlab {

Mat3 boxInertia(double M, const Vec3& size) {
  // Square the edge lengths
  const Vec3 s2 = size.cwiseProduct(size);
  // Each axis feels the two edges across it
  return (M / 12.0) * Vec3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y()).asDiagonal();
}

Mat3 sphereInertia(double M, double radius) {
  // Every axis through the centre is alike
  return (0.4 * M * radius * radius) * Mat3::Identity();
}

Mat3 cylinderInertia(double M, double radius, double height) {
  // Across the axis: a disc stack; along it: a disc
  const double across = M / 12.0 * (3.0 * radius * radius + height * height);
  return Vec3(across, across, 0.5 * M * radius * radius).asDiagonal();
}

Mat3 pointMassInertia(const VecX& m, const Mat3X& r) {
  // Move the centre of mass to the origin
  const Vec3 c = r * m / m.sum();
  // Sum m ((r0 . r0) 1 - r0 r0^T) over the points
  Mat3 I = Mat3::Zero();
  for (Index i = 0; i < m.size(); ++i) {
    const Vec3 r0 = r.col(i) - c;
    I += m[i] * (r0.squaredNorm() * Mat3::Identity() - r0 * r0.transpose());
  }
  return I;
}

}  // namespace physlab
