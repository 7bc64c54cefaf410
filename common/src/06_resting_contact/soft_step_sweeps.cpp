// Lab 6 framework: the soft step's step. It prepares each point once per step, then runs the
// substeps with the students' softCoefficients() and softNormalImpulse(), and keeps each body's
// motion for placeBodies() (soft_step.cpp).
//
// In a grade this file runs in the worker, beside the submitted functions it calls (IN_WORKER in
// CMakeLists.txt; docs/grading.md, "Where submitted code runs"): the sweeps call
// softNormalImpulse() once per point, per sweep, per substep, some 10^5 times a second of a
// stack, which across the wire would cost a pipe round trip each.
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "physlab/error.hpp"
#include "physlab/rigid.hpp"
#include "physlab/soft_step.hpp"

namespace physlab {

namespace {
// A point whose effective mass along a row is not positive (both bodies fixed), out of line
[[noreturn, gnu::cold, gnu::noinline]] void throwNoMovingBody(int contact, const Vec3& K) {
  int row = 0;
  while (row < 2 && K(row) > 0.0) ++row;
  throw InvalidInput("soft step: contact " + std::to_string(contact) + " has no moving body along row " +
                     std::to_string(row));
}
}  // namespace

int SoftStepSolver::solve(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts,
                          const std::vector<int>& resting, const std::vector<BodyDescription>& /*descriptions*/,
                          const std::vector<BodyState>& /*states*/, const Vec3& gravity, double h) {
  const int n = settings_.substeps;
  const double h_s = h / n;
  soft_ = softCoefficients(settings_.contact_hertz, settings_.damping_ratio, h_s);
  soft_fixed_ = softCoefficients(settings_.fixed_hertz_scale * settings_.contact_hertz, settings_.damping_ratio, h_s);

  // Gravity, applied by the World over h, comes back per substep; no motion yet
  dq_.assign(bodies.size(), Quat::Identity());
  motion_.resize(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const ContactBody& body = bodies[i];
    motion_[i] = {body.inv_mass > 0.0 ? Vec3(body.v - h * gravity) : body.v, body.omega, body.inv_mass, Vec3::Zero(),
                  Vec3::Zero()};
  }

  // The sweep order: a pair's points together (the sweeps keep its two bodies in registers while
  // they visit them, as Box2D solves a manifold), the pairs from the highest point down along
  // -gravity (or in the World's order). A pair here is a run of points with the same bodies and
  // normal
  order_.clear();
  for (std::size_t k = 0; k < resting.size(); ++k) {
    const Contact& c = contacts[static_cast<std::size_t>(resting[k])];
    const double height = settings_.top_down ? c.p.dot(gravity) : 0.0;
    const Contact* previous = k > 0 ? &contacts[static_cast<std::size_t>(resting[k - 1])] : nullptr;
    const bool same_pair = previous && previous->a == c.a && previous->b == c.b && previous->n == c.n;
    if (same_pair) {
      order_.back().height = std::min(order_.back().height, height);
      ++order_.back().count;
    } else {
      order_.push_back({height, static_cast<int>(k), 1});
    }
  }
  if (settings_.top_down) {
    // Ties keep the World's order (std::stable_sort would, but it takes a buffer from the heap
    // at every step)
    std::sort(order_.begin(), order_.end(),
              [](const Run& x, const Run& y) { return x.height < y.height || (x.height == y.height && x.first < y.first); });
  }
  sweep_contacts_.clear();
  for (const Run& run : order_) {
    for (int k = run.first; k < run.first + run.count; ++k) sweep_contacts_.push_back(resting[static_cast<std::size_t>(k)]);
  }

  // Pairs: bodies and rows' directions. Points: Jacobian parts from the anchors, effective
  // masses; the warm start is last step's impulse per substep
  pairs_.resize(order_.size());
  points_.resize(resting.size());
  const double per_substep = 1.0 / n;
  for (std::size_t p = 0, k = 0; p < order_.size(); ++p) {
    const Contact& first = contacts[static_cast<std::size_t>(sweep_contacts_[k])];
    Pair& pair = pairs_[p];
    pair.a = static_cast<std::size_t>(first.a);
    pair.b = static_cast<std::size_t>(first.b);
    pair.d[0] = first.n;
    std::tie(pair.d[1], pair.d[2]) = tangentPair(first.n);
    const ContactBody& A = bodies[pair.a];
    const ContactBody& B = bodies[pair.b];
    pair.soft_fixed = A.inv_mass == 0.0 || B.inv_mass == 0.0;
    pair.first = static_cast<int>(k);
    pair.count = order_[p].count;
    for (int m = 0; m < pair.count; ++m, ++k) {
      const Contact& c = contacts[static_cast<std::size_t>(sweep_contacts_[k])];
      Point& pt = points_[k];
      const Vec3 r_a = c.p - A.x, r_b = c.p - B.x;  // the anchors, from the centres at the step's start
      Vec3 K;
      for (int i = 0; i < 3; ++i) {
        Row& row = pt.rows[i];
        row.ang_a = r_a.cross(pair.d[i]);
        row.ang_b = r_b.cross(pair.d[i]);
        row.turn_a = A.I_inv_world * row.ang_a;
        row.turn_b = B.I_inv_world * row.ang_b;
        K(i) = A.inv_mass + B.inv_mass + row.ang_a.dot(row.turn_a) + row.ang_b.dot(row.turn_b);
      }
      if (!(K.minCoeff() > 0.0)) throwNoMovingBody(sweep_contacts_[k], K);
      for (int i = 0; i < 3; ++i) pt.mass[i] = 1.0 / K(i);
      // The n row's velocity change per unit tangent impulse, and the reverse (K is symmetric;
      // the rows' directions are orthogonal, so only the turns couple them)
      for (int i = 1; i < 3; ++i) {
        pt.coupling(i - 1) = pt.rows[0].ang_a.dot(pt.rows[i].turn_a) + pt.rows[0].ang_b.dot(pt.rows[i].turn_b);
      }
      pt.depth = c.depth;
      pt.separation = -c.depth;
      pt.mu = c.mu;
      pt.bounce = c.kind == ContactKind::Colliding && c.epsilon > 0.0;
      pt.target = -c.epsilon * c.v_rel_minus;
      pt.pushed = 0.0;
      pt.total = Vec3::Zero();
      pt.lambda = Vec3(std::max(0.0, c.j), c.j_t.dot(pair.d[1]), c.j_t.dot(pair.d[2])) * per_substep;
      const double radius = pt.mu * pt.lambda(0), length2 = pt.lambda.tail<2>().squaredNorm();
      if (length2 > radius * radius) pt.lambda.tail<2>() *= radius / std::sqrt(length2);
    }
  }

  // The substeps: gravity and the warm start (the last substep's impulses again), soft sweeps,
  // positions, relax sweeps. The first warm start is last step's impulses, gathered per body
  // from the points. A substep's impulses add up to the change they made to its bodies'
  // velocities, so each later warm start is that change, taken per body (the velocity at the
  // substep's end less the one before its warm start), with no second pass over the points
  const Vec3 dv = h_s * gravity;
  warm_.assign(bodies.size(), Velocity{});
  for (const Pair& pair : pairs_) {
    for (int k = pair.first; k < pair.first + pair.count; ++k) {
      const Point& pt = points_[static_cast<std::size_t>(k)];
      pt.apply(pair, warm_[pair.a], warm_[pair.b], motion_[pair.a].inv_mass, motion_[pair.b].inv_mass, pt.lambda);
    }
  }
  const int sweeps = settings_.solve_iterations + settings_.relax_iterations;
  bool moved = false;  // the bodies moved since the points' separations were found
  for (int step = 0; step < n; ++step) {
    for (std::size_t i = 0; i < motion_.size(); ++i) {
      Motion& body = motion_[i];
      if (body.inv_mass > 0.0) body.v += dv;
      const Velocity warm = warm_[i];
      warm_[i] = {-body.v, -body.omega};
      body.v += warm.v;
      body.omega += warm.omega;
    }
    for (int i = 0; i < sweeps; ++i) {
      const bool relax = i >= settings_.solve_iterations;
      if (relax) {
        sweep<true>(h_s, i + 1 == sweeps, moved);
      } else {
        sweep<false>(h_s, i + 1 == sweeps, moved);
      }
      moved = false;
      if (i + 1 != settings_.solve_iterations) continue;
      moved = true;
      for (std::size_t j = 0; j < motion_.size(); ++j) {
        Motion& body = motion_[j];
        if (!(body.inv_mass > 0.0)) continue;
        body.dx += h_s * body.v;
        if (body.omega.isZero()) continue;
        body.dtheta += h_s * body.omega;
        dq_[j] = exponentialUpdate(dq_[j], body.omega, h_s);
      }
    }
    for (std::size_t i = 0; i < motion_.size(); ++i) {
      warm_[i].v += motion_[i].v;
      warm_[i].omega += motion_[i].omega;
    }
  }

  // Restitution: a colliding point that was pushed aims at its bounce, once. Then the step's
  // impulses go back to the contacts
  for (const Pair& pair : pairs_) {
    Motion &A = motion_[pair.a], &B = motion_[pair.b];
    for (int k = pair.first; k < pair.first + pair.count; ++k) {
      Point& pt = points_[static_cast<std::size_t>(k)];
      if (pt.bounce && pt.pushed > 0.0) {
        const double v_n = pt.velocity(pair.d[0], A.v - B.v, A, B, 0);
        const double lambda = std::max(0.0, pt.lambda(0) - pt.mass[0] * (v_n - pt.target));
        const double change = lambda - pt.lambda(0);
        pt.apply(pair, A, B, A.inv_mass, B.inv_mass, Vec3(change, 0.0, 0.0), 0, 1);
        pt.lambda(0) = lambda;
        pt.total(0) += change;
      }
      Contact& c = contacts[static_cast<std::size_t>(sweep_contacts_[static_cast<std::size_t>(k)])];
      c.j = pt.total(0);
      c.j_t = pt.total(1) * pair.d[1] + pt.total(2) * pair.d[2];
    }
  }
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    bodies[i].v = motion_[i].v;
    bodies[i].omega = motion_[i].omega;
  }
  moved_ = true;
  return n * (settings_.solve_iterations + settings_.relax_iterations);
}

