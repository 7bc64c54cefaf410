// Lab 5, sections 5-6: many contact points, sequentially (Gauss-Seidel) and simultaneously
// (Jacobi), with accumulated impulses, clamping and warm starting.
#include <algorithm>
#include <limits>

#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab {

int solveSequential(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const Settings& settings) {
  // Refuse bad bodies and contacts before anything changes
  // TODO(student): one pass before the warm start, throwing InvalidInput that names the contact (or body) and field when
  // TODO(student): a body's inv_mass < 0 or not finite; c.a or c.b outside [0, bodies.size()); |c.n| off 1 by more than 1e-9
  // TODO(student): or NaN; c.p not finite; c.epsilon outside [0, 1]; c.mu < 0 or not finite; c.v_rel_minus not finite;
  // TODO(student): c.j < 0 or not finite; c.j_t not finite. Build the message only when throwing (no strings otherwise).
  // Prepare once per solve what no sweep changes: each point's lever arms and K matrix
  // TODO(student): for every contact c.r_a = p - x_A, c.r_b = p - x_B and
  // TODO(student): c.K_matrix = (1/m_A + 1/m_B) 1 - [r_a]x I_A^-1 [r_a]x - [r_b]x I_B^-1 [r_b]x ([r]x y = r x y);
  // TODO(student): d . (K_matrix d) must equal inverseEffectiveMass(A, B, p, d): test yours against it.
  // Warm start: apply the impulses carried over from the last step
  // TODO(student): apply c.j n + c.j_t at every point before the first sweep (whatever settings.warm_start says), as
  // TODO(student): applyImpulse does but with the prepared r_a, r_b: the sweeps below call none of the section 2-4 functions.
  // Aim at v_rel+ = -epsilon v_rel-, decided before the solve (resting points aim at 0), and
  // clamp the accumulated total, not the correction: j >= 0, so a sweep may take some back
  // TODO(student): sweep the contacts in order, with the velocities the sweep has left so far; target = -c.epsilon c.v_rel_minus
  // TODO(student): when c.v_rel_minus < -settings.restitution_threshold, else 0 (never from the v_rel you see now).
  // TODO(student): u = relative velocity of the points (prepared r), K = n . K_matrix n, j = max(0, c.j + (target - n . u) / K);
  // TODO(student): dj = j - c.j; its velocity change is K |dj|; store c.j = j.
  // Stop the sliding left after this change (u + K n dj: the bodies move only once, below),
  // keeping the accumulated friction inside the cone |j_t| <= mu j of the normal impulse just
  // found (a cone of radius 0 takes everything back)
  // TODO(student): when mu > 0: from u + dj K_matrix n, the stopping impulse -(|u_t| / K_t) t with t = u_t / |u_t|,
  // TODO(student): K_t = t . K_matrix t (zero when u_t = 0); j_t = c.j_t + it, shortened to mu c.j (the new c.j);
  // TODO(student): dj_t = j_t - c.j_t; its velocity change is (dj_t . K_matrix dj_t) / |dj_t|.
  // Apply the point's normal and friction changes together
  // TODO(student): apply dj n + dj_t once (the same change as applying dj n, then dj_t).
  // Converged when no point's velocity changed by more than the tolerance in a whole sweep
  // TODO(student): stop when the largest change of the sweep is <= settings.tolerance, or after settings.iterations sweeps;
  // TODO(student): return the sweeps made, the quiet last one included (no contacts: 1).
  notImplemented("solveSequential", "Lab 5 handout, section 5", bodies, contacts, settings);
}

int solveSimultaneous(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const Settings& settings) {
  // Refuse bad bodies and contacts before anything changes
  // TODO(student): the same checks as solveSequential (share them in a helper), before anything changes.
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
