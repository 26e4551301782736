// Linear-algebra types shared by the physics core.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rigid {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
// Unit quaternion. Eigen's constructor takes (w, x, y, z) but stores (x, y, z, w);
// files and FMI variables always use the order (w, x, y, z).
using Quat = Eigen::Quaterniond;

}  // namespace rigid
