// Framework-internal: spheres and capsules (a point or segment core grown by a radius) against
// convex polyhedra, used by collide().
#pragma once

#include "physlab/collision.hpp"

namespace physlab {

/// Contact of the core segment [p0, p1] (p0 = p1 for a sphere) grown by `radius` (shape A)
/// against the polyhedron B; normal from B to A, positions as midpoints.
Manifold collideRoundedPolytope(const Vec3& p0, const Vec3& p1, double radius, const ConvexPolyhedron& b,
                                const Pose& pose_b);

}  // namespace physlab
