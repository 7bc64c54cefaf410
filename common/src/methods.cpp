#include <cmath>
#include <stdexcept>

#include "physlab/error.hpp"
#include "physlab/integrators.hpp"

namespace physlab {

std::string methodName(Method method) {
  switch (method) {
    case Method::ExplicitEuler: return "explicit Euler";
    case Method::SymplecticEuler: return "symplectic Euler";
    case Method::Midpoint: return "midpoint";
    case Method::Trapezoid: return "trapezoid";
    case Method::RK4: return "RK4";
    case Method::Verlet: return "Verlet";
    case Method::ImplicitEuler: return "implicit Euler";
  }
  throw std::logic_error("unknown Method");
}

std::string methodId(Method method) {
  switch (method) {
    case Method::ExplicitEuler: return "explicit_euler";
    case Method::SymplecticEuler: return "symplectic_euler";
    case Method::Midpoint: return "midpoint";
    case Method::Trapezoid: return "trapezoid";
    case Method::RK4: return "rk4";
    case Method::Verlet: return "verlet";
    case Method::ImplicitEuler: return "implicit_euler";
  }
  throw std::logic_error("unknown Method");
}

Method methodFromId(const std::string& id) {
  for (Method m : kAllMethods) {
    if (methodId(m) == id) return m;
  }
  throw InvalidInput("unknown integrator '" + id +
                     "' (expected explicit_euler, symplectic_euler, midpoint, trapezoid, rk4, "
                     "verlet or implicit_euler)");
}

int methodOrder(Method method) {
  switch (method) {
    case Method::RK4: return 4;
    case Method::Midpoint:
    case Method::Trapezoid:
    case Method::Verlet: return 2;
    case Method::ExplicitEuler:
    case Method::SymplecticEuler:
    case Method::ImplicitEuler: return 1;
  }
  throw std::logic_error("unknown Method");
}

double spectralRadius(const Eigen::Matrix2d& A) {
  const double half_trace = 0.5 * A.trace(), det = A.determinant();
  const double discriminant = half_trace * half_trace - det;
  // A complex pair has |lambda|^2 = lambda conj(lambda) = det; of a real pair the root on the
  // side of the trace is the larger
  if (discriminant < 0.0) return std::sqrt(det);
  return std::abs(half_trace) + std::sqrt(discriminant);
}

}  // namespace physlab
