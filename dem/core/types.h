#pragma once
// Basic numeric types. SI units everywhere, z up, gravity along -z.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

namespace upgrain::dem {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using GlobalId = std::int64_t;

}  // namespace upgrain::dem
