// Framework half of Lab 2's implicit step: the block matrix of a spring network, its block-Jacobi
// conjugate gradients and its LDLT with the pattern analysed once.
#include <algorithm>
#include <string>

#include "physlab/error.hpp"
#include "physlab/springs.hpp"

namespace physlab {

namespace {

// Position of entry (row, col) in a compressed column-major matrix (the entry must exist).
Index valuePosition(const Eigen::SparseMatrix<double>& m, Index row, Index col) {
  using StorageIndex = Eigen::SparseMatrix<double>::StorageIndex;
  const StorageIndex* begin = m.innerIndexPtr() + m.outerIndexPtr()[col];
  const StorageIndex* end = m.innerIndexPtr() + m.outerIndexPtr()[col + 1];
  return std::lower_bound(begin, end, static_cast<StorageIndex>(row)) - m.innerIndexPtr();
}

}  // namespace

SpringMatrix::SpringMatrix(const SpringNetwork& network) {
  validate(network);
  build(network);
}

void SpringMatrix::build(const SpringNetwork& network) {
  const Index n = network.masses.size();
  const std::size_t particles = static_cast<std::size_t>(n);
  diagonal_.assign(particles, Mat3::Zero());
  inverse_diagonal_.assign(particles, Mat3::Zero());
  // Distinct pairs in (i, j) order, and each spring's block among them.
  std::vector<std::pair<Pair, std::size_t>> keyed;  // pair, spring
  keyed.reserve(network.springs.size());
  for (std::size_t k = 0; k < network.springs.size(); ++k) {
    const Spring& s = network.springs[k];
    keyed.push_back({{std::min(s.a, s.b), std::max(s.a, s.b)}, k});
  }
  std::sort(keyed.begin(), keyed.end(), [](const auto& l, const auto& r) {
    return l.first.i != r.first.i ? l.first.i < r.first.i : l.first.j < r.first.j;
  });
  pairs_.clear();
  slots_.resize(network.springs.size());
  for (const auto& [pair, k] : keyed) {
    if (pairs_.empty() || pairs_.back().i != pair.i || pairs_.back().j != pair.j) pairs_.push_back(pair);
    slots_[k] = {pairs_.size() - 1, network.springs[k].a > network.springs[k].b};
  }
  off_diagonal_.assign(pairs_.size(), Mat3::Zero());
  r_ = z_ = p_ = Ap_ = VecX::Zero(3 * n);

  // The lower triangle's pattern in CSC: the stored block (i, j), i < j, appears there as its
  // transpose at rows 3j.., columns 3i...
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(6 * particles + 9 * pairs_.size());
  for (Index i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      for (int r = c; r < 3; ++r) triplets.emplace_back(3 * i + r, 3 * i + c, 0.0);
    }
  }
  for (const Pair& pair : pairs_) {
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) triplets.emplace_back(3 * pair.j + r, 3 * pair.i + c, 0.0);
    }
  }
  lower_.resize(3 * n, 3 * n);
  lower_.setFromTriplets(triplets.begin(), triplets.end());
  lower_.makeCompressed();
  analysed_ = false;  // LDLT's analysis was of the pattern this replaces
  diagonal_entries_.clear();
  diagonal_entries_.reserve(6 * particles);
  for (Index i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      for (int r = c; r < 3; ++r) {
        diagonal_entries_.push_back(valuePosition(lower_, 3 * i + r, 3 * i + c));
      }
    }
  }
  off_diagonal_entries_.clear();
  off_diagonal_entries_.reserve(9 * pairs_.size());
  for (const Pair& pair : pairs_) {
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) {
        off_diagonal_entries_.push_back(valuePosition(lower_, 3 * pair.j + r, 3 * pair.i + c));
      }
    }
  }
}

void SpringMatrix::setZero() {
  std::fill(diagonal_.begin(), diagonal_.end(), Mat3::Zero());
  std::fill(off_diagonal_.begin(), off_diagonal_.end(), Mat3::Zero());
}

void SpringMatrix::addDiagonal(Index i, const Mat3& block) {
  if (i < 0 || i >= count()) {
    throw InvalidInput("SpringMatrix::addDiagonal: particle " + std::to_string(i) + " of " +
                       std::to_string(count()));
  }
  diagonal_[static_cast<std::size_t>(i)] += block;
}

void SpringMatrix::addSpring(std::size_t k, const Mat3& block) {
  if (k >= slots_.size()) {
    throw InvalidInput("SpringMatrix::addSpring: spring " + std::to_string(k) + " of " +
                       std::to_string(slots_.size()));
  }
  const Slot& slot = slots_[k];
  if (slot.transposed) {
    off_diagonal_[slot.pair] += block.transpose();
  } else {
    off_diagonal_[slot.pair] += block;
  }
}

