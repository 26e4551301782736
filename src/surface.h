// Surfaces of the seed paper: bounded boxes that bodies rest and slide on, with
// static and kinetic friction.
#pragma once

#include <memory>
#include <string>

#include "math_types.h"
#include "mesh_shape.h"

namespace rigid {

struct Surface {
  std::string name;
  Vec3 min = Vec3::Zero();  // m, corners before the turn about the centre
  Vec3 max = Vec3::Zero();
  Quat orientation = Quat::Identity();  // turns the box about its centre
  double staticFriction = 0.6;          // mu_s, 1
  double kineticFriction = 0.4;         // mu_k, 1
  double restitution = 0.5;             // xi, 1
  double rollingResistance = 0.0;       // m, the lever of the moment that resists rolling
  bool forceOutput = true;              // the FMU reports NAME.force (the scene's "outputs")
  // A conveyor: the scene gives "beltVelocity", the velocity of the surface's material
  // (m/s, world frame), and the FMU has the input NAME.beltVelocity with it as start
  // (its value in a run: WorldData::beltVelocity).
  bool belt = false;
  Vec3 beltVelocity = Vec3::Zero();
  // A surface of a mesh file's triangles (the scene's "mesh"); min and max then bound
  // them, and the box is not a surface of its own.
  std::shared_ptr<const SurfaceMesh> mesh;
  // Derived by finishSurface():
  Vec3 centre = Vec3::Zero();      // m, world frame
  Mat3 R_WS = Mat3::Identity();    // surface frame -> world
  Vec3 halfExtent = Vec3::Zero();  // m, in the surface frame
};

// Fills the derived fields from min, max and orientation.
void finishSurface(Surface& surface);

// Half the surface's least thickness (m): how far a body may move between two
// detections without passing through it unseen. A mesh surface's triangles are prisms
// `thickness` deep.
inline double surfaceHalfThickness(const Surface& s) {
  return s.mesh ? 0.5 * s.mesh->thickness : s.halfExtent.minCoeff();
}

}  // namespace rigid
