// Lab 3, section 1: inertia tensors in the body frame.
#include <string>

#include "physlab/error.hpp"
#include "physlab/rigid.hpp"

namespace physlab {

Mat3 boxInertia(double M, const Vec3& size) {
  // Refuse what has no inertia
  requirePositive(M, "boxInertia mass M");
  for (Index k = 0; k < 3; ++k) requirePositive(size[k], "boxInertia edge length size(" + std::to_string(k) + ")");
  // Square the edge lengths
  const Vec3 s2 = size.cwiseProduct(size);
  // Each axis feels the two edges across it
  return (M / 12.0) * Vec3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y()).asDiagonal();
}

Mat3 sphereInertia(double M, double radius) {
  // Refuse what has no inertia
  requirePositive(M, "sphereInertia mass M");
  requirePositive(radius, "sphereInertia radius");
  // Every axis through the centre is alike
  return (0.4 * M * radius * radius) * Mat3::Identity();
}

Mat3 cylinderInertia(double M, double radius, double height) {
  // Refuse what has no inertia
  requirePositive(M, "cylinderInertia mass M");
  requirePositive(radius, "cylinderInertia radius");
  requirePositive(height, "cylinderInertia height");
  // Across the axis: a disc stack; along it: a disc
  const double across = M / 12.0 * (3.0 * radius * radius + height * height);
  return Vec3(across, across, 0.5 * M * radius * radius).asDiagonal();
}

Mat3 pointMassInertia(const VecX& m, const Mat3X& r) {
  // Refuse what has no inertia
  requireSize(r.cols(), m.size(), "pointMassInertia positions r (columns)");
  if (m.size() == 0) throw InvalidInput("pointMassInertia needs at least one point mass");
  for (Index i = 0; i < m.size(); ++i) requirePositive(m[i], "pointMassInertia mass m(" + std::to_string(i) + ")");
  requireFinite(r, "pointMassInertia positions r");
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
