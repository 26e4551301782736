// What the collision module keeps per world instance between steps: the detector, the
// contacts it found, and the buffers of the step's sub-stepping and contact solve.
#pragma once

#include <vector>

#include "collision_detection.h"
#include "contact_solver.h"

namespace rigid {

struct CollisionCache {
  CollisionDetector detector;
  std::vector<Contact> contacts;
  std::vector<double> halfThickness;    // m, per body (0 for bodies that meet nothing)
  std::vector<double> boundingRadius;   // m, per body (0 for bodies that meet nothing)
  std::vector<double> travel;           // m, scratch: each body's reach in a step
  ContactScratchPtr solver;             // the contact solver's buffers
};

}  // namespace rigid
