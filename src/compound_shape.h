// A body made of several shapes (issue 42): primitives and meshes placed in one frame,
// one rigid body of one density, whose mass properties combine the parts' by the
// parallel-axis theorem.
#pragma once

#include <vector>

#include "math_types.h"
#include "shape.h"

namespace rigid {

// One part: its shape (no compound), its centre of mass and axes in the body frame.
struct ShapePart {
  Shape shape;
  Vec3 position = Vec3::Zero();         // m, the part's centre of mass, body frame
  Quat orientation = Quat::Identity();  // the part's axes -> body frame
};

struct CompoundShape {
  std::vector<ShapePart> parts;
  // The body frame is the compound's frame (the scene's part poses) moved to the centre
  // of mass: the compound's origin lies at `origin` in the body frame.
  Vec3 origin = Vec3::Zero();             // m
  double volume = 0.0;                    // m^3, the parts' summed (overlaps count twice)
  Mat3 inertiaPerDensity = Mat3::Zero();  // m^5, about the centre of mass, body frame
  double halfThickness = 0.0;             // m, the thinnest part's
  double boundingRadius = 0.0;            // m, about the centre of mass
};

}  // namespace rigid
