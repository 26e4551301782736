#include "collision_detection.h"

#include <chrono>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/box_box.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "broadphase.h"
#include "compound_shape.h"
#include "contact_rules.h"

namespace rigid {

namespace {

// A contact normal within this angle of a box face's normal (cos ~11.5 deg) makes a
// face contact: that face is the reference face of the patch.
constexpr double kFaceAlign = 0.98;
// A cylinder or capsule whose axis makes |cos| below this (~11.5 deg) with the normal
// lies on its side: a line contact.
constexpr double kSideAlign = 0.2;
// Largest number of points of one pair's patch (the response wants few, well spread).
constexpr int kMaxPatch = 4;
// Vertices of an incident polygon (an octagon for a cylinder's end, a hull's face of at
// most kMaxFaceEdges), plus one per clip by a reference face's side.
constexpr int kMaxFaceEdges = 32;
constexpr int kMaxPoly = 2 * kMaxFaceEdges;
constexpr int kDiscVertices = 8;  // the octagon drawn on a cylinder's end disc
// m: how far libccd's EPA depth may exceed a face axis's overlap before its answer is
// taken for a wrong one (its own tolerance is 1e-6).
constexpr double kGjkSlack = 1e-6;

// Geometry of one collision object in the frame FCL sees it: centre p and rotation
// R (shape frame -> world), refreshed by detect().
struct Geo {
  ShapeType type = ShapeType::Box;
  const ConvexHull* hull = nullptr;  // mesh: its hull, body frame
  Vec3 half = Vec3::Zero();          // m, box half extents (shape frame)
  double radius = 0.0;               // m, sphere, cylinder, capsule
  double halfLength = 0.0;           // m, cylinder, capsule: half the length along shape z
  Mat3 R = Mat3::Identity();         // shape frame -> world
  Vec3 p = Vec3::Zero();             // m, centre, world frame
  // A mesh surface's triangle (a prism behind it): its front normal, along which a body
  // is pushed out; zero for every other shape.
  Vec3 front = Vec3::Zero();
  // A compound's part: its pose in the body frame, which the body's pose carries.
  bool part = false;
  Mat3 partR = Mat3::Identity();
  Vec3 partP = Vec3::Zero();
};

// The geometry of a shape (not a compound) at rest in its own frame.
Geo geometryOf(const Shape& s) {
  Geo g;
  g.type = s.type;
  g.half = 0.5 * s.size;
  g.radius = s.radius;
  g.halfLength = 0.5 * s.length;
  if (s.type == ShapeType::Mesh) g.hull = &s.mesh->hull;
  return g;
}

// Support function: max over the shape of d.x, for x relative to the centre.
double supportExtent(const Geo& g, const Vec3& d) {
  switch (g.type) {
    case ShapeType::Sphere: return g.radius * d.norm();
    case ShapeType::Box: return (g.R.transpose() * d).cwiseAbs().dot(g.half);
    case ShapeType::Cylinder: {
      const double du = g.R.col(2).dot(d);
      return g.halfLength * std::abs(du) + g.radius * std::sqrt(std::max(0.0, d.squaredNorm() - du * du));
    }
    case ShapeType::Capsule: return g.halfLength * std::abs(g.R.col(2).dot(d)) + g.radius * d.norm();
    case ShapeType::Mesh: {
      const Vec3 local = g.R.transpose() * d;
      return g.hull->vertices[supportVertex(*g.hull, local)].dot(local);
    }
    case ShapeType::Compound: break;  // (a slot per part: no Geo is a compound)
  }
  return 0.0;
}

// Half extents of the tight world AABB of the shape g turned by R (g.R's value, passed
// apart so that the box of every body of every step reads it from registers).
inline Vec3 aabbHalfExtent(const Geo& g, const Mat3& R) {
  switch (g.type) {
    case ShapeType::Sphere: return Vec3::Constant(g.radius);
    case ShapeType::Box: return R.cwiseAbs() * g.half;
    case ShapeType::Cylinder: {
      const Vec3 u = R.col(2);
      Vec3 e;
      for (int i = 0; i < 3; ++i)
        e[i] = g.halfLength * std::abs(u[i]) + g.radius * std::sqrt(std::max(0.0, 1.0 - u[i] * u[i]));
      return e;
    }
    case ShapeType::Capsule: return g.halfLength * R.col(2).cwiseAbs() + Vec3::Constant(g.radius);
    case ShapeType::Mesh: {  // its extent each way along each axis (about the centre of mass, not its middle)
      Vec3 e;
      for (int i = 0; i < 3; ++i) {
        const Vec3 axis = R.row(i).transpose();  // world axis i in the hull's frame
        const ConvexHull& h = *g.hull;
        e[i] = std::max(h.vertices[supportVertex(h, axis)].dot(axis), -h.vertices[supportVertex(h, -axis)].dot(axis));
      }
      return e;
    }
    case ShapeType::Compound: break;  // (a slot per part: no Geo is a compound)
  }
  return Vec3::Zero();
}

Vec3 aabbHalfExtent(const Geo& g) { return aabbHalfExtent(g, g.R); }

// A point of the shape farthest along d (world frame).
Vec3 supportPoint(const Geo& g, const Vec3& d) {
  const Vec3 dn = d.normalized();
  switch (g.type) {
    case ShapeType::Sphere: return g.p + g.radius * dn;
    case ShapeType::Box: {
      const Vec3 dl = g.R.transpose() * d;
      return g.p + g.R * Vec3(dl.x() >= 0 ? g.half.x() : -g.half.x(), dl.y() >= 0 ? g.half.y() : -g.half.y(),
                              dl.z() >= 0 ? g.half.z() : -g.half.z());
    }
    case ShapeType::Cylinder:
    case ShapeType::Capsule: {
      const Vec3 u = g.R.col(2);
      const double du = u.dot(dn);
      const Vec3 end = g.p + u * (du >= 0.0 ? g.halfLength : -g.halfLength);
      if (g.type == ShapeType::Capsule) return end + g.radius * dn;
      const Vec3 across = dn - du * u;
      return across.norm() > 1e-12 ? Vec3(end + g.radius * across.normalized()) : end;
    }
    case ShapeType::Mesh: return g.p + g.R * g.hull->vertices[supportVertex(*g.hull, g.R.transpose() * d)];
    case ShapeType::Compound: break;  // (a slot per part: no Geo is a compound)
  }
  return g.p;
}

// Sutherland-Hodgman: keeps the part of the polygon `in` (n vertices) where
// t.(x - o) <= e. Returns the vertex count written to `out`.
int clipPolygon(const Vec3* in, int n, const Vec3& t, double e, const Vec3& o, Vec3* out) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3& prev = in[(i + n - 1) % n];
    const Vec3& cur = in[i];
    const double dp = t.dot(prev - o) - e;
    const double dc = t.dot(cur - o) - e;
    if (dc <= 0.0) {
      if (dp > 0.0 && m < kMaxPoly) out[m++] = prev + (cur - prev) * (dp / (dp - dc));
      if (m < kMaxPoly) out[m++] = cur;
    } else if (dp <= 0.0 && m < kMaxPoly) {
      out[m++] = prev + (cur - prev) * (dp / (dp - dc));
    }
  }
  return m;
}

// Liang-Barsky: clips the segment s[0]-s[1] to t.(x - o) <= e; false when nothing is left.
bool clipSegment(Vec3* s, const Vec3& t, double e, const Vec3& o) {
  const double d0 = t.dot(s[0] - o) - e;
  const double d1 = t.dot(s[1] - o) - e;
  if (d0 > 0.0 && d1 > 0.0) return false;
  if (d0 > 0.0)
    s[0] = s[0] + (s[1] - s[0]) * (d0 / (d0 - d1));
  else if (d1 > 0.0)
    s[1] = s[1] + (s[0] - s[1]) * (d1 / (d1 - d0));
  return true;
}

