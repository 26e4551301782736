// Collision detection: contacts of body pairs and body-surface pairs against the
// geometry worked out here (overlaps, normals, depths and the corners of the contact
// patches), with explicit tolerances.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include "collision_detection.h"
#include "world.h"

namespace {

using rigid::Contact;
using rigid::Mat3;
using rigid::Quat;
using rigid::Vec3;

constexpr double kPi = 3.14159265358979323846;
// Exact (clipping, closed-form) contacts: only rounding differs.
constexpr double kExact = 1e-9;
// Contacts from FCL's GJK/EPA (libccd) or GJK distance: its tolerances.
constexpr double kGjk = 1e-5;

rigid::BodyConstants body(rigid::ShapeType type, double radius, const Vec3& size, double length) {
  rigid::BodyConstants b;
  b.shape.type = type;
  b.shape.radius = radius;
  b.shape.size = size;
  b.shape.length = length;
  return b;
}
rigid::BodyConstants sphere(double r) { return body(rigid::ShapeType::Sphere, r, Vec3::Zero(), 0.0); }
rigid::BodyConstants box(const Vec3& size) { return body(rigid::ShapeType::Box, 0.0, size, 0.0); }
rigid::BodyConstants cylinder(double r, double l) { return body(rigid::ShapeType::Cylinder, r, Vec3::Zero(), l); }
rigid::BodyConstants capsule(double r, double l) { return body(rigid::ShapeType::Capsule, r, Vec3::Zero(), l); }

rigid::Surface surface(const Vec3& min, const Vec3& max, const Quat& q = Quat::Identity()) {
  rigid::Surface s;
  s.name = "s";
  s.min = min;
  s.max = max;
  s.orientation = q;
  rigid::finishSurface(s);
  return s;
}
// Top face at z = 0, from -5 to 5 in x and y.
rigid::Surface floorSurface() { return surface(Vec3(-5, -5, -1), Vec3(5, 5, 0)); }

rigid::BodyState pose(const Vec3& X, const Quat& q = Quat::Identity()) {
  rigid::BodyState y;
  y.X = X;
  y.q = q;
  return y;
}

Quat about(const Vec3& axis, double angle) { return Quat(Eigen::AngleAxisd(angle, axis.normalized())); }

std::vector<Contact> detect(const rigid::WorldModel& m, const std::vector<rigid::BodyState>& Y, double margin = 0.0,
                            std::vector<bool> collides = {}) {
  if (collides.empty()) collides.assign(m.bodies.size(), true);
  rigid::CollisionDetector detector(m, collides);
  std::vector<Contact> out;
  detector.detect(Y, margin, out);
  return out;
}

// Corners of a box's face with outward normal -z of the body (its bottom), world frame.
std::vector<Vec3> bottomCorners(const Vec3& size, const rigid::BodyState& y) {
  std::vector<Vec3> c;
  const Mat3 R = y.q.toRotationMatrix();
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0}) c.push_back(y.X + R * Vec3(sx * size.x(), sy * size.y(), -size.z()) * 0.5);
  return c;
}

// Every expected point has a contact point within tol, and every contact an expected point.
void expectSamePoints(const std::vector<Vec3>& expected, const std::vector<Contact>& contacts, double tol) {
  for (const Vec3& e : expected) {
    double best = 1e300;
    for (const Contact& c : contacts) best = std::min(best, (c.point - e).norm());
    EXPECT_LT(best, tol) << "no contact at " << e.transpose();
  }
  for (const Contact& c : contacts) {
    double best = 1e300;
    for (const Vec3& e : expected) best = std::min(best, (c.point - e).norm());
    EXPECT_LT(best, tol) << "unexpected contact at " << c.point.transpose();
  }
}

}  // namespace

