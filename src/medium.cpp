#include "medium.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <utility>

#include "medium_detail.h"

// Buoyancy and drag of the media (docs/media.md has the formulas, the coefficients and
// the errors of the approximations). Everything here lives on the stack in fixed-size
// arrays: no allocation per call, no state kept between calls.

namespace rigid {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The scene reader refuses a mesh or compound body in a scene with media (issue 42 left
// it): the shape functions below never see one.
[[noreturn]] void noMeshInMedia() { throw std::logic_error("media: a mesh or compound body reached the medium"); }

// ---- submerged part: convex polyhedra clipped by the medium's box -----------------------

// A convex polygon, vertices in order, counter-clockwise seen from the side its outward
// normal points to. Clipping by a half-space adds at most one vertex.
template <int N>
struct Polygon {
  std::array<Vec3, N> v;
  int n = 0;
  void push(const Vec3& p) {
    if (n < N) v[n++] = p;  // capacities below are upper bounds; the guard is for safety
  }
};

// out = the part of in where n.x <= d (Sutherland-Hodgman). A crossing point is always
// computed from the edge's inside end, so that the two faces sharing an edge get the
// same point to the last bit.
template <int N>
void clip(const Polygon<N>& in, const Vec3& n, double d, Polygon<N>& out) {
  out.n = 0;
  if (in.n < 3) return;
  for (int i = 0; i < in.n; ++i) {
    const Vec3& a = in.v[i];
    const Vec3& b = in.v[i + 1 == in.n ? 0 : i + 1];
    const double da = n.dot(a) - d;
    const double db = n.dot(b) - d;
    if (da <= 0.0) out.push(a);
    if ((da <= 0.0) != (db <= 0.0)) {
      if (da <= 0.0)
        out.push(a + (b - a) * (da / (da - db)));
      else
        out.push(b + (a - b) * (db / (db - da)));
    }
  }
  if (out.n < 3) out.n = 0;
}

// Volume and first moment of a closed surface, from the signed tetrahedra that its
// polygons span with the origin (the body's centre of mass).
struct Moments {
  double volume = 0.0;         // m^3
  Vec3 moment = Vec3::Zero();  // m^4, integral of x dV
  template <int N>
  void addFace(const Polygon<N>& p) {
    for (int i = 1; i + 1 < p.n; ++i) {
      const double vol = p.v[0].dot(p.v[i].cross(p.v[i + 1])) / 6.0;
      volume += vol;
      moment += vol * 0.25 * (p.v[0] + p.v[i] + p.v[i + 1]);
    }
  }
};

// A convex polyhedron in coordinates relative to the centre of mass, world axes:
// vertices, faces (index lists, counter-clockwise from outside) and the faces' planes.
constexpr int kMaxProfile = 2 * kCapsuleRings + 2;  // capsule: rings and two poles
constexpr int kMaxVertices = kLatheSides * kMaxProfile;
constexpr int kMaxFaces = kLatheSides * (kMaxProfile - 1) + 2;
constexpr int kMaxIndices = 4 * kLatheSides * (kMaxProfile - 1) + 2 * kLatheSides;
// A box face clipped by every plane of the polyhedron: 4 + one vertex per plane at most.
constexpr int kMaxSection = 4 + kMaxFaces;
constexpr int kMaxFace = kLatheSides + 6;  // a face clipped by the box's six planes

struct Polyhedron {
  std::array<Vec3, kMaxVertices> vertex;
  int nVertices = 0;
  std::array<int, kMaxIndices> index;
  std::array<int, kMaxFaces + 1> faceStart{};
  int nFaces = 0;
  std::array<Vec3, kMaxFaces> normal;    // outward, not normalised
  std::array<double, kMaxFaces> offset;  // normal . x <= offset inside
  double radius = 0.0;                   // m, bounding sphere about the centre of mass

  void addFace(std::initializer_list<int> ids) { addFace(ids.begin(), static_cast<int>(ids.size())); }
  void addFace(const int* ids, int n) {
    const int at = faceStart[nFaces];
    for (int i = 0; i < n; ++i) index[at + i] = ids[i];
    // Newell's normal: robust for any planar polygon.
    Vec3 nrm = Vec3::Zero();
    Vec3 c = Vec3::Zero();
    for (int i = 0; i < n; ++i) {
      const Vec3& a = vertex[ids[i]];
      const Vec3& b = vertex[ids[i + 1 == n ? 0 : i + 1]];
      nrm += a.cross(b);
      c += a;
    }
    normal[nFaces] = nrm;
    offset[nFaces] = nrm.dot(c / n);
    ++nFaces;
    faceStart[nFaces] = at + n;
  }
};

// The box body: vertices R (+-l/2), faces outward.
void makeBox(const Vec3& size, const Mat3& R, Polyhedron& p) {
  const Vec3 h = 0.5 * size;
  p.nVertices = 8;
  for (int i = 0; i < 8; ++i) {
    const Vec3 s((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
    p.vertex[i] = R * s.cwiseProduct(h);
  }
  p.radius = h.norm();
  // Face +k: corners (-,-), (+,-), (+,+), (-,+) in the cyclic axes (k1, k2); face -k reversed.
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    const int corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int side = 0; side < 2; ++side) {
      int ids[4];
      for (int c = 0; c < 4; ++c) {
        const int(&cc)[2] = corners[side == 1 ? c : 3 - c];
        ids[c] = (side << k) | (cc[0] << k1) | (cc[1] << k2);
      }
      p.addFace(ids, 4);
    }
  }
}

// A convex solid of revolution about body z, as a polyhedron with kLatheSides sides:
// profile points (z_j, rho_j), z increasing; rho = 0 is a pole. Radii are scaled so that
// the polyhedron's volume is the solid's (volume).
void makeLathe(const double* z, const double* rho, int J, double volume, const Mat3& R, Polyhedron& p) {
  constexpr int N = kLatheSides;
  // cos and sin of the N corners' angles: a constant table, filled once.
  static const std::array<std::array<double, 2>, N> circle = [] {
    std::array<std::array<double, 2>, N> c{};
    for (int i = 0; i < N; ++i) c[i] = {std::cos(2.0 * kPi * i / N), std::sin(2.0 * kPi * i / N)};
    return c;
  }();
  const double k = 0.5 * N * std::sin(2.0 * kPi / N);  // N-gon area / rho^2
  // The volume of the polyhedron at scale 1: frusta of similar N-gons.
  double v1 = 0.0;
  for (int j = 0; j + 1 < J; ++j)
    v1 += k * (z[j + 1] - z[j]) / 3.0 * (rho[j] * rho[j] + rho[j + 1] * rho[j + 1] + rho[j] * rho[j + 1]);
  const double s = std::sqrt(volume / v1);
  // Vertex index of ring j, corner i; a pole has one vertex.
  std::array<int, kMaxProfile> first{};
  p.nVertices = 0;
  p.radius = 0.0;
  for (int j = 0; j < J; ++j) {
    first[j] = p.nVertices;
    const int count = rho[j] > 0.0 ? N : 1;
    for (int i = 0; i < count; ++i) {
      const Vec3 b(s * rho[j] * circle[i][0], s * rho[j] * circle[i][1], z[j]);
      p.vertex[p.nVertices++] = R * b;
      p.radius = std::max(p.radius, b.norm());
    }
  }
  auto at = [&](int j, int i) { return rho[j] > 0.0 ? first[j] + (i % N) : first[j]; };
  if (rho[0] > 0.0) {  // bottom end face, outward -z
    int ids[N];
    for (int i = 0; i < N; ++i) ids[i] = at(0, N - 1 - i);
    p.addFace(ids, N);
  }
  for (int j = 0; j + 1 < J; ++j) {
    for (int i = 0; i < N; ++i) {
      if (rho[j] <= 0.0)
        p.addFace({at(j, 0), at(j + 1, i + 1), at(j + 1, i)});
      else if (rho[j + 1] <= 0.0)
        p.addFace({at(j, i), at(j, i + 1), at(j + 1, 0)});
      else
        p.addFace({at(j, i), at(j, i + 1), at(j + 1, i + 1), at(j + 1, i)});
    }
  }
  if (rho[J - 1] > 0.0) {  // top end face, outward +z
    int ids[N];
    for (int i = 0; i < N; ++i) ids[i] = at(J - 1, i);
    p.addFace(ids, N);
  }
}

void makeCylinder(double r, double l, const Mat3& R, Polyhedron& p) {
  const double z[2] = {-0.5 * l, 0.5 * l};
  const double rho[2] = {r, r};
  makeLathe(z, rho, 2, kPi * r * r * l, R, p);
}

// Rings at latitudes 0, 90/K, ... degrees on each hemisphere, and the poles.
void makeCapsule(double r, double l, const Mat3& R, Polyhedron& p) {
  constexpr int K = kCapsuleRings;
  double z[kMaxProfile], rho[kMaxProfile];
  int J = 0;
  for (int j = K; j >= 0; --j) {  // bottom pole (j = K) up to the bottom equator (j = 0)
    const double phi = 0.5 * kPi * j / K;
    z[J] = -0.5 * l - r * std::sin(phi);
    rho[J++] = j == K ? 0.0 : r * std::cos(phi);
  }
  for (int j = l > 0.0 ? 0 : 1; j <= K; ++j) {  // l = 0: a ball, one equator
    const double phi = 0.5 * kPi * j / K;
    z[J] = 0.5 * l + r * std::sin(phi);
    rho[J++] = j == K ? 0.0 : r * std::cos(phi);
  }
  makeLathe(z, rho, J, kPi * r * r * l + 4.0 / 3.0 * kPi * r * r * r, R, p);
}

// A face of the medium's box that cuts the body's bounding sphere, in coordinates
// relative to the centre of mass: the plane x_axis = offset, outward normal sign e_axis
// (inside: sign x_axis <= sign offset).
struct BoxPlane {
  int axis;
  double sign;    // +1: the upper face (max), -1: the lower face (min)
  double offset;  // m
};

// The planes of the box [lo, hi] that cut P's bounding sphere: the others leave P whole.
struct CuttingPlanes {
  BoxPlane plane[6];
  int n = 0;
};

CuttingPlanes planesCutting(const Polyhedron& P, const Vec3& lo, const Vec3& hi) {
  CuttingPlanes box;
  for (int k = 0; k < 3; ++k) {
    if (hi[k] < P.radius) box.plane[box.n++] = {k, 1.0, hi[k]};
    if (lo[k] > -P.radius) box.plane[box.n++] = {k, -1.0, lo[k]};
  }
  return box;
}

// Adds to m the faces of P clipped by the box. Most faces are wholly inside or wholly
// outside one of the planes: they are taken or dropped without clipping.
void addFacesInBox(const Polyhedron& P, const CuttingPlanes& box, Moments& m) {
  Polygon<kMaxFace> faceA, faceB;
  for (int f = 0; f < P.nFaces; ++f) {
    const int begin = P.faceStart[f], end = P.faceStart[f + 1];
    int cutting[6];
    int nCutting = 0;
    bool dropped = false;
    for (int c = 0; c < box.n && !dropped; ++c) {
      const BoxPlane& bp = box.plane[c];
      int out = 0;
      for (int i = begin; i < end; ++i) out += bp.sign * (P.vertex[P.index[i]][bp.axis] - bp.offset) > 0.0;
      if (out == end - begin)
        dropped = true;
      else if (out > 0)
        cutting[nCutting++] = c;
    }
    if (dropped) continue;
    Polygon<kMaxFace>* a = &faceA;
    Polygon<kMaxFace>* b = &faceB;
    a->n = 0;
    for (int i = begin; i < end; ++i) a->push(P.vertex[P.index[i]]);
    for (int c = 0; c < nCutting && a->n > 0; ++c) {
      const BoxPlane& bp = box.plane[cutting[c]];
      clip(*a, bp.sign * Vec3::Unit(bp.axis), bp.sign * bp.offset, *b);
      std::swap(a, b);
    }
    m.addFace(*a);
  }
}

// Adds to m the section that P makes in the box's plane bp: a rectangle bounded by the
// box in the other two axes (and by P's bounding cube, to keep the numbers small),
// clipped by the faces of P that reach the plane. Only those bound the section (a
// convex polygon is the intersection of its edges' half-planes); the others are
// skipped. A plane that no face reaches misses P and adds nothing.
void addBoxSection(const Polyhedron& P, const BoxPlane& bp, const Vec3& lo, const Vec3& hi, Moments& m) {
  const double big = 2.0 * P.radius;
  const int k = bp.axis, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
  const double l1 = std::max(lo[k1], -big), h1 = std::min(hi[k1], big);
  const double l2 = std::max(lo[k2], -big), h2 = std::min(hi[k2], big);
  if (!(l1 < h1 && l2 < h2)) return;
  const double corners[4][2] = {{l1, l2}, {h1, l2}, {h1, h2}, {l1, h2}};
  Polygon<kMaxSection> sectionA, sectionB;
  Polygon<kMaxSection>* s = &sectionA;
  Polygon<kMaxSection>* t = &sectionB;
  s->n = 0;
  for (int q = 0; q < 4; ++q) {
    const double(&cc)[2] = corners[bp.sign > 0 ? q : 3 - q];
    Vec3 p;
    p[k] = bp.offset;
    p[k1] = cc[0];
    p[k2] = cc[1];
    s->push(p);
  }
  int reaching = 0;
  for (int f = 0; f < P.nFaces && s->n > 0; ++f) {
    double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
    for (int i = P.faceStart[f]; i < P.faceStart[f + 1]; ++i) {
      zmin = std::min(zmin, P.vertex[P.index[i]][k]);
      zmax = std::max(zmax, P.vertex[P.index[i]][k]);
    }
    if (zmin > bp.offset || zmax < bp.offset) continue;
    ++reaching;
    clip(*s, P.normal[f], P.offset[f], *t);
    std::swap(s, t);
  }
  if (reaching == 0) return;  // the plane misses P: no section
  m.addFace(*s);
}

// P inside the box [lo, hi] (relative to the centre of mass). Every face of the result
// is either a face of P clipped by the box or a face of the box clipped by P; their
// signed tetrahedra with the origin give volume and moment. The box is first shrunk by
// a margin eps above rounding, so that a face of P that lies exactly in a face of the
// box (a box resting flush on the floor of a tank, a top flush with the surface) is
// never counted twice nor half: the result is that of a box eps smaller on each side.
SubmergedPart clipPolyhedron(const Polyhedron& P, const Vec3& X, const Vec3& lo0, const Vec3& hi0) {
  // 64 ulps of the coordinates involved: above the rounding of R p and of min - X, far
  // below anything a scene resolves (1.4e-14 m for a body 1 m from the origin).
  const double eps = 64.0 * std::numeric_limits<double>::epsilon() * (X.cwiseAbs().maxCoeff() + P.radius);
  const Vec3 lo = (lo0.array() + eps).matrix();
  const Vec3 hi = (hi0.array() - eps).matrix();
  const CuttingPlanes box = planesCutting(P, lo, hi);
  Moments m;
  addFacesInBox(P, box, m);
  for (int c = 0; c < box.n; ++c) addBoxSection(P, box.plane[c], lo, hi, m);
  SubmergedPart part;
  part.volume = m.volume;
  part.centroid = X + (m.volume > 0.0 ? Vec3(m.moment / m.volume) : Vec3::Zero());
  return part;
}

// Volume and first moment (about the centre, along the axis) of the slab a <= x <= b of
// a ball of radius r centred at 0, -r <= a < b <= r. From the cap of height h at the
// pole x = -r: V(h) = pi h^2 (3r - h) / 3, moment -pi h^2 (2r - h)^2 / 4. A slab in the
// upper half is mirrored, so that small caps are never a difference of large numbers.
void sphereSlab(double r, double a, double b, double& V, double& M) {
  const bool mirror = a + b > 0.0;
  if (mirror) {
    const double t = a;
    a = -b;
    b = -t;
  }
  auto vol = [r](double h) { return kPi * h * h * (3.0 * r - h) / 3.0; };
  auto mom = [r](double h) { return -0.25 * kPi * h * h * (2.0 * r - h) * (2.0 * r - h); };
  const double ha = a + r, hb = b + r;
  V = vol(hb) - vol(ha);
  M = mom(hb) - mom(ha);
  if (mirror) M = -M;
}

// A ball in a box. Cut along one axis (one plane, or two parallel ones) it is the exact
// slab. Cut along several axes, the exact one-axis slabs are combined as if independent
// (the product of their fractions, the sum of their centroid offsets), and the error of
// that product is taken out as measured on the polyhedral ball of makeCapsule(r, 0):
//   V = V_product + (V_poly(box) - V_poly,product),
// likewise for the first moment. The correction vanishes as the second axis stops
// cutting, so V and the centroid stay continuous; its error is the polyhedron's.
SubmergedPart sphereInBox(double r, const Vec3& X, const Vec3& lo, const Vec3& hi) {
  const double full = 4.0 / 3.0 * kPi * r * r * r;
  const double reach = 1.1 * r;  // beyond the polyhedral ball's vertices (1.006 r)
  double fraction = 1.0;
  Vec3 offset = Vec3::Zero();
  int axes[3];
  int nCut = 0;
  for (int k = 0; k < 3; ++k) {
    if (lo[k] <= -reach && hi[k] >= reach) continue;  // the polyhedron is not cut either
    axes[nCut++] = k;
    const double a = std::max(lo[k], -r), b = std::min(hi[k], r);
    if (a <= -r && b >= r) continue;  // the ball is not cut
    double V = 0.0, M = 0.0;
    sphereSlab(r, a, b, V, M);
    if (!(V > 0.0)) return SubmergedPart{0.0, X};
    fraction *= V / full;
    offset[k] = M / V;
  }
  double volume = fraction * full;
  Vec3 moment = volume * offset;
  if (nCut >= 2) {
    Polyhedron P;
    makeCapsule(r, 0.0, Mat3::Identity(), P);
    const SubmergedPart all = clipPolyhedron(P, Vec3::Zero(), lo, hi);
    double polyFraction = 1.0;
    Vec3 polyOffset = Vec3::Zero();
    for (int c = 0; c < nCut; ++c) {
      const int k = axes[c];
      Vec3 l1 = Vec3::Constant(-2.0 * reach), h1 = Vec3::Constant(2.0 * reach);
      l1[k] = lo[k];
      h1[k] = hi[k];
      const SubmergedPart one = clipPolyhedron(P, Vec3::Zero(), l1, h1);
      if (!(one.volume > 0.0)) return SubmergedPart{0.0, X};
      polyFraction *= one.volume / full;
      polyOffset += one.centroid;
    }
    const double polyProduct = polyFraction * full;
    volume += all.volume - polyProduct;
    moment += all.volume * all.centroid - polyProduct * polyOffset;
  }
  if (!(volume > 1e-14 * full)) return SubmergedPart{0.0, X};
  SubmergedPart part;
  part.volume = std::min(volume, full);
  part.centroid = X + moment / volume;
  return part;
}

// Linear interpolation in a table of (x, y), x increasing; clamped at the ends.
double interpolate(const double (*table)[2], int n, double x) {
  if (x <= table[0][0]) return table[0][1];
  for (int i = 1; i < n; ++i)
    if (x <= table[i][0]) {
      const double t = (x - table[i - 1][0]) / (table[i][0] - table[i - 1][0]);
      return table[i - 1][1] + t * (table[i][1] - table[i - 1][1]);
    }
  return table[n - 1][1];
}

// Drag coefficients of a circular cylinder at Re ~ 1e4..1e5 (Hoerner, Fluid-Dynamic
// Drag, 1965, as tabulated in the Aeronautical Engineer Data Book, fig. 5.13):
// axial flow on the end area pi r^2, by l/d (l/d = 0 is the flat disc, 1.17);
double axialCd(double lOverD) {
  static constexpr double table[][2] = {{0.0, 1.17}, {1.0, 0.91}, {2.0, 0.85}, {4.0, 0.87}, {7.0, 0.99}};
  return interpolate(table, 5, lOverD);
}
// cross flow on the side area d l, by d/l (d/l = 0: the infinite cylinder, 1.20).
double crossCd(double dOverL) {
  static constexpr double table[][2] = {{0.0, 1.20}, {0.025, 0.98}, {0.1, 0.82}, {0.2, 0.74}, {0.5, 0.68}, {1.0, 0.63}};
  return interpolate(table, 6, dOverL);
}

constexpr double kSphereCd = 0.47;  // smooth sphere, 1e3 < Re < 2e5
constexpr double kBoxCd = 1.05;     // cube face-on; on each face's projection

}  // namespace

// ---- public pieces ----------------------------------------------------------------------

SubmergedPart submergedPart(const Shape& shape, const Vec3& X_W, const Mat3& R_WB, const Vec3& min_W,
                            const Vec3& max_W) {
  const Vec3 lo = min_W - X_W, hi = max_W - X_W;
  const double r = shape.radius, l = shape.length;
  // Bounding radius about the centre of mass (of the polyhedron, for cylinder and
  // capsule, whose scaled rings reach a little further than the solid).
  double bound = 0.0;
  switch (shape.type) {
    case ShapeType::Sphere: bound = r; break;
    case ShapeType::Box: bound = 0.5 * shape.size.norm(); break;
    case ShapeType::Cylinder: bound = std::hypot(1.1 * r, 0.5 * l); break;
    case ShapeType::Capsule: bound = 0.5 * l + 1.1 * r; break;
    case ShapeType::Mesh:
    case ShapeType::Compound: noMeshInMedia();
  }
  for (int k = 0; k < 3; ++k)
    if (hi[k] <= -bound || lo[k] >= bound) return SubmergedPart{0.0, X_W};  // outside
  if ((lo.array() <= -bound).all() && (hi.array() >= bound).all())
    return SubmergedPart{shapeVolume(shape), X_W};  // fully inside
  if (shape.type == ShapeType::Sphere) return sphereInBox(r, X_W, lo, hi);

  Polyhedron P;
  switch (shape.type) {
    case ShapeType::Box: makeBox(shape.size, R_WB, P); break;
    case ShapeType::Cylinder: makeCylinder(r, l, R_WB, P); break;
    case ShapeType::Capsule: makeCapsule(r, l, R_WB, P); break;
    case ShapeType::Sphere: break;
    case ShapeType::Mesh:
    case ShapeType::Compound: noMeshInMedia();
  }
  SubmergedPart part = clipPolyhedron(P, X_W, lo, hi);
  const double full = shapeVolume(shape);
  if (!(part.volume > 1e-14 * full)) return SubmergedPart{0.0, X_W};
  part.volume = std::min(part.volume, full);
  return part;
}

double projectedArea(const Shape& shape, const Vec3& d) {
  const double r = shape.radius, l = shape.length;
  const double axial = std::abs(d.z());
  const double side = std::sqrt(std::max(0.0, 1.0 - d.z() * d.z()));
  switch (shape.type) {
    case ShapeType::Sphere: return kPi * r * r;
    case ShapeType::Box: {
      const Vec3& s = shape.size;
      return std::abs(d.x()) * s.y() * s.z() + std::abs(d.y()) * s.x() * s.z() + std::abs(d.z()) * s.x() * s.y();
    }
    case ShapeType::Cylinder: return kPi * r * r * axial + 2.0 * r * l * side;
    case ShapeType::Capsule: return kPi * r * r + 2.0 * r * l * side;
    case ShapeType::Mesh:
    case ShapeType::Compound: noMeshInMedia();
  }
  return 0.0;
}

double surfaceArea(const Shape& shape) {
  const double r = shape.radius, l = shape.length;
  switch (shape.type) {
    case ShapeType::Sphere: return 4.0 * kPi * r * r;
    case ShapeType::Box: {
      const Vec3& s = shape.size;
      return 2.0 * (s.x() * s.y() + s.y() * s.z() + s.x() * s.z());
    }
    case ShapeType::Cylinder: return 2.0 * kPi * r * r + 2.0 * kPi * r * l;
    case ShapeType::Capsule: return 4.0 * kPi * r * r + 2.0 * kPi * r * l;
    case ShapeType::Mesh:
    case ShapeType::Compound: noMeshInMedia();
  }
  return 0.0;
}

double dragArea(const Shape& shape, const Vec3& d) {
  const double r = shape.radius, l = shape.length;
  const double axial = std::abs(d.z());
  const double side = std::sqrt(std::max(0.0, 1.0 - d.z() * d.z()));
  switch (shape.type) {
    case ShapeType::Sphere: return kSphereCd * kPi * r * r;
    case ShapeType::Box: return kBoxCd * projectedArea(shape, d);
    case ShapeType::Cylinder:
      return axialCd(l / (2.0 * r)) * kPi * r * r * axial + crossCd(2.0 * r / std::max(l, 1e-300)) * 2.0 * r * l * side;
    case ShapeType::Capsule:
      return kSphereCd * kPi * r * r + crossCd(2.0 * r / std::max(l, 1e-300)) * 2.0 * r * l * side;
    case ShapeType::Mesh:
    case ShapeType::Compound: noMeshInMedia();
  }
  return 0.0;
}

double stokesFactor(const Shape& shape, const Vec3& d) {
  const double rn = std::sqrt(projectedArea(shape, d) / kPi);     // projected-area radius
  const double rs = std::sqrt(surfaceArea(shape) / (4.0 * kPi));  // surface-area radius
  return 6.0 * kPi * (rn / 3.0 + 2.0 * rs / 3.0);
}

double rotationalStokesFactor(const Shape& shape) {
  const double rs = std::sqrt(surfaceArea(shape) / (4.0 * kPi));
  return 8.0 * kPi * rs * rs * rs;
}

Vec3 pressureTorqueFactor(const Shape& shape) {
  const double r = shape.radius, l = shape.length;
  switch (shape.type) {
    case ShapeType::Sphere: return Vec3::Zero();
    case ShapeType::Box: {
      // About axis k: the faces normal to k1 and k2 as flat strips, the element at s
      // from the axis moving at omega s: 1/2 Cd l_k ((l_k1/2)^4 + (l_k2/2)^4).
      const Vec3 h4 = (0.5 * shape.size).array().pow(4.0).matrix();
      Vec3 k2;
      for (int k = 0; k < 3; ++k) k2[k] = 0.5 * kBoxCd * shape.size[k] * (h4[(k + 1) % 3] + h4[(k + 2) % 3]);
      return k2;
    }
    case ShapeType::Cylinder: {
      // About a transverse axis: the side as a strip of width 2r, 1/2 Cd_cross r (l/2)^4,
      // and the two flat ends, 1/2 Cd_axial 16 r^5 / 15. About its own axis: none.
      const double t = 0.5 * (crossCd(2.0 * r / std::max(l, 1e-300)) * r * std::pow(0.5 * l, 4) +
                              axialCd(l / (2.0 * r)) * 16.0 / 15.0 * std::pow(r, 5));
      return Vec3(t, t, 0.0);
    }
    case ShapeType::Capsule: {
      // The cylinder part's side only; the rounded ends, like a sphere, add none.
      const double t = 0.5 * crossCd(2.0 * r / std::max(l, 1e-300)) * r * std::pow(0.5 * l, 4);
      return Vec3(t, t, 0.0);
    }
    case ShapeType::Mesh:
    case ShapeType::Compound: noMeshInMedia();
  }
  return Vec3::Zero();
}

// ---- the force stage's medium term -------------------------------------------------------

void addMediumForces(const Medium& medium, const BodyConstants& body, const BodyState& y, const Vec3& gravity,
                     BodyAux& aux) {
  if (!(medium.density > 0.0) && !(medium.viscosity > 0.0)) return;
  const SubmergedPart part = submergedPart(body.shape, y.X, aux.R, medium.min, medium.max);
  if (!(part.volume > 0.0)) return;
  const double rho = medium.density, mu = medium.viscosity;
  const double fraction = std::min(1.0, part.volume / shapeVolume(body.shape));
  const Vec3 r_W = part.centroid - y.X;  // centre of mass -> centre of buoyancy

  // Archimedes: the weight of the displaced fluid, upward, at the centre of buoyancy.
  Vec3 F = -rho * part.volume * gravity;

  // Translational drag at the centre of buoyancy, from the velocity of that point of the
  // body relative to the fluid at rest: linear (Stokes) and quadratic (pressure), scaled
  // by the submerged fraction. F . v <= 0: it never gives energy.
  const Vec3 v = aux.V + aux.omega.cross(r_W);
  const double speed = v.norm();
  if (speed > 0.0) {
    const Vec3 d_B = aux.R.transpose() * (v / speed);
    const double c = mu * stokesFactor(body.shape, d_B) + 0.5 * rho * dragArea(body.shape, d_B) * speed;
    F -= fraction * c * v;
  }
  aux.F += F;
  aux.T += r_W.cross(F);

  // Angular drag about the centre of mass, per body axis: -(k1 + k2_i |omega|) omega_i.
  const double w = aux.omega.norm();
  if (w > 0.0) {
    const Vec3 w_B = aux.R.transpose() * aux.omega;
    const Vec3 k = Vec3::Constant(mu * rotationalStokesFactor(body.shape)) + rho * w * pressureTorqueFactor(body.shape);
    aux.T -= fraction * (aux.R * k.cwiseProduct(w_B));
  }
}

}  // namespace rigid