// Picks at most kMaxPatch of the n points, well spread: the deepest, the farthest
// from it, and the farthest on either side of the line through those two (in the
// plane of normal m). Writes indices to keep[]; returns their count.
int reducePatch(const Vec3* pts, const double* sep, int n, const Vec3& m, int* keep) {
  if (n <= kMaxPatch) {
    for (int i = 0; i < n; ++i) keep[i] = i;
    return n;
  }
  int i0 = 0;
  for (int i = 1; i < n; ++i)
    if (sep[i] < sep[i0]) i0 = i;
  int i1 = i0 == 0 ? 1 : 0;
  for (int i = 0; i < n; ++i)
    if ((pts[i] - pts[i0]).squaredNorm() > (pts[i1] - pts[i0]).squaredNorm()) i1 = i;
  const Vec3 line = pts[i1] - pts[i0];
  int i2 = -1, i3 = -1;
  double best2 = 0.0, best3 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double s = m.dot(line.cross(pts[i] - pts[i0]));
    if (s > best2) {
      best2 = s;
      i2 = i;
    }
    if (s < best3) {
      best3 = s;
      i3 = i;
    }
  }
  int k = 0;
  keep[k++] = i0;
  keep[k++] = i1;
  if (i2 >= 0) keep[k++] = i2;
  if (i3 >= 0) keep[k++] = i3;
  return k;
}

// The reference face of a face contact: face k of the box `ref` (its axes k1 and k2
// span the face), or face `hullFace` of a mesh's hull; its outward normal m points
// toward the incident shape `inc`.
struct ReferenceFace {
  const Geo* ref = nullptr;
  const Geo* inc = nullptr;
  bool refIsB = false;  // the face is B's: the patch's normal (a -> b) is then -m
  int k = 0, k1 = 1, k2 = 2;
  int hullFace = -1;
  Vec3 m = Vec3::Zero();           // outward unit normal, world frame
  Vec3 faceCentre = Vec3::Zero();  // m, world frame: a box face's centre, a point of a hull's face
};

// The face of g whose outward normal is nearest to the direction `dir`: the cosine
// between them, and its index in `face` (a box's axis, whose sign the caller takes
// from dir; a hull's face of at most kMaxFaceEdges edges); -1 for other shapes.
double facingFace(const Geo& g, const Vec3& dir, int& face) {
  face = -1;
  double align = -1.0;
  if (g.type == ShapeType::Box) {
    for (int k = 0; k < 3; ++k)
      if (std::abs(g.R.col(k).dot(dir)) > align) align = std::abs(g.R.col(k).dot(dir)), face = k;
  } else if (g.type == ShapeType::Mesh) {  // among the faces around the vertex farthest along dir
    const Vec3 local = g.R.transpose() * dir;
    const ConvexHull& h = *g.hull;
    const int v = supportVertex(h, local);
    for (int k = h.vertexFaceStart[v]; k < h.vertexFaceStart[v + 1]; ++k) {
      const int f = h.vertexFace[k];
      if (h.faceSize(f) <= kMaxFaceEdges && h.faceNormal[f].dot(local) > align)
        align = h.faceNormal[f].dot(local), face = f;
    }
  }
  return align;
}

// The face of A or B (a box's or a hull's) most nearly along the contact normal n
// (a -> b), when it is within kFaceAlign of it; none for an edge or corner contact
// (or no face at all).
std::optional<ReferenceFace> referenceFace(const Geo& A, const Geo& B, const Vec3& n) {
  int kA = -1, kB = -1;
  const double alignA = facingFace(A, n, kA);
  const double alignB = facingFace(B, -n, kB);
  // B (the surface, when there is one) is the reference on a tie.
  const bool refIsB = kB >= 0 && alignB >= alignA - 1e-12;
  const double align = refIsB ? alignB : alignA;
  if (align < kFaceAlign) return std::nullopt;
  ReferenceFace f;
  f.refIsB = refIsB;
  f.ref = refIsB ? &B : &A;
  f.inc = refIsB ? &A : &B;
  const int face = refIsB ? kB : kA;
  if (f.ref->type == ShapeType::Mesh) {
    f.hullFace = face;
    f.m = f.ref->R * f.ref->hull->faceNormal[face];
    f.faceCentre = f.ref->p + f.ref->R * f.ref->hull->faceVertexAt(face, 0);
    return f;
  }
  f.k = face;
  f.k1 = (f.k + 1) % 3;
  f.k2 = (f.k + 2) % 3;
  const Vec3 toward = refIsB ? Vec3(-n) : n;  // from the reference shape to the incident one
  const Vec3 axis = f.ref->R.col(f.k);
  f.m = axis.dot(toward) > 0.0 ? axis : Vec3(-axis);
  f.faceCentre = f.ref->p + f.m * f.ref->half[f.k];
  return f;
}

// The face of the box `inc` that faces a reference face of normal m (its own normal
// most nearly -m), as 4 vertices in pts.
int incidentBoxFace(const Geo& inc, const Vec3& m, Vec3* pts) {
  int j = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(inc.R.col(i).dot(m)) > std::abs(inc.R.col(j).dot(m))) j = i;
  const Vec3 faceOut = inc.R.col(j).dot(m) > 0.0 ? Vec3(-inc.R.col(j)) : Vec3(inc.R.col(j));
  const Vec3 c = inc.p + faceOut * inc.half[j];
  const Vec3 u1 = inc.R.col((j + 1) % 3) * inc.half[(j + 1) % 3];
  const Vec3 u2 = inc.R.col((j + 2) % 3) * inc.half[(j + 2) % 3];
  pts[0] = c - u1 - u2;
  pts[1] = c + u1 - u2;
  pts[2] = c + u1 + u2;
  pts[3] = c - u1 + u2;
  return 4;
}

// The feature of a cylinder or capsule `inc` nearest a reference face of normal m, by
// the tilt of its axis: an end disc (cylinder), a side line, or one lowest point.
int incidentRoundFeature(const Geo& inc, const Vec3& m, Vec3* pts) {
  const Vec3 u = inc.R.col(2);
  const double c = u.dot(m);
  const Vec3 down = -(m - c * u);  // in the plane across the axis, toward the face
  if (inc.type == ShapeType::Cylinder && std::abs(c) >= kFaceAlign) {
    // End disc facing the reference face: an octagon on its rim, starting at the
    // rim's deepest point.
    const Vec3 centre = inc.p + u * (c > 0.0 ? -inc.halfLength : inc.halfLength);
    const Vec3 w1 = down.norm() > 1e-9 ? Vec3(down.normalized()) : anyPerpendicular(u);
    const Vec3 w2 = u.cross(w1);
    // (cos, sin) of i 45 deg as constants: the C runtimes' cos and sin differ in the last bit
    constexpr double h = 0.70710678118654752;
    constexpr double ring[kDiscVertices][2] = {{1, 0}, {h, h}, {0, 1}, {-h, h}, {-1, 0}, {-h, -h}, {0, -1}, {h, -h}};
    for (int i = 0; i < kDiscVertices; ++i) pts[i] = centre + inc.radius * (ring[i][0] * w1 + ring[i][1] * w2);
    return kDiscVertices;
  }
  if (std::abs(c) <= kSideAlign) {
    // Lying on its side: the line of the side (cylinder) or of the caps' lowest
    // points (capsule).
    const Vec3 off = inc.type == ShapeType::Cylinder ? Vec3(inc.radius * down.normalized()) : Vec3(-inc.radius * m);
    pts[0] = inc.p - u * inc.halfLength + off;
    pts[1] = inc.p + u * inc.halfLength + off;
    return 2;
  }
  // Standing capsule or tilted cylinder: one point, the lowest of the end cap
  // (capsule) or of the end's rim (cylinder) nearer the face.
  const Vec3 end = inc.p + u * (c > 0.0 ? -inc.halfLength : inc.halfLength);
  pts[0] = inc.type == ShapeType::Capsule ? Vec3(end - inc.radius * m) : Vec3(end + inc.radius * down.normalized());
  return 1;
}

