// The auxiliaries of a body's state (src/body.cpp): V = P / M, R of q, I(t)^-1 and
// omega = I(t)^-1 L.
// Expected values are closed-form physics computed here.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <vector>

#include "builders.h"
#include "world.h"

namespace {

using rigid::Mat3;
using rigid::Quat;
using rigid::Vec3;
using rigid::test::maxAbs;
using rigid::test::rotationOf;
using rigid::test::unitQuat;
using rigid::test::world;

}  // namespace

TEST(Body, AuxiliariesFromState) {
  rigid::WorldModel model = world(rigid::Method::RK4, Vec3(0, 0, -9.81));
  rigid::BodyConstants b;
  b.name = "b";
  b.shape.type = rigid::ShapeType::Box;
  b.shape.size = Vec3(0.3, 0.5, 0.7);
  const double m = 2.5;
  rigid::setMass(b, m);
  Mat3 Ibody;
  Ibody << 0.9, 0.12, -0.05, 0.12, 0.7, 0.08, -0.05, 0.08, 0.5;
  rigid::setInertia(b, Ibody);
  b.start.orientation = unitQuat(0.8, 0.2, -0.5, 0.3);
  b.start.velocity = Vec3(0.4, -1.2, 3.0);
  const Vec3 w0(0.7, -2.0, 1.1);
  b.start.angularVelocity = w0;
  model.bodies.push_back(b);
  rigid::WorldData data = rigid::initialData(model);

  auto check = [&](const char* when) {
    SCOPED_TRACE(when);
    const rigid::BodyState& y = data.Y[0];
    const rigid::BodyAux& aux = data.aux[0];
    EXPECT_LT(maxAbs(aux.V - y.P / m), 1e-15);
    const Quat qn = y.q.normalized();
    const Mat3 R = rotationOf(qn.w(), qn.x(), qn.y(), qn.z());
    EXPECT_LT(maxAbs(aux.R - R), 1e-14);
    const Mat3 I = R * Ibody * R.transpose();
    const Mat3 Iinv = I.fullPivLu().inverse();
    // the world keeps V, R and omega; I(t)^-1 is formed by computeAuxiliaries for contacts
    rigid::BodyAux full;
    rigid::computeAuxiliaries(model.bodies[0], y, full);
    EXPECT_LT(maxAbs(full.Iinv - Iinv), 1e-12 * maxAbs(Iinv));
    EXPECT_LT(maxAbs(full.omega - aux.omega), 1e-12 * aux.omega.norm());
    EXPECT_LT(maxAbs(aux.omega - Iinv * y.L), 1e-12 * (Iinv * y.L).norm());
  };
  check("initial");
  // At the start: P = M V0 and omega = omega0.
  EXPECT_LT(maxAbs(data.Y[0].P - m * b.start.velocity), 1e-15);
  EXPECT_LT(maxAbs(data.aux[0].omega - w0), 1e-12);

  data.input[0].torque = Vec3(0.3, 0.1, -0.2);
  data.input[0].force = Vec3(1.0, 2.0, 3.0);
  for (int n = 0; n < 500; ++n) ASSERT_TRUE(rigid::step(model, data, 1e-3).ok);
  check("after 500 steps");
}

// The Lie-group method moves q by exponentials only: before any renormalisation, q
// stays unit to rounding step after step; classic RK4 drifts off the unit sphere.
