// Body shapes of the scene format and the mass properties of their solids.
#pragma once

#include <memory>

#include "math_types.h"
#include "mesh_shape.h"

namespace rigid {

enum class ShapeType { Sphere, Box, Cylinder, Capsule, Mesh, Compound };

struct CompoundShape;  // compound_shape.h

struct Shape {
  ShapeType type = ShapeType::Sphere;
  double radius = 0.0;                            // m: sphere, cylinder, capsule
  Vec3 size = Vec3::Zero();                       // m: box, full edge lengths (lx, ly, lz)
  double length = 0.0;                            // m: cylinder length; capsule's cylinder part. Axis = body z.
  std::shared_ptr<const MeshShape> mesh;          // mesh: the file's solid and hull, body frame
  std::shared_ptr<const CompoundShape> compound;  // compound: its parts, body frame
};

const char* shapeTypeName(ShapeType type);

// Half the smallest dimension of a shape (m): how far a body may move between two
// detections without passing through it unseen.
double halfThickness(const Shape& shape);

// Radius (m) of the sphere about the centre of mass that holds the shape.
double boundingRadius(const Shape& shape);

// Volume of the solid, m^3.
double shapeVolume(const Shape& shape);

// Principal moments (kg m^2) of the homogeneous solid of this mass about its centre of
// mass. A primitive's body axes are its symmetry axes, so these are its tensor's
// diagonal; a mesh's body axes are its file's, and its tensor is solidInertia's.
Vec3 solidPrincipalInertia(const Shape& shape, double mass);

// Inertia tensor (kg m^2) of the homogeneous solid of this mass about its centre of
// mass, in the body frame.
Mat3 solidInertia(const Shape& shape, double mass);

}  // namespace rigid