TEST(CollisionDetection, OverlappingSpheresAlongAnArbitraryDirection) {
  rigid::WorldModel m;
  m.bodies = {sphere(0.2), sphere(0.5)};
  const Vec3 dir = Vec3(1.0, 2.0, -0.5).normalized();
  const double d = 0.01;
  const Vec3 c0(0.1, -0.2, 0.3);
  const Vec3 c1 = c0 + dir * (0.2 + 0.5 - d);
  const std::vector<Contact> out = detect(m, {pose(c0), pose(c1)});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].a, 0);
  EXPECT_EQ(out[0].b, 1);
  EXPECT_EQ(out[0].surface, -1);
  EXPECT_NEAR((out[0].normal - dir).norm(), 0.0, kExact);
  EXPECT_NEAR(out[0].depth, d, kExact);
  // Midway in the overlap: the overlap runs from c0 + (0.2 - d) dir to c0 + 0.2 dir.
  EXPECT_NEAR((out[0].point - (c0 + dir * (0.2 - 0.5 * d))).norm(), 0.0, kExact);
}

TEST(CollisionDetection, SwappedBodiesGiveTheNormalFromTheNewAToTheNewB) {
  rigid::WorldModel m;
  m.bodies = {sphere(0.5), sphere(0.2)};  // the previous test's bodies, swapped
  const Vec3 dir = Vec3(1.0, 2.0, -0.5).normalized();
  const double d = 0.01;
  const Vec3 c0(0.1, -0.2, 0.3);
  const Vec3 c1 = c0 + dir * (0.2 + 0.5 - d);
  const std::vector<Contact> out = detect(m, {pose(c1), pose(c0)});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].a, 0);
  EXPECT_EQ(out[0].b, 1);
  EXPECT_NEAR((out[0].normal + dir).norm(), 0.0, kExact);  // from body 0 (at c1) to body 1 (at c0)
  EXPECT_NEAR(out[0].depth, d, kExact);
  EXPECT_NEAR((out[0].point - (c0 + dir * (0.2 - 0.5 * d))).norm(), 0.0, kExact);
}

TEST(CollisionDetection, SpheresApartGiveNothingOrAGapWithinTheMargin) {
  rigid::WorldModel m;
  m.bodies = {sphere(0.3), sphere(0.3)};
  const Vec3 dir = Vec3(-0.3, 0.4, 1.2).normalized();
  const double gap = 0.05;
  const Vec3 c0(1.0, 2.0, 3.0);
  const Vec3 c1 = c0 + dir * (0.6 + gap);
  const std::vector<rigid::BodyState> Y = {pose(c0), pose(c1)};
  EXPECT_TRUE(detect(m, Y).empty());
  EXPECT_TRUE(detect(m, Y, 0.04).empty());
  const std::vector<Contact> out = detect(m, Y, 0.1);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].depth, -gap, kGjk);
  EXPECT_NEAR((out[0].normal - dir).norm(), 0.0, kGjk);
  EXPECT_NEAR((out[0].point - (c0 + dir * (0.3 + 0.5 * gap))).norm(), 0.0, kGjk);  // midway in the gap
}

TEST(CollisionDetection, SphereOnTheFloorPointsIntoTheSurface) {
  rigid::WorldModel m;
  m.bodies = {sphere(0.1)};
  m.surfaces = {floorSurface()};
  const double d = 0.002;
  const std::vector<Contact> out = detect(m, {pose(Vec3(0.4, -0.3, 0.1 - d))});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].a, 0);
  EXPECT_EQ(out[0].b, -1);
  EXPECT_EQ(out[0].surface, 0);
  EXPECT_NEAR((out[0].normal - Vec3(0, 0, -1)).norm(), 0.0, kExact);  // from the body into the surface
  EXPECT_NEAR(out[0].depth, d, kExact);
  EXPECT_NEAR((out[0].point - Vec3(0.4, -0.3, -0.5 * d)).norm(), 0.0, kExact);
}

