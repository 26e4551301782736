#include "mesh_file.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "scene.h"
#include "solid_mass.h"

namespace rigid {

namespace {

using json = nlohmann::json;

// The file's canonical form, as rigidfmu build writes it (decision 0006).
constexpr const char* kFormat = "rigidfmu-mesh";
constexpr int kVersion = 1;
// A hull's face may bend, or a vertex stand outside a face, by this share of the
// mesh's size: qhull's merged facets are planar to rounding, not exactly.
constexpr double kPlaneTolerance = 1e-7;

// A path that stays in the scene's folder: relative, '/' between its parts, no part
// "..", nothing a platform reads as a root (a drive, a URI's scheme).
std::string pathFault(const std::string& file) {
  if (file.empty()) return "is empty";
  if (file.find('\\') != std::string::npos) return "uses \\ (separate folders by /)";
  if (file.find(':') != std::string::npos) return "names a drive or scheme (\":\")";
  if (file.front() == '/') return "is absolute";
  std::istringstream parts(file);
  for (std::string part; std::getline(parts, part, '/');) {
    if (part == "..") return "leaves the scene's folder (\"..\")";
    if (part.empty()) return "has an empty folder name (\"//\")";
  }
  if (file.back() == '/') return "names a folder";
  return "";
}

[[noreturn]] void refuse(const std::string& field, const std::string& file, const std::string& what) {
  throw SceneError(field + ": " + file + ": " + what);
}

Vec3 point(const json& j, const std::string& where, const std::string& field, const std::string& file) {
  if (!j.is_array() || j.size() != 3) refuse(field, file, where + " must be 3 numbers");
  Vec3 p;
  for (int k = 0; k < 3; ++k) {
    if (!j[k].is_number()) refuse(field, file, where + " must be 3 numbers");
    p[k] = j[k].get<double>();
  }
  return p;
}

std::vector<int> indices(const json& j, size_t least, const std::string& where, const std::string& field,
                         const std::string& file) {
  if (!j.is_array() || j.size() < least)
    refuse(field, file, where + " must list at least " + std::to_string(least) + " vertex indices");
  std::vector<int> out;
  for (const json& i : j) {
    if (!i.is_number_integer()) refuse(field, file, where + " must list vertex indices (integers)");
    out.push_back(i.get<int>());
  }
  return out;
}

const json& member(const json& j, const char* key, const std::string& field, const std::string& file) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_array())
    refuse(field, file, std::string("no \"") + key + "\" list");
  return j[key];
}

json readCanonical(const std::string& folder, const std::string& file, const std::string& field) {
  if (const std::string fault = pathFault(file); !fault.empty())
    throw SceneError(field +
                     ": must be a path inside the scene's folder (relative, no \"..\", \"/\" between folders); \"" +
                     file + "\" " + fault);
  const std::string path = (folder.empty() ? "" : folder + "/") + file + ".mesh.json";
  std::ifstream in(std::filesystem::u8path(path), std::ios::binary);
  if (!in)
    refuse(field, file, "no " + file + ".mesh.json beside the scene (rigidfmu build writes it from " + file + ")");
  json j;
  try {
    j = json::parse(in);
  } catch (const json::exception& e) {
    refuse(field, file, file + ".mesh.json is not valid JSON: " + e.what());
  }
  if (!j.is_object() || j.value("format", "") != kFormat || j.value("version", 0) != kVersion)
    refuse(field, file,
           file + ".mesh.json is not a \"" + std::string(kFormat) + "\" file of version " + std::to_string(kVersion));
  return j;
}

// The hull's faces as convex polygons with their outward planes (addFace), vertices
// moved by `shift`; refused when a face has no area, bends, or leaves a point of
// `inside` outside its plane.
void readHull(const json& j, const Vec3& scale, const Vec3& shift, const std::vector<Vec3>& inside, double size,
              const std::string& field, const std::string& file, ConvexHull& hull) {
  for (const json& v : member(j, "vertices", field, file))
    hull.vertices.push_back(point(v, "a hull vertex", field, file).cwiseProduct(scale) + shift);
  const double tol = kPlaneTolerance * size;
  hull.faceStart.push_back(0);
  for (const json& f : member(j, "faces", field, file)) {
    const std::string where = "hull face " + std::to_string(hull.faceNormal.size());
    const std::vector<int> loop = indices(f, 3, where, field, file);
    for (int i : loop)
      if (i < 0 || i >= static_cast<int>(hull.vertices.size()))
        refuse(field, file, where + " names vertex " + std::to_string(i) + ", which the hull lacks");
    if (!addFace(hull, loop)) refuse(field, file, where + " has no area");
    const Vec3& n = hull.faceNormal.back();
    const double offset = hull.faceOffset.back();
    for (int i : loop)
      if (std::abs(n.dot(hull.vertices[i]) - offset) > tol) refuse(field, file, where + " is not flat");
    for (const Vec3& p : inside)
      if (n.dot(p) > offset + tol) refuse(field, file, where + " leaves part of the mesh outside: not its hull");
  }
}

// The hull's faces as triangles (fans), for its volume and its closedness.
std::vector<std::array<int, 3>> hullTriangles(const ConvexHull& h) {
  std::vector<std::array<int, 3>> out;
  for (int f = 0; f < h.faceCount(); ++f)
    for (int k = 1; k + 1 < h.faceSize(f); ++k)
      out.push_back(
          {h.faceVertex[h.faceStart[f]], h.faceVertex[h.faceStart[f] + k], h.faceVertex[h.faceStart[f] + k + 1]});
  return out;
}