// The face of the hull of `inc` whose normal is most nearly -m, its vertices in pts (a
// face of more than kMaxFaceEdges: that many of them, evenly spread, a polygon inside it).
int incidentHullFace(const Geo& inc, const Vec3& m, Vec3* pts) {
  const Vec3 local = inc.R.transpose() * m;
  const ConvexHull& h = *inc.hull;
  const int v = supportVertex(h, -local);  // the face is among those around the deepest vertex
  int best = h.vertexFace[h.vertexFaceStart[v]];
  for (int k = h.vertexFaceStart[v]; k < h.vertexFaceStart[v + 1]; ++k)
    if (h.faceNormal[h.vertexFace[k]].dot(local) < h.faceNormal[best].dot(local)) best = h.vertexFace[k];
  const int n = h.faceSize(best);
  const int count = std::min(n, kMaxFaceEdges);
  for (int i = 0; i < count; ++i) pts[i] = inc.p + inc.R * h.faceVertexAt(best, i * n / count);
  return count;
}

// The incident feature of the other shape, facing the reference face of normal m: a
// polygon (>= 3 vertices), a segment (2) or a point (1), written to pts (kMaxPoly).
int incidentFeature(const Geo& inc, const Vec3& m, Vec3* pts) {
  switch (inc.type) {
    case ShapeType::Sphere:
      pts[0] = inc.p - inc.radius * m;  // its lowest point on the face
      return 1;
    case ShapeType::Box: return incidentBoxFace(inc, m, pts);
    case ShapeType::Cylinder:
    case ShapeType::Capsule: return incidentRoundFeature(inc, m, pts);
    case ShapeType::Mesh: return incidentHullFace(inc, m, pts);
    case ShapeType::Compound: break;  // (a slot per part: no Geo is a compound)
  }
  return 0;
}

// The sides of a reference face as planes t.(x - o) <= e in the face's plane, t outward:
// a box face's four, a hull face's edges (counter-clockwise seen along m, so that
// edge x m points out). Returns how many.
int faceSides(const ReferenceFace& f, Vec3* t, double* e, Vec3* o) {
  const Geo& ref = *f.ref;
  if (f.hullFace < 0) {
    const Vec3 axes[4] = {ref.R.col(f.k1), -ref.R.col(f.k1), ref.R.col(f.k2), -ref.R.col(f.k2)};
    const double halves[4] = {ref.half[f.k1], ref.half[f.k1], ref.half[f.k2], ref.half[f.k2]};
    for (int s = 0; s < 4; ++s) t[s] = axes[s], e[s] = halves[s], o[s] = f.faceCentre;
    return 4;
  }
  const ConvexHull& h = *ref.hull;
  const int n = h.faceSize(f.hullFace);
  for (int s = 0; s < n; ++s) {
    const Vec3 a = ref.p + ref.R * h.faceVertexAt(f.hullFace, s);
    const Vec3 b = ref.p + ref.R * h.faceVertexAt(f.hullFace, (s + 1) % n);
    t[s] = (b - a).cross(f.m).normalized();
    e[s] = 0.0;
    o[s] = a;
  }
  return n;
}

// Clips the np points of the incident feature in pts to the reference face (its side
// planes), using spare as the second buffer of the polygon clipping; pts is left
// pointing at the buffer that holds the result. Returns the points left: none when a
// point or a segment misses the face, which makes it an edge contact.
int clipToFace(const ReferenceFace& f, int np, Vec3*& pts, Vec3* spare) {
  Vec3 sideAxis[kMaxFaceEdges], sideOrigin[kMaxFaceEdges];
  double sideOffset[kMaxFaceEdges];
  const int sides = faceSides(f, sideAxis, sideOffset, sideOrigin);
  if (np == 1) {
    for (int s = 0; s < sides; ++s)
      if (sideAxis[s].dot(pts[0] - sideOrigin[s]) > sideOffset[s]) return 0;
  } else if (np == 2) {
    for (int s = 0; s < sides; ++s)
      if (!clipSegment(pts, sideAxis[s], sideOffset[s], sideOrigin[s])) return 0;
  } else {
    Vec3* other = spare;
    for (int s = 0; s < sides && np > 0; ++s) {
      np = clipPolygon(pts, np, sideAxis[s], sideOffset[s], sideOrigin[s], other);
      std::swap(pts, other);
    }
  }
  return np;
}

// asinh t from +, -, *, / and sqrt alone, as log(|t| + sqrt(t^2 + 1)) with the
// logarithm's series: the C runtimes' asinh differ in the last bit (glibc's against
// MinGW's), and a tumbling body's twist friction carries that difference into the
// trajectory, which then differs between linux64 and win64. frexp is exact everywhere.
double portableAsinh(double t) {
  const double x = std::abs(t) + std::sqrt(t * t + 1.0);  // >= 1
  int e = 0;
  double m = std::frexp(x, &e);                        // x = m 2^e, m in [0.5, 1)
  if (m < 0.70710678118654752) m *= 2.0, --e;          // m in [1/sqrt 2, sqrt 2)
  const double z = (m - 1.0) / (m + 1.0), z2 = z * z;  // |z| < 0.1716
  // log m = 2 (z + z^3/3 + z^5/5 + ...): 12 terms leave < 1e-18
  double sum = 0.0;
  for (int k = 23; k >= 1; k -= 2) sum = sum * z2 + 1.0 / k;
  const double log = e * 0.69314718055994530942 + 2.0 * z * sum;
  return t < 0.0 ? -log : log;
}

// The mean distance (m) of a convex polygon's area from its area centroid, the
// polygon's np vertices in order (projected along the normal m); for 2 points a
// quarter of the segment, for fewer 0. Each triangle of the fan from the centroid
// integrates r over its area in closed form: with d the centroid's distance to the
// edge's line and t = s / d the position along that line, d^3 / 6 [t sqrt(1 + t^2) +
// asinh t] between the edge's ends.
double meanDistanceFromCentroid(const Vec3* pts, int np, const Vec3& m) {
  if (np < 2) return 0.0;
  if (np == 2) return 0.25 * ((pts[1] - pts[0]) - m * m.dot(pts[1] - pts[0])).norm();
  Vec3 centroid = Vec3::Zero();
  double area = 0.0;
  for (int i = 1; i + 1 < np; ++i) {  // the fan from vertex 0: area and area centroid
    const double a = 0.5 * (pts[i] - pts[0]).cross(pts[i + 1] - pts[0]).dot(m);
    area += a;
    centroid += a * (pts[0] + pts[i] + pts[i + 1]) / 3.0;
  }
  if (!(std::abs(area) > 1e-18)) return 0.0;
  centroid /= area;
  auto primitive = [](double t) { return t * std::sqrt(1.0 + t * t) + portableAsinh(t); };
  double moment = 0.0;  // integral of r over the area
  for (int i = 0; i < np; ++i) {
    Vec3 p = pts[i] - centroid, q = pts[(i + 1) % np] - centroid;
    p -= m * m.dot(p), q -= m * m.dot(q);
    const Vec3 edge = q - p;
    const double length = edge.norm();
    if (!(length > 0.0)) continue;
    const Vec3 u = edge / length;
    const Vec3 foot = p - u * u.dot(p);  // the centroid's nearest point on the edge's line
    const double d = foot.norm();
    if (!(d > 1e-15)) continue;
    moment += d * d * d / 6.0 * (primitive(u.dot(q) / d) - primitive(u.dot(p) / d));
  }
  return moment / std::abs(area);
}

