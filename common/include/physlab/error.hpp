/// \file error.hpp
/// \brief The two errors PhysLab throws: a stub not yet written, and input that makes no sense.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>

#include "physlab/math.hpp"

namespace physlab {

/// Thrown by every student stub until it is implemented.
/// The grader reports it as "not implemented" rather than as a crash.
class NotImplemented : public std::logic_error {
 public:
  /// \param function the function that is still a stub, e.g. "explicitEuler"
  /// \param section  the handout section that explains it, e.g. "Lab 1, section 3.1"
  NotImplemented(const std::string& function, const std::string& section)
      : std::logic_error("not implemented: " + function + " (see " + section + ")") {}
};

/// The body of a student stub: throws NotImplemented. The stub passes its parameters along so
/// that the compiler sees them used (no warnings) and the signature stays the solution's.
template <class... Unused>
[[noreturn]] void notImplemented(const char* function, const char* section, const Unused&... /*args*/) {
  throw NotImplemented(function, section);
}

/// Thrown when a caller passes input that has no physical meaning: a negative mass, a
/// non-positive step, a NaN in a state, vectors of mismatched sizes. The message names it.
class InvalidInput : public std::invalid_argument {
 public:
  /// \param what what was wrong, naming the argument (e.g. "step size h must be positive")
  explicit InvalidInput(const std::string& what) : std::invalid_argument("invalid input: " + what) {}
};

/// Thrown when a numerical method fails on valid input (e.g. Newton's method does not converge).
class NumericalFailure : public std::runtime_error {
 public:
  /// \param what which method failed and why
  explicit NumericalFailure(const std::string& what) : std::runtime_error("numerical failure: " + what) {}
};

/// Internals of the checks below.
namespace detail {
/// The search half of firstNonFinite(), out of line and cold, so that the check itself is a few
/// instructions the compiler inlines into every caller.
template <class Derived>
[[gnu::cold, gnu::noinline]] Index searchNonFinite(const Eigen::DenseBase<Derived>& values) {
  for (Index j = 0; j < values.cols(); ++j) {
    for (Index i = 0; i < values.rows(); ++i) {
      if (!std::isfinite(values(i, j))) return j * values.rows() + i;
    }
  }
  return -1;
}

/// requirePositive()'s message, built out of line and only on failure: the checks stay a few
/// instructions inside hot functions, with no string work in their way.
[[noreturn, gnu::cold, gnu::noinline]] inline void throwNotPositive(std::string_view what, double value) {
  throw InvalidInput(std::string(what) + " must be positive and finite, got " + std::to_string(value));
}

/// requireNonNegative()'s message, built out of line and only on failure.
[[noreturn, gnu::cold, gnu::noinline]] inline void throwNegative(std::string_view what, double value) {
  throw InvalidInput(std::string(what) + " must be non-negative and finite, got " + std::to_string(value));
}

/// requireFinite()'s message for a number, built out of line and only on failure.
[[noreturn, gnu::cold, gnu::noinline]] inline void throwNotFinite(std::string_view what, double value) {
  throw InvalidInput(std::string(what) + " must be finite, got " + std::to_string(value));
}

/// requireInRange()'s message, built out of line and only on failure.
[[noreturn, gnu::cold, gnu::noinline]] inline void throwOutOfRange(std::string_view what, double value, double lo,
                                                                   double hi) {
  throw InvalidInput(std::string(what) + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                     std::to_string(value));
}

/// requireUnit()'s message, built out of line and only on failure.
[[noreturn, gnu::cold, gnu::noinline]] inline void throwNotUnit(std::string_view what, double length) {
  throw InvalidInput(std::string(what) + " must be a finite unit vector (length within 1e-9 of 1), got length " +
                     std::to_string(length));
}

/// requireFinite()'s message, built out of line for the same reason.
[[noreturn, gnu::cold, gnu::noinline]] inline void throwNonFinite(std::string_view what, Index row, Index col) {
  throw InvalidInput(std::string(what) + " has a non-finite entry at (" + std::to_string(row) + ", " +
                     std::to_string(col) + ")");
}
}  // namespace detail

/// Throw InvalidInput naming `what` unless `value` is finite and strictly positive.
inline void requirePositive(double value, std::string_view what) {
  if (!(std::isfinite(value) && value > 0.0)) detail::throwNotPositive(what, value);
}

/// Throw InvalidInput naming `what` unless `value` is finite and not negative.
inline void requireNonNegative(double value, std::string_view what) {
  if (!(std::isfinite(value) && value >= 0.0)) detail::throwNegative(what, value);
}

/// Column-major index of the first NaN or infinite entry of `values`, or -1 when every entry is
/// finite. A sum is finite exactly when no entry is NaN or infinite (barring overflow, which the
/// search then clears): one vectorised pass in the common case, the search only on failure.
template <class Derived>
Index firstNonFinite(const Eigen::DenseBase<Derived>& values) {
  return std::isfinite(values.sum()) ? -1 : detail::searchNonFinite(values);
}

/// Throw InvalidInput naming `what` and the first bad entry unless every entry is finite.
template <class Derived>
void requireFinite(const Eigen::DenseBase<Derived>& values, std::string_view what) {
  if (const Index k = firstNonFinite(values); k >= 0) detail::throwNonFinite(what, k % values.rows(), k / values.rows());
}

/// Throw InvalidInput naming `what` unless `value` is finite.
inline void requireFinite(double value, std::string_view what) {
  if (!std::isfinite(value)) detail::throwNotFinite(what, value);
}

/// Throw InvalidInput naming `what` unless lo <= value <= hi: both ends allowed, NaN never (hi may
/// be +infinity, and then so may value).
inline void requireInRange(double value, double lo, double hi, std::string_view what) {
  if (!(value >= lo && value <= hi)) detail::throwOutOfRange(what, value, lo, hi);
}

/// Throw InvalidInput naming `what` unless `v` is finite and of unit length, its length within 1e-9
/// of 1 as tangentDirections() asks: a normalised vector's round-off passes, a NaN never does.
inline void requireUnit(const Vec3& v, std::string_view what) {
  if (const double length = v.norm(); !(std::abs(length - 1.0) <= 1e-9)) detail::throwNotUnit(what, length);
}

/// Throw InvalidInput unless `actual == expected`, naming both sizes.
inline void requireSize(Index actual, Index expected, std::string_view what) {
  if (actual != expected) {
    throw InvalidInput(std::string(what) + " has size " + std::to_string(actual) + ", expected " +
                       std::to_string(expected));
  }
}

}  // namespace physlab