// Half the hull's least width across its faces, and its reach from the centre of mass.
void measureHull(MeshShape& m) {
  const ConvexHull& h = m.hull;
  double least = std::numeric_limits<double>::infinity();
  for (int f = 0; f < h.faceCount(); ++f) {
    double low = h.faceOffset[f];
    for (const Vec3& v : h.vertices) low = std::min(low, h.faceNormal[f].dot(v));
    least = std::min(least, h.faceOffset[f] - low);
  }
  m.halfThickness = 0.5 * least;
  for (const Vec3& v : h.vertices) m.boundingRadius = std::max(m.boundingRadius, v.norm());
}

// The file's vertices, scaled, and its triangles.
void readTriangles(const json& j, const Vec3& scale, const std::string& field, const std::string& file,
                   std::vector<Vec3>& vertices, std::vector<std::array<int, 3>>& triangles) {
  for (const json& v : member(j, "vertices", field, file))
    vertices.push_back(point(v, "a vertex", field, file).cwiseProduct(scale));
  for (const json& t : member(j, "triangles", field, file)) {
    const std::vector<int> i = indices(t, 3, "triangle " + std::to_string(triangles.size()), field, file);
    if (i.size() != 3) refuse(field, file, "triangle " + std::to_string(triangles.size()) + " must list 3 vertices");
    triangles.push_back({i[0], i[1], i[2]});
  }
}

// The prism of the triangle (a, b, c), counter-clockwise seen from its front, reaching
// `thickness` behind it, about its centre: front, back and three sides, each wound
// counter-clockwise seen from outside.
ConvexHull prism(const Vec3& a, const Vec3& b, const Vec3& c, double thickness, Vec3& centre) {
  const Vec3 front = (b - a).cross(c - a).normalized();
  centre = (a + b + c) / 3.0 - 0.5 * thickness * front;
  ConvexHull h;
  for (const Vec3& v : {a, b, c}) h.vertices.push_back(v - centre);
  for (const Vec3& v : {a, b, c}) h.vertices.push_back(v - thickness * front - centre);
  for (const std::vector<int>& f : {std::vector<int>{0, 1, 2}, {3, 5, 4}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}})
    addFace(h, f);  // (a triangle of some area, sheetFault checked: so is every face)
  return h;
}

}  // namespace

std::shared_ptr<const SurfaceMesh> readSurfaceMesh(const std::string& folder, const std::string& file,
                                                   const Vec3& scale, const Vec3& position, const Quat& orientation,
                                                   double thickness, const std::string& field) {
  const json j = readCanonical(folder, file, field);
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
  readTriangles(j, scale, field, file, vertices, triangles);
  if (const std::string fault = sheetFault(vertices, triangles); !fault.empty()) refuse(field, file, fault);
  auto m = std::make_shared<SurfaceMesh>();
  m->file = file;
  m->thickness = thickness;
  const Mat3 R = orientation.normalized().toRotationMatrix();
  for (Vec3& v : vertices) v = position + R * v;
  for (const std::array<int, 3>& t : triangles) {
    Vec3 centre;
    m->prisms.push_back(prism(vertices[t[0]], vertices[t[1]], vertices[t[2]], thickness, centre));
    linkHull(m->prisms.back());
    m->centres.push_back(centre);
    m->fronts.push_back(m->prisms.back().faceNormal[0]);
    m->triangles.insert(m->triangles.end(), t.begin(), t.end());
  }
  m->vertices = std::move(vertices);
  return m;
}

std::shared_ptr<const MeshShape> readMeshShape(const std::string& folder, const std::string& file, const Vec3& scale,
                                               const std::string& field, std::string& warning) {
  const json j = readCanonical(folder, file, field);
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
  readTriangles(j, scale, field, file, vertices, triangles);
  if (const std::string fault = meshFault(vertices, triangles); !fault.empty()) refuse(field, file, fault);
  const SolidMass solid = meshSolidMass(vertices, triangles);
  auto m = std::make_shared<MeshShape>();
  m->file = file;
  m->scale = scale;
  m->fileOrigin = -solid.centre;
  m->volume = solid.volume;
  m->inertiaPerDensity = solid.inertia;
  for (Vec3& v : vertices) v -= solid.centre;
  Vec3 lo = vertices.front(), hi = vertices.front();
  for (const Vec3& v : vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  if (!j.contains("hull")) refuse(field, file, "spans no volume (no hull)");
  readHull(j["hull"], scale, -solid.centre, vertices, (hi - lo).norm(), field, file, m->hull);
  const std::vector<std::array<int, 3>> hullFaces = hullTriangles(m->hull);
  if (const std::string fault = meshFault(m->hull.vertices, hullFaces); !fault.empty())
    refuse(field, file, "its hull: " + fault);
  m->hullVolume = meshSolidMass(m->hull.vertices, hullFaces).volume;
  measureHull(*m);
  linkHull(m->hull);
  m->vertices = std::move(vertices);
  for (const auto& t : triangles) m->triangles.insert(m->triangles.end(), t.begin(), t.end());
  if (m->hullVolume > (1.0 + kHullExcess) * m->volume) {
    std::ostringstream note;
    note << field << ": " << file << ": its convex hull, which collides, holds " << m->hullVolume / m->volume
         << " times the solid's volume (the mass comes from the solid)";
    warning = note.str();
  }
  return m;
}

}  // namespace rigid