TEST(CollisionDetection, SphereOnARamp) {
  rigid::WorldModel m;
  m.bodies = {sphere(0.1)};
  const Quat turn = about(Vec3(0.3, 1.0, 0.0), kPi / 6.0);  // a 30 deg ramp, turned about its centre
  m.surfaces = {surface(Vec3(-2, -1, -0.5), Vec3(2, 1, 0), turn)};
  const Mat3 R = turn.toRotationMatrix();
  const Vec3 nOut = R.col(2);                                         // the top face's outward normal
  const Vec3 onFace = Vec3(0, 0, -0.25) + R * Vec3(0.7, -0.2, 0.25);  // a point of the top face
  const double d = 0.003;
  const std::vector<Contact> out = detect(m, {pose(onFace + nOut * (0.1 - d))});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].surface, 0);
  EXPECT_NEAR((out[0].normal + nOut).norm(), 0.0, kExact);
  EXPECT_NEAR(out[0].depth, d, kExact);
  EXPECT_NEAR((out[0].point - (onFace - nOut * (0.5 * d))).norm(), 0.0, kExact);
}

TEST(CollisionDetection, BoxFlatOnTheFloorGivesItsFourBottomCorners) {
  rigid::WorldModel m;
  const Vec3 size(0.4, 0.3, 0.2);
  m.bodies = {box(size)};
  m.surfaces = {floorSurface()};
  const double d = 0.001;
  const rigid::BodyState y = pose(Vec3(0.5, 0.2, 0.1 - d), about(Vec3::UnitZ(), 0.3));
  const std::vector<Contact> out = detect(m, {y});
  ASSERT_GE(out.size(), 4u);
  for (const Contact& c : out) {
    EXPECT_EQ(c.surface, 0);
    EXPECT_NEAR((c.normal - Vec3(0, 0, -1)).norm(), 0.0, kExact);
    EXPECT_NEAR(c.depth, d, kExact);
  }
  std::vector<Vec3> corners = bottomCorners(size, y);
  for (Vec3& c : corners) c.z() += 0.5 * d;  // midway between the corner and the face
  expectSamePoints(corners, out, kExact);
}

TEST(CollisionDetection, BoxAboveTheFloorWithinTheMarginGivesItsCornersWithTheGap) {
  rigid::WorldModel m;
  const Vec3 size(0.4, 0.3, 0.2);
  m.bodies = {box(size)};
  m.surfaces = {floorSurface()};
  const double gap = 0.002;
  const rigid::BodyState y = pose(Vec3(-0.5, 0.2, 0.1 + gap), about(Vec3::UnitZ(), -0.7));
  EXPECT_TRUE(detect(m, {y}).empty());
  EXPECT_TRUE(detect(m, {y}, 0.001).empty());
  const std::vector<Contact> out = detect(m, {y}, 0.005);
  ASSERT_EQ(out.size(), 4u);
  for (const Contact& c : out) {
    EXPECT_NEAR((c.normal - Vec3(0, 0, -1)).norm(), 0.0, kExact);
    EXPECT_NEAR(c.depth, -gap, kExact);
  }
  std::vector<Vec3> corners = bottomCorners(size, y);
  for (Vec3& c : corners) c.z() -= 0.5 * gap;
  expectSamePoints(corners, out, kExact);
}

TEST(CollisionDetection, BoxTouchingTheFloorExactlyIsAContactOfDepthZero) {
  rigid::WorldModel m;
  const Vec3 size(0.2, 0.2, 0.2);
  m.bodies = {box(size)};
  m.surfaces = {floorSurface()};
  const rigid::BodyState y = pose(Vec3(0.0, 0.0, 0.1));
  for (double margin : {0.0, 0.01}) {
    const std::vector<Contact> out = detect(m, {y}, margin);
    ASSERT_EQ(out.size(), 4u) << "margin " << margin;
    for (const Contact& c : out) EXPECT_NEAR(c.depth, 0.0, kExact);
    expectSamePoints(bottomCorners(size, y), out, kExact);
  }
}

