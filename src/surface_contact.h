// A body resting or sliding on the top face of a surface (the +z face of the surface
// box in its own frame, after its turn). Support and Coulomb friction act as forces
// at the centre of mass inside the force stage, so that every integrator stage sees
// them; what is instantaneous (landing, reaching rest) is answered after the step.
#pragma once

#include <vector>

#include "body.h"
#include "surface.h"

namespace rigid {

// Where a body is with respect to a surface's top face.
struct SurfaceContact {
  bool overFace = false;  // centre of mass above the face's bounds
  Vec3 n = Vec3::Zero();  // unit normal of the face, out of the surface, world frame
  double gap = 0.0;       // m, height of the body's lowest point above the face (< 0: penetration)
  double mus = 0.0;       // combined static friction coefficient
  double muk = 0.0;       // combined kinetic friction coefficient
  double xi = 0.0;        // combined restitution
};

SurfaceContact surfaceContact(const Surface& surface, const BodyConstants& body, const BodyState& y);

// Whether a body whose centre of mass is at X stays clear of every surface while it
// moves by up to `travel` (m): the sphere that holds it (boundingRadius) is farther
// than that from each surface's box. Such a body feels no surface force in the step and
// needs no landing: the per-body checks are skipped.
bool clearOfSurfaces(const std::vector<Surface>& surfaces, const Shape& shape, const Vec3& X, double travel);

// Normal speed (m/s) below which an impact does not bounce and a body may rest: what
// gravity adds in two steps, so that a resting body's per-step sinking never bounces.
double restingNormalSpeed(const Vec3& gravity, double h);

// Combination rule of a body's and a surface's coefficients: the geometric mean, so
// that equal values combine to that value and a frictionless partner gives none.
double combineCoefficients(double body, double surface);

// Distance (m) from the centre of mass to the body's farthest point along the unit
// direction d (world frame): the support function of the shape.
double supportDistance(const Shape& shape, const Mat3& R, const Vec3& d);

// Where friction acts, from the centre of mass (m, world frame): the lowest point of
// a round shape (sphere, capsule), so that it rolls; the centre of mass itself for
// flat-bottomed shapes (box, cylinder), which in this version neither tip nor roll.
Vec3 frictionArm(const Shape& shape, const Mat3& R, const Vec3& n);

// How far from the contact's centre friction against spin about the normal n acts
// (m): the mean distance from the centre of the patch a body rests on, under even
// pressure. A box on its face of half sides p, q (d = sqrt(p^2 + q^2)):
// (2 p q d + p^3 ln((q + d) / p) + q^3 ln((p + d) / q)) / (6 p q), 0.383 a for a square
// of side a; a cylinder on its end 2R/3; a cylinder or capsule lying on its side, a
// line of length L: L/4; a sphere or a standing capsule touches at a point: 0.
double spinFrictionArm(const Shape& shape, const Mat3& R, const Vec3& n);

// Force stage: support N n and friction for every surface the body rests on.
// aux.F and aux.T must already hold every other force (gravity, inputs, media).
void addSurfaceForces(const std::vector<Surface>& surfaces, const BodyConstants& body,
                      const BodyState& y, BodyAux& aux);

// After a step from `before` to `after` of length h: a body that reached a face lands
// (the seed's impulse with restitution, only while approaching; penetration removed),
// and a slipping body sticks (slip at the friction point removed by an impulse) when
// its slip reversed in the step (kinetic friction stops slipping, never reverses it)
// or is small enough for friction to remove within one step while static friction
// holds the load. `applied` holds the auxiliaries of `after` with F and T the applied
// loads (every force but the surfaces').
// Returns the number of surfaces the body touches.
int respondToSurfaces(const std::vector<Surface>& surfaces, const BodyConstants& body,
                      const Vec3& gravity, const BodyAux& applied, double h,
                      const BodyState& before, BodyState& after);

// Whether the body, moved from `before` to `after`, has struck a surface's face:
// penetrating it while approaching faster than a resting body can. The step then
// locates the instant of impact instead of answering at the end of the step.
bool struckSurface(const std::vector<Surface>& surfaces, const BodyConstants& body,
                   const Vec3& gravity, double h, const BodyState& after);

}  // namespace rigid
