// Forces at load points (the scene's "loads"): the force stage adds the force and its
// moment r x F with r turning with the body; a body-frame force turns with it too.
// Expected values are closed forms computed here.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "dynamics.h"
#include "scene.h"
#include "world.h"

namespace {

using rigid::Quat;
using rigid::Vec3;

// One free disc (a cylinder about body z), gravity off, spinning at w0 about z, with a
// load point at (r, 0, 0) whose force is given in `frame`.
rigid::WorldModel disc(const char* frame, double w0, const char* method = "rk4") {
  const std::string scene = std::string(R"({"name": "Disc", "gravity": [0, 0, 0],
    "solver": {"method": ")") +
                            method + R"(", "step": 0.001},
    "bodies": [{"name": "disc", "shape": {"type": "cylinder", "radius": 0.5, "length": 0.1}, "mass": 2.0,
                "angularVelocity": [0, 0, )" +
                            std::to_string(w0) + R"(],
                "loads": [{"name": "rim", "point": [0.5, 0, 0], "frame": ")" +
                            frame + R"("}]}]})";
  return rigid::parseScene(scene).model;
}

TEST(Loads, AForceAtAPointIsTheForceAtTheCentreOfMassPlusItsMoment) {
  const rigid::WorldModel model = disc("world", 0.0);
  rigid::BodyState y;
  y.q = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, -1).normalized()));
  y.L = Vec3(0.1, -0.2, 0.3);
  const Vec3 F(1.5, -2.0, 0.25);
  rigid::BodyInput atPoint = rigid::zeroInput(1), atCentre = rigid::zeroInput(1);
  atPoint.loads[0] = F;
  rigid::BodyAux a, b;
  rigid::computeVelocities(model.bodies[0], y, a);
  rigid::computeVelocities(model.bodies[0], y, b);
  atCentre.force = F;
  atCentre.torque = (a.R * model.bodies[0].loads[0].point).cross(F);
  rigid::accumulateAppliedForces(model, model.bodies[0], atPoint, y, a);
  rigid::accumulateAppliedForces(model, model.bodies[0], atCentre, y, b);
  EXPECT_EQ(a.F, b.F);  // bitwise
  EXPECT_EQ(a.T, b.T);
  // in the body frame: the force is R F
  rigid::WorldModel turned = disc("body", 0.0);
  rigid::BodyAux c;
  rigid::computeVelocities(turned.bodies[0], y, c);
  rigid::accumulateAppliedForces(turned, turned.bodies[0], atPoint, y, c);
  EXPECT_LT((c.F - c.R * F).norm(), 1e-15);
  EXPECT_LT((c.T - (c.R * turned.bodies[0].loads[0].point).cross(c.R * F)).norm(), 1e-15);
}

// A tangential force F in the body frame at the rim of a spinning disc is a follower
// force: its moment about the axis stays r F, so omega = w0 + F r t / I with
// I = m r^2 / 2, and the spin stays about z.
TEST(Loads, AFollowerForceAtTheRimSpinsADiscUpAtTheClosedFormRate) {
  const double w0 = 3.0, F = 0.8, r = 0.5, m = 2.0, I = 0.5 * m * r * r, T = 2.0;
  for (const char* method : {"rk4", "dopri5", "euler"}) {
    SCOPED_TRACE(method);
    const rigid::WorldModel model = disc("body", w0, method);
    rigid::WorldData data = rigid::initialData(model);
    data.input[0].loads[0] = Vec3(0, F, 0);
    const long steps = std::lround(T / model.maxStep);
    for (long k = 0; k < steps; ++k) ASSERT_TRUE(rigid::step(model, data, model.maxStep).ok);
    const double expected = w0 + F * r * T / I;
    EXPECT_NEAR(data.aux[0].omega.z(), expected, 1e-9 * expected);
    EXPECT_LT(data.aux[0].omega.head<2>().norm(), 1e-12);
  }
}

// A world-frame force at the centre of mass point is b.force: the same motion.
TEST(Loads, ALoadAtTheCentreOfMassMovesTheBodyAsItsForceInputDoes) {
  rigid::WorldModel model = disc("world", 1.0);
  model.bodies[0].loads[0].point = Vec3::Zero();
  rigid::WorldData viaLoad = rigid::initialData(model), viaForce = rigid::initialData(model);
  const Vec3 F(0.3, -0.1, 0.7);
  viaLoad.input[0].loads[0] = F;
  viaForce.input[0].force = F;
  for (int k = 0; k < 1000; ++k) {
    ASSERT_TRUE(rigid::step(model, viaLoad, model.maxStep).ok);
    ASSERT_TRUE(rigid::step(model, viaForce, model.maxStep).ok);
  }
  const double t = 1.0;
  EXPECT_LT((viaLoad.Y[0].X - 0.5 * F / 2.0 * t * t).norm(), 1e-12);  // X = F t^2 / (2 m)
  EXPECT_LT((viaLoad.Y[0].X - viaForce.Y[0].X).norm(), 1e-12);
  EXPECT_LT((viaLoad.Y[0].q.coeffs() - viaForce.Y[0].q.coeffs()).norm(), 1e-12);
}

}  // namespace