namespace rigid {

MediumRates mediumRates(const Medium& medium, const BodyConstants& body, const BodyState& y, const BodyAux& aux,
                        const Vec3& gravity) {
  MediumRates rates;
  const SubmergedPart part = submergedPart(body.shape, y.X, aux.R, medium.min, medium.max);
  if (!(part.volume > 0.0)) return rates;
  const double rho = medium.density, mu = medium.viscosity;
  const double volume = shapeVolume(body.shape);
  const double fraction = std::min(1.0, part.volume / volume);
  // Translational damping: the largest rate of the drag's velocity Jacobian, Stokes
  // along the worst body axis plus the pressure drag's d(|v| v)/dv = 2 |v| bound.
  double stokes = 0.0, area = 0.0;
  for (int i = 0; i < 3; ++i) {
    stokes = std::max(stokes, stokesFactor(body.shape, Vec3::Unit(i)));
    area = std::max(area, dragArea(body.shape, Vec3::Unit(i)));
  }
  const double speed = aux.V.norm() + aux.omega.norm() * std::cbrt(volume);
  rates.damping = fraction * (mu * stokes + rho * area * speed) / body.mass;
  const double angular =
      mu * rotationalStokesFactor(body.shape) + rho * aux.omega.norm() * pressureTorqueFactor(body.shape).maxCoeff();
  rates.damping = std::max(rates.damping, fraction * angular / body.principalMoments.minCoeff());
  // Heave: buoyancy's restoring rate sqrt(rho |g| A_wp / m), with the waterplane area
  // A_wp = dV_sub/d(depth) by a central difference along gravity.
  const double g = gravity.norm();
  if (g > 0.0 && rho > 0.0 && part.volume < volume) {
    const Vec3 down = gravity / g;
    const double delta = 1e-4 * std::cbrt(volume);
    const double deeper = submergedPart(body.shape, y.X + delta * down, aux.R, medium.min, medium.max).volume;
    const double higher = submergedPart(body.shape, y.X - delta * down, aux.R, medium.min, medium.max).volume;
    const double waterplane = std::max(0.0, (deeper - higher) / (2.0 * delta));
    rates.oscillation = std::sqrt(rho * g * waterplane / body.mass);
  }
  return rates;
}

}  // namespace rigid
