#include "modules.h"

#include "world.h"

namespace rigid {

unsigned modulesNeeded(const WorldModel& model) {
  unsigned m = 0;
  if (!model.media.empty()) m |= kModuleMedia;
  int colliding = 0;
  for (const BodyConstants& b : model.bodies) colliding += b.collides ? 1 : 0;
  // FCL answers body-body contacts and every body on a surface (a static box of the
  // contact solve): surfaces come with the collision module.
  if (colliding >= 2 || !model.surfaces.empty()) m |= kModuleCollisions | kModuleSurfaces;
  if (!model.joints.empty()) m |= kModuleJoints | kModuleCollisions | kModuleSurfaces;
  for (const BodyConstants& b : model.bodies)
    if (b.shape.type == ShapeType::Mesh || b.shape.type == ShapeType::Compound) m |= kModuleMeshes;
  for (const Surface& s : model.surfaces)
    if (s.mesh) m |= kModuleMeshes;
  return m;
}

std::string moduleNames(unsigned modules) {
  std::string s;
  auto add = [&](unsigned bit, const char* name) {
    if (modules & bit) s += (s.empty() ? "" : ", ") + std::string(name);
  };
  add(kModuleSurfaces, "surfaces");
  add(kModuleMedia, "media");
  add(kModuleCollisions, "collisions");
  add(kModuleJoints, "joints");
  add(kModuleMeshes, "meshes");
  return s.empty() ? "none" : s;
}

}  // namespace rigid