TEST(CollisionDetection, BoxOnARampLiesOnItsFace) {
  rigid::WorldModel m;
  const Vec3 size(0.3, 0.3, 0.1);
  m.bodies = {box(size)};
  const Quat turn = about(Vec3::UnitY(), kPi / 6.0);
  m.surfaces = {surface(Vec3(-2, -1, -0.5), Vec3(2, 1, 0), turn)};
  const Mat3 R = turn.toRotationMatrix();
  const Vec3 nOut = R.col(2);
  const double d = 0.0005;
  const Vec3 onFace = Vec3(0, 0, -0.25) + R * Vec3(0.3, 0.1, 0.25);
  const rigid::BodyState y = pose(onFace + nOut * (0.05 - d), turn * about(Vec3::UnitZ(), 0.2));
  const std::vector<Contact> out = detect(m, {y});
  ASSERT_EQ(out.size(), 4u);
  for (const Contact& c : out) {
    EXPECT_NEAR((c.normal + nOut).norm(), 0.0, kExact);
    EXPECT_NEAR(c.depth, d, kExact);
  }
  std::vector<Vec3> corners = bottomCorners(size, y);
  for (Vec3& c : corners) c += nOut * (0.5 * d);
  expectSamePoints(corners, out, kExact);
}

TEST(CollisionDetection, BoxOnBoxGivesTheCornersOfTheFacePatch) {
  rigid::WorldModel m;
  m.bodies = {box(Vec3(1, 1, 1)), box(Vec3(0.5, 0.5, 0.5))};
  const double d = 0.01;
  // The small box wholly on the big one's top face, turned: its four bottom corners.
  const rigid::BodyState lower = pose(Vec3(0, 0, 0));
  const rigid::BodyState upper = pose(Vec3(0.1, 0.05, 0.75 - d), about(Vec3::UnitZ(), 0.4));
  std::vector<Contact> out = detect(m, {lower, upper});
  ASSERT_EQ(out.size(), 4u);
  for (const Contact& c : out) {
    EXPECT_EQ(c.a, 0);
    EXPECT_EQ(c.b, 1);
    EXPECT_NEAR((c.normal - Vec3(0, 0, 1)).norm(), 0.0, kExact);  // from the lower box (a) up to b
    EXPECT_NEAR(c.depth, d, kExact);
  }
  std::vector<Vec3> corners = bottomCorners(Vec3(0.5, 0.5, 0.5), upper);
  for (Vec3& c : corners) c.z() += 0.5 * d;
  expectSamePoints(corners, out, kExact);

  // Equal boxes, the upper one hanging over the edge: the corners of the overlap
  // x in [0.2, 0.5], y in [-0.5, 0.5].
  m.bodies = {box(Vec3(1, 1, 1)), box(Vec3(1, 1, 1))};
  out = detect(m, {lower, pose(Vec3(0.7, 0, 1 - d))});
  ASSERT_EQ(out.size(), 4u);
  for (const Contact& c : out) EXPECT_NEAR(c.depth, d, kExact);
  const double z = 0.5 - 0.5 * d;
  expectSamePoints({Vec3(0.2, -0.5, z), Vec3(0.2, 0.5, z), Vec3(0.5, -0.5, z), Vec3(0.5, 0.5, z)}, out, kExact);
}

TEST(CollisionDetection, CylinderStandingAndLyingOnTheFloor) {
  rigid::WorldModel m;
  const double r = 0.2, l = 0.5, d = 0.003;
  m.bodies = {cylinder(r, l)};
  m.surfaces = {floorSurface()};
  const Vec3 foot(0.3, -0.4, 0.0);

  // Standing on its end: points on the rim of the bottom disc, all at depth d.
  std::vector<Contact> out = detect(m, {pose(foot + Vec3(0, 0, 0.5 * l - d))});
  ASSERT_GE(out.size(), 3u);
  for (const Contact& c : out) {
    EXPECT_NEAR((c.normal - Vec3(0, 0, -1)).norm(), 0.0, kExact);
    EXPECT_NEAR(c.depth, d, kExact);
    EXPECT_NEAR(c.point.z(), -0.5 * d, kExact);
    EXPECT_NEAR((c.point - foot).head<2>().norm(), r, kExact);
  }

  // Lying on its side (axis along world y): the two ends of the line of contact.
  const rigid::BodyState lying = pose(foot + Vec3(0, 0, r - d), about(Vec3::UnitX(), kPi / 2.0));
  out = detect(m, {lying});
  ASSERT_EQ(out.size(), 2u);
  for (const Contact& c : out) {
    EXPECT_NEAR((c.normal - Vec3(0, 0, -1)).norm(), 0.0, kExact);
    EXPECT_NEAR(c.depth, d, kExact);
  }
  expectSamePoints({foot + Vec3(0, -0.5 * l, -0.5 * d), foot + Vec3(0, 0.5 * l, -0.5 * d)}, out, kExact);

  // Tilted by 45 deg: one point, the lowest of its rim.
  const double tilt = kPi / 4.0;
  const double height = 0.5 * l * std::cos(tilt) + r * std::sin(tilt);  // centre above the lowest rim point
  out = detect(m, {pose(foot + Vec3(0, 0, height - d), about(Vec3::UnitX(), tilt))});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].depth, d, kGjk);
  EXPECT_NEAR((out[0].normal - Vec3(0, 0, -1)).norm(), 0.0, kGjk);
}

