// The shapes of real parts (issue 42): compounds, and the mesh files a scene names (issue 42,
// docs/decisions/0006-meshes-read-at-build-time.md): `rigidfmu build` reads STL and OBJ files and writes FILE.mesh.json
// beside each (the triangles and their convex hull, plainly); the core reads that, checks it, and measures the solid. A
// binary built without the meshes module (src/modules.h) links mesh_file_absent.cpp instead, which refuses every mesh
// by name.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "compound_shape.h"
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

// The static surface of FILE's triangles (open or closed; none without area), scaled,
// turned by `orientation` and moved by `position` into the world; SceneError naming
// `field` as readMeshShape's.
std::shared_ptr<const SurfaceMesh> readSurfaceMesh(const std::string& folder, const std::string& file,
                                                   const Vec3& scale, const Vec3& position, const Quat& orientation,
                                                   double thickness, const std::string& field);

// A hull larger than the solid by more than this share of its volume is reported.
constexpr double kHullExcess = 0.1;

// A part of a compound as the scene places it in the compound's frame: a primitive by
// its centre, a mesh by its file's origin.
struct PlacedShape {
  Shape shape;
  Vec3 position = Vec3::Zero();         // m
  Quat orientation = Quat::Identity();  // the part's axes (a mesh's: its file's) -> compound frame
};

// The compound of the parts, of one density: its centre of mass the parts' volume-
// weighted mean, its inertia their sum about it by the parallel-axis theorem, the parts
// placed in the body frame (the compound's frame moved to that centre). SceneError
// naming `field` when the binary has no meshes module.
std::shared_ptr<const CompoundShape> makeCompound(const std::vector<PlacedShape>& parts, const std::string& field);

}  // namespace rigid