// Appends the clipped points whose separation from the reference face is below
// `margin` (or that touch or overlap it), at most kMaxPatch of them, well spread.
int appendPatchPoints(const ReferenceFace& f, Vec3* pts, int np, double disc, double margin, const Contact& proto,
                      std::vector<Contact>& out) {
  // Separation of each point from the reference face (< 0: penetration).
  double sep[kMaxPoly];
  int kept = 0;
  for (int i = 0; i < np; ++i) {
    const double s = f.m.dot(pts[i] - f.faceCentre);
    if (s <= 0.0 || s < margin) {
      pts[kept] = pts[i];
      sep[kept] = s;
      ++kept;
    }
  }
  const double radius = disc > 0.0 && kept == np ? disc : meanDistanceFromCentroid(pts, kept, f.m);
  int keep[kMaxPatch];
  const int count = reducePatch(pts, sep, kept, f.m, keep);
  const Vec3 normal = f.refIsB ? Vec3(-f.m) : f.m;
  for (int i = 0; i < count; ++i) {
    Contact c = proto;
    c.patchRadius = radius;
    c.normal = normal;
    c.depth = -sep[keep[i]];
    c.point = pts[keep[i]] - f.m * (0.5 * sep[keep[i]]);  // midway between the feature and the face
    out.push_back(c);
  }
  return count;
}

// The patch of a face contact: the reference face is the face of a box (A or B) whose
// normal is within kFaceAlign of the contact normal n (a -> b); the incident feature
// of the other shape (a box's face, a cylinder's end or side, a capsule's side; the
// lowest point of a sphere, a standing capsule or a tilted cylinder) is clipped to the
// reference face's rectangle. Points with a separation below `margin`
// (or touching/overlapping) are appended to `out` as copies of `proto` with point,
// normal and depth filled. Returns the number appended: 0 when this is no face
// contact (or nothing of the feature lies on the face), and the caller keeps FCL's.
int appendFacePatch(const Geo& A, const Geo& B, const Vec3& n, double margin, const Contact& proto,
                    std::vector<Contact>& out) {
  const std::optional<ReferenceFace> face = referenceFace(A, B, n);
  if (!face) return 0;
  Vec3 bufA[kMaxPoly], bufB[kMaxPoly];
  Vec3* pts = bufA;
  const int whole = incidentFeature(*face->inc, face->m, pts);
  const int np = clipToFace(*face, whole, pts, bufB);
  // a cylinder's end disc (drawn as an octagon) that lies whole on the face: the
  // disc's own radius, not the octagon's
  const bool disc = face->inc->type == ShapeType::Cylinder && whole == kDiscVertices && np == whole;
  return appendPatchPoints(*face, pts, np, disc ? 2.0 / 3.0 * face->inc->radius : 0.0, margin, proto, out);
}

// The largest separation of the pair over the face normals of its boxes, and that
// axis n (a -> b); -infinity and the centre line when neither is a box. For when the
// nearest points coincide (touching), and as a bound of the depth: no overlap is
// deeper than the overlap along any axis.
double faceSeparation(const Geo& A, const Geo& B, Vec3& n) {
  double best = -std::numeric_limits<double>::infinity();
  n = B.p - A.p;
  n = n.norm() > 0.0 ? Vec3(n.normalized()) : Vec3(Vec3::UnitZ());
  for (int k = 0; k < 3; ++k) {
    for (double s : {-1.0, 1.0}) {
      if (B.type == ShapeType::Box) {  // m out of B: sep = min over A of m.x - max over B of m.x
        const Vec3 m = s * B.R.col(k);
        const double sep = m.dot(A.p - B.p) - supportExtent(A, -m) - supportExtent(B, m);
        if (sep > best) {
          best = sep;
          n = -m;
        }
      }
      if (A.type == ShapeType::Box) {
        const Vec3 m = s * A.R.col(k);
        const double sep = m.dot(B.p - A.p) - supportExtent(B, -m) - supportExtent(A, m);
        if (sep > best) {
          best = sep;
          n = m;
        }
      }
    }
  }
  return best;
}

// Largest separation of two boxes over the 15 axes of the separating-axis test (face
// normals of both, cross products of their edges), with the axis n (a -> b) that
// gives it. A positive value is a lower bound of their distance: moving b by less than
// it along n (relative to a) cannot make them overlap, which is all that the position
// correction asks of a pair that is apart. Costs far less than GJK. Stops at the first
// axis that separates them by `enough` or more (face axes first: most pairs end there).
// faceAxis: whether the axis found is a face normal (not the crossing of two edges).
double boxSeparation(const Geo& A, const Geo& B, Vec3& n, double enough, bool& faceAxis) {
  // In A's frame (Gottschalk's OBB test): C = A^T B, t = A^T (pB - pA). Each axis's
  // separation is then a few products of C, t and the half extents.
  const Mat3 C = A.R.transpose() * B.R;
  const Mat3 absC = C.cwiseAbs();
  const Vec3 t = A.R.transpose() * (B.p - A.p);
  const Vec3& a = A.half;
  const Vec3& b = B.half;
  double best = -std::numeric_limits<double>::infinity();
  Vec3 axis = Vec3::Zero();  // the best axis, world frame, unit, a -> b
  for (int i = 0; i < 3 && best < enough; ++i) {
    const double sepA = std::abs(t[i]) - a[i] - absC.row(i).dot(b);  // A's face normal i
    if (sepA > best) best = sepA, axis = t[i] >= 0.0 ? Vec3(A.R.col(i)) : Vec3(-A.R.col(i));
    const double along = C.col(i).dot(t);  // B's face normal i
    const double sepB = std::abs(along) - absC.col(i).dot(a) - b[i];
    if (sepB > best) best = sepB, axis = along >= 0.0 ? Vec3(B.R.col(i)) : Vec3(-B.R.col(i));
  }
  faceAxis = true;
  // An edge crossing must beat the faces by a margin to be taken for an overlapping
  // pair (as ODE's box-box test does), so that a resting face contact is not taken
  // for an edge contact by rounding.
  const double faceBest = best;
  for (int i = 0; i < 3 && best < enough; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3 && best < enough; ++j) {
      // |A_i x B_j| from the cross product itself: sqrt(1 - C_ij^2) loses its digits
      // for the nearly parallel edges of stacked boxes, and a separation divided by a
      // wrong small length claims a gap that is not there. Edges within 1e-6 rad of
      // parallel are skipped: their axis is nearly a face normal, already tested, and
      // leaving an axis out only makes the bound smaller.
      const Vec3 cross = A.R.col(i).cross(B.R.col(j));
      const double len = cross.norm();
      if (len < 1e-6) continue;
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double along = t[i2] * C(i1, j) - t[i1] * C(i2, j);  // d . (A_i x B_j)
      const double ra = a[i1] * absC(i2, j) + a[i2] * absC(i1, j);
      const double rb = b[j1] * absC(i, j2) + b[j2] * absC(i, j1);
      const double sep = (std::abs(along) - ra - rb) / len;
      if (sep > best && (sep > 0.0 || sep > faceBest / 1.05)) {
        faceAxis = false;
        best = sep;
        const Vec3 u = cross / len;
        axis = along >= 0.0 ? u : Vec3(-u);
      }
    }
  }
  n = axis;
  return best;
}