// One Gauss-Seidel sweep over the points: the normal row by softNormalImpulse() at the separation
// now, then friction on the disc of radius mu lambda_n (a relax sweep only shrinks the friction
// impulse onto the new disc: it takes back the normal push, friction was solved by the soft
// sweep). A pair's points come together: its two bodies' velocities are read once, updated in
// local copies and written back once. The first sweep after the bodies moved (`moved`) finds
// each point's separation, the others reuse it. The substep's closing sweep adds each point's
// final impulses to the step's
template <bool relax>
void SoftStepSolver::sweep(double h_s, bool closing, bool moved) {
  for (const Pair& pair : pairs_) {
    const std::size_t a = pair.a, b = pair.b;
    const double inv_a = motion_[a].inv_mass, inv_b = motion_[b].inv_mass;
    const SoftCoefficients& soft = pair.soft_fixed ? soft_fixed_ : soft_;
    Velocity A{motion_[a].v, motion_[a].omega}, B{motion_[b].v, motion_[b].omega};
    for (int k = pair.first; k < pair.first + pair.count; ++k) {
      Point& pt = points_[static_cast<std::size_t>(k)];
      if (moved) pt.separation = pt.gap(pair.d[0], motion_[a], motion_[b]);
      const Vec3 dv = A.v - B.v;
      const double v_n = pt.velocity(pair.d[0], dv, A, B, 0);
      const double lambda_n =
          softNormalImpulse(pt.lambda(0), v_n, pt.separation, pt.mass[0], soft, h_s, settings_.max_push, relax);
      const double change_n = lambda_n - pt.lambda(0);
      // Friction: rigid, each tangent's own effective mass, the pair clamped to the disc. Its
      // velocities are read before the normal impulse and moved by it through the rows' coupling
      Eigen::Vector2d lambda_T = pt.lambda.tail<2>();
      if constexpr (!relax) {
        const Eigen::Vector2d v_T(pt.velocity(pair.d[1], dv, A, B, 1), pt.velocity(pair.d[2], dv, A, B, 2));
        lambda_T -= Eigen::Vector2d(pt.mass[1], pt.mass[2]).cwiseProduct(v_T + change_n * pt.coupling);
      }
      const double radius = pt.mu * lambda_n, length2 = lambda_T.squaredNorm();
      if (length2 > radius * radius) lambda_T *= radius / std::sqrt(length2);
      const Vec3 lambda(lambda_n, lambda_T(0), lambda_T(1));
      if (relax && lambda_T == pt.lambda.tail<2>()) {
        pt.apply(pair, A, B, inv_a, inv_b, Vec3(change_n, 0.0, 0.0), 0, 1);  // friction as it was: the normal row alone
      } else {
        pt.apply(pair, A, B, inv_a, inv_b, lambda - pt.lambda);
      }
      pt.lambda = lambda;
      if (closing) pt.addToStep();
    }
    motion_[a].v = A.v;
    motion_[a].omega = A.omega;
    motion_[b].v = B.v;
    motion_[b].omega = B.omega;
  }
}

}  // namespace physlab
