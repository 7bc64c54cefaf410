/// \file math.hpp
/// \brief The fixed Eigen aliases every PhysLab file uses (double precision only).
///
/// Eigen expressions are lazy: never store one in `auto` (it may refer to temporaries that are
/// gone); name the concrete type below instead.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace physlab {

using Index = Eigen::Index;           ///< signed index type used by Eigen
using Vec3 = Eigen::Vector3d;         ///< 3-vector, frame stated where used
using Mat3 = Eigen::Matrix3d;         ///< 3x3 matrix
using Quat = Eigen::Quaterniond;      ///< unit quaternion, stored (x,y,z,w), constructed (w,x,y,z)
using VecX = Eigen::VectorXd;         ///< dynamic column vector
using MatX = Eigen::MatrixXd;         ///< dynamic dense matrix
using Mat3X = Eigen::Matrix3Xd;       ///< 3 x n matrix, one column per particle

/// Read-only view of 3n consecutive doubles as a 3 x n matrix (one column per particle).
using ConstPoints = Eigen::Map<const Mat3X>;
/// Writable view of 3n consecutive doubles as a 3 x n matrix.
using Points = Eigen::Map<Mat3X>;

}  // namespace physlab
