#include "solid_mass.h"

#include <algorithm>
#include <map>
#include <utility>

namespace rigid {

namespace {

// For one coordinate w of a triangle's vertices: the polynomial terms of Eberly's
// integrals over it (f1, f2, f3: the sums of the monomials of degree 1, 2, 3; g: the
// derivatives of f3 by each vertex, for the products of two coordinates).
struct Terms {
  double f1, f2, f3;
  std::array<double, 3> g;
};

Terms termsOf(double w0, double w1, double w2) {
  Terms t;
  const double sum01 = w0 + w1, square0 = w0 * w0, partial = square0 + w1 * sum01;
  t.f1 = sum01 + w2;
  t.f2 = partial + w2 * t.f1;
  t.f3 = w0 * square0 + w1 * partial + w2 * t.f2;
  t.g = {t.f2 + w0 * (t.f1 + w0), t.f2 + w1 * (t.f1 + w1), t.f2 + w2 * (t.f1 + w2)};
  return t;
}

}  // namespace

SolidMass meshSolidMass(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles) {
  Vec3 origin = Vec3::Zero();
  for (const Vec3& v : vertices) origin += v;
  if (!vertices.empty()) origin /= static_cast<double>(vertices.size());
  // The integrals of 1, x, y, z, x^2, y^2, z^2, xy, yz, zx over the solid, about origin.
  double one = 0.0;
  Vec3 first = Vec3::Zero(), second = Vec3::Zero(), mixed = Vec3::Zero();
  for (const std::array<int, 3>& t : triangles) {
    const Vec3 p[3] = {vertices[t[0]] - origin, vertices[t[1]] - origin, vertices[t[2]] - origin};
    const Vec3 n = (p[1] - p[0]).cross(p[2] - p[0]);  // twice the area, outward
    Terms c[3];
    for (int k = 0; k < 3; ++k) c[k] = termsOf(p[0][k], p[1][k], p[2][k]);
    one += n.x() * c[0].f1;
    for (int k = 0; k < 3; ++k) {
      first[k] += n[k] * c[k].f2;
      second[k] += n[k] * c[k].f3;
      const int next = (k + 1) % 3;  // xy from the x terms, yz from y's, zx from z's
      mixed[k] += n[k] * (p[0][next] * c[k].g[0] + p[1][next] * c[k].g[1] + p[2][next] * c[k].g[2]);
    }
  }
  SolidMass s;
  s.volume = one / 6.0;
  if (s.volume == 0.0) return s;
  first /= 24.0, second /= 60.0, mixed /= 120.0;
  const Vec3 c = first / s.volume;  // about origin
  const double v = s.volume;
  s.centre = origin + c;
  s.inertia(0, 0) = second.y() + second.z() - v * (c.y() * c.y() + c.z() * c.z());
  s.inertia(1, 1) = second.z() + second.x() - v * (c.z() * c.z() + c.x() * c.x());
  s.inertia(2, 2) = second.x() + second.y() - v * (c.x() * c.x() + c.y() * c.y());
  s.inertia(0, 1) = s.inertia(1, 0) = -(mixed.x() - v * c.x() * c.y());
  s.inertia(1, 2) = s.inertia(2, 1) = -(mixed.y() - v * c.y() * c.z());
  s.inertia(2, 0) = s.inertia(0, 2) = -(mixed.z() - v * c.z() * c.x());
  return s;
}

namespace {

std::string triangleName(size_t k) { return "triangle " + std::to_string(k); }

// The first fault of a triangle on its own, or "".
std::string triangleFault(const std::vector<Vec3>& vertices, const std::array<int, 3>& t, size_t k) {
  const int n = static_cast<int>(vertices.size());
  for (int i : t)
    if (i < 0 || i >= n) return triangleName(k) + " names vertex " + std::to_string(i) + " of " + std::to_string(n);
  if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return triangleName(k) + " names a vertex twice";
  const Vec3 n2 = (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]);
  const double scale = std::max(
      {(vertices[t[1]] - vertices[t[0]]).squaredNorm(), (vertices[t[2]] - vertices[t[0]]).squaredNorm(), 1e-300});
  if (!(n2.norm() > 1e-12 * scale)) return triangleName(k) + " has no area (its vertices are on one line)";
  return "";
}

}  // namespace

std::string meshFault(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles) {
  for (size_t i = 0; i < vertices.size(); ++i)
    if (!vertices[i].allFinite()) return "vertex " + std::to_string(i) + " is not finite";
  if (triangles.size() < 4) return "a closed mesh has at least 4 triangles, got " + std::to_string(triangles.size());
  // Each directed edge once; its reverse once, from the triangle on the other side.
  std::map<std::pair<int, int>, size_t> directed;
  for (size_t k = 0; k < triangles.size(); ++k) {
    const std::array<int, 3>& t = triangles[k];
    if (std::string why = triangleFault(vertices, t, k); !why.empty()) return why;
    for (int e = 0; e < 3; ++e) {
      const std::pair<int, int> edge{t[e], t[(e + 1) % 3]};
      if (!directed.emplace(edge, k).second)
        return "the edge from vertex " + std::to_string(edge.first) + " to " + std::to_string(edge.second) + " of " +
               triangleName(k) + " runs the same way in " + triangleName(directed[edge]) +
               " (the triangles are not wound alike, or more than two share it)";
    }
  }
  for (const auto& [edge, k] : directed)
    if (!directed.count({edge.second, edge.first}))
      return "the edge from vertex " + std::to_string(edge.first) + " to " + std::to_string(edge.second) + " of " +
             triangleName(k) + " borders no other triangle: the mesh is open";
  const double volume = meshSolidMass(vertices, triangles).volume;
  if (!(volume > 0.0))
    return volume < 0.0 ? "the mesh is inside out (its triangles wound clockwise seen from outside)"
                        : "the mesh bounds no volume";
  return "";
}

std::string sheetFault(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles) {
  for (size_t i = 0; i < vertices.size(); ++i)
    if (!vertices[i].allFinite()) return "vertex " + std::to_string(i) + " is not finite";
  if (triangles.empty()) return "no triangles";
  for (size_t k = 0; k < triangles.size(); ++k)
    if (std::string why = triangleFault(vertices, triangles[k], k); !why.empty()) return why;
  return "";
}

PartMass placePart(const SolidMass& solid, double density, const Vec3& position, const Quat& orientation) {
  const Mat3 R = orientation.normalized().toRotationMatrix();
  return {density * solid.volume, position + R * solid.centre, density * R * solid.inertia * R.transpose()};
}

PartMass combineParts(const std::vector<PartMass>& parts) {
  PartMass all;
  for (const PartMass& p : parts) {
    all.mass += p.mass;
    all.centre += p.mass * p.centre;
  }
  if (!(all.mass > 0.0)) return all;
  all.centre /= all.mass;
  for (const PartMass& p : parts) {
    const Vec3 d = p.centre - all.centre;
    all.inertia += p.inertia + p.mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  }
  return all;
}

}  // namespace rigid
