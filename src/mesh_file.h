// The mesh files a scene names (issue 42, docs/decisions/0006-meshes-read-at-build-time.md):
// `rigidfmu build` reads STL and OBJ files and writes FILE.mesh.json beside each (the
// triangles and their convex hull, plainly); the core reads that, checks it, and
// measures the solid. A binary built without the meshes module (src/modules.h) links
// mesh_file_absent.cpp instead, which refuses every mesh by name.
#pragma once

#include <memory>
#include <string>

#include "math_types.h"
#include "mesh_shape.h"

namespace rigid {

// The mesh shape of FILE (relative to `folder`, the scene's) scaled by `scale`, from
// FOLDER/FILE.mesh.json. SceneError naming `field` when the path leaves the folder, the
// file is missing or malformed, its triangles bound no solid (meshFault) or its hull
// does not hold them. `warning` gets a note for the user, or stays empty: the hull, which
// collides, exceeding the solid's volume by more than kHullExcess.
std::shared_ptr<const MeshShape> readMeshShape(const std::string& folder, const std::string& file, const Vec3& scale,
                                               const std::string& field, std::string& warning);

// A hull larger than the solid by more than this share of its volume is reported.
constexpr double kHullExcess = 0.1;

}  // namespace rigid
