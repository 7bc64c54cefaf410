// Lab 5, sections 5-6: many contact points, sequentially (collision propagation) and
// simultaneously (Jacobi), with accumulated impulses, clamping and warm starting.
#include <algorithm>
#include <limits>

#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab {

int solveSequential(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const Settings& settings) {
  // Give a point that approaches now its full impulse, with the v_rel it has now
  // TODO(student): sweep the contacts in order; when v_rel = n . relativeVelocity < -settings.tolerance, apply
  // TODO(student): j = impulseMagnitude(A, B, p, n, epsilon) along n and add it to c.j; the sweep changed something.
  // Below the threshold a bounce would only be jitter: such points rest (epsilon = 0)
  // TODO(student): epsilon = c.epsilon when v_rel < -settings.restitution_threshold, else 0.
  // Stop the sliding, keeping the accumulated friction inside the cone |j_t| <= mu j
  // TODO(student): when mu > 0 and c.j > 0: j_t = c.j_t + frictionImpulse(..., infinity), shortened to mu c.j; apply j_t - c.j_t.
  // Friction turns the bodies and may make other points approach: sweep again unless
  // the change of sliding speed it caused is within the tolerance
  // TODO(student): a sweep changed something when it gave a normal impulse or a friction change with |dj_t| K > tolerance
  // TODO(student): (K = inverseEffectiveMass along dj_t); repeat until a sweep changes nothing or settings.iterations; return the sweeps.
  notImplemented("solveSequential", "Lab 5 handout, section 5", bodies, contacts, settings);
}

int solveSimultaneous(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const Settings& settings) {
  // Count the points on each moving body, to split a body's correction between them
  // TODO(student): points_on[i] = contacts touching body i when bodies[i].inv_mass > 0; share = 1 / max(1, on a, on b).
  // Warm start: apply the impulses carried over from the last step
  // TODO(student): applyImpulse(A, B, p, c.j n + c.j_t) for every contact before the first sweep.
  // Every point sees the same velocities: those at the start of the sweep
  // TODO(student): copy the bodies at the start of each sweep and compute every correction from the copy.
  // Aim at v_rel+ = -epsilon v_rel- (resting points aim at 0), keeping the accumulated j >= 0
  // TODO(student): target = -c.epsilon c.v_rel_minus when c.v_rel_minus < -threshold, else 0; j = max(0, c.j + share (target - v_rel) / K).
  // Stop the sliding, keeping the accumulated friction inside the cone |j_t| <= mu j; it
  // sees this point's own normal correction (Jacobi across points, not within one)
  // TODO(student): on copies of A and B apply this point's dj n, then j_t = c.j_t + share frictionImpulse(copies, ..., infinity),
  // TODO(student): shortened to mu c.j; keep the change.
  // Apply every correction at once
  // TODO(student): after the sweep apply each change (dj n + dj_t); stop when K (|dj| + |dj_t|) <= tolerance everywhere.
  notImplemented("solveSimultaneous", "Lab 5 handout, section 6", bodies, contacts, settings);
}

}  // namespace physlab
