// Surfaces: support function, coefficient rule, contact geometry, and the support and
// friction forces of the force stage, against values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "surface_contact.h"
#include "world.h"

namespace {

using rigid::Mat3;
using rigid::Quat;
using rigid::Vec3;

constexpr double kPi = 3.14159265358979323846;

rigid::Surface floorSurface(double mus = 0.5, double muk = 0.3) {
  rigid::Surface s;
  s.name = "floor";
  s.min = Vec3(-1, -1, -1);
  s.max = Vec3(1, 1, 0);
  s.staticFriction = mus;
  s.kineticFriction = muk;
  s.restitution = 0.5;
  rigid::finishSurface(s);
  return s;
}

rigid::BodyConstants cube(double edge = 0.2, double m = 2.0) {
  rigid::BodyConstants b;
  b.name = "cube";
  b.shape.type = rigid::ShapeType::Box;
  b.shape.size = Vec3(edge, edge, edge);
  rigid::setMass(b, m);
  b.staticFriction = 0.5;
  b.kineticFriction = 0.3;
  b.restitution = 0.5;
  return b;
}

rigid::BodyAux auxOf(const rigid::BodyConstants& b, const rigid::BodyState& y, const Vec3& F) {
  rigid::BodyAux aux;
  rigid::computeAuxiliaries(b, y, aux);
  aux.F = F;
  aux.T = Vec3::Zero();
  return aux;
}

rigid::BodyAux applied(const rigid::BodyConstants& b, const rigid::BodyState& y, const Vec3& F) {
  return auxOf(b, y, F);
}

}  // namespace

TEST(Surface, SupportDistanceOfShapes) {
  rigid::Shape sphere;
  sphere.radius = 0.3;
  EXPECT_DOUBLE_EQ(rigid::supportDistance(sphere, Mat3::Identity(), Vec3(0, 0, -1)), 0.3);

  rigid::Shape box;
  box.type = rigid::ShapeType::Box;
  box.size = Vec3(0.4, 0.2, 0.1);
  EXPECT_NEAR(rigid::supportDistance(box, Mat3::Identity(), Vec3(0, 0, -1)), 0.05, 1e-15);
  // turned 45 degrees about x: the lowest point is an edge at (0.1 + 0.05)/sqrt(2)
  const Mat3 R = Eigen::AngleAxisd(kPi / 4, Vec3::UnitX()).toRotationMatrix();
  EXPECT_NEAR(rigid::supportDistance(box, R, Vec3(0, 0, -1)), 0.15 / std::sqrt(2.0), 1e-15);

  rigid::Shape cyl;
  cyl.type = rigid::ShapeType::Cylinder;
  cyl.radius = 0.1;
  cyl.length = 0.6;
  EXPECT_NEAR(rigid::supportDistance(cyl, Mat3::Identity(), Vec3(0, 0, -1)), 0.3, 1e-15);
  EXPECT_NEAR(rigid::supportDistance(cyl, Mat3::Identity(), Vec3(1, 0, 0)), 0.1, 1e-15);
  // axis tilted by 30 degrees from the direction: rim point at L/2 cos + r sin
  const Mat3 R30 = Eigen::AngleAxisd(kPi / 6, Vec3::UnitY()).toRotationMatrix();
  EXPECT_NEAR(rigid::supportDistance(cyl, R30, Vec3(0, 0, 1)),
              0.3 * std::cos(kPi / 6) + 0.1 * std::sin(kPi / 6), 1e-15);

  rigid::Shape capsule = cyl;
  capsule.type = rigid::ShapeType::Capsule;
  EXPECT_NEAR(rigid::supportDistance(capsule, R30, Vec3(0, 0, 1)), 0.3 * std::cos(kPi / 6) + 0.1,
              1e-15);
}

TEST(Surface, EqualCoefficientsCombineToThatValue) {
  for (double mu : {0.0, 0.1, 0.5, 0.9, 1.0})
    EXPECT_DOUBLE_EQ(rigid::combineCoefficients(mu, mu), mu);
  EXPECT_DOUBLE_EQ(rigid::combineCoefficients(0.25, 1.0), 0.5);
  EXPECT_DOUBLE_EQ(rigid::combineCoefficients(0.0, 0.8), 0.0);
}

TEST(Surface, ContactGapOnFlatAndTurnedSurfaces) {
  const rigid::BodyConstants b = cube();
  rigid::BodyState y;
  y.X = Vec3(0.3, -0.2, 0.1 + 0.02);
  const rigid::SurfaceContact c = rigid::surfaceContact(floorSurface(), b, y);
  ASSERT_TRUE(c.overFace);
  EXPECT_NEAR(c.gap, 0.02, 1e-15);
  EXPECT_TRUE(c.n.isApprox(Vec3::UnitZ()));

  y.X.x() = 1.05;  // beyond the face's bounds
  EXPECT_FALSE(rigid::surfaceContact(floorSurface(), b, y).overFace);

  // a ramp turned 20 degrees about y, a cube resting on it with the same turn
  rigid::Surface ramp = floorSurface();
  const double th = 20.0 * kPi / 180.0;
  ramp.orientation = Quat(Eigen::AngleAxisd(th, Vec3::UnitY()));
  rigid::finishSurface(ramp);
  const Vec3 n(std::sin(th), 0, std::cos(th));
  rigid::BodyState on;
  on.q = ramp.orientation;
  on.X = ramp.centre + (0.5 + 0.1) * n;
  const rigid::SurfaceContact cr = rigid::surfaceContact(ramp, b, on);
  ASSERT_TRUE(cr.overFace);
  EXPECT_NEAR(cr.gap, 0.0, 1e-15);
  EXPECT_TRUE(cr.n.isApprox(n, 1e-15));
}

