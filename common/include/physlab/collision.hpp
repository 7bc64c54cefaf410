/// \file collision.hpp
/// \brief Lab 4: shapes, contact manifolds, the narrow phase, GJK distance and time of impact.
///
/// The lecture's rule for convex bodies: two of them do not interpenetrate if and only if a
/// separating plane exists between them. The narrow phase searches for that plane (the
/// separating-axis test); when none exists it reports *where* the bodies touch, as a contact
/// manifold that Labs 5 and 6 turn into impulses and contact forces.
///
/// Conventions (see \ref conventions, section Contacts):
/// - A Manifold's normal \f$\hat n\f$ is a unit vector, world frame, pointing **from B to A**: moving A
///   along \f$+\hat n\f$ by the depth separates the pair.
/// - A contact's depth \f$d\f$ is **positive when the shapes overlap** [m].
/// - A contact's position is the midpoint of the two touching surface points: A's deepest point
///   inside B is \f$p - \tfrac d2 \hat n\f$ and B's deepest point inside A is \f$p + \tfrac d2 \hat n\f$.
///   The position (and the depth) do not change when A and B are swapped; the normal flips.
/// - A contact's feature id names the pair of features (faces, edges, vertices) that produced it;
///   it stays the same from step to step while the same features touch, so a solver can carry
///   the previous step's impulse over (warm starting). Ids are unique within one manifold and
///   carry no other meaning.
///
/// Shapes are described in their body frame, centred on the body's centre of mass; a Pose
/// places them in the world: \f$p_{world} = x + R(q)\, p_{body}\f$. Plane is the exception: it is a
/// static half-space given in the world frame, and its pose is ignored.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "physlab/broadphase.hpp"
#include "physlab/math.hpp"

