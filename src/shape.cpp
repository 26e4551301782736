#include "shape.h"

#include "compound_shape.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace rigid {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

const char* shapeTypeName(ShapeType type) {
  switch (type) {
    case ShapeType::Sphere: return "sphere";
    case ShapeType::Box: return "box";
    case ShapeType::Cylinder: return "cylinder";
    case ShapeType::Capsule: return "capsule";
    case ShapeType::Mesh: return "mesh";
    case ShapeType::Compound: return "compound";
  }
  return "?";
}

double shapeVolume(const Shape& s) {
  const double r = s.radius;
  switch (s.type) {
    case ShapeType::Sphere: return 4.0 / 3.0 * kPi * r * r * r;
    case ShapeType::Box: return s.size.prod();
    case ShapeType::Cylinder: return kPi * r * r * s.length;
    case ShapeType::Capsule: return kPi * r * r * s.length + 4.0 / 3.0 * kPi * r * r * r;
    case ShapeType::Mesh: return s.mesh->volume;
    case ShapeType::Compound: return s.compound->volume;
  }
  return 0.0;
}

Vec3 solidPrincipalInertia(const Shape& s, double m) {
  const double r = s.radius;
  const double l = s.length;
  switch (s.type) {
    case ShapeType::Sphere: {
      const double I = 0.4 * m * r * r;
      return Vec3(I, I, I);
    }
    case ShapeType::Box: {
      const Vec3 sq = s.size.cwiseProduct(s.size);
      return m / 12.0 * Vec3(sq.y() + sq.z(), sq.x() + sq.z(), sq.x() + sq.y());
    }
    case ShapeType::Cylinder: {
      const double Ixx = m * (3.0 * r * r + l * l) / 12.0;
      return Vec3(Ixx, Ixx, 0.5 * m * r * r);
    }
    case ShapeType::Capsule: {
      // Mass splits by volume between the cylinder and the two hemispherical caps.
      // A cap's centroid lies 3r/8 from its flat face, i.e. l/2 + 3r/8 from the centre;
      // about a transverse axis through the flat face a cap has 2/5 m_cap r^2, so by the
      // parallel-axis theorem each cap adds m_cap (2r^2/5 + l^2/4 + 3lr/8).
      const double vCyl = kPi * r * r * l;
      const double vCap = 2.0 / 3.0 * kPi * r * r * r;
      const double mCyl = m * vCyl / (vCyl + 2.0 * vCap);
      const double mCap = m * vCap / (vCyl + 2.0 * vCap);
      const double Ixx =
          mCyl * (3.0 * r * r + l * l) / 12.0 + 2.0 * mCap * (0.4 * r * r + 0.25 * l * l + 0.375 * l * r);
      const double Izz = 0.5 * mCyl * r * r + 2.0 * 0.4 * mCap * r * r;
      return Vec3(Ixx, Ixx, Izz);
    }
    case ShapeType::Mesh:
    case ShapeType::Compound: return Eigen::SelfAdjointEigenSolver<Mat3>(solidInertia(s, m)).eigenvalues();
  }
  return Vec3::Zero();
}

Mat3 solidInertia(const Shape& s, double m) {
  if (s.type == ShapeType::Mesh) return s.mesh->inertiaPerDensity * (m / s.mesh->volume);
  if (s.type == ShapeType::Compound) return s.compound->inertiaPerDensity * (m / s.compound->volume);
  return solidPrincipalInertia(s, m).asDiagonal();
}

double halfThickness(const Shape& s) {
  switch (s.type) {
    case ShapeType::Sphere:
    case ShapeType::Capsule: return s.radius;
    case ShapeType::Box: return 0.5 * s.size.minCoeff();
    case ShapeType::Cylinder: return std::min(s.radius, 0.5 * s.length);
    case ShapeType::Mesh: return s.mesh->halfThickness;
    case ShapeType::Compound: return s.compound->halfThickness;
  }
  return 0.0;
}

double boundingRadius(const Shape& s) {
  switch (s.type) {
    case ShapeType::Sphere: return s.radius;
    case ShapeType::Capsule: return s.radius + 0.5 * s.length;
    case ShapeType::Box: return 0.5 * s.size.norm();
    case ShapeType::Cylinder: return std::hypot(s.radius, 0.5 * s.length);
    case ShapeType::Mesh: return s.mesh->boundingRadius;
    case ShapeType::Compound: return s.compound->boundingRadius;
  }
  return 0.0;
}

}  // namespace rigid
