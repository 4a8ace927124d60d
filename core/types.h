#pragma once
// Shared numeric types: dense vectors in SI units, fixed-size 3-vectors and 3x3 tensors.
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products of Vec3
#include <cstdint>

namespace kerf {

using Index = std::int32_t;
using Vector = Eigen::VectorXd;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Mat9 = Eigen::Matrix<double, 9, 9>;

}  // namespace kerf