namespace physlab {

// ---------------------------------------------------------------------------------------------
/// \name Poses and motions
///@{

/// Where a body is: the world position of its centre and its orientation (as in Lab 3).
struct Pose {
  Vec3 x = Vec3::Zero();     ///< centre of the body (its centre of mass), world frame [m]
  Quat q = Quat::Identity();  ///< orientation, unit quaternion: body -> world
  /// World coordinates of a body-frame point: \f$x + R\, p_{body}\f$ [m].
  Vec3 toWorld(const Vec3& p_body) const { return x + q * p_body; }
  /// Body coordinates of a world point: \f$R^T (p - x)\f$ [m].
  Vec3 toBody(const Vec3& p_world) const { return q.conjugate() * (p_world - x); }
};

/// \cond INTERNAL
// The checks of validatePose() that name the fault (shapes.cpp).
void refuseBadPose(const Pose& pose, std::string_view what);
/// \endcond

/// Throws InvalidInput naming `what` when the pose has a non-finite position or a quaternion that
/// is not finite and of unit norm (within 1e-6). Every Lab 4 routine calls it on its poses before
/// using them; it allocates nothing unless it throws.
inline void validatePose(const Pose& pose, std::string_view what) {
  // Inline, as every narrow-phase call pays it: the common case in a few instructions (every
  // entry finite, by one sum; |q|^2 within the bounds of |q| in [1 - 1e-6, 1 + 1e-6]), the checks
  // that name the fault out of line
  constexpr double kLow = (1.0 - 1e-6) * (1.0 - 1e-6), kHigh = (1.0 + 1e-6) * (1.0 + 1e-6);
  const double norm2 = pose.q.squaredNorm();
  if (!(std::isfinite(pose.x.sum() + norm2) && norm2 >= kLow && norm2 <= kHigh)) refuseBadPose(pose, what);
}

/// Constant velocities of a body over one step, world frame.
struct Motion {
  Vec3 v = Vec3::Zero();      ///< velocity of the centre, world frame [m/s]
  Vec3 omega = Vec3::Zero();  ///< angular velocity, world frame [rad/s]
};

/// Throws InvalidInput naming `what` when the velocity or the angular velocity is not finite
/// (the time-of-impact routines call it on their motions); allocates nothing unless it throws.
void validateMotion(const Motion& motion, std::string_view what);

/// The pose after time `t` [s] of constant `motion`: \f$x + v t\f$ and
/// \f$q(t) = \exp(\tfrac t2 \omega)\, q\f$ (a turn by \f$|\omega| t\f$ about \f$\omega\f$, about the centre).
Pose advance(const Pose& pose, const Motion& motion, double t);
///@}

// ---------------------------------------------------------------------------------------------
/// \name Shapes
/// Each constructor validates its sizes and throws InvalidInput naming what is wrong.
///@{

/// A ball of radius r about the body origin.
struct Sphere {
  /// A sphere of radius r > 0 [m]; throws InvalidInput otherwise.
  explicit Sphere(double radius);
  double radius;  ///< r [m]
};

/// A box \f$|p_i| \le h_i\f$ in the body frame.
struct Box {
  /// A box of positive, finite half extents [m]; throws InvalidInput otherwise.
  explicit Box(const Vec3& half_extents);
  Vec3 half_extents;  ///< \f$h = (h_x, h_y, h_z)\f$, body frame [m]
};

/// The points within `radius` of the segment from \f$(0, 0, -h)\f$ to \f$(0, 0, h)\f$, body frame.
struct Capsule {
  /// A capsule of radius r > 0 and half height h > 0 [m]; throws InvalidInput otherwise.
  Capsule(double radius, double half_height);
  double radius;       ///< r [m]
  double half_height;  ///< h: half the length of the core segment, along body z [m]
  /// The two ends of the core segment in the world, \f$x \mp h\, R e_z\f$ [m].
  std::array<Vec3, 2> segment(const Pose& pose) const;
};

/// The static half-space \f$\hat n \cdot p \le d\f$, world frame (its pose is ignored). The solid is
/// on the side opposite to the normal: a ground at height 0 is Plane(Vec3::UnitZ(), 0).
struct Plane {
  /// The normal is normalised (and `offset` scaled with it); a zero normal is refused.
  Plane(const Vec3& normal, double offset);
  Vec3 normal;    ///< \f$\hat n\f$, unit, pointing out of the solid, world frame
  double offset;  ///< d [m]
};

/// A convex polyhedron: vertices and faces in the body frame.
struct ConvexPolyhedron {
  /// Each face lists its vertex indices counter-clockwise seen from outside. Throws InvalidInput
  /// when there are fewer than 4 vertices or they are coplanar, a face has fewer than 3 vertices
  /// (or more than 32) or is not planar, a vertex lies outside a face's plane (not convex), or an
  /// edge is not shared by exactly two faces in opposite directions (inconsistent faces).
  ConvexPolyhedron(std::vector<Vec3> vertices, std::vector<std::vector<int>> faces);
  /// A box with the given half extents as a polyhedron (8 vertices, 6 faces).
  static ConvexPolyhedron box(const Vec3& half_extents);
  /// The tetrahedron with corners a, b, c, d (any order), body frame; refused when flat.
  static ConvexPolyhedron tetrahedron(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

  std::vector<Vec3> vertices;            ///< body frame [m]
  std::vector<std::vector<int>> faces;   ///< vertex indices, counter-clockwise from outside
  std::vector<Vec3> normals;             ///< outward unit normal of each face, body frame
  std::vector<double> offsets;           ///< face plane \f$\hat n_f \cdot p = o_f\f$, body frame [m]
  std::vector<std::array<int, 2>> edges;  ///< each edge once, as a pair of vertex indices
};

/// A triangle with corners a, b, c in the body frame (a flat, two-sided shape).
struct Triangle {
  /// Refuses a degenerate triangle (zero area) or non-finite corners.
  Triangle(const Vec3& a, const Vec3& b, const Vec3& c);
  std::array<Vec3, 3> corners;  ///< a, b, c, body frame [m]
};

/// Any of the shapes above.
using Shape = std::variant<Sphere, Box, Capsule, Plane, ConvexPolyhedron, Triangle>;

/// A shape's fields are public, so one changed after construction (`Sphere s(1); s.radius = -1;`)
/// escapes its constructor's checks: every Lab 4 routine calls validateShape() on its shapes
/// before using them. Throws InvalidInput naming `what` and the field when a size is not positive
/// and finite (sphere, box, capsule), a plane's normal is not a finite unit vector (length within
/// 1e-9 of 1) or its offset not finite, a triangle's corner is not finite or its area zero, or a
/// polyhedron has a non-finite vertex, fewer than 4 vertices or faces, a face of fewer than 3 or
/// more than 32 vertices, a vertex index out of range (in a face or an edge), normals or offsets
/// not one per face, a normal that is not a finite unit vector or an offset that is not finite.
/// A polyhedron's convexity is its constructor's check only (too dear to repeat per query): its
/// check here is linear in its size, the others' constant. Allocates nothing unless it throws.
void validateShape(const Shape& shape, std::string_view what);
void validateShape(const Sphere& sphere, std::string_view what);              ///< as for a Shape
inline void validateShape(const Box& box, std::string_view what);             ///< as for a Shape
void validateShape(const Capsule& capsule, std::string_view what);            ///< as for a Shape
void validateShape(const Plane& plane, std::string_view what);                ///< as for a Shape
void validateShape(const ConvexPolyhedron& polyhedron, std::string_view what);  ///< as for a Shape
void validateShape(const Triangle& triangle, std::string_view what);          ///< as for a Shape

/// \cond INTERNAL
// The checks of validateShape(Box) that name the fault (shapes.cpp).
void refuseBadBox(const Box& box, std::string_view what);
/// \endcond

// Inline, as every narrow-phase call pays it: the common case in a few instructions (every extent
// finite, by one sum, and positive), the checks that name the fault out of line.
inline void validateShape(const Box& box, std::string_view what) {
  if (!(std::isfinite(box.half_extents.sum()) && box.half_extents.minCoeff() > 0.0)) refuseBadBox(box, what);
}

/// A short name of the shape's kind: "sphere", "box", "capsule", "plane", "convex polyhedron",
/// "triangle".
const char* shapeName(const Shape& shape);

/// The support point: a point of the posed shape farthest along the world direction `d`,
/// \f$s(d) = \arg\max_{p \in S} d \cdot p\f$, world frame [m]. For a Plane (unbounded) it throws
/// InvalidInput. `d` need not be unit; for d = 0 any point of the shape is returned.
Vec3 support(const Shape& shape, const Pose& pose, const Vec3& d);

/// Every convex shape here is a *core* (a point, a segment, a polytope) grown by a radius, its
/// margin: a sphere is a point grown by r, a capsule a segment grown by r; the other shapes have
/// margin 0. GJK works on the cores (exact on flat faces) and subtracts the margins.
double margin(const Shape& shape);
/// The support point of the shape's core (see margin()), world frame [m].
Vec3 coreSupport(const Shape& shape, const Pose& pose, const Vec3& d);

/// The world-frame bounding box of the posed shape [m]. A Plane's box is infinite except along
/// an axis its normal is parallel to.
Aabb aabb(const Shape& shape, const Pose& pose);

/// The largest distance from the body origin to a point of the shape [m] (infinite for a Plane):
/// a point of the body moves at most \f$|v| + |\omega|\, \rho\f$ with \f$\rho\f$ this radius.
double boundingRadius(const Shape& shape);
/// The radius of a ball about the body origin inside the shape [m] (0 for a Triangle, infinite
/// for a Plane): a body moving less than this per sample cannot pass through a thin wall unseen.
double innerRadius(const Shape& shape);
///@}

// ---------------------------------------------------------------------------------------------
/// \name Contact manifolds
///@{

/// One contact point of a manifold (see the file's conventions).
struct ContactPoint {
  Vec3 position = Vec3::Zero();  ///< midpoint of the two touching surface points, world frame [m]
  double depth = 0.0;             ///< penetration along the normal, positive when overlapping [m]
  std::uint32_t id = 0;           ///< feature id: the same while the same features touch
};

/// The contact between two shapes: a normal from B to A and up to 4 points. Fixed capacity, so
/// building one allocates nothing.
struct Manifold {
  static constexpr int kMaxPoints = 4;  ///< at most 4 points (a face needs no more to rest on)
  Vec3 normal = Vec3::Zero();           ///< unit, world frame, from B to A (zero when empty)
  std::array<ContactPoint, kMaxPoints> points;  ///< the first `count` are valid
  int count = 0;                        ///< number of contact points, 0 when the shapes are apart
  /// True when the shapes are apart (no contact points).
  bool empty() const { return count == 0; }
  /// Appends a point (ignored when already full).
  void add(const Vec3& position, double depth, std::uint32_t id) {
    if (count < kMaxPoints) points[count++] = ContactPoint{position, depth, id};
  }
  /// The largest depth of its points [m] (0 when empty).
  double maxDepth() const;
};

/// Candidate contact points before reduction, e.g. a clipped polygon (fixed capacity 64).
struct ContactPolygon {
  static constexpr int kCapacity = 64;  ///< enough for a 32-gon clipped by 32 planes
  std::array<ContactPoint, kCapacity> points;  ///< the first `count` are valid
  int count = 0;                        ///< number of points
  /// Appends a point (ignored when already full).
  void add(const Vec3& position, double depth, std::uint32_t id) {
    if (count < kCapacity) points[count++] = ContactPoint{position, depth, id};
  }
};

/// Throws InvalidInput naming `what` when the polygon's count is outside [0, kCapacity] (its
/// points would be read out of bounds) or one of its first `count` points has a position or
/// depth that is not finite. Allocates nothing unless it throws.
void validatePolygon(const ContactPolygon& polygon, std::string_view what);

/// Combines two feature numbers into one id (order matters), for ids of clipped points.
constexpr std::uint32_t combineFeatures(std::uint32_t a, std::uint32_t b) {
  return (a ^ 0x9e3779b9u) * 16777619u ^ (b + 0x7f4a7c15u);
}
///@}

// ---------------------------------------------------------------------------------------------
/// \name Student functions (Lab 4): narrow phase
/// Each returns an empty Manifold when the shapes are apart (by any margin, however small) and
/// otherwise a normal from B to A with 1 to 4 points (positions as midpoints, depths >= 0). Each
/// first refuses (InvalidInput, naming the argument: "shape a", "pose_b") a shape validateShape()
/// refuses and a pose validatePose() refuses, so no bad input gives a NaN depth.
///@{

/// Two spheres: one point on the line of centres, depth \f$r_A + r_B - |x_A - x_B|\f$,
/// normal \f$(x_A - x_B)/|x_A - x_B|\f$ (+z when the centres coincide). Handout: Lab 4, section 2.
Manifold collideSphereSphere(const Sphere& a, const Pose& pose_a, const Sphere& b, const Pose& pose_b);
/// Sphere A against the plane B: depth \f$r - (\hat n \cdot x - d)\f$, normal \f$\hat n\f$.
/// Handout: Lab 4, section 2.
Manifold collideSpherePlane(const Sphere& a, const Pose& pose_a, const Plane& b);
/// Sphere A against box B: through the point of the box closest to the centre; when the centre
/// is inside the box, through the nearest face. Handout: Lab 4, section 2.
Manifold collideSphereBox(const Sphere& a, const Pose& pose_a, const Box& b, const Pose& pose_b);
/// Capsule A against sphere B: a sphere at the point of A's core segment closest to B's centre.
/// Handout: Lab 4, section 3.
Manifold collideCapsuleSphere(const Capsule& a, const Pose& pose_a, const Sphere& b, const Pose& pose_b);
/// Two capsules: spheres at the closest points of the two core segments; two points (the ends of
/// the overlap) when the segments are parallel. Handout: Lab 4, section 3.
Manifold collideCapsuleCapsule(const Capsule& a, const Pose& pose_a, const Capsule& b, const Pose& pose_b);
/// Box A against the plane B: every corner below the plane is a contact (id = corner index
/// \f$i_x + 2 i_y + 4 i_z\f$, \f$i_k = 1\f$ on the + side), reduced to 4 by reduceContacts().
/// Handout: Lab 4, section 4.
Manifold collideBoxPlane(const Box& a, const Pose& pose_a, const Plane& b);
/// The parameters s, t in [0, 1] of the closest points \f$p_1 + s (q_1 - p_1)\f$ and
/// \f$p_2 + t (q_2 - p_2)\f$ of two segments (either may be a single point). InvalidInput naming the
/// point when p1, q1, p2 or q2 is not finite. Handout: Lab 4, section 3.
std::array<double, 2> closestSegmentParameters(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2);

/// One step of Sutherland-Hodgman clipping: keeps the part of the convex polygon with
/// \f$\hat m \cdot p \le o\f$; a point made where an edge crosses the plane gets the id
/// combineFeatures(id of the edge's first point, `plane_id`) and depth 0. InvalidInput naming it
/// when the polygon's count is outside [0, kCapacity] or a point it counts is not finite, or the
/// plane's normal or offset is not finite. Handout: Lab 4, section 5.
ContactPolygon clipPolygon(const ContactPolygon& polygon, const Vec3& plane_normal, double plane_offset,
                           std::uint32_t plane_id);
/// At most 4 of the candidates, chosen to keep the contact area: the deepest point, the point
/// farthest from it, the point farthest from the line through those two, and the point outside
/// that triangle that adds the most area to it (distances and areas measured in the plane normal
/// to `normal`), in this order. Points are copied unchanged. With at most 4 candidates (4
/// included) every candidate is kept, in its order, even when they span no area. InvalidInput
/// naming it when the normal is not finite, or the candidates' count is outside [0, kCapacity] or
/// a point it counts has a non-finite position or depth. Handout: Lab 4, section 5.
Manifold reduceContacts(const Vec3& normal, const ContactPolygon& candidates);

/// A face axis wins over an edge axis unless the edge axis's overlap is smaller by more than this
/// fraction: faces give stable multi-point manifolds, and near-ties would flip between axes.
constexpr double kEdgeAxisBias = 0.02;

/// Two boxes by the separating-axis test over the 15 axes (3 faces of A, 3 of B, 9 edge pairs).
/// The axis of least overlap gives the normal; a face axis is then a reference face whose side
/// planes clip the most anti-parallel (incident) face of the other box, keeping the clipped
/// points below the reference face (at most 8, reduced to 4); an edge axis gives one point at
/// the closest points of the two edges. Handout: Lab 4, section 5.
Manifold collideBoxBox(const Box& a, const Pose& pose_a, const Box& b, const Pose& pose_b);
/// Two convex polyhedra by the separating-axis test over the face normals of both and the cross
/// products of their edge directions, then clipping as for boxes. Handout: Lab 4, section 6.
Manifold collideConvexConvex(const ConvexPolyhedron& a, const Pose& pose_a, const ConvexPolyhedron& b,
                             const Pose& pose_b);
/// Whether two triangles intersect, as in the lecture: triangles ABC and DEF intersect when two
/// edges of one pierce the interior of the other, or one edge of each pierces the other.
/// (Coplanar triangles count as not intersecting.) Handout: Lab 4, section 7.
bool trianglesIntersect(const Triangle& a, const Pose& pose_a, const Triangle& b, const Pose& pose_b);
///@}

/// The narrow phase for any pair: validates both shapes and poses, then calls the routine for the pair's
/// kinds (swapping A and B, and flipping the normal back, when the routine takes them the other
/// way round). Boxes meet polyhedra as polyhedra; capsules and polyhedra meet planes through
/// their corners and end spheres; the framework handles spheres against polyhedra and capsules
/// against boxes and polyhedra (closest points of the core; when the core reaches inside, the
/// face of least overlap). Throws InvalidInput for a pair without a routine (naming it): plane-plane
/// and triangles (use trianglesIntersect()).
Manifold collide(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b);

// ---------------------------------------------------------------------------------------------
/// \name Student functions (Lab 4): GJK distance
///@{

/// The result of a distance query.
struct DistanceResult {
  double distance = 0.0;           ///< \f$\min |p_A - p_B|\f$ when apart, 0 when overlapping [m]
  bool overlap = false;            ///< true when the shapes intersect (or touch within round-off)
  Vec3 point_a = Vec3::Zero();     ///< closest point on A, world frame [m] (meaningful when apart)
  Vec3 point_b = Vec3::Zero();     ///< closest point on B, world frame [m] (meaningful when apart)
  int iterations = 0;              ///< GJK iterations (support queries) used
};

/// Distance between two bounded convex shapes by GJK on the Minkowski difference of their cores
/// (see margin()): the simplex's closest point to the origin \f$v\f$ is refined with the support
/// point \f$w = s_A(-v) - s_B(v)\f$ until \f$|v|^2 - v \cdot w \le \varepsilon |v|^2\f$
/// (\f$\varepsilon = 10^{-10}\f$) or \f$|v|\f$ stops shrinking (round-off); the origin inside the
/// simplex means overlap. The margins are then subtracted. Planes are refused (InvalidInput); use
/// distance(). Like the narrow phase, refuses bad shapes and poses naming them ("shape a",
/// "pose_b"). Handout: Lab 4, section 8.
DistanceResult gjkDistance(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b);
///@}

/// Distance for any pair: closed forms against a Plane (the other shape's support point along
/// \f$-\hat n\f$) and for a Sphere against a Sphere or a Box (its centre clamped to the box in
/// the box's frame), gjkDistance() otherwise. Closed forms report 1 iteration; touching counts as
/// overlap, as in GJK. So time of impact on those pairs needs no GJK. Validates both shapes and
/// poses.
DistanceResult distance(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b);

// ---------------------------------------------------------------------------------------------
/// \name Student functions (Lab 4): time of impact
/// Both methods move the bodies with advance() over the step [0, h] and report the first time
/// of contact \f$t_c\f$ to a distance `tolerance`: the returned time \f$t\f$ has the shapes apart
/// (or touching) with a gap of at most `tolerance` [m], \f$t \le t_c\f$. A Plane must not move.
/// Both throw InvalidInput, naming the argument, unless `h` and `tolerance` are positive and finite,
/// the shapes pass validateShape(), the poses validatePose() and the motions validateMotion()
/// ("shape a", "pose_a", "motion_a", and the same for b).
///@{

/// The answer of a time-of-impact query.
struct ToiResult {
  bool hit = false;   ///< whether the shapes touch within the step
  double time = 0.0;  ///< the time of first contact when hit, in [0, h] [s]
  int queries = 0;    ///< overlap tests (bisection) or distance queries (advancement) made
};

/// The largest speed at which any point of A can approach B along the unit direction `n` (from
/// B to A): \f$(v_B - v_A) \cdot \hat n + |\omega_A|\rho_A + |\omega_B|\rho_B\f$ with \f$\rho\f$ the
/// bounding radii (a Plane, which does not move, contributes nothing) [m/s].
double approachSpeedBound(const Shape& a, const Motion& motion_a, const Shape& b, const Motion& motion_b,
                          const Vec3& n);

/// Bisection on the overlap test (distance().overlap). The step is first sampled at N + 1 evenly
/// spaced times 0, h/N, ..., h, with N the fewest samples such that no point approaches by more
/// than the sum of the shapes' innerRadius() between samples (so a fast body cannot pass through
/// a thin wall unseen): \f$N = \lceil \mu h / (r_{in,A} + r_{in,B}) \rceil\f$ with \f$\mu\f$ the
/// approachSpeedBound() along the relative velocity, clamped to [1, 4096]. A pair overlapping at
/// t = 0 is a hit at time 0; otherwise the first sample that overlaps brackets the contact with
/// the previous one, and the bracket is halved until the approach over it, \f$\mu\f$ times its
/// length, is at most `tolerance`. Every overlap test counts in `queries`. Handout: Lab 4,
/// section 9.
ToiResult toiBisection(const Shape& a, const Pose& pose_a, const Motion& motion_a, const Shape& b,
                       const Pose& pose_b, const Motion& motion_b, double h, double tolerance);
/// Conservative advancement (Mirtich): from the distance \f$d\f$ and closest-point direction
/// \f$\hat n\f$ at time t, no contact can happen before \f$t + d / \mu\f$ with \f$\mu\f$ the
/// approachSpeedBound(); advance to it and repeat until \f$d \le\f$ `tolerance` (hit) or past h
/// (none; a time exactly h is still in the step). A pair overlapping at t = 0 is a hit at time 0.
/// Every distance query counts in `queries`, the last one included. Handout: Lab 4, section 9.
ToiResult toiConservativeAdvancement(const Shape& a, const Pose& pose_a, const Motion& motion_a, const Shape& b,
                                     const Pose& pose_b, const Motion& motion_b, double h, double tolerance);
///@}

// ---------------------------------------------------------------------------------------------
/// \name Scenes for tests, demos and benchmarks
///@{

/// A body of a collision scene: shape, pose now, and velocities over the next step.
struct CollisionBody {
  Shape shape;    ///< the shape, body frame
  Pose pose;      ///< where it is
  Motion motion;  ///< its velocities
};

/// `count` random spheres, boxes, capsules and tetrahedra (sizes 0.1-0.5 m) at random poses and
/// velocities (up to 2 m/s, 3 rad/s) inside the cube \f$[-L/2, L/2]^3\f$, L = `size`; the same
/// `seed` gives the same soup.
std::vector<CollisionBody> shapeSoup(int count, double size, std::uint64_t seed);
/// A ground plane z <= 0 (first) and `count` unit cubes stacked on it, each resting on the one
/// below with overlap `overlap` [m].
std::vector<CollisionBody> boxStack(int count, double overlap = 0.0);
/// A ground plane z <= 0 (first) and a pyramid of unit cubes, `rows` at the bottom, one fewer
/// per row up, in the x-z plane, touching side by side.
std::vector<CollisionBody> boxPyramid(int rows);
/// A thin wall (a box 0.02 m thick, 2 m square, normal x, at the origin) and a small sphere
/// (radius 0.05 m) 1 m before it flying at `speed` [m/s] towards it: at 300 m/s and a step of
/// 1/60 s it passes the wall between the start and the end of a step.
std::vector<CollisionBody> bulletAndWall(double speed = 300.0);
///@}

}  // namespace physlab