std::shared_ptr<fcl::CollisionGeometryd> makeGeometry(const Geo& g) {
  switch (g.type) {
    case ShapeType::Sphere: return std::make_shared<fcl::Sphered>(g.radius);
    case ShapeType::Box: return std::make_shared<fcl::Boxd>(2.0 * g.half);  // FCL takes full edge lengths
    case ShapeType::Cylinder:
      return std::make_shared<fcl::Cylinderd>(g.radius, 2.0 * g.halfLength);  // axis z, total length
    case ShapeType::Capsule:
      return std::make_shared<fcl::Capsuled>(g.radius, 2.0 * g.halfLength);  // cylinder part, axis z
    case ShapeType::Mesh: {
      // FCL's faces: each its vertex count, then its vertices, counter-clockwise from outside
      const ConvexHull& h = *g.hull;
      auto faces = std::make_shared<std::vector<int>>();
      for (int f = 0; f < h.faceCount(); ++f) {
        faces->push_back(h.faceSize(f));
        for (int k = 0; k < h.faceSize(f); ++k) faces->push_back(h.faceVertex[h.faceStart[f] + k]);
      }
      return std::make_shared<fcl::Convexd>(std::make_shared<const std::vector<Vec3>>(h.vertices), h.faceCount(),
                                            faces);
    }
    case ShapeType::Compound: break;  // (a slot per part: no Geo is a compound)
  }
  return nullptr;
}

}  // namespace

Coefficients coefficientsOf(const WorldModel& model, const Contact& c) {
  const BodyConstants& a = model.bodies[c.a];
  const bool body = c.b >= 0;
  const double xi = body ? model.bodies[c.b].restitution : model.surfaces[c.surface].restitution;
  const double mus = body ? model.bodies[c.b].staticFriction : model.surfaces[c.surface].staticFriction;
  const double muk = body ? model.bodies[c.b].kineticFriction : model.surfaces[c.surface].kineticFriction;
  const double rolling = body ? model.bodies[c.b].rollingResistance : model.surfaces[c.surface].rollingResistance;
  return {combineCoefficients(a.restitution, xi), combineCoefficients(a.staticFriction, mus),
          combineCoefficients(a.kineticFriction, muk), std::max(a.rollingResistance, rolling)};
}

struct CollisionDetector::Impl {
  // A candidate pair of the broadphase, ordered: a is a body; b a body of a higher
  // index, or -1 with `surface` set.
  struct Pair {
    int a, b, surface;
    int slotA, slotB;
    // by bodies, then by slots: a compound's parts are slots of one body
    bool operator<(const Pair& o) const {
      const int kind = surface >= 0, okind = o.surface >= 0;
      const int other = kind ? surface : b, oother = okind ? o.surface : o.b;
      return std::tie(a, kind, other, slotA, slotB) < std::tie(o.a, okind, oother, o.slotA, o.slotB);
    }
  };

  int nBodies = 0;                // bodies of the model
  int nBodySlots = 0;             // slots [0, nBodySlots): bodies that meet something (a slot per
                                  // compound part); then surfaces
  std::vector<int> slotIndex;     // slot -> body or surface index
  std::vector<char> meetsBodies;  // per body slot: pairs with other bodies too, not only surfaces
  std::vector<char> immovable;    // per slot: a surface or a driven body (no pair of two of them)
  // body pairs that a joint joins without "collide": their contacts are not detected
  std::vector<std::pair<int, int>> jointPairs;                  // (lower, higher) body index, sorted
  std::vector<Geo> geo;                                         // per slot
  std::vector<Vec3> surfaceHalfAabb;                            // per surface slot: half extents of its world AABB
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;  // per slot
  // per slot: its FCL object has this step's pose. Most pairs of a pile end in the
  // separating-axis test, so FCL's objects are placed only when a pair reaches FCL.
  std::vector<char> placed;
  SweepAndPrune broadphase;
  std::vector<int> active;                       // scratch of detect(): the slots in the sweep (all but sleepers)
  std::vector<Vec3> lo, hi;                      // scratch of detect(): each active slot's bounding box
  std::vector<int> hits;                         // scratch of detect(): sleepers near an awake body
  std::vector<std::pair<int, int>> overlapping;  // scratch of detect(): slots whose boxes overlap
  std::vector<Pair> pairs;                       // scratch of detect()
  std::vector<Pair> found;                       // scratch of detect(): pairs in the sweep's order
  std::vector<int> firstOf;                      // scratch of detect(): where each body's pairs start
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::DistanceRequestd distanceRequest;
  fcl::DistanceResultd distanceResult;

  bool isBody(int slot) const { return slot < nBodySlots; }
  bool joined(int i, int j) const {
    return !jointPairs.empty() &&
           std::binary_search(jointPairs.begin(), jointPairs.end(), std::make_pair(std::min(i, j), std::max(i, j)));
  }

  Vec3 pose(int slot, const std::vector<BodyState>& Y);
  void pairWithSleepers(const Sleepers& sleepers, const std::vector<BodyState>& Y, const Vec3& grow);
  void sortPairs();

  // The FCL object of a slot, at this step's pose.
  fcl::CollisionObjectd* object(int slot) {
    if (!placed[slot]) {
      objects[slot]->setTransform(geo[slot].R, geo[slot].p);
      placed[slot] = true;
    }
    return objects[slot].get();
  }

  // The candidate pair of two slots whose boxes overlap; false for two that nothing
  // moves (surfaces, driven bodies): contacts answer neither.
  bool candidate(int s1, int s2, Pair& p) const {
    if (immovable[s1] && immovable[s2]) return false;
    if (isBody(s1) && isBody(s2) && slotIndex[s1] == slotIndex[s2]) return false;  // a compound's parts
    if (isBody(s1) && isBody(s2) && !(meetsBodies[s1] && meetsBodies[s2])) return false;
    if (isBody(s1) && isBody(s2) && joined(slotIndex[s1], slotIndex[s2])) return false;
    if (!isBody(s1) || (isBody(s2) && slotIndex[s2] < slotIndex[s1])) std::swap(s1, s2);
    p = Pair{slotIndex[s1], -1, -1, s1, s2};
    if (isBody(s2))
      p.b = slotIndex[s2];
    else
      p.surface = slotIndex[s2];
    return true;
  }

  std::vector<fcl::ContactPointd> boxContacts;  // scratch of the box-box routine

