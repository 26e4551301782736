// Mass properties of solids bounded by closed triangle meshes, and of bodies made of
// several solids (issue 42: convex meshes from CAD files, compound bodies).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "math_types.h"

namespace rigid {

// A solid's mass properties for a density of 1 kg/m^3: scale volume and inertia by the
// density for kilograms. In the frame its vertices are given in.
struct SolidMass {
  double volume = 0.0;          // m^3
  Vec3 centre = Vec3::Zero();   // m, the centre of mass
  Mat3 inertia = Mat3::Zero();  // m^5 (kg m^2 per kg/m^3), about the centre of mass
};

// The solid bounded by a closed mesh, by the divergence theorem over its triangles
// (Eberly, "Polyhedral Mass Properties (Revisited)", 2002). Each triangle lists its
// vertices counter-clockwise seen from outside; a mesh turned inside out gives a
// negative volume. The integrals are taken about the vertices' mean, so that a part far
// from the file's origin loses no digits to cancellation.
SolidMass meshSolidMass(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles);

// Why the triangles do not bound a solid that meshSolidMass can measure, or "": a vertex
// not finite, a triangle naming no vertex or one vertex twice, a triangle of no area, an
// edge that fewer or more than two triangles share or that two share in the same
// direction (an open or inconsistently wound mesh), no volume or a negative one (the
// triangles wound clockwise seen from outside). The reason names the triangle or edge.
std::string meshFault(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles);

// Why the triangles are no surface to collide with, or "": a vertex not finite, no
// triangle, a triangle naming no vertex or one vertex twice, or of no area. An open
// mesh (a sheet, a bin) is a surface.
std::string sheetFault(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles);

// A part of a compound body, or the compound: mass, centre of mass and inertia tensor
// about that centre, all in the compound's frame.
struct PartMass {
  double mass = 0.0;            // kg
  Vec3 centre = Vec3::Zero();   // m
  Mat3 inertia = Mat3::Zero();  // kg m^2
};

// A solid of the given density placed in the compound's frame at `position`,
// turned by `orientation` (its own frame's axes in the compound's).
PartMass placePart(const SolidMass& solid, double density, const Vec3& position, const Quat& orientation);

// The compound of the parts: the masses summed, the centre their weighted mean, and the
// inertia about it by the parallel-axis theorem, I = sum(I_i + m_i (|d_i|^2 E - d_i d_i^T)).
PartMass combineParts(const std::vector<PartMass>& parts);

}  // namespace rigid
