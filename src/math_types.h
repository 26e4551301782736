// Linear-algebra types shared by the physics core.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rigid {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
// Unit quaternion. Eigen's constructor takes (w, x, y, z) but stores (x, y, z, w);
// files and FMI variables always use the order (w, x, y, z).
using Quat = Eigen::Quaterniond;

// A unit vector perpendicular to the unit vector u.
inline Vec3 anyPerpendicular(const Vec3& u) {
  const Vec3 other = std::abs(u.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return u.cross(other).normalized();
}

}  // namespace rigid