// A cylinder standing exactly on the floor (the default scene's puck): its rim at
// depth zero, pointing into the floor, with the margin or without it.
TEST(CollisionDetection, CylinderTouchingTheFloorExactlyIsAContactOfDepthZero) {
  rigid::WorldModel m;
  const double r = 0.15, l = 0.1;
  m.bodies = {cylinder(r, l)};
  m.surfaces = {surface(Vec3(-6, 3, -0.2), Vec3(0, 6, 0))};
  const Vec3 foot(-5.0, 4.5, 0.0);
  for (double margin : {0.0, 0.004}) {
    const std::vector<Contact> out = detect(m, {pose(foot + Vec3(0, 0, 0.5 * l))}, margin);
    ASSERT_GE(out.size(), 3u) << "margin " << margin;
    for (const Contact& c : out) {
      EXPECT_NEAR((c.normal - Vec3(0, 0, -1)).norm(), 0.0, kExact) << "margin " << margin;
      EXPECT_NEAR(c.depth, 0.0, kExact) << "margin " << margin;
      EXPECT_NEAR(c.point.z(), 0.0, kExact);
      EXPECT_NEAR((c.point - foot).head<2>().norm(), r, kExact);
    }
  }
}

// A tilted capsule whose lower cap touches the floor at 2e-16 m, where libccd gives no
// normal (a pose the replay test's tumbling rod met, written out to all its digits):
// the contact points into the floor, unit, at depth zero.
TEST(CollisionDetection, CapsuleCapTouchingTheFloorGetsTheFloorsNormal) {
  rigid::WorldModel m;
  m.bodies = {capsule(0.1, 0.5)};
  m.surfaces = {surface(Vec3(-3, -2, -0.2), Vec3(3, 2, 0))};
  const Quat q(0.7134488626480523, 0.6868676961971466, -0.058085925852615718, 0.12581539462589372);
  const Vec3 X(1.1656863698413125, 0.86743630522371695, 0.11241939656682355);
  for (double margin : {0.0, 0.004}) {
    const std::vector<Contact> out = detect(m, {pose(X, q.normalized())}, margin);
    ASSERT_GE(out.size(), 1u) << "margin " << margin;
    for (const Contact& c : out) {
      EXPECT_NEAR((c.normal - Vec3(0, 0, -1)).norm(), 0.0, 1e-9) << "margin " << margin;
      EXPECT_NEAR(c.depth, 0.0, 1e-9) << "margin " << margin;
    }
  }
}

TEST(CollisionDetection, CapsuleStandingAndLyingOnTheFloor) {
  rigid::WorldModel m;
  const double r = 0.1, l = 0.4, d = 0.002;
  m.bodies = {capsule(r, l)};
  m.surfaces = {floorSurface()};
  const Vec3 foot(-0.3, 0.4, 0.0);

  // Standing: one point, the bottom of the lower cap.
  std::vector<Contact> out = detect(m, {pose(foot + Vec3(0, 0, 0.5 * l + r - d))});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].surface, 0);
  EXPECT_NEAR((out[0].normal - Vec3(0, 0, -1)).norm(), 0.0, kExact);
  EXPECT_NEAR(out[0].depth, d, kExact);
  EXPECT_NEAR((out[0].point - (foot - Vec3(0, 0, 0.5 * d))).norm(), 0.0, kExact);

  // Lying along a horizontal direction: the bottoms of both caps.
  const Quat q = about(Vec3::UnitZ(), 0.6) * about(Vec3::UnitY(), kPi / 2.0);
  const Vec3 axis = q.toRotationMatrix().col(2);
  out = detect(m, {pose(foot + Vec3(0, 0, r - d), q)});
  ASSERT_EQ(out.size(), 2u);
  for (const Contact& c : out) {
    EXPECT_NEAR((c.normal - Vec3(0, 0, -1)).norm(), 0.0, kExact);
    EXPECT_NEAR(c.depth, d, kExact);
  }
  const Vec3 below(0, 0, -0.5 * d);
  expectSamePoints({foot + below - 0.5 * l * axis, foot + below + 0.5 * l * axis}, out, kExact);
}

