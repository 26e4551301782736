// Mass properties of closed triangle meshes and of compounds (src/solid_mass.h), against
// closed forms: a box, Tonon's tetrahedron, tessellated spheres and cylinders between
// their inscribed and circumscribed solids, and an L-shaped prism as one mesh and as two
// boxes.
#include "solid_mass.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

namespace {

using rigid::Mat3;
using rigid::Quat;
using rigid::SolidMass;
using rigid::Vec3;
using Triangles = std::vector<std::array<int, 3>>;

constexpr double kPi = 3.14159265358979323846;

struct Mesh {
  std::vector<Vec3> vertices;
  Triangles triangles;
};

// A quad a b c d, counter-clockwise from outside, as two triangles.
void quad(Triangles& t, int a, int b, int c, int d) {
  t.push_back({a, b, c});
  t.push_back({a, c, d});
}

// A box of edges `size` centred at `centre`, its faces outward.
Mesh boxMesh(const Vec3& size, const Vec3& centre) {
  Mesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.push_back(
        centre + 0.5 * Vec3((k & 1 ? 1 : -1) * size.x(), (k & 2 ? 1 : -1) * size.y(), (k & 4 ? 1 : -1) * size.z()));
  quad(m.triangles, 0, 2, 3, 1);  // -z
  quad(m.triangles, 4, 5, 7, 6);  // +z
  quad(m.triangles, 0, 1, 5, 4);  // -y
  quad(m.triangles, 2, 6, 7, 3);  // +y
  quad(m.triangles, 0, 4, 6, 2);  // -x
  quad(m.triangles, 1, 3, 7, 5);  // +x
  return m;
}

SolidMass of(const Mesh& m) { return rigid::meshSolidMass(m.vertices, m.triangles); }

void expectNear(const Mat3& a, const Mat3& b, double tolerance) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a(r, c), b(r, c), tolerance) << "(" << r << ", " << c << ")";
}

// A unit sphere's triangles: an octahedron subdivided `levels` times, pushed out to R.
Mesh sphereMesh(double R, int levels) {
  Mesh m;
  m.vertices = {Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int level = 0; level < levels; ++level) {
    Triangles finer;
    for (const auto& t : m.triangles) {
      int mid[3];
      for (int k = 0; k < 3; ++k) {
        m.vertices.push_back((m.vertices[t[k]] + m.vertices[t[(k + 1) % 3]]).normalized());
        mid[k] = static_cast<int>(m.vertices.size()) - 1;
      }
      finer.push_back({t[0], mid[0], mid[2]});
      finer.push_back({mid[0], t[1], mid[1]});
      finer.push_back({mid[2], mid[1], t[2]});
      finer.push_back({mid[0], mid[1], mid[2]});
    }
    m.triangles = finer;
  }
  for (Vec3& v : m.vertices) v *= R;
  return m;
}

// The least distance from the origin to the planes of the triangles: the radius of the
// ball about the origin that a convex mesh holds.
double inscribedRadius(const Mesh& m) {
  double r = INFINITY;
  for (const auto& t : m.triangles) {
    const Vec3 n = (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).normalized();
    r = std::min(r, n.dot(m.vertices[t[0]]));
  }
  return r;
}

// A prism of `sides` on a circle of radius R, from z = -L/2 to L/2, its caps fanned.
Mesh prismMesh(double R, double L, int sides) {
  Mesh m;
  for (int k = 0; k < sides; ++k) {
    const double a = 2 * kPi * k / sides;
    m.vertices.push_back(Vec3(R * std::cos(a), R * std::sin(a), -L / 2));
    m.vertices.push_back(Vec3(R * std::cos(a), R * std::sin(a), L / 2));
  }
  m.vertices.push_back(Vec3(0, 0, -L / 2));
  m.vertices.push_back(Vec3(0, 0, L / 2));
  const int bottom = 2 * sides, top = bottom + 1;
  for (int k = 0; k < sides; ++k) {
    const int j = (k + 1) % sides;
    quad(m.triangles, 2 * k, 2 * j, 2 * j + 1, 2 * k + 1);
    m.triangles.push_back({bottom, 2 * j, 2 * k});
    m.triangles.push_back({top, 2 * k + 1, 2 * j + 1});
  }
  return m;
}

}  // namespace

