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

// A cube spinning about the vertical on the floor: friction over its bottom face
// brakes the spin at the constant rate mu_k M g rho / I_zz, rho = 0.38260 a the mean
// distance of a square's points from its centre ((sqrt 2 + asinh 1) / 6 a), I_zz =
// M a^2 / 6; it stops at omega0 / rate (within a step) and stays stopped, without
// sliding. (The first contact model, whose surface friction acts over the patch;
// the manifold solver's, at the patch's corners, is ContactSolver.SpinOnAFace....)
TEST(Surface, SpinOnAFaceIsBrakedByFrictionOverThePatchAndStops) {
  const double edge = 0.2, m = 2.0, g = 9.81, omega0 = 5.0;
  rigid::WorldModel model;
  model.contactSolver = rigid::ContactSolver::Centroid;
  model.gravity = Vec3(0, 0, -g);
  model.surfaces = {floorSurface()};
  rigid::BodyConstants b = cube(edge, m);
  b.start.position = Vec3(0, 0, 0.5 * edge);
  b.start.angularVelocity = Vec3(0, 0, omega0);
  model.bodies = {b};
  const double muk = 0.3;  // body and floor alike
  const double rho = (std::sqrt(2.0) + std::asinh(1.0)) / 6.0 * edge;
  EXPECT_NEAR(rigid::spinFrictionArm(b.shape, Mat3::Identity(), Vec3(0, 0, 1)), rho, 1e-15);
  const double rate = muk * m * g * rho / (m * edge * edge / 6.0);  // rad/s^2
  rigid::WorldData data = rigid::initialData(model);
  const double h = 1e-3;
  const double stopAt = omega0 / rate;
  for (int k = 1; k <= static_cast<int>(2.0 * stopAt / h); ++k) {
    ASSERT_TRUE(rigid::step(model, data, h).ok);
    const double t = k * h;
    const double expected = std::max(0.0, omega0 - rate * t);
    if (expected > rate * h) {
      ASSERT_NEAR(data.aux[0].omega.z(), expected, 1e-6 * omega0) << "t = " << t;
    } else {  // within a step of stopping: friction may stop it at this step's end
      ASSERT_GE(data.aux[0].omega.z(), 0.0) << "t = " << t;
      ASSERT_LE(data.aux[0].omega.z(), expected + 1e-6 * omega0) << "t = " << t;
    }
    ASSERT_LT(data.aux[0].omega.head<2>().norm(), 1e-12);
    ASSERT_LT(data.aux[0].V.norm(), 1e-12);
  }
  EXPECT_EQ(data.aux[0].omega.z(), 0.0);
  EXPECT_NEAR(data.Y[0].X.z(), 0.5 * edge, 1e-12);
}

// Round contacts and lying shapes: a sphere touches at a point (no spin friction), a
// cylinder on its end brakes at 2R/3, lying on its side (a line of length L) at L/4.
TEST(Surface, SpinFrictionArmOfRoundShapes) {
  rigid::Shape sphere;
  sphere.radius = 0.3;
  EXPECT_EQ(rigid::spinFrictionArm(sphere, Mat3::Identity(), Vec3(0, 0, 1)), 0.0);
  rigid::Shape cylinder;
  cylinder.type = rigid::ShapeType::Cylinder;
  cylinder.radius = 0.3;
  cylinder.length = 1.2;
  EXPECT_NEAR(rigid::spinFrictionArm(cylinder, Mat3::Identity(), Vec3(0, 0, 1)), 0.2, 1e-15);
  const Mat3 lying = Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitX()).toRotationMatrix();
  EXPECT_NEAR(rigid::spinFrictionArm(cylinder, lying, Vec3(0, 0, 1)), 0.3, 1e-15);
  rigid::Shape capsule = cylinder;
  capsule.type = rigid::ShapeType::Capsule;
  EXPECT_EQ(rigid::spinFrictionArm(capsule, Mat3::Identity(), Vec3(0, 0, 1)), 0.0);
  // a 0.2 x 0.4 face: the closed form against a midpoint sum over the rectangle
  rigid::Shape slab;
  slab.type = rigid::ShapeType::Box;
  slab.size = Vec3(0.2, 0.4, 0.05);
  double sum = 0.0;
  const int cells = 2000;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j)
      sum += std::hypot((i + 0.5) / cells * 0.2 - 0.1, (j + 0.5) / cells * 0.4 - 0.2);
  EXPECT_NEAR(rigid::spinFrictionArm(slab, Mat3::Identity(), Vec3(0, 0, 1)),
              sum / (cells * cells), 1e-7);  // the midpoint sum errs by ~1e-8 here
}
