// The mesh reader of binaries built without the meshes module (src/modules.h): a scene
// that names a mesh is refused, and none of the mesh code is linked.
#include "mesh_file.h"
#include "scene.h"

namespace rigid {

std::shared_ptr<const MeshShape> readMeshShape(const std::string&, const std::string&, const Vec3&,
                                               const std::string& field, std::string&) {
  throw SceneError(field +
                   ": meshes are not in this binary (it lacks the meshes module); build the FMU with "
                   "rigidfmu build, which picks a binary with the modules a scene needs");
}

}  // namespace rigid
