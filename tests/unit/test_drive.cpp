// Driven bodies (drive.h): over a communication step a driven body follows the path
// from where it is to where its inputs put it at the step's end, internal step by
// internal step, whatever their number; the world moves it and nothing else does.
#include <gtest/gtest.h>

#include <cmath>

#include "builders.h"
#include "drive.h"
#include "world.h"

namespace {

using rigid::Quat;
using rigid::Vec3;
using namespace rigid::test;

// A driven box alone under gravity, given inputs; returns it after a communication
// step h of n internal steps taken by step().
rigid::BodyState afterStep(const rigid::DriveInput& in, const rigid::BodyState& from, double h, int n) {
  rigid::WorldModel model = world(rigid::Method::RK4, Vec3(0, 0, -9.81));
  rigid::BodyConstants b = bodyOf(box(1, 1, 0.1), 1.0, "platform");
  rigid::makeDriven(b);
  model.bodies.push_back(b);
  model.maxStep = h / n;
  rigid::WorldData data = rigid::initialData(model);
  data.Y[0] = from;
  data.drive[0] = in;
  const std::vector<rigid::DrivePath> paths = {rigid::drivePath(data.Y[0], in, h)};
  for (int k = 0; k < n; ++k) {
    const double t0 = h * k / n, t1 = h * (k + 1) / n;
    rigid::setDriveVelocities(model, data, data.drive, paths, t0, t1);
    EXPECT_TRUE(rigid::step(model, data, t1 - t0).ok);
  }
  return data.Y[0];
}

rigid::DriveInput inputs() {
  rigid::DriveInput in;
  in.position = Vec3(0.1, -0.2, 0.3);
  in.orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 2).normalized()));
  in.velocity = Vec3(1.5, 0.0, -0.5);
  in.angularVelocity = Vec3(0.0, 0.0, 2.0);
  in.acceleration = Vec3(0.0, 3.0, 1.0);
  return in;
}

TEST(Drive, ABodyWhereItsInputsSayEndsTheStepWhereTheyTakeIt) {
  const rigid::DriveInput in = inputs();
  rigid::BodyState start;
  start.X = in.position;
  start.q = in.orientation;
  const double h = 0.01;
  for (int n : {1, 3, 10}) {
    const rigid::BodyState end = afterStep(in, start, h, n);
    // position + h velocity + h^2/2 acceleration, gravity acting on nothing
    EXPECT_LT((end.X - (in.position + h * in.velocity + 0.5 * h * h * in.acceleration)).norm(), 1e-15) << n;
    // the constant angular velocity's rotation, exp(h omega) q
    const Quat expected = Quat(Eigen::AngleAxisd(h * 2.0, Vec3::UnitZ())) * in.orientation;
    EXPECT_LT(end.q.angularDistance(expected), 1e-14) << n;
    EXPECT_EQ(end.P, in.velocity + h * (1.0 - 0.5 / n) * in.acceleration) << n;  // the last internal step's
  }
}

TEST(Drive, ABodyElsewhereClosesTheGapWithinTheStepWithoutAJump) {
  const rigid::DriveInput in = inputs();
  rigid::BodyState start;
  start.X = in.position - Vec3(0.05, 0.0, 0.02);
  start.q = Quat(Eigen::AngleAxisd(0.03, Vec3::UnitX())) * in.orientation;
  const double h = 0.01;
  const rigid::DrivePath path = rigid::drivePath(start, in, h);
  EXPECT_NEAR(path.jump, std::hypot(0.05, 0.02), 1e-15);
  const rigid::BodyState end = afterStep(in, start, h, 10);
  EXPECT_LT((end.X - (in.position + h * in.velocity + 0.5 * h * h * in.acceleration)).norm(), 1e-15);
  // the turn that closes the gap and the input's spin, composed over ten internal
  // steps: second order in the two small rotations (0.03 and 0.02 rad)
  const Quat expected = Quat(Eigen::AngleAxisd(h * 2.0, Vec3::UnitZ())) * in.orientation;
  EXPECT_LT(end.q.angularDistance(expected), 1e-3);
}

TEST(Drive, ADrivenBodyIsNotMovedByGravityOrAnyForce) {
  rigid::DriveInput in;
  rigid::BodyState start;
  const rigid::BodyState end = afterStep(in, start, 0.01, 5);
  EXPECT_EQ(end.X, Vec3::Zero());
  EXPECT_EQ(end.P, Vec3::Zero());
}

}  // namespace
