// The optional modules of the physics core. Which ones an FMU's binary carries is a
// build choice: one binary per combination, built once, and the scene picks the
// smallest one that has what it needs. Where a module is absent, the code that calls
// it is compiled out (RIGID_WITH_* macros in world.cpp and dynamics.cpp), so an absent
// feature costs nothing in the step and its libraries (FCL) are not linked.
#pragma once

#include <string>

namespace rigid {

struct WorldModel;

enum ModuleBits : unsigned {
  kModuleSurfaces = 1u << 0,    // surfaces, as static boxes of the contact solve (with collisions)
  kModuleMedia = 1u << 1,       // medium: buoyancy, drag
  kModuleCollisions = 1u << 2,  // collision_detection (FCL), constraint_solver
  kModuleJoints = 1u << 3,      // joint_rows: the joints' rows in the constraint solver (with collisions)
  kModuleMeshes = 1u << 4,      // mesh_file, compound, solid_mass: mesh and compound bodies (issue 42)
};

// The modules a world needs. Surfaces and collisions come together: a surface is a
// static box of the contact solve, and body pairs meet surfaces through it. Joints come
// with both: their rows are the constraint solver's, which the collision module holds.
// Meshes are read and measured by their own module; they collide through the
// collision module's hulls.
unsigned modulesNeeded(const WorldModel& model);

// The modules compiled into this binary.
unsigned modulesBuilt();

// "surfaces, media, collisions" style list of the bits set.
std::string moduleNames(unsigned modules);

}  // namespace rigid