  // Contacts of one candidate pair, appended to out; pairs apart by less than
  // `speculative` (beyond the margin) as one contact along their separating axis.
  void narrowphase(const Pair& pr, double margin, double speculative, std::vector<Contact>& out);
  // Two boxes by the separating-axis test: nothing when apart by `speculative` or more,
  // their contacts when apart by less or overlapping across a face. False for a pair
  // that overlaps at an edge, which FCL's box-box routine answers.
  bool appendBoxesBySeparatingAxis(const Pair& pr, double margin, double speculative, const Contact& proto,
                                   std::vector<Contact>& out);
  // Two boxes apart by 0 < separation < speculative along n (a -> b): the touching
  // contacts within the margin, else the facing patch or one point between them.
  void appendApartBoxes(const Pair& pr, const Vec3& n, double separation, double margin, double speculative,
                        const Contact& proto, std::vector<Contact>& out);
  // Two overlapping boxes: the face patch along FCL's box-box normal, else its points.
  void appendOverlappingBoxes(const Pair& pr, double margin, const Contact& proto, std::vector<Contact>& out);
  // Any other pair, by fcl::collide: the face patch along its normal, else its points;
  // false when FCL finds no overlap.
  bool appendFclContacts(const Pair& pr, double margin, const Contact& proto, std::vector<Contact>& out);
  // A body and a mesh surface's triangle (B): pushed out along its front, or at its edge.
  void appendTriangleContacts(const Pair& pr, double margin, double speculative, const Contact& proto,
                              std::vector<Contact>& out);
  // The contacts from `begin` on, of one body with one mesh surface's triangles: those
  // along one normal (coplanar triangles, a flat floor's seams) become one patch of at
  // most kMaxPatch points, as one face gives, so that a body resting across a seam is
  // held as on one face.
  void mergeCoplanar(std::vector<Contact>& out, size_t begin);
  std::vector<Contact> meshContacts;  // scratch of mergeCoplanar
  std::vector<Vec3> meshPoints;       // scratch of mergeCoplanar
  std::vector<double> meshGaps;       // scratch of mergeCoplanar
  std::vector<size_t> meshMembers;    // scratch of mergeCoplanar
  // A pair that does not overlap: its contacts when closer than the margin.
  void appendWithinMargin(const Pair& pr, double margin, const Contact& proto, std::vector<Contact>& out);
};

CollisionDetector::CollisionDetector(const WorldModel& model, const std::vector<bool>& collides,
                                     const std::vector<bool>& meetsSurfaces)
    : impl_(std::make_unique<Impl>()) {
  if (collides.size() != model.bodies.size())
    throw std::invalid_argument("CollisionDetector: collides has " + std::to_string(collides.size()) + " entries for " +
                                std::to_string(model.bodies.size()) + " bodies");
  if (!meetsSurfaces.empty() && meetsSurfaces.size() != model.bodies.size())
    throw std::invalid_argument("CollisionDetector: meetsSurfaces has " + std::to_string(meetsSurfaces.size()) +
                                " entries for " + std::to_string(model.bodies.size()) + " bodies");
  Impl& d = *impl_;
  d.nBodies = static_cast<int>(model.bodies.size());
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    const bool onSurfaces = !meetsSurfaces.empty() && meetsSurfaces[i];
    if (!collides[i] && !onSurfaces) continue;
    auto addSlot = [&](const Geo& g) {
      d.meetsBodies.push_back(collides[i]);
      d.immovable.push_back(driven(model.bodies[i]));
      d.slotIndex.push_back(static_cast<int>(i));
      d.geo.push_back(g);
    };
    const Shape& s = model.bodies[i].shape;
    if (s.type != ShapeType::Compound) {
      addSlot(geometryOf(s));
      continue;
    }
    for (const ShapePart& part : s.compound->parts) {
      Geo g = geometryOf(part.shape);
      g.part = true;
      g.partR = part.orientation.toRotationMatrix();
      g.partP = part.position;
      addSlot(g);
    }
  }
  d.nBodySlots = static_cast<int>(d.geo.size());
  for (const JointConstants& j : model.joints)
    if (j.a >= 0 && !j.collide) d.jointPairs.emplace_back(std::min(j.a, j.b), std::max(j.a, j.b));
  std::sort(d.jointPairs.begin(), d.jointPairs.end());
  for (size_t j = 0; j < model.surfaces.size(); ++j) {
    const Surface& s = model.surfaces[j];
    auto addSlot = [&](const Geo& g) {
      d.slotIndex.push_back(static_cast<int>(j));
      d.immovable.push_back(1);
      d.geo.push_back(g);
      d.surfaceHalfAabb.push_back(aabbHalfExtent(g));
    };
    if (s.mesh) {  // a slot per triangle
      for (size_t k = 0; k < s.mesh->prisms.size(); ++k) {
        Geo g;
        g.type = ShapeType::Mesh;
        g.hull = &s.mesh->prisms[k];
        g.p = s.mesh->centres[k];
        g.front = s.mesh->fronts[k];
        addSlot(g);
      }
      continue;
    }
    Geo g;
    g.type = ShapeType::Box;
    g.half = s.halfExtent;
    g.R = s.R_WS;
    g.p = s.centre;
    addSlot(g);
  }
  for (size_t slot = 0; slot < d.geo.size(); ++slot) {
    const Geo& g = d.geo[slot];
    auto obj = std::make_unique<fcl::CollisionObjectd>(makeGeometry(g), g.R, g.p);
    d.objects.push_back(std::move(obj));
  }
  d.placed.assign(d.geo.size(), true);  // surfaces never move; bodies are placed at their first pair
  d.active.reserve(d.geo.size());
  d.lo.reserve(d.geo.size());
  d.hi.reserve(d.geo.size());
  d.pairs.reserve(4 * d.geo.size());
  d.boxContacts.reserve(8);

  d.request.num_max_contacts = 8;
  d.request.enable_contact = true;
  d.request.gjk_solver_type = fcl::GST_LIBCCD;  // GST_INDEP gives negative depths for GJK pairs
  d.distanceRequest.enable_nearest_points = true;
  d.distanceRequest.gjk_solver_type = fcl::GST_LIBCCD;
}

CollisionDetector::~CollisionDetector() = default;
CollisionDetector::CollisionDetector(CollisionDetector&&) noexcept = default;
CollisionDetector& CollisionDetector::operator=(CollisionDetector&&) noexcept = default;

// The pose of a slot's body in Y, and its tight bounding box's half extents.
Vec3 CollisionDetector::Impl::pose(int slot, const std::vector<BodyState>& Y) {
  Geo& g = geo[slot];
  const BodyState& y = Y[slotIndex[slot]];
  const Mat3 R = y.q.normalized().toRotationMatrix();
  placed[slot] = false;
  if (g.part) {
    g.R = R * g.partR;
    g.p = y.X + R * g.partP;
    return aabbHalfExtent(g, g.R);
  }
  g.R = R;
  g.p = y.X;
  return aabbHalfExtent(g, R);
}

std::shared_ptr<const FixedBoxes> CollisionDetector::fixedBoxes(const std::vector<BodyState>& Y,
                                                                const std::vector<char>& asleep) {
  Impl& d = *impl_;
  std::vector<int> slots;
  std::vector<Vec3> lo, hi;
  for (int slot = 0; slot < d.nBodySlots; ++slot) {
    if (!asleep[d.slotIndex[slot]]) continue;
    const Vec3 half = d.pose(slot, Y);
    slots.push_back(slot);
    lo.push_back(d.geo[slot].p - half);
    hi.push_back(d.geo[slot].p + half);
  }
  return std::make_shared<const FixedBoxes>(slots, lo, hi);
}