// Far from the file's origin, as CAD parts often are: exact to rounding.
TEST(SolidMass, ABoxIsExact) {
  const Vec3 size(1, 2, 3), centre(10, -20, 30);
  const SolidMass s = of(boxMesh(size, centre));
  const double V = 6.0;
  EXPECT_NEAR(s.volume, V, 1e-12 * V);
  EXPECT_NEAR((s.centre - centre).norm(), 0.0, 1e-12 * centre.norm());
  const Mat3 expected = (V / 12.0 * Vec3(4 + 9, 1 + 9, 1 + 4)).asDiagonal();
  expectNear(s.inertia, expected, 1e-12 * expected.norm());
}

// Tonon (2004), "Explicit exact formulas for the 3-D tetrahedron inertia tensor in
// terms of its vertex coordinates": with coordinates from the centroid and |det J| = 6 V.
TEST(SolidMass, ATetrahedronMatchesTononsClosedForm) {
  const std::vector<Vec3> p = {Vec3(8.33220, -11.86875, 0.93355), Vec3(0.75523, 5.00000, 16.37072),
                               Vec3(52.61236, 5.00000, -5.38580), Vec3(2.00000, 5.00000, 3.00000)};
  const Mesh m{p, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}};
  const SolidMass s = of(m);
  const Vec3 centroid = (p[0] + p[1] + p[2] + p[3]) / 4.0;
  const double det = std::abs((p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]));
  EXPECT_NEAR(s.volume, det / 6.0, 1e-12 * det);
  EXPECT_NEAR((s.centre - centroid).norm(), 0.0, 1e-12 * centroid.norm());
  std::array<Vec3, 4> q;
  for (int i = 0; i < 4; ++i) q[i] = p[i] - centroid;
  auto square = [&](int k) {  // sum over i <= j of q_i[k] q_j[k]
    double sum = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int j = i; j < 4; ++j) sum += q[i][k] * q[j][k];
    return sum;
  };
  auto product = [&](int k, int l) {  // sum over i, j of (1 + [i == j]) q_i[k] q_j[l]
    double sum = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) sum += (i == j ? 2.0 : 1.0) * q[i][k] * q[j][l];
    return sum;
  };
  const double a = det * (square(1) + square(2)) / 60.0, b = det * (square(0) + square(2)) / 60.0,
               c = det * (square(0) + square(1)) / 60.0;
  const double a2 = det * product(1, 2) / 120.0, b2 = det * product(0, 2) / 120.0, c2 = det * product(0, 1) / 120.0;
  Mat3 tonon;
  tonon << a, -c2, -b2, -c2, b, -a2, -b2, -a2, c;
  expectNear(s.inertia, tonon, 1e-12 * tonon.norm());
  // and the figures Tonon's paper gives for this tetrahedron (density 1), to what its
  // vertices' five decimals allow (half a unit of the last digit moves them by ~1e-7)
  Mat3 published;
  published << 43520.33257, -11996.20119, 46343.16662, -11996.20119, 194711.28938, -4417.66150, 46343.16662,
      -4417.66150, 191168.76173;
  expectNear(s.inertia, published, 1e-6 * published.norm());
}

// A tessellated sphere (its vertices on the sphere, star-shaped about the centre) lies
// between the balls of its least face distance r and of its radius R: its volume and
// moments lie between theirs (4/3 pi r^3, 8/15 pi r^5), which close on the sphere's as
// the tessellation refines (r within 0.1 % of R at 8192 triangles).
TEST(SolidMass, ATessellatedSphereLiesBetweenItsInscribedAndCircumscribedBalls) {
  const double R = 0.3;
  const Mesh m = sphereMesh(R, 5);
  const SolidMass s = of(m);
  const double r = inscribedRadius(m);
  EXPECT_GT(r, 0.999 * R);
  EXPECT_GT(s.volume, 4.0 / 3.0 * kPi * std::pow(r, 3));
  EXPECT_LT(s.volume, 4.0 / 3.0 * kPi * std::pow(R, 3));
  EXPECT_NEAR(s.centre.norm(), 0.0, 1e-15);
  for (int k = 0; k < 3; ++k) {
    EXPECT_GT(s.inertia(k, k), 8.0 / 15.0 * kPi * std::pow(r, 5));
    EXPECT_LT(s.inertia(k, k), 8.0 / 15.0 * kPi * std::pow(R, 5));
    EXPECT_NEAR(s.inertia(k, (k + 1) % 3), 0.0, 1e-15);
  }
}

