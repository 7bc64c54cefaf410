// Framework half of Lab 2: building and checking networks, and the System around them. The
// spring physics and the implicit step are the student's, in labs/02_springs.
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"
#include "physlab/springs.hpp"

namespace physlab {

void validate(const SpringNetwork& network) {
  const Index n = network.masses.size();
  if (n == 0) throw InvalidInput("a spring network needs at least one particle");
  for (Index i = 0; i < n; ++i) {
    if (!(network.masses[i] > 0.0)) {
      throw InvalidInput("mass of particle " + std::to_string(i) + " must be positive, got " +
                         std::to_string(network.masses[i]));
    }
  }
  requireSize(network.rest_positions.cols(), n, "rest positions (columns)");
  requireFinite(network.gravity, "gravity");
  requireNonNegative(network.drag, "drag");
  requireNonNegative(network.ground.stiffness, "ground stiffness");
  requireNonNegative(network.ground.damping, "ground damping");
  for (std::size_t k = 0; k < network.springs.size(); ++k) {
    const Spring& s = network.springs[k];
    const std::string name = "spring " + std::to_string(k);
    for (Index i : {s.a, s.b}) {
      if (i < 0 || i >= n) {
        throw InvalidInput(name + " names particle " + std::to_string(i) + " but the network has " +
                           std::to_string(n));
      }
    }
    if (s.a == s.b) throw InvalidInput(name + " joins particle " + std::to_string(s.a) + " to itself");
    requireNonNegative(s.rest, name + " rest length");
    requireNonNegative(s.ks, name + " stiffness ks");
    requireNonNegative(s.kd, name + " damping kd");
  }
}

namespace {

// One spring per pair, at rest at the distance the pair was built at.
void connectWithin(SpringNetwork& net, const std::vector<std::pair<Index, Index>>& pairs, double ks,
                   double kd) {
  for (const auto& [a, b] : pairs) {
    net.springs.push_back({a, b, (net.rest_positions.col(a) - net.rest_positions.col(b)).norm(), ks, kd});
  }
}

}  // namespace

SpringNetwork makeRope(Index n, double length, double mass, double ks, double kd) {
  if (n < 2) throw InvalidInput("a rope needs at least 2 particles");
  requirePositive(length, "rope length");
  requirePositive(mass, "rope mass");
  SpringNetwork net;
  net.masses = VecX::Constant(n, mass / static_cast<double>(n - 1));
  net.masses[0] = std::numeric_limits<double>::infinity();
  net.rest_positions = Mat3X::Zero(3, n);
  for (Index i = 0; i < n; ++i) net.rest_positions(2, i) = -length * i / static_cast<double>(n - 1);
  std::vector<std::pair<Index, Index>> pairs;
  for (Index i = 0; i + 1 < n; ++i) pairs.emplace_back(i, i + 1);
  connectWithin(net, pairs, ks, kd);
  net.gravity = Vec3(0, 0, -9.81);
  return net;
}

SpringNetwork makeCloth(Index nx, Index ny, double size, double height, double mass, double ks,
                        double kd) {
  if (nx < 2 || ny < 2) throw InvalidInput("a cloth needs at least 2 x 2 particles");
  requirePositive(size, "cloth size");
  requirePositive(mass, "cloth mass");
  SpringNetwork net;
  const Index n = nx * ny;
  net.masses = VecX::Constant(n, mass / static_cast<double>(n));
  net.rest_positions.resize(3, n);
  auto id = [nx](Index i, Index j) { return j * nx + i; };
  for (Index j = 0; j < ny; ++j) {
    for (Index i = 0; i < nx; ++i) {
      net.rest_positions.col(id(i, j)) =
          Vec3(size * i / static_cast<double>(nx - 1), size * j / static_cast<double>(ny - 1), height);
    }
  }
  std::vector<std::pair<Index, Index>> pairs;
  for (Index j = 0; j < ny; ++j) {
    for (Index i = 0; i < nx; ++i) {
      if (i + 1 < nx) pairs.emplace_back(id(i, j), id(i + 1, j));           // structural
      if (j + 1 < ny) pairs.emplace_back(id(i, j), id(i, j + 1));           // structural
      if (i + 1 < nx && j + 1 < ny) {
        pairs.emplace_back(id(i, j), id(i + 1, j + 1));                     // shear
        pairs.emplace_back(id(i + 1, j), id(i, j + 1));                     // shear
      }
      if (i + 2 < nx) pairs.emplace_back(id(i, j), id(i + 2, j));           // bending
      if (j + 2 < ny) pairs.emplace_back(id(i, j), id(i, j + 2));           // bending
    }
  }
  connectWithin(net, pairs, ks, kd);
  net.gravity = Vec3(0, 0, -9.81);
  return net;
}

SpringNetwork makeJelly(Index n, double size, double height, double mass, double ks, double kd) {
  if (n < 2) throw InvalidInput("a jelly cube needs at least 2 particles per side");
  requirePositive(size, "jelly size");
  requirePositive(mass, "jelly mass");
  SpringNetwork net;
  const Index count = n * n * n;
  net.masses = VecX::Constant(count, mass / static_cast<double>(count));
  net.rest_positions.resize(3, count);
  auto id = [n](Index i, Index j, Index k) { return (k * n + j) * n + i; };
  const double d = size / static_cast<double>(n - 1);
  for (Index k = 0; k < n; ++k) {
    for (Index j = 0; j < n; ++j) {
      for (Index i = 0; i < n; ++i) net.rest_positions.col(id(i, j, k)) = Vec3(d * i, d * j, height + d * k);
    }
  }
  std::vector<std::pair<Index, Index>> pairs;
  for (Index k = 0; k < n; ++k) {
    for (Index j = 0; j < n; ++j) {
      for (Index i = 0; i < n; ++i) {
        // Each neighbour once: only those later in (k, j, i) order.
        for (Index dk = 0; dk <= 1; ++dk) {
          for (Index dj = -1; dj <= 1; ++dj) {
            for (Index di = -1; di <= 1; ++di) {
              const bool later = dk > 0 || dj > 0 || (dj == 0 && di > 0);
              const Index i2 = i + di, j2 = j + dj, k2 = k + dk;
              if (later && i2 >= 0 && i2 < n && j2 >= 0 && j2 < n && k2 < n) {
                pairs.emplace_back(id(i, j, k), id(i2, j2, k2));
              }
            }
          }
        }
      }
    }
  }
  connectWithin(net, pairs, ks, kd);
  net.gravity = Vec3(0, 0, -9.81);
  return net;
}

SpringSystem::SpringSystem(SpringNetwork network) : network_(std::move(network)) {
  validate(network_);
  inverse_masses_ = network_.masses.cwiseInverse();  // 1 / inf = 0 for pinned particles
  workspace_ = std::make_unique<ImplicitWorkspace>(network_);
}

VecX SpringSystem::restState() const {
  VecX X = VecX::Zero(size());
  X.head(positionSize()) = network_.rest_positions.reshaped();
  return X;
}

VecX SpringSystem::forces(const VecX& X) const {
  VecX f;
  forces(X, f);
  return f;
}

double SpringSystem::energy(const VecX& X) const {
  requireSize(X.size(), size(), "spring network state");
  const ConstPoints x = positions(X), v = velocities(X);
  double E = 0.0;
  for (const Spring& s : network_.springs) {
    const double stretch = (x.col(s.a) - x.col(s.b)).norm() - s.rest;
    E += 0.5 * s.ks * stretch * stretch;
  }
  for (Index i = 0; i < count(); ++i) {
    if (inverse_masses_[i] == 0.0) continue;
    const double m = network_.masses[i];
    E += 0.5 * m * v.col(i).squaredNorm() - m * network_.gravity.dot(x.col(i));
    const double depth = network_.ground.height - x(2, i);
    if (network_.ground.stiffness > 0.0 && depth > 0.0) E += 0.5 * network_.ground.stiffness * depth * depth;
  }
  return E;
}

double SpringSystem::maxStrain(const VecX& X) const {
  const ConstPoints x = positions(X);
  double worst = 0.0;
  for (const Spring& s : network_.springs) {
    if (s.rest > 0.0) worst = std::max(worst, std::abs((x.col(s.a) - x.col(s.b)).norm() - s.rest) / s.rest);
  }
  return worst;
}

void SpringSystem::computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const {
  qdot = X.tail(velocitySize());
}

void SpringSystem::computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const {
  pdot = forces(X);
  Points(pdot.data(), 3, count()).array().rowwise() *= inverse_masses_.transpose().array();
}

std::string solverName(LinearSolver solver) {
  return solver == LinearSolver::ConjugateGradient ? "CG" : "LDLT";
}

ImplicitStats implicitEulerStep(const SpringSystem& sys, VecX& X, double h,
                                const ImplicitSettings& settings) {
  requirePositive(h, "step size h");
  sys.validateState(X);
  requirePositive(settings.cg_tolerance, "CG tolerance");
  if (settings.cg_max_iterations < 1) throw InvalidInput("CG max iterations must be at least 1");
  return implicitEulerUpdate(sys, X, h, settings, sys.implicitWorkspace());
}

}  // namespace physlab