void CollisionDetector::detect(const std::vector<BodyState>& Y, double margin, std::vector<Contact>& out,
                               StepProfile* profile, double speculative, const Sleepers* sleepers) {
  Impl& d = *impl_;
  const auto start = profile ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  if (Y.size() != static_cast<size_t>(d.nBodies))
    throw std::invalid_argument("CollisionDetector::detect: " + std::to_string(Y.size()) + " states for " +
                                std::to_string(d.nBodies) + " bodies");
  if (sleepers && sleepers->asleep.size() != static_cast<size_t>(d.nBodies))
    throw std::invalid_argument("CollisionDetector::detect: " + std::to_string(sleepers->asleep.size()) +
                                " sleep flags for " + std::to_string(d.nBodies) + " bodies");
  margin = std::max(margin, 0.0);
  speculative = std::max(speculative, margin);
  out.clear();
  // The slots that move (awake bodies) and the surfaces: each shape's tight axis-aligned
  // box, grown by half the speculative distance, so that two shapes closer than it are
  // candidates. Sleeping bodies keep their boxes in `sleepers` and are only asked for.
  const Vec3 grow = Vec3::Constant(0.5 * speculative);
  d.active.clear();
  for (int slot = 0; slot < static_cast<int>(d.geo.size()); ++slot)
    if (!d.isBody(slot) || !sleepers || !sleepers->asleep[d.slotIndex[slot]]) d.active.push_back(slot);
  const int nActive = static_cast<int>(d.active.size());
  d.lo.resize(nActive);
  d.hi.resize(nActive);
  for (int k = 0; k < nActive; ++k) {
    const int slot = d.active[k];
    const Vec3 half = d.isBody(slot) ? d.pose(slot, Y) : d.surfaceHalfAabb[slot - d.nBodySlots];
    d.lo[k] = d.geo[slot].p - half - grow;
    d.hi[k] = d.geo[slot].p + half + grow;
  }
  d.broadphase.overlaps(d.lo, d.hi, d.overlapping);
  d.found.clear();
  for (const auto& [k1, k2] : d.overlapping)
    if (Impl::Pair p; d.candidate(d.active[k1], d.active[k2], p)) d.found.push_back(p);
  if (sleepers) d.pairWithSleepers(*sleepers, Y, grow);
  d.sortPairs();
  const auto broad = profile ? std::chrono::steady_clock::now() : start;
  // A body's contacts with one mesh surface are merged once all its triangles are done.
  size_t meshBegin = 0;
  std::pair<int, int> mesh{-1, -1};  // (body, surface) of the contacts from meshBegin on
  for (const Impl::Pair& p : d.pairs) {
    const std::pair<int, int> on =
        d.geo[p.slotB].front != Vec3::Zero() ? std::make_pair(p.a, p.surface) : std::make_pair(-1, -1);
    if (on != mesh) {
      if (mesh.first >= 0) d.mergeCoplanar(out, meshBegin);
      mesh = on;
      meshBegin = out.size();
    }
    d.narrowphase(p, margin, speculative, out);
  }
  if (mesh.first >= 0) d.mergeCoplanar(out, meshBegin);
  if (profile) {
    profile->broadphase += std::chrono::duration<double, std::nano>(broad - start).count();
    profile->narrowphase += std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - broad).count();
    profile->boxes += nActive - static_cast<int>(d.surfaceHalfAabb.size());
  }
}

// The awake bodies' pairs with sleeping ones: each awake body that meets bodies asks
// the sleepers' boxes for those within the speculative distance of its own.
void CollisionDetector::Impl::pairWithSleepers(const Sleepers& sleepers, const std::vector<BodyState>& Y,
                                               const Vec3& grow) {
  for (int k = 0; k < static_cast<int>(active.size()); ++k) {
    const int slot = active[k];
    if (!isBody(slot) || !meetsBodies[slot]) continue;
    hits.clear();
    sleepers.boxes.overlapping(lo[k] - grow, hi[k] + grow, hits);
    for (int other : hits) {
      if (Pair p; candidate(slot, other, p)) {
        pose(other, Y);
        found.push_back(p);
      }
    }
  }
}

// Pairs in one order whatever the sweep's history (a restored FMU state has none): the
// response's passes, and so its results, follow it. Counting sort by body, then each
// body's few pairs by partner.
void CollisionDetector::Impl::sortPairs() {
  pairs.clear();
  if (found.empty()) return;  // (bodies far apart: no per-body work)
  firstOf.assign(nBodies + 1, 0);
  for (const Pair& p : found) ++firstOf[p.a + 1];
  for (size_t b = 1; b < firstOf.size(); ++b) firstOf[b] += firstOf[b - 1];
  pairs.resize(found.size());
  for (const Pair& p : found) pairs[firstOf[p.a]++] = p;  // firstOf[a]: now where a's pairs end
  for (size_t b = 0, begin = 0; b < static_cast<size_t>(nBodies); begin = firstOf[b++])
    std::sort(pairs.begin() + begin, pairs.begin() + firstOf[b]);
}

void CollisionDetector::Impl::narrowphase(const Pair& pr, double margin, double speculative,
                                          std::vector<Contact>& out) {
  Contact proto;
  proto.a = pr.a;
  proto.b = pr.b;
  proto.surface = pr.surface;
  if (geo[pr.slotA].type == ShapeType::Box && geo[pr.slotB].type == ShapeType::Box) {
    if (speculative > 0.0 && appendBoxesBySeparatingAxis(pr, margin, speculative, proto, out)) return;
    appendOverlappingBoxes(pr, margin, proto, out);
    return;
  }
  if (geo[pr.slotB].front != Vec3::Zero()) {
    appendTriangleContacts(pr, margin, speculative, proto, out);
    return;
  }
  if (appendFclContacts(pr, margin, proto, out)) return;
  appendWithinMargin(pr, speculative, proto, out);
}

void CollisionDetector::Impl::appendTriangleContacts(const Pair& pr, double margin, double speculative,
                                                     const Contact& proto, std::vector<Contact>& out) {
  // Along the front only: the patch of the body's feature over the triangle, touching or
  // within the speculative distance. A neighbour's prism beside the body (the seam of a
  // flat floor) would otherwise stop a sliding body on its side face.
  const Geo& A = geo[pr.slotA];
  const Geo& B = geo[pr.slotB];
  if (appendFacePatch(A, B, -B.front, speculative, proto, out) > 0) return;
  // Over no part of the triangle yet overlapping it: the body strikes its edge or corner.
  appendFclContacts(pr, margin, proto, out);
}

bool CollisionDetector::Impl::appendBoxesBySeparatingAxis(const Pair& pr, double margin, double speculative,
                                                          const Contact& proto, std::vector<Contact>& out) {
  const Geo& A = geo[pr.slotA];
  const Geo& B = geo[pr.slotB];
  // Apart: the separating-axis test bounds the gap from below, cheaply, and most
  // candidate pairs of a pile end here (their bounding boxes overlap, they do not).
  // Only a bound below the margin needs FCL's distance (GJK, costly) for the touching
  // contact's points; a pair within the speculative distance is one contact along
  // that axis, or its facing patch.
  Vec3 n;
  bool faceAxis = false;
  const double separation = boxSeparation(A, B, n, speculative, faceAxis);
  if (separation >= speculative) return true;
  // Overlapping across a face: that face's patch, with the axis of least
  // penetration as its normal (what FCL's box-box routine would find), and the
  // pair's overlap along it for the position correction.
  if (separation <= 0.0 && faceAxis) {
    const size_t first = out.size();
    if (appendFacePatch(A, B, n, margin, proto, out) > 0) {
      for (size_t k = first; k < out.size(); ++k) out[k].pairOverlap = -separation;
      return true;
    }
  }
  if (!(separation > 0.0)) return false;  // overlapping at an edge: FCL's box-box routine
  appendApartBoxes(pr, n, separation, margin, speculative, proto, out);
  return true;
}