// A prism of 512 sides holds the cylinder of its apothem and lies in the one of its
// radius: volume and moments between theirs (pi r^2 L; about z pi r^4 L / 2, about x
// pi r^2 L (3 r^2 + L^2) / 12).
TEST(SolidMass, ATessellatedCylinderLiesBetweenItsInscribedAndCircumscribedCylinders) {
  const double R = 0.2, L = 0.5;
  const int sides = 512;
  const SolidMass s = of(prismMesh(R, L, sides));
  const double r = R * std::cos(kPi / sides);
  auto volume = [&](double x) { return kPi * x * x * L; };
  EXPECT_GT(s.volume, volume(r));
  EXPECT_LT(s.volume, volume(R));
  EXPECT_GT(s.inertia(2, 2), volume(r) * r * r / 2);
  EXPECT_LT(s.inertia(2, 2), volume(R) * R * R / 2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_GT(s.inertia(k, k), volume(r) * (3 * r * r + L * L) / 12);
    EXPECT_LT(s.inertia(k, k), volume(R) * (3 * R * R + L * L) / 12);
  }
  EXPECT_NEAR(s.centre.norm(), 0.0, 1e-15);
}

TEST(SolidMass, AMeshTurnedInsideOutHasANegativeVolume) {
  Mesh m = boxMesh(Vec3(1, 1, 1), Vec3::Zero());
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  EXPECT_NEAR(of(m).volume, -1.0, 1e-15);
}

// An L of two boxes (1 x 0.2 and 0.2 x 0.8, depth 0.3), as one closed mesh of the L
// prism and as the compound of the two box meshes: the same mass, centre and inertia
// (1e-12), the centre where the areas' moments put it.
TEST(SolidMass, AnLShapedCompoundIsTheParallelAxisSumOfItsParts) {
  const double density = 7800.0, depth = 0.3;
  const SolidMass foot = of(boxMesh(Vec3(1.0, 0.2, depth), Vec3::Zero()));
  const SolidMass upright = of(boxMesh(Vec3(0.2, 0.8, depth), Vec3::Zero()));
  const rigid::PartMass compound =
      rigid::combineParts({rigid::placePart(foot, density, Vec3(0.5, 0.1, 0), Quat::Identity()),
                           rigid::placePart(upright, density, Vec3(0.1, 0.6, 0), Quat::Identity())});
  // the L's outline in the xy plane, counter-clockwise, extruded over z in [-depth/2, depth/2]
  const std::vector<Vec3> outline = {Vec3(0, 0, 0),     Vec3(1, 0, 0),   Vec3(1, 0.2, 0),
                                     Vec3(0.2, 0.2, 0), Vec3(0.2, 1, 0), Vec3(0, 1, 0)};
  Mesh l;
  for (const Vec3& v : outline) {
    l.vertices.push_back(v - Vec3(0, 0, depth / 2));
    l.vertices.push_back(v + Vec3(0, 0, depth / 2));
  }
  for (int k = 0; k < 6; ++k) quad(l.triangles, 2 * k, 2 * ((k + 1) % 6), 2 * ((k + 1) % 6) + 1, 2 * k + 1);
  for (const std::array<int, 3>& cap : {std::array<int, 3>{0, 3, 1}, {1, 3, 2}, {0, 4, 3}, {0, 5, 4}}) {
    l.triangles.push_back({2 * cap[0], 2 * cap[1], 2 * cap[2]});              // bottom, seen from below
    l.triangles.push_back({2 * cap[0] + 1, 2 * cap[2] + 1, 2 * cap[1] + 1});  // top
  }
  const SolidMass whole = of(l);
  const double area = 1.0 * 0.2 + 0.2 * 0.8;
  EXPECT_NEAR(compound.mass, density * area * depth, 1e-12 * compound.mass);
  EXPECT_NEAR(density * whole.volume, compound.mass, 1e-12 * compound.mass);
  const Vec3 centre((0.2 * 0.5 + 0.16 * 0.1) / area, (0.2 * 0.1 + 0.16 * 0.6) / area, 0.0);
  EXPECT_NEAR((compound.centre - centre).norm(), 0.0, 1e-12);
  EXPECT_NEAR((whole.centre - centre).norm(), 0.0, 1e-12);
  expectNear(compound.inertia, density * whole.inertia, 1e-12 * compound.inertia.norm());
}

