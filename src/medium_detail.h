// The pieces of addMediumForces (medium.cpp), exposed for the unit tests: the part of a
// body inside a medium's box (volume and centroid) and the drag model's coefficients.
// The formulas, coefficients and the errors of the approximations are in docs/media.md.
#pragma once

#include "math_types.h"
#include "shape.h"

namespace rigid {

// The part of a body inside an axis-aligned box.
struct SubmergedPart {
  double volume = 0.0;           // m^3, V_sub
  Vec3 centroid = Vec3::Zero();  // m, world frame: the centre of buoyancy (X when volume is 0)
};

// Resolution of the convex polyhedra that stand for cylinders and capsules: sides
// around the axis, and rings of latitude on each hemispherical end of a capsule.
constexpr int kLatheSides = 24;
constexpr int kCapsuleRings = 6;

// The part of a body (centre of mass X_W, rotation R_WB body -> world) inside the box
// [min, max] (world frame, axis-aligned).
//   box:      exact (convex polyhedron clipped by the box's six planes), any pose.
//   sphere:   exact when the cuts are along one world axis (one plane, or two parallel
//             planes); cuts along several axes are combined as if independent (product
//             of the one-axis fractions; error in docs/media.md).
//   cylinder, capsule: a convex polyhedron of the same volume (kLatheSides around,
//             kCapsuleRings per hemisphere) clipped exactly; error in docs/media.md.
// Fully inside gives exactly the shape's volume at X; fully outside gives 0.
SubmergedPart submergedPart(const Shape& shape, const Vec3& X_W, const Mat3& R_WB, const Vec3& min_W,
                            const Vec3& max_W);

// Area of the body's shadow on a plane normal to the unit direction dir_B (body frame),
// m^2. Exact for the four shapes.
double projectedArea(const Shape& shape, const Vec3& dir_B);

// Surface area of the body, m^2.
double surfaceArea(const Shape& shape);

// Quadratic (pressure) drag: C_d A for motion along the unit direction dir_B (body
// frame), m^2; the force is -1/2 rho (C_d A) |v| v.
double dragArea(const Shape& shape, const Vec3& dir_B);

// Linear (viscous, Stokes) drag coefficient b for motion along dir_B, N s/m, per Pa s of
// viscosity: the force is -mu b' v with b' = 6 pi (r_n / 3 + 2 r_s / 3) (Leith 1987);
// 6 pi r for a sphere.
double stokesFactor(const Shape& shape, const Vec3& dir_B);

// Angular drag: the torque is -(k1 + k2_i |omega|) omega_i about body axis i, with
// k1 = mu * rotationalStokesFactor (8 pi r_s^3; 8 pi r^3 for a sphere) and
// k2_i = rho * pressureTorqueFactor_i (flat-strip model, zero for smooth rotation about
// an axis of symmetry of a round body).
double rotationalStokesFactor(const Shape& shape);
Vec3 pressureTorqueFactor(const Shape& shape);

}  // namespace rigid
