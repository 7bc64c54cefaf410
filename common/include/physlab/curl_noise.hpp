/// \file curl_noise.hpp
/// \brief Lab 1 section 7: curl noise (Bridson, Hourihan and Nordenstam 2007), a divergence-free
/// velocity field that flows around a solid.
///
/// The flow is planar, in the \f$(x, y)\f$ plane (a point's \f$z\f$ is carried along and ignored).
/// A scalar stream function \f$\psi\f$ gives the velocity
/// \f[ v = \nabla \times (0, 0, \psi) = \Big(\frac{\partial\psi}{\partial y},\ -\frac{\partial\psi}{\partial x},\ 0\Big), \f]
/// whose divergence \f$\psi_{yx} - \psi_{xy}\f$ is zero for any smooth \f$\psi\f$, and which is
/// tangent to every level set of \f$\psi\f$: particles follow the curves \f$\psi = \text{const}\f$.
///
/// The solid is the disc \f$\lvert p - c\rvert \le R\f$ (an infinite cylinder along \f$z\f$), with
/// signed distance \f$d(p) = \lvert p - c\rvert - R\f$ (in the plane). The stream function is the
/// noise \f$\psi_0\f$ (a sum of sinusoids) times a smooth ramp of the distance,
/// \f[ \psi(p) = \operatorname{ramp}\!\big(d(p)/L\big)\,\psi_0(p), \qquad
///     \psi_0(p) = \sum_k a_k \sin(\kappa_k \cdot p + \varphi_k), \f]
/// \f[ \operatorname{ramp}(s) = \begin{cases} 1 & s \ge 1 \\ \tfrac{15}{8}s - \tfrac{10}{8}s^3 + \tfrac38 s^5 & \lvert s\rvert < 1 \\ -1 & s \le -1 \end{cases} \f]
/// so \f$\psi = 0\f$ on the boundary circle: the circle is a streamline, the normal velocity is
/// zero there, and no particle crosses it. Farther than \f$L\f$ from the solid, \f$\psi = \psi_0\f$.
/// The ramp is odd, \f$C^2\f$ at \f$s = \pm 1\f$ (value \f$\pm 1\f$, first and second derivatives 0).
#pragma once

#include <vector>

#include "physlab/math.hpp"

namespace physlab {

/// One term \f$a \sin(\kappa \cdot p + \varphi)\f$ of the noise \f$\psi_0\f$.
struct NoiseWave {
  double amplitude;        ///< a [m^2/s]
  Eigen::Vector2d kappa;   ///< wave vector \f$\kappa\f$ in the plane [1/m]
  double phase;            ///< \f$\varphi\f$ [rad]
};

/// The parameters of a curl-noise flow around a disc (framework code: holds and checks them,
/// evaluates the noise).
class CurlNoise {
 public:
  /// \param waves the terms of \f$\psi_0\f$, each finite
  /// \param centre centre \f$c\f$ of the solid disc (its z is ignored) [m]
  /// \param radius \f$R > 0\f$ of the disc [m]
  /// \param ramp_width \f$L > 0\f$: how far from the solid the flow is bent [m]
  /// \param step \f$e > 0\f$, the finite-difference step of curlNoiseVelocity() [m]
  /// Throws InvalidInput naming the first bad parameter.
  CurlNoise(std::vector<NoiseWave> waves, const Vec3& centre, double radius, double ramp_width, double step);
  /// \f$\psi_0(p) = \sum_k a_k \sin(\kappa_k \cdot (p_x, p_y) + \varphi_k)\f$ [m^2/s].
  double noise(const Vec3& p) const;
  /// The signed distance \f$d(p) = \lvert (p - c)_{xy}\rvert - R\f$ to the disc [m]: negative inside.
  double distance(const Vec3& p) const;

  const std::vector<NoiseWave> waves;  ///< terms of psi_0
  const Vec3 centre;                   ///< disc centre c [m]
  const double radius;                 ///< disc radius R [m]
  const double ramp_width;             ///< ramp width L [m]
  const double step;                   ///< finite-difference step e [m]
};

/// \name Curl noise (student functions, Lab 1 section 7)
///@{

/// The smooth ramp of Bridson et al.: 1 for \f$s \ge 1\f$, \f$-1\f$ for \f$s \le -1\f$,
/// \f$\frac{15}{8}s - \frac{10}{8}s^3 + \frac38 s^5\f$ between. Throws InvalidInput on a NaN.
double smoothRamp(double s);

/// The stream function \f$\psi(p) = \operatorname{ramp}(d(p)/L)\,\psi_0(p)\f$ [m^2/s] (use the
/// field's noise() and distance()). Throws InvalidInput naming a non-finite point.
double streamFunction(const CurlNoise& field, const Vec3& p);

/// The velocity \f$v = (\partial_y\psi, -\partial_x\psi, 0)\f$ [m/s] by central differences of
/// streamFunction() with the field's step \f$e\f$:
/// \f[ v_x = \frac{\psi(p + e\,\hat y) - \psi(p - e\,\hat y)}{2e}, \qquad
///     v_y = -\frac{\psi(p + e\,\hat x) - \psi(p - e\,\hat x)}{2e}, \qquad v_z = 0. \f]
/// Its truncation error against the exact curl is \f$O(e^2)\f$; its discrete divergence with the
/// same step (central differences of \f$v_x\f$ along x and \f$v_y\f$ along y) is exactly zero
/// in exact arithmetic, the two sums evaluating \f$\psi\f$ at the same four corners
/// \f$p \pm e\hat x \pm e\hat y\f$. Throws InvalidInput naming a non-finite point.
Vec3 curlNoiseVelocity(const CurlNoise& field, const Vec3& p);
///@}

}  // namespace physlab
