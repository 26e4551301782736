// Builders shared by the C++ unit tests: the shapes, bodies and worlds their closed-form
// cases are stated in, written once (each test file used to carry its own copies).
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "body.h"
#include "shape.h"
#include "world.h"

namespace rigid::test {

inline Shape sphere(double r) {
  Shape s;
  s.type = ShapeType::Sphere;
  s.radius = r;
  return s;
}

// Full edge lengths.
inline Shape box(double lx, double ly, double lz) {
  Shape s;
  s.type = ShapeType::Box;
  s.size = Vec3(lx, ly, lz);
  return s;
}

// Axis along the body's z.
inline Shape cylinder(double r, double l) {
  Shape s;
  s.type = ShapeType::Cylinder;
  s.radius = r;
  s.length = l;
  return s;
}

// l: the length of the cylindrical part.
inline Shape capsule(double r, double l) {
  Shape s;
  s.type = ShapeType::Capsule;
  s.radius = r;
  s.length = l;
  return s;
}

// A body of that shape and mass with the solid shape's inertia.
inline BodyConstants bodyOf(const Shape& shape, double mass, const std::string& name = "b") {
  BodyConstants b;
  b.name = name;
  b.shape = shape;
  setMass(b, mass);
  return b;
}

// An empty world (no bodies yet) with that method and gravity.
inline WorldModel world(Method method, const Vec3& gravity) {
  WorldModel m;
  m.name = "w";
  m.gravity = gravity;
  m.method = method;
  return m;
}

// An asymmetric body: a box whose inertia is replaced by a given diagonal tensor.
inline BodyConstants asymmetricBody(const Vec3& principal, double mass) {
  BodyConstants b = bodyOf(box(0.1, 0.2, 0.3), mass, "a");
  setInertia(b, principal.asDiagonal());
  return b;
}

// Rotation matrix of a unit quaternion (w, x, y, z), body -> world, written out here
// (not through Eigen's conversion, which the code under test uses).
inline Mat3 rotationOf(double w, double x, double y, double z) {
  Mat3 R;
  R << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y), 2 * (x * y + w * z), 1 - 2 * (x * x + z * z),
      2 * (y * z - w * x), 2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
  return R;
}

inline Quat unitQuat(double w, double x, double y, double z) {
  const double n = std::sqrt(w * w + x * x + y * y + z * z);
  return Quat(w / n, x / n, y / n, z / n);
}

inline double maxAbs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

constexpr double kPi = 3.14159265358979323846;

// The turn by `angle` (rad) about `axis`.
inline Quat about(const Vec3& axis, double angle) { return Quat(Eigen::AngleAxisd(angle, axis.normalized())); }

}  // namespace rigid::test