// A part turned a quarter about z swaps its moments about x and y.
TEST(SolidMass, APlacedPartsInertiaTurnsWithIt) {
  const SolidMass bar = of(boxMesh(Vec3(1.0, 0.1, 0.1), Vec3::Zero()));
  const rigid::PartMass turned =
      rigid::placePart(bar, 2.0, Vec3(1, 2, 3), Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ())));
  EXPECT_NEAR(turned.inertia(0, 0), 2.0 * bar.inertia(1, 1), 1e-15);
  EXPECT_NEAR(turned.inertia(1, 1), 2.0 * bar.inertia(0, 0), 1e-15);
  EXPECT_NEAR((turned.centre - Vec3(1, 2, 3)).norm(), 0.0, 1e-15);
}

// What a file's mesh must be before it is measured: each fault named with its place.
TEST(SolidMass, AMeshThatBoundsNoSolidIsRefusedWithItsFault) {
  const Mesh box = boxMesh(Vec3(1, 1, 1), Vec3::Zero());
  EXPECT_EQ(rigid::meshFault(box.vertices, box.triangles), "");
  Mesh open = box;  // the last triangle {1, 7, 5} gone: its neighbours' edges 1->5, 5->7, 7->1 unmatched
  open.triangles.pop_back();
  EXPECT_EQ(rigid::meshFault(open.vertices, open.triangles),
            "the edge from vertex 1 to 5 of triangle 4 borders no other triangle: the mesh is open");
  Mesh flipped = box;  // {4, 7, 6} wound {4, 6, 7}: its edge 7->4 is also triangle 2's {4, 5, 7}
  std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
  EXPECT_EQ(rigid::meshFault(flipped.vertices, flipped.triangles),
            "the edge from vertex 7 to 4 of triangle 3 runs the same way in triangle 2 (the triangles are not wound "
            "alike, or more than two share it)");
  Mesh insideOut = box;
  for (auto& t : insideOut.triangles) std::swap(t[1], t[2]);
  EXPECT_EQ(rigid::meshFault(insideOut.vertices, insideOut.triangles),
            "the mesh is inside out (its triangles wound clockwise seen from outside)");
  Mesh flat = box;
  flat.vertices.push_back(0.5 * (box.vertices[0] + box.vertices[1]));
  flat.triangles[0] = {0, 8, 1};
  EXPECT_EQ(rigid::meshFault(flat.vertices, flat.triangles), "triangle 0 has no area (its vertices are on one line)");
  Mesh beyond = box;
  beyond.triangles[5] = {0, 1, 8};
  EXPECT_EQ(rigid::meshFault(beyond.vertices, beyond.triangles), "triangle 5 names vertex 8 of 8");
  Mesh twice = box;
  twice.triangles[2] = {0, 0, 1};
  EXPECT_EQ(rigid::meshFault(twice.vertices, twice.triangles), "triangle 2 names a vertex twice");
  Mesh nan = box;
  nan.vertices[6].y() = std::nan("");
  EXPECT_EQ(rigid::meshFault(nan.vertices, nan.triangles), "vertex 6 is not finite");
  EXPECT_EQ(rigid::meshFault(box.vertices, Triangles(box.triangles.begin(), box.triangles.begin() + 3)),
            "a closed mesh has at least 4 triangles, got 3");
}