TEST(CollisionDetection, BoxEdgeOnTheFloorGivesTheEdge) {
  rigid::WorldModel m;
  const Vec3 size(0.2, 0.2, 0.2);
  m.bodies = {box(size)};
  m.surfaces = {floorSurface()};
  const double d = 0.001;
  // Turned 30 deg about x: its lowest edge is along x.
  const double tilt = kPi / 6.0;
  const double height = 0.1 * std::cos(tilt) + 0.1 * std::sin(tilt);
  const std::vector<Contact> out = detect(m, {pose(Vec3(0, 0, height - d), about(Vec3::UnitX(), tilt))});
  ASSERT_EQ(out.size(), 2u);
  for (const Contact& c : out) {
    EXPECT_NEAR((c.normal - Vec3(0, 0, -1)).norm(), 0.0, kExact);
    EXPECT_NEAR(c.depth, d, kExact);
    EXPECT_NEAR(std::abs(c.point.x()), 0.1, kExact);
  }
}

TEST(CollisionDetection, BodyThatDoesNotCollideGivesNothing) {
  rigid::WorldModel m;
  m.bodies = {sphere(0.3), sphere(0.3), box(Vec3(0.2, 0.2, 0.2))};
  m.surfaces = {floorSurface()};
  const std::vector<rigid::BodyState> Y = {pose(Vec3(0, 0, 0.25)), pose(Vec3(0.5, 0, 0.25)), pose(Vec3(2, 0, 0.09))};
  ASSERT_EQ(detect(m, Y).size(), 3u + 4u);  // sphere-sphere, two spheres on the floor, the box
  const std::vector<Contact> out = detect(m, Y, 0.0, {true, false, true});
  ASSERT_EQ(out.size(), 1u + 4u);
  for (const Contact& c : out) {
    EXPECT_NE(c.a, 1);
    EXPECT_NE(c.b, 1);
  }
  EXPECT_TRUE(detect(m, Y, 0.1, {false, false, false}).empty());
}

TEST(CollisionDetection, StackOfTenBoxesTouchesOnlyItsNeighbours) {
  rigid::WorldModel m;
  const Vec3 size(0.2, 0.2, 0.2);
  const int n = 10;
  const double d = 0.001;
  std::vector<rigid::BodyState> Y;
  for (int i = 0; i < n; ++i) {
    m.bodies.push_back(box(size));
    Y.push_back(pose(Vec3(0.0, 0.0, 0.1 - d + i * (0.2 - d)), about(Vec3::UnitZ(), 0.1 * i)));
  }
  m.surfaces = {floorSurface()};
  rigid::CollisionDetector detector(m, std::vector<bool>(n, true));
  std::vector<Contact> out;
  for (int call = 0; call < 3; ++call) {  // the same answer every call
    detector.detect(Y, 0.0, out);
    std::vector<int> perPair(n, 0);  // perPair[i]: contacts between i and i + 1; [n - 1]: with the floor
    for (const Contact& c : out) {
      EXPECT_NEAR(c.depth, d, kExact);
      if (c.b == -1) {
        EXPECT_EQ(c.a, 0);
        EXPECT_NEAR((c.normal - Vec3(0, 0, -1)).norm(), 0.0, kExact);
        ++perPair[n - 1];
      } else {
        ASSERT_EQ(c.b, c.a + 1) << "contact between " << c.a << " and " << c.b;
        EXPECT_NEAR((c.normal - Vec3(0, 0, 1)).norm(), 0.0, kExact);
        EXPECT_NEAR(c.point.z(), 0.2 - d + c.a * (0.2 - d) - 0.5 * d, kExact);
        // Within both squares (the patch of two squares turned 0.1 rad apart).
        for (int k : {c.a, c.b}) {
          const Vec3 local = Y[k].q.conjugate() * (c.point - Y[k].X);
          EXPECT_LE(std::abs(local.x()), 0.1 + kExact);
          EXPECT_LE(std::abs(local.y()), 0.1 + kExact);
        }
        ++perPair[c.a];
      }
    }
    for (int i = 0; i < n; ++i) EXPECT_EQ(perPair[i], 4) << "pair " << i;
  }
}