void CollisionDetector::Impl::appendApartBoxes(const Pair& pr, const Vec3& n, double separation, double margin,
                                               double speculative, const Contact& proto, std::vector<Contact>& out) {
  const Geo& A = geo[pr.slotA];
  const Geo& B = geo[pr.slotB];
  if (separation < margin) {
    // touching within the margin by GJK's distance; if that distance is not
    // within it after all, the pair is still a speculative one
    const size_t before = out.size();
    appendWithinMargin(pr, margin, proto, out);
    if (out.size() > before) return;
  }
  // Facing faces (a cube above another): the patch, whose centre is where an
  // impulse stopping the approach acts without turning the pair; edges and
  // corners: one point between the two support points.
  if (appendFacePatch(A, B, n, speculative, proto, out) > 0) return;
  Contact c = proto;
  c.normal = n;
  c.depth = -separation;
  c.point = 0.5 * (supportPoint(A, n) + supportPoint(B, -n));
  out.push_back(c);
}

void CollisionDetector::Impl::appendOverlappingBoxes(const Pair& pr, double margin, const Contact& proto,
                                                     std::vector<Contact>& out) {
  const Geo& A = geo[pr.slotA];
  const Geo& B = geo[pr.slotB];
  // FCL's own box-box routine (ODE's dBoxBox2, the one fcl::collide runs for this
  // pair), called directly into a reused buffer so that the hot pair of a box pile
  // allocates nothing. Its normal points from box 1 to 2.
  boxContacts.clear();
  Vec3 n;
  double depth = 0.0;
  int code = 0;
  fcl::detail::boxBox2<double>(2.0 * A.half, object(pr.slotA)->getTransform(), 2.0 * B.half,
                               object(pr.slotB)->getTransform(), n, &depth, &code, 4, boxContacts);
  if (code == 0) {
    // touching to rounding (the two tests disagree at a gap of zero)
    appendWithinMargin(pr, margin, proto, out);
    return;
  }
  if (appendFacePatch(A, B, n, margin, proto, out) > 0) return;
  for (const fcl::ContactPointd& cp : boxContacts) {  // edge-edge: one point
    Contact c = proto;
    c.normal = cp.normal;
    c.depth = std::max(cp.penetration_depth, 0.0);
    c.point = cp.pos;
    out.push_back(c);
  }
}

bool CollisionDetector::Impl::appendFclContacts(const Pair& pr, double margin, const Contact& proto,
                                                std::vector<Contact>& out) {
  const Geo& A = geo[pr.slotA];
  const Geo& B = geo[pr.slotB];
  fcl::CollisionObjectd* oA = object(pr.slotA);
  fcl::CollisionObjectd* oB = object(pr.slotB);
  result.clear();
  fcl::collide(oA, oB, request, result);
  if (result.numContacts() == 0) return false;
  // FCL's normal points from o1 to o2; o1 is A's geometry unless FCL swapped them.
  const fcl::Contactd& first = result.getContact(0);
  const double sign = first.o1 == oA->collisionGeometry().get() ? 1.0 : -1.0;
  Vec3 n = sign * first.normal;
  // libccd's EPA answers a pair that only touches with an arbitrary normal and depth
  // (a puck standing exactly on the floor: 1.65 m along the slab's side), or with none
  // (a capsule's cap touching the floor at 2e-16 m). A box's face normals bound the
  // depth: when one of them separates the pair or meets it at zero, the pair touches
  // at most and is answered along that face; when FCL's depth exceeds the overlap along
  // one, or FCL gives no normal, that face's normal (without a box, the centre line)
  // is the answer.
  Vec3 axis;
  const double separation = faceSeparation(A, B, axis);  // -infinity without a box
  if (separation >= 0.0) return appendFacePatch(A, B, axis, margin, proto, out) > 0;
  auto unit = [](const Vec3& v) { return std::abs(v.norm() - 1.0) < 1e-6; };
  if (!unit(n) || first.penetration_depth > -separation + kGjkSlack) n = axis;
  if (appendFacePatch(A, B, n, margin, proto, out) > 0) return true;
  for (size_t i = 0; i < result.numContacts(); ++i) {
    const fcl::Contactd& fc = result.getContact(i);
    Contact c = proto;
    c.normal = (fc.o1 == oA->collisionGeometry().get() ? 1.0 : -1.0) * fc.normal;
    if (!unit(c.normal)) c.normal = n;
    c.depth = std::max(fc.penetration_depth, 0.0);
    c.point = fc.pos;
    if (A.type == ShapeType::Sphere && B.type == ShapeType::Sphere)  // midway in the overlap
      c.point = A.p + c.normal * (A.radius - 0.5 * c.depth);
    out.push_back(c);
  }
  return true;
}

void CollisionDetector::Impl::mergeCoplanar(std::vector<Contact>& out, size_t begin) {
  if (out.size() - begin <= static_cast<size_t>(kMaxPatch)) return;
  meshContacts.assign(out.begin() + static_cast<std::ptrdiff_t>(begin), out.end());
  out.resize(begin);
  constexpr double kSameNormal = 1e-9;
  for (size_t i = 0; i < meshContacts.size(); ++i) {
    if (meshContacts[i].a < 0) continue;  // taken into an earlier patch
    const Vec3 n = meshContacts[i].normal;
    meshPoints.clear();
    meshGaps.clear();
    std::vector<size_t>& members = meshMembers;
    members.clear();
    double radius = 0.0;
    for (size_t j = i; j < meshContacts.size(); ++j) {
      if (meshContacts[j].a < 0 || (meshContacts[j].normal - n).norm() > kSameNormal) continue;
      members.push_back(j);
      meshPoints.push_back(meshContacts[j].point);
      meshGaps.push_back(-meshContacts[j].depth);
      radius = std::max(radius, meshContacts[j].patchRadius);
    }
    int keep[kMaxPatch];
    const int count = reducePatch(meshPoints.data(), meshGaps.data(), static_cast<int>(members.size()), n, keep);
    for (int k = 0; k < count; ++k) {
      Contact c = meshContacts[members[keep[k]]];
      c.patchRadius = radius;
      out.push_back(c);
    }
    for (size_t j : members) meshContacts[j].a = -1;
  }
}

void CollisionDetector::Impl::appendWithinMargin(const Pair& pr, double margin, const Contact& proto,
                                                 std::vector<Contact>& out) {
  if (margin <= 0.0) return;
  const Geo& A = geo[pr.slotA];
  const Geo& B = geo[pr.slotB];
  fcl::CollisionObjectd* oA = object(pr.slotA);
  fcl::CollisionObjectd* oB = object(pr.slotB);
  distanceResult.clear();
  const double dist = fcl::distance(oA, oB, distanceRequest, distanceResult);
  if (dist >= margin) return;
  // Nearest points in the world frame, on A and on B (FCL keeps o1's first).
  const bool swapped = distanceResult.o1 != oA->collisionGeometry().get();
  Vec3 pA = distanceResult.nearest_points[swapped ? 1 : 0];
  Vec3 pB = distanceResult.nearest_points[swapped ? 0 : 1];
  const Vec3 gap = pB - pA;
  // Touching within FCL's tolerance (or, rarely, overlapping by it): no direction from
  // the nearest points, which FCL does not even fill when it finds an overlap.
  const bool touching = !(dist > 0.0 && gap.norm() > 1e-12);
  Vec3 n = gap.normalized();
  if (touching) faceSeparation(A, B, n);
  if (appendFacePatch(A, B, n, margin, proto, out) > 0) return;
  if (touching) {
    pA = supportPoint(A, n);
    pB = supportPoint(B, -n);
  }
  Contact c = proto;
  c.normal = n;
  c.depth = -std::max(dist, 0.0);
  c.point = 0.5 * (pA + pB);
  out.push_back(c);
}

}  // namespace rigid
