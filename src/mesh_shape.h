// A body shape read from a mesh file (issue 42): the solid the file's closed triangle
// mesh bounds, which gives the mass properties, and its convex hull, which collides.
// Read once when the scene is read (mesh_file.h), shared by every copy of the model.
#pragma once

#include <string>
#include <vector>

#include "math_types.h"

namespace rigid {

// A convex polyhedron in the body frame: its vertices and its faces, each a convex
// polygon listed counter-clockwise seen from outside, with its outward plane.
struct ConvexHull {
  std::vector<Vec3> vertices;      // m, body frame
  std::vector<int> faceStart;      // face f's vertices are faceVertex[faceStart[f] .. faceStart[f + 1])
  std::vector<int> faceVertex;     // indices into vertices
  std::vector<Vec3> faceNormal;    // unit, outward
  std::vector<double> faceOffset;  // m: the plane is normal . x = offset
  // Each vertex's neighbours along the edges, and the faces around it, so that the
  // vertex farthest along a direction is found by walking uphill (linkHull).
  std::vector<int> neighbourStart, neighbour;
  std::vector<int> vertexFaceStart, vertexFace;

  int faceCount() const { return static_cast<int>(faceNormal.size()); }
  int faceSize(int f) const { return faceStart[f + 1] - faceStart[f]; }
  const Vec3& faceVertexAt(int f, int k) const { return vertices[faceVertex[faceStart[f] + k]]; }
};

// Appends a face, its vertices' indices counter-clockwise seen from outside, with its
// outward plane: Newell's normal (robust for any planar polygon) through the vertices'
// mean. False, and nothing appended, when the face has no area.
bool addFace(ConvexHull& hull, const std::vector<int>& loop);

// Fills a hull's neighbours and faces around each vertex from its faces.
void linkHull(ConvexHull& hull);

// The index of a vertex of the hull farthest along `direction` (hull frame): walks from
// vertex to neighbouring vertex while the next is farther, which on a convex polytope
// ends at the farthest (a few dozen steps for a thousand vertices, not a thousand).
int supportVertex(const ConvexHull& hull, const Vec3& direction);

struct MeshShape {
  std::string file;           // as the scene names it, relative to the scene's folder
  Vec3 scale = Vec3::Ones();  // applied to the file's coordinates
  // The body frame is the file's frame (scaled), moved to the centre of mass: a point x
  // of the file lies at scale * x + fileOrigin in the body frame.
  Vec3 fileOrigin = Vec3::Zero();         // m
  double volume = 0.0;                    // m^3, of the solid the mesh bounds
  Mat3 inertiaPerDensity = Mat3::Zero();  // m^5 (kg m^2 per kg/m^3), about the centre of mass, body frame
  double hullVolume = 0.0;                // m^3
  double halfThickness = 0.0;             // m, half the hull's least width across its faces
  double boundingRadius = 0.0;            // m, of the hull about the centre of mass
  ConvexHull hull;
  std::vector<Vec3> vertices;  // m, body frame: the mesh itself (for drawing)
  std::vector<int> triangles;  // three indices each
};

// A static surface given by a triangle mesh (a bin, a chute, terrain), in the world
// frame. It need not be closed: each triangle is one-sided, its front the side its
// vertices run counter-clockwise around, and collides as a prism `thickness` deep
// behind it, so that a body pressed into it is pushed out along its front.
struct SurfaceMesh {
  std::string file;                // as the scene names it
  double thickness = 0.0;          // m
  std::vector<ConvexHull> prisms;  // one per triangle, about its centre
  std::vector<Vec3> centres;       // m, world frame: each prism's
  std::vector<Vec3> fronts;        // unit, world frame: each triangle's front normal
  std::vector<Vec3> vertices;      // m, world frame (for drawing)
  std::vector<int> triangles;      // three indices each
};

}  // namespace rigid
