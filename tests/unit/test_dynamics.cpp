// The derivative dY/dt = (V, 1/2 omega q, F, T) (src/dynamics.cpp) through the world's
// step: free fall, a constant force, a constant torque, a free spin.
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
using rigid::test::bodyOf;
using rigid::test::maxAbs;
using rigid::test::rotationOf;
using rigid::test::sphere;
using rigid::test::unitQuat;
using rigid::test::world;

}  // namespace

TEST(Dynamics, FreeFallRk4MatchesClosedForm) {
  const Vec3 g(0.3, -0.2, -9.81);
  rigid::WorldModel model = world(rigid::Method::RK4, g);
  rigid::BodyConstants b = bodyOf(sphere(0.1), 1.3, "ball");
  const Vec3 x0(1.0, -2.0, 10.0), v0(0.5, 0.3, 4.0);
  b.start.position = x0;
  b.start.velocity = v0;
  model.bodies.push_back(b);
  rigid::WorldData data = rigid::initialData(model);
  const double h = 1e-3;
  for (int n = 1; n <= 1500; ++n) {
    ASSERT_TRUE(rigid::step(model, data, h).ok);
    const double t = n * h;
    const Vec3 x = x0 + v0 * t + 0.5 * g * t * t;
    const Vec3 v = v0 + g * t;
    ASSERT_LT(maxAbs(data.Y[0].X - x), 1e-12) << "t = " << t;
    ASSERT_LT(maxAbs(data.aux[0].V - v), 1e-12) << "t = " << t;
    ASSERT_LT(maxAbs(data.Y[0].P - 1.3 * v), 1e-12) << "t = " << t;
  }
}

TEST(Dynamics, ConstantForceGivesAccelerationFOverM) {
  for (rigid::Method method : {rigid::Method::RK4, rigid::Method::Euler}) {
    SCOPED_TRACE(rigid::methodName(method));
    rigid::WorldModel model = world(method, Vec3::Zero());
    const double m = 2.5;
    rigid::BodyConstants b = bodyOf(sphere(0.2), m, "ball");
    const Vec3 v0(1.0, -1.0, 0.5);
    b.start.velocity = v0;
    model.bodies.push_back(b);
    rigid::WorldData data = rigid::initialData(model);
    const Vec3 F(3.0, -1.0, 2.0);
    data.input[0].force = F;
    const double h = 1e-3;
    const int n = 800;
    for (int i = 0; i < n; ++i) ASSERT_TRUE(rigid::step(model, data, h).ok);
    const double t = n * h;
    const Vec3 a = (data.aux[0].V - v0) / t;
    EXPECT_LT(maxAbs(a - F / m), 1e-12);
    EXPECT_LT(maxAbs(data.Y[0].P - (m * v0 + F * t)), 1e-12);
    if (method == rigid::Method::RK4) {  // exact for a quadratic in t
      EXPECT_LT(maxAbs(data.Y[0].X - (v0 * t + 0.5 * F / m * t * t)), 1e-12);
    }
  }
}

TEST(Dynamics, ConstantTorqueOnSphere) {
  for (rigid::Method method : {rigid::Method::RK4, rigid::Method::Euler}) {
    SCOPED_TRACE(rigid::methodName(method));
    rigid::WorldModel model = world(method, Vec3(0, 0, -9.81));
    const double r = 0.2, m = 3.0;
    const double I = 0.4 * m * r * r;  // solid sphere
    rigid::BodyConstants b = bodyOf(sphere(r), m, "ball");
    b.start.orientation = unitQuat(0.9, 0.1, -0.3, 0.2);
    const Vec3 w0(1.0, 2.0, -0.5);
    b.start.angularVelocity = w0;
    model.bodies.push_back(b);
    rigid::WorldData data = rigid::initialData(model);
    const Vec3 L0 = I * w0;
    EXPECT_LT(maxAbs(data.Y[0].L - L0), 1e-15);
    const Vec3 T(0.1, -0.3, 0.2);
    data.input[0].torque = T;
    const double h = 1e-3;
    for (int n = 1; n <= 1000; ++n) {
      ASSERT_TRUE(rigid::step(model, data, h).ok);
      const Vec3 L = L0 + T * (n * h);
      // L' = T exactly; only rounding of the sums differs.
      ASSERT_LT(maxAbs(data.Y[0].L - L), 1e-14) << "step " << n;
      ASSERT_LT(maxAbs(data.aux[0].omega - L / I), 1e-12) << "step " << n;
    }
  }
}

// A sphere spinning at constant omega (world frame) turns as q(t) = exp(omega t / 2) q0.
TEST(Dynamics, SpinningSphereOrientationFollowsClosedForm) {
  rigid::WorldModel model = world(rigid::Method::RK4, Vec3::Zero());
  rigid::BodyConstants b = bodyOf(sphere(0.3), 2.0, "ball");
  const Quat q0 = unitQuat(0.7, -0.2, 0.4, 0.5);
  const Vec3 axis = Vec3(1.0, 2.0, 2.0) / 3.0;
  const double rate = 3.0;
  b.start.orientation = q0;
  b.start.angularVelocity = rate * axis;
  model.bodies.push_back(b);
  rigid::WorldData data = rigid::initialData(model);
  const double h = 1e-3;
  for (int n = 1; n <= 1000; ++n) {
    ASSERT_TRUE(rigid::step(model, data, h).ok);
    const double half = 0.5 * rate * n * h;
    const Quat turn(std::cos(half), std::sin(half) * axis.x(), std::sin(half) * axis.y(), std::sin(half) * axis.z());
    const Quat q = turn * q0;  // world-frame rotation multiplies from the left
    ASSERT_LT((data.Y[0].q.coeffs() - q.coeffs()).cwiseAbs().maxCoeff(), 1e-10) << "step " << n;
  }
  // Independent check of the frame convention: the body x axis, mapped to the world.
  const double half = 0.5 * rate * 1.0;
  const Mat3 Rturn = Eigen::AngleAxisd(2 * half, axis).toRotationMatrix();
  const Mat3 R0 = rotationOf(q0.w(), q0.x(), q0.y(), q0.z());
  EXPECT_LT(maxAbs(data.aux[0].R - Rturn * R0), 1e-9);
}