void SpringMatrix::multiply(const VecX& x, VecX& y) const {
  requireSize(x.size(), 3 * count(), "SpringMatrix::multiply: x");
  if (&x == &y) throw InvalidInput("SpringMatrix::multiply: y must not be x");
  y.resize(x.size());
  for (std::size_t i = 0; i < diagonal_.size(); ++i) {
    const Index at = 3 * static_cast<Index>(i);
    y.segment<3>(at).noalias() = diagonal_[i] * x.segment<3>(at);
  }
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const Pair& pair = pairs_[k];
    const Mat3& B = off_diagonal_[k];
    y.segment<3>(3 * pair.i).noalias() += B * x.segment<3>(3 * pair.j);
    y.segment<3>(3 * pair.j).noalias() += B.transpose() * x.segment<3>(3 * pair.i);
  }
}

MatX SpringMatrix::toDense() const {
  MatX A = MatX::Zero(3 * count(), 3 * count());
  for (std::size_t i = 0; i < diagonal_.size(); ++i) {
    const Index at = 3 * static_cast<Index>(i);
    A.block<3, 3>(at, at) = diagonal_[i];
  }
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    A.block<3, 3>(3 * pairs_[k].i, 3 * pairs_[k].j) += off_diagonal_[k];
    A.block<3, 3>(3 * pairs_[k].j, 3 * pairs_[k].i) += off_diagonal_[k].transpose();
  }
  return A;
}

void SpringMatrix::invertDiagonal() {
  for (std::size_t i = 0; i < diagonal_.size(); ++i) {
    bool invertible = false;
    diagonal_[i].computeInverseWithCheck(inverse_diagonal_[i], invertible);
    if (!invertible || !inverse_diagonal_[i].allFinite()) {
      throw NumericalFailure("block-Jacobi CG: the diagonal block of particle " + std::to_string(i) +
                             " is singular or not finite");
    }
  }
}

CGResult SpringMatrix::solveCG(const VecX& b, VecX& x, double tolerance, int max_iterations) {
  requireSize(b.size(), 3 * count(), "CG right-hand side");
  requireSize(x.size(), 3 * count(), "CG starting guess");
  CGResult result;
  const double b_norm2 = b.squaredNorm();
  if (b_norm2 == 0.0) {
    x.setZero();
    result.converged = true;
    return result;
  }
  invertDiagonal();
  const double threshold = tolerance * tolerance * b_norm2;
  auto precondition = [this]() {
    for (std::size_t i = 0; i < diagonal_.size(); ++i) {
      const Index at = 3 * static_cast<Index>(i);
      z_.segment<3>(at).noalias() = inverse_diagonal_[i] * r_.segment<3>(at);
    }
  };
  multiply(x, Ap_);
  r_ = b - Ap_;
  double r_norm2 = r_.squaredNorm();
  if (r_norm2 <= threshold) {
    result.converged = true;
    return result;
  }
  precondition();
  p_ = z_;
  double rz = r_.dot(z_);
  while (result.iterations < max_iterations) {
    multiply(p_, Ap_);
    const double alpha = rz / p_.dot(Ap_);
    x += alpha * p_;
    r_ -= alpha * Ap_;
    ++result.iterations;
    r_norm2 = r_.squaredNorm();
    if (r_norm2 <= threshold) {
      result.converged = true;
      return result;
    }
    precondition();
    const double rz_next = r_.dot(z_);
    p_ = z_ + (rz_next / rz) * p_;
    rz = rz_next;
  }
  return result;
}

void SpringMatrix::refillCsc() {
  double* values = lower_.valuePtr();
  for (std::size_t i = 0; i < diagonal_.size(); ++i) {
    const Index* at = diagonal_entries_.data() + 6 * i;
    for (int c = 0, e = 0; c < 3; ++c) {
      for (int r = c; r < 3; ++r) values[at[e++]] = diagonal_[i](r, c);
    }
  }
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const Index* at = off_diagonal_entries_.data() + 9 * k;
    for (int c = 0, e = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) values[at[e++]] = off_diagonal_[k](c, r);  // the transpose
    }
  }
}

bool SpringMatrix::solveLDLT(const VecX& b, VecX& x) {
  requireSize(b.size(), 3 * count(), "LDLT right-hand side");
  refillCsc();
  if (!analysed_) {
    ldlt_.analyzePattern(lower_);
    analysed_ = true;
  }
  ldlt_.factorize(lower_);
  if (ldlt_.info() != Eigen::Success) return false;
  x = ldlt_.solve(b);
  return true;
}

ImplicitWorkspace::ImplicitWorkspace(const SpringNetwork& network)
    : A(network),
      b(VecX::Zero(3 * network.masses.size())),
      Kv(b),
      dv(b),
      Adv(b) {}

}  // namespace physlab