TEST(Surface, SupportCancelsThePressAndStaticFrictionTheTangentialLoad) {
  const rigid::BodyConstants b = cube();
  rigid::BodyState y;
  y.X = Vec3(0, 0, 0.1);
  const std::vector<rigid::Surface> floor = {floorSurface()};
  // weight plus a push below mu_s N = 0.5 * 19.62 N
  const Vec3 F(9.0, -2.0, -19.62);
  rigid::BodyAux aux = auxOf(b, y, F);
  rigid::addSurfaceForces(floor, b, y, aux);
  EXPECT_LT(aux.F.norm(), 1e-14);
}

TEST(Surface, LoadAboveStaticLimitSlidesWithKineticFriction) {
  const rigid::BodyConstants b = cube();
  rigid::BodyState y;
  y.X = Vec3(0, 0, 0.1);
  const std::vector<rigid::Surface> floor = {floorSurface()};
  const double N = 19.62;
  const Vec3 push(12.0, 0.0, 0.0);  // above mu_s N = 9.81
  rigid::BodyAux aux = auxOf(b, y, push + Vec3(0, 0, -N));
  rigid::addSurfaceForces(floor, b, y, aux);
  EXPECT_NEAR(aux.F.x(), 12.0 - 0.3 * N, 1e-12);  // starts along the load
  EXPECT_NEAR(aux.F.z(), 0.0, 1e-14);

  // already sliding in -y: friction opposes the velocity, whatever the load
  y.P = b.mass * Vec3(0.0, -1.0, 0.0);
  aux = auxOf(b, y, Vec3(0, 0, -N));
  rigid::addSurfaceForces(floor, b, y, aux);
  EXPECT_NEAR(aux.F.y(), 0.3 * N, 1e-12);
  EXPECT_NEAR(aux.F.x(), 0.0, 1e-15);
}

TEST(Surface, NoSupportWhenPulledAwayOrLeaving) {
  const rigid::BodyConstants b = cube();
  rigid::BodyState y;
  y.X = Vec3(0, 0, 0.1);
  const std::vector<rigid::Surface> floor = {floorSurface()};
  rigid::BodyAux aux = auxOf(b, y, Vec3(1.0, 0, 5.0));  // pulled up
  rigid::addSurfaceForces(floor, b, y, aux);
  EXPECT_EQ(aux.F, Vec3(1.0, 0, 5.0));
  y.P = b.mass * Vec3(0, 0, 0.5);  // moving up off the face
  aux = auxOf(b, y, Vec3(0, 0, -19.62));
  rigid::addSurfaceForces(floor, b, y, aux);
  EXPECT_EQ(aux.F, Vec3(0, 0, -19.62));
}

TEST(Surface, LandingReversesTheNormalVelocityScaledByRestitution) {
  rigid::BodyConstants b = cube();
  const std::vector<rigid::Surface> floor = {floorSurface()};  // xi 0.5 both: combined 0.5
  rigid::BodyState before, after;
  before.X = Vec3(0, 0, 0.11);
  before.P = b.mass * Vec3(0.2, 0, -3.0);
  after.X = Vec3(0.0002, 0, 0.098);  // 2 mm into the floor
  after.P = b.mass * Vec3(0.2, 0, -3.01);
  rigid::respondToSurfaces(floor, b, Vec3(0, 0, -9.81), applied(b, after, b.mass * Vec3(0, 0, -9.81)), 1e-3, before, after);
  EXPECT_NEAR(after.X.z(), 0.1, 1e-15);            // penetration removed along n
  EXPECT_NEAR(after.P.z() / b.mass, 0.5 * 3.01, 1e-12);
  EXPECT_NEAR(after.P.x() / b.mass, 0.2, 1e-15);   // tangential velocity kept
}

TEST(Surface, SlidingThatReversesInAStepEndsAtRest) {
  rigid::BodyConstants b = cube();
  const std::vector<rigid::Surface> floor = {floorSurface()};
  rigid::BodyState before, after;
  before.X = after.X = Vec3(0, 0, 0.1);
  before.P = b.mass * Vec3(1e-3, 0, 0);
  after.P = b.mass * Vec3(-2e-3, 0, 0);  // friction overshot within the step
  rigid::respondToSurfaces(floor, b, Vec3(0, 0, -9.81), applied(b, after, b.mass * Vec3(0, 0, -9.81)), 1e-3, before, after);
  EXPECT_EQ(after.P, Vec3::Zero());
  // no reversal, but slow enough for friction (0.3 g h = 2.9 mm/s) to stop it in a step
  after.P = b.mass * Vec3(5e-4, 0, 0);
  rigid::respondToSurfaces(floor, b, Vec3(0, 0, -9.81), applied(b, after, b.mass * Vec3(0, 0, -9.81)), 1e-3, before, after);
  EXPECT_EQ(after.P, Vec3::Zero());
  // the same, but pushed with 12 N, more than static friction holds (9.81 N): slides on
  after.P = b.mass * Vec3(5e-4, 0, 0);
  rigid::respondToSurfaces(floor, b, Vec3(0, 0, -9.81), applied(b, after, Vec3(12.0, 0, -19.62)), 1e-3, before, after);
  EXPECT_NEAR(after.P.x() / b.mass, 5e-4, 1e-18);
  // fast: the slide goes on
  after.P = b.mass * Vec3(0.5, 0, 0);
  rigid::respondToSurfaces(floor, b, Vec3(0, 0, -9.81), applied(b, after, b.mass * Vec3(0, 0, -9.81)), 1e-3, before, after);
  EXPECT_NEAR(after.P.x() / b.mass, 0.5, 1e-15);
}
