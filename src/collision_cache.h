// What the collision module keeps per world instance between steps: the detector, the
// contacts it found, and the buffers of the step's sub-stepping and contact solve.
#pragma once

#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "collision_detection.h"
#include "constraint_solver.h"
#include "contact_memory.h"
#include "islands.h"

namespace rigid {

struct CollisionCache {
  explicit CollisionCache(CollisionDetector d) : detector(std::move(d)) {}
  CollisionDetector detector;
  std::vector<Contact> contacts;
  std::vector<double> halfThickness;   // m, per body (0 for bodies that meet nothing)
  std::vector<double> boundingRadius;  // m, per body (0 for bodies that meet nothing)
  double thinnest =
      std::numeric_limits<double>::infinity();  // m, the least half thickness of all these and the surfaces
  std::vector<double> travel;                   // m, scratch: each body's reach in a step
  // the constraint solver (constraint_solver.h): the contacts of the step's start (the
  // cache's `contacts` may hold a probe's while an impact is located), its buffers,
  // the memory it stores, and the impulses it gave
  std::vector<Contact> stepContacts;
  ConstraintScratchPtr constraints;
  std::vector<ContactMemory> storedMemory;
  ContactImpulses impulses;
  // the joints' rows (joint_rows.h), when the world has joints: buffers only, like the
  // solver's, so copies of the data may share them
  std::unique_ptr<ExtraRows> joints;
  // the step's islands (islands.h), and which of them are still long enough (sleep.cpp)
  Islands islands;
  std::vector<char> ready;
};

}  // namespace rigid
