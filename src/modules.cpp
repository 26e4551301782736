#include "modules.h"

#include "world.h"

namespace rigid {

unsigned modulesNeeded(const WorldModel& model) {
  unsigned m = 0;
  if (!model.surfaces.empty()) m |= kModuleSurfaces;
  if (!model.media.empty()) m |= kModuleMedia;
  int colliding = 0;
  for (const BodyConstants& b : model.bodies) colliding += b.collides ? 1 : 0;
  // FCL answers body-body contacts and, with the manifold solver, every body on a
  // surface (the first model: colliding bodies against the sides of surfaces).
  const bool manifold = model.contactSolver == ContactSolver::Manifold;
  if (manifold && !model.surfaces.empty()) colliding = static_cast<int>(model.bodies.size());
  if (colliding >= 2 || (colliding >= 1 && !model.surfaces.empty()))
    m |= kModuleCollisions | kModuleSurfaces;
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
  return s.empty() ? "none" : s;
}

}  // namespace rigid
