// Bullet's btDiscreteDynamicsWorld holding one of our Scenes (Labs 5 and 6 benchmarks): the same
// shapes (spheres, boxes, planes), masses, diagonal inertias, restitution, friction, poses and
// velocities, with our World's pair rules and Settings where Bullet has a knob (iterations,
// restitution threshold, gravity), two friction directions per point, sleeping off unless asked
// for (then Bullet's own deactivation with its defaults: see BulletWorld()). Compiled only with
// Bullet (PHYSLAB_HAVE_BULLET); nothing else needs it.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <LinearMath/btScalar.h>
#include <btBulletDynamicsCommon.h>

#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab::bench {

inline btVector3 toBt(const Vec3& v) { return btVector3(v.x(), v.y(), v.z()); }
inline Vec3 fromBt(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }

// Our World's pair rules (World::computeContacts), installed in place of Bullet's products.
inline btScalar minRestitution(const btCollisionObject* a, const btCollisionObject* b) {
  return std::min(a->getRestitution(), b->getRestitution());
}
inline btScalar meanFriction(const btCollisionObject* a, const btCollisionObject* b) {
  return std::sqrt(a->getFriction() * b->getFriction());
}

// A Bullet world holding the same scene: shapes, masses, diagonal inertias, restitution,
// friction and initial states taken from our descriptions. Every body has DISABLE_DEACTIVATION
// unless `deactivation`: then each keeps Bullet's default activation (ACTIVE_TAG) and sleeping
// thresholds (0.8 m/s, 1 rad/s, for gDeactivationTime = 2 s), and an island all of whose bodies
// stayed below them sleeps (ISLAND_SLEEPING) until something wakes it.
class BulletWorld {
 public:
  BulletWorld(const Scene& scene, const Settings& settings, bool deactivation = false) : deactivation_(deactivation) {
    // A box meeting a plane gets its full manifold at once (Bullet's perturbed multipoint
    // contacts, 3 iterations below 3 points), not one corner per step: by default a box dropped
    // flat lands on a single corner and tumbles, a torque no engine with a face manifold gives
    config_.setPlaneConvexMultipointIterations();
    world_.setGravity(toBt(settings.gravity));
    btContactSolverInfo& info = world_.getSolverInfo();
    info.m_numIterations = settings.iterations;
    info.m_restitutionVelocityThreshold = settings.restitution_threshold;
    info.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) add(scene.bodies[i], scene.states[i]);
  }
  ~BulletWorld() {
    // The world's destructor touches its objects: take them out while they still exist
    for (auto it = bodies_.rbegin(); it != bodies_.rend(); ++it) world_.removeRigidBody(it->get());
  }
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  void step(double h) { world_.stepSimulation(h, 0); }  // maxSubSteps = 0: one step of exactly h

  // The deepest penetration and the number of contact points of the manifolds now.
  std::pair<double, int> contacts() const {
    double deepest = 0.0;
    int points = 0;
    btDispatcher* dispatcher = world_.getDispatcher();
    for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
      const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
      for (int k = 0; k < manifold->getNumContacts(); ++k) {
        deepest = std::max(deepest, -static_cast<double>(manifold->getContactPoint(k).getDistance()));
        ++points;
      }
    }
    return {deepest, points};
  }

  Vec3 position(int i) const { return fromBt(bodies_[static_cast<std::size_t>(i)]->getWorldTransform().getOrigin()); }
  Vec3 velocity(int i) const { return fromBt(bodies_[static_cast<std::size_t>(i)]->getLinearVelocity()); }
  int size() const { return static_cast<int>(bodies_.size()); }
  /// Moving bodies Bullet has put to sleep (ISLAND_SLEEPING).
  int asleep() const {
    return static_cast<int>(std::count_if(bodies_.begin(), bodies_.end(), [](const std::unique_ptr<btRigidBody>& b) {
      return !b->isStaticObject() && b->getActivationState() == ISLAND_SLEEPING;
    }));
  }
  /// Body i as our BodyState: x, q, \f$P = m v\f$, \f$L = R I_{body} R^T \omega\f$ (zero momenta when fixed).
  BodyState state(int i) const {
    const std::size_t k = static_cast<std::size_t>(i);
    const btRigidBody& rb = *bodies_[k];
    const btTransform& pose = rb.getWorldTransform();
    const btQuaternion r = pose.getRotation();
    BodyState s;
    s.x = fromBt(pose.getOrigin());
    s.q = Quat(r.w(), r.x(), r.y(), r.z());
    if (masses_[k] > 0.0) {
      const Mat3 R = s.q.toRotationMatrix();
      s.P = masses_[k] * fromBt(rb.getLinearVelocity());
      s.L = R * inertias_[k] * R.transpose() * fromBt(rb.getAngularVelocity());
    }
    return s;
  }

 private:
  void add(const BodyDescription& body, const BodyState& state) {
    std::unique_ptr<btCollisionShape> shape;
    if (const auto* sphere = std::get_if<Sphere>(&body.shape)) {
      shape = std::make_unique<btSphereShape>(sphere->radius);
    } else if (const auto* box = std::get_if<Box>(&body.shape)) {
      shape = std::make_unique<btBoxShape>(toBt(box->half_extents));
    } else if (const auto* plane = std::get_if<Plane>(&body.shape)) {
      shape = std::make_unique<btStaticPlaneShape>(toBt(plane->normal), plane->offset);
    } else {
      throw InvalidInput(std::string("the Bullet scene has no ") + shapeName(body.shape));
    }
    const Mat3& I = body.inertia_body;
    if (!body.fixed && !I.isApprox(Mat3(I.diagonal().asDiagonal()))) {
      throw InvalidInput("the Bullet scene takes diagonal body inertias only");
    }
    const double mass = body.fixed ? 0.0 : body.mass;
    masses_.push_back(mass);
    inertias_.push_back(I);
    const btVector3 inertia = body.fixed ? btVector3(0, 0, 0) : toBt(I.diagonal());
    const btTransform pose(btQuaternion(state.q.x(), state.q.y(), state.q.z(), state.q.w()), toBt(state.x));
    motions_.push_back(std::make_unique<btDefaultMotionState>(pose));
    btRigidBody::btRigidBodyConstructionInfo info(mass, motions_.back().get(), shape.get(), inertia);
    info.m_restitution = body.epsilon;
    info.m_friction = body.mu;
    bodies_.push_back(std::make_unique<btRigidBody>(info));
    btRigidBody& rb = *bodies_.back();
    if (!body.fixed) {
      const Mat3 R = state.q.normalized().toRotationMatrix();
      rb.setLinearVelocity(toBt(state.P / body.mass));
      rb.setAngularVelocity(toBt(R * I.inverse() * R.transpose() * state.L));
    }
    if (!deactivation_) rb.setActivationState(DISABLE_DEACTIVATION);
    shapes_.push_back(std::move(shape));
    world_.addRigidBody(&rb);
  }

  bool deactivation_;
  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_{&config_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  mutable btDiscreteDynamicsWorld world_{&dispatcher_, &broadphase_, &solver_, &config_};
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btDefaultMotionState>> motions_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::vector<double> masses_;  // 0 when fixed
  std::vector<Mat3> inertias_;  // body frame
};

/// Installs our pair rules (restitution the min, friction the geometric mean) in place of
/// Bullet's products; global in Bullet, so once per program.
inline void useOurPairRules() {
  gCalculateCombinedRestitutionCallback = &minRestitution;
  gCalculateCombinedFrictionCallback = &meanFriction;
}

/// "Bullet 3.24 (double)".
inline std::string bulletName() {
  return "Bullet " + std::to_string(btGetVersion() / 100) + "." + std::to_string(btGetVersion() % 100) +
         (sizeof(btScalar) == 8 ? " (double)" : " (float)");
}

}  // namespace physlab::bench
