// Lab 6 framework: the soft step (sub-stepping with soft contacts and relaxation) as a resting
// solver: its settings, and the bodies' moves. Its step is in soft_step_sweeps.cpp.
#include <sstream>

#include "physlab/error.hpp"
#include "physlab/rigid.hpp"
#include "physlab/soft_step.hpp"

namespace physlab {

std::string SoftStepSettings::toString() const {
  std::ostringstream out;
  out << "soft step: substeps=" << substeps << " contact_hertz=" << contact_hertz
      << " fixed_hertz_scale=" << fixed_hertz_scale << " damping_ratio=" << damping_ratio
      << " solve_iterations=" << solve_iterations << " relax_iterations=" << relax_iterations
      << " max_push=" << max_push << " top_down=" << (top_down ? "yes" : "no");
  return out.str();
}

SoftStepSolver::SoftStepSolver(SoftStepSettings settings) : settings_(settings) {
  if (settings_.substeps < 1) throw InvalidInput("soft step settings substeps must be at least 1");
  requireNonNegative(settings_.contact_hertz, "soft step settings contact_hertz");
  requireNonNegative(settings_.fixed_hertz_scale, "soft step settings fixed_hertz_scale");
  requireNonNegative(settings_.damping_ratio, "soft step settings damping_ratio");
  if (settings_.solve_iterations < 1) throw InvalidInput("soft step settings solve_iterations must be at least 1");
  if (settings_.relax_iterations < 0) throw InvalidInput("soft step settings relax_iterations must be at least 0");
  if (!(settings_.max_push > 0.0)) throw InvalidInput("soft step settings max_push must be positive");
}

std::string SoftStepSolver::describe() const { return settings_.toString(); }

bool SoftStepSolver::placeBodies(std::vector<BodyState>& states) {
  if (!moved_) return false;
  moved_ = false;
  for (std::size_t i = 0; i < states.size() && i < motion_.size(); ++i) {
    states[i].x += motion_[i].dx;
    states[i].q = (dq_[i] * states[i].q).normalized();
  }
  return true;
}

}  // namespace physlab
