// The shapes of real parts in binaries built without the meshes module (src/modules.h):
// a scene that names a mesh or a compound is refused, and none of their code is linked.
#include "mesh_file.h"
#include "scene.h"

namespace rigid {

namespace {

[[noreturn]] void absent(const std::string& field, const char* what) {
  throw SceneError(field + ": " + what +
                   " are not in this binary (it lacks the meshes module); build the FMU with rigidfmu build, which "
                   "picks a binary with the modules a scene needs");
}

}  // namespace

std::shared_ptr<const MeshShape> readMeshShape(const std::string&, const std::string&, const Vec3&,
                                               const std::string& field, std::string&) {
  absent(field, "meshes");
}

std::shared_ptr<const SurfaceMesh> readSurfaceMesh(const std::string&, const std::string&, const Vec3&, const Vec3&,
                                                   const Quat&, double, const std::string& field) {
  absent(field, "meshes");
}

std::shared_ptr<const CompoundShape> makeCompound(const std::vector<PlacedShape>&, const std::string& field) {
  absent(field, "compounds");
}

}  // namespace rigid