TEST(CollisionDetection, ContactsAreSortedAndTheDetectorMoves) {
  rigid::WorldModel m;
  m.bodies = {sphere(0.3), sphere(0.3), sphere(0.3)};
  m.surfaces = {floorSurface(), surface(Vec3(-5, -5, -2), Vec3(5, 5, -0.5))};  // overlapping surfaces
  const std::vector<rigid::BodyState> Y = {pose(Vec3(0, 0, 0.29)), pose(Vec3(0.55, 0, 0.29)),
                                           pose(Vec3(0.0, 0.55, 0.29))};
  rigid::CollisionDetector first(m, {true, true, true});
  rigid::CollisionDetector detector(std::move(first));
  std::vector<Contact> out;
  detector.detect(Y, 0.0, out);
  // 0-1, 0-2, 0-floor, 1-floor, 2-floor; 1-2 are 0.78 apart.
  ASSERT_EQ(out.size(), 5u);
  const int expected[5][3] = {{0, 1, -1}, {0, 2, -1}, {0, -1, 0}, {1, -1, 0}, {2, -1, 0}};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(out[i].a, expected[i][0]);
    EXPECT_EQ(out[i].b, expected[i][1]);
    EXPECT_EQ(out[i].surface, expected[i][2]);
  }
}

TEST(CollisionDetection, DetectorsRunSideBySideInThreads) {
  rigid::WorldModel m;
  const int n = 20;
  std::vector<rigid::BodyState> Y;
  for (int i = 0; i < n; ++i) {
    m.bodies.push_back(i % 2 ? box(Vec3(0.2, 0.2, 0.2)) : cylinder(0.1, 0.2));
    Y.push_back(pose(Vec3(0.3 * i, 0.0, 0.099), about(Vec3::UnitZ(), 0.1 * i)));
  }
  m.surfaces = {floorSurface()};
  std::vector<Contact> reference;
  rigid::CollisionDetector(m, std::vector<bool>(n, true)).detect(Y, 0.01, reference);
  ASSERT_FALSE(reference.empty());
  std::vector<std::vector<Contact>> results(4);
  std::vector<std::thread> threads;
  for (auto& r : results)
    threads.emplace_back([&m, &Y, &r, n] {
      rigid::CollisionDetector detector(m, std::vector<bool>(n, true));
      for (int k = 0; k < 50; ++k) detector.detect(Y, 0.01, r);
    });
  for (std::thread& t : threads) t.join();
  for (const auto& r : results) {
    ASSERT_EQ(r.size(), reference.size());
    for (size_t i = 0; i < r.size(); ++i) {
      EXPECT_EQ(r[i].a, reference[i].a);
      EXPECT_EQ(r[i].point, reference[i].point);
      EXPECT_EQ(r[i].depth, reference[i].depth);
    }
  }
}

TEST(CollisionDetection, WrongSizesAreRefused) {
  rigid::WorldModel m;
  m.bodies = {sphere(0.3), sphere(0.3)};
  EXPECT_THROW(rigid::CollisionDetector(m, {true}), std::invalid_argument);
  rigid::CollisionDetector detector(m, {true, true});
  std::vector<Contact> out;
  EXPECT_THROW(detector.detect({pose(Vec3::Zero())}, 0.0, out), std::invalid_argument);
}
