// The integration methods (src/integrator.cpp, src/methods.cpp) through the world's
// step: their orders of accuracy, what each keeps exactly (angular momentum, the unit
// quaternion).
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
using rigid::test::asymmetricBody;
using rigid::test::rotationOf;
using rigid::test::unitQuat;
using rigid::test::world;

}  // namespace

TEST(Integrator, TorqueFreeAsymmetricBodyKeepsLBitwiseAndUnitQuaternion) {
  for (rigid::Method method : {rigid::Method::RK4, rigid::Method::Euler}) {
    SCOPED_TRACE(rigid::methodName(method));
    rigid::WorldModel model = world(method, Vec3(0, 0, -9.81));
    model.energyGainLimit = 0.0;  // Euler's energy gain is refused otherwise (next test)
    rigid::BodyConstants b = asymmetricBody(Vec3(1.0, 2.0, 2.5), 4.0);
    b.start.orientation = unitQuat(0.3, 0.5, -0.7, 0.1);
    b.start.angularVelocity = Vec3(0.2, 4.0, -0.3);  // tumbles: near the unstable axis
    model.bodies.push_back(b);
    rigid::WorldData data = rigid::initialData(model);
    const Vec3 L0 = data.Y[0].L;
    ASSERT_GT(L0.norm(), 1.0);
    for (int n = 1; n <= 3000; ++n) {
      ASSERT_TRUE(rigid::step(model, data, 1e-3).ok);
      ASSERT_EQ(data.Y[0].L.x(), L0.x()) << "step " << n;
      ASSERT_EQ(data.Y[0].L.y(), L0.y()) << "step " << n;
      ASSERT_EQ(data.Y[0].L.z(), L0.z()) << "step " << n;
      ASSERT_LT(std::abs(data.Y[0].q.norm() - 1.0), 1e-14) << "step " << n;
    }
  }
}

// 2 E = L . I(t)^-1 L, from the auxiliaries (independent of the audit's body-frame form).

namespace {

// Orientation after time T of a torque-free asymmetric body spinning near its major
// axis (a smooth, bounded nutation), integrated with steps of h.
Quat spinningBody(rigid::Method method, double h, double T, double spin) {
  rigid::WorldModel model = world(method, Vec3::Zero());
  rigid::BodyConstants b = asymmetricBody(Vec3(1.0, 1.6, 2.2), 1.0);
  b.start.orientation = unitQuat(0.9, 0.2, -0.3, 0.25);
  const Mat3 R =
      rotationOf(b.start.orientation.w(), b.start.orientation.x(), b.start.orientation.y(), b.start.orientation.z());
  b.start.angularVelocity = R * (spin * Vec3(0.08, -0.05, 1.0));  // body z = major axis
  model.bodies.push_back(b);
  rigid::WorldData data = rigid::initialData(model);
  const int n = static_cast<int>(std::lround(T / h));
  for (int i = 0; i < n; ++i)
    if (!rigid::step(model, data, h).ok) return Quat(NAN, NAN, NAN, NAN);
  return data.Y[0].q;
}

double quatDistance(const Quat& a, const Quat& b) {
  return std::min((a.coeffs() - b.coeffs()).norm(), (a.coeffs() + b.coeffs()).norm());
}

// Least-squares slope of log(err) against log(h).
double orderOf(rigid::Method method, double spin) {
  const double T = 1.0;
  const std::vector<double> hs = {4e-3, 2e-3, 1e-3, 5e-4};
  const Quat ref = spinningBody(rigid::Method::RK4, 5e-4 / 32, T, spin);
  std::vector<double> x, y;
  for (double h : hs) {
    const double err = quatDistance(spinningBody(method, h, T, spin), ref);
    std::cout << "  " << rigid::methodName(method) << " h = " << h << " error = " << err << "\n";
    x.push_back(std::log(h));
    y.push_back(std::log(err));
  }
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace

TEST(Integrator, Rk4GlobalErrorIsFourthOrder) {
  const double slope = orderOf(rigid::Method::RK4, 12.0);
  EXPECT_NEAR(slope, 4.0, 0.4);
}

TEST(Integrator, EulerGlobalErrorIsFirstOrder) {
  const double slope = orderOf(rigid::Method::Euler, 2.0);
  EXPECT_NEAR(slope, 1.0, 0.2);
}

TEST(Integrator, LieRk4KeepsTheQuaternionUnitByConstruction) {
  for (rigid::Method method : {rigid::Method::LieRK4, rigid::Method::RK4}) {
    rigid::WorldModel model = world(method, Vec3::Zero());
    rigid::BodyConstants b = asymmetricBody(Vec3(1.0, 2.0, 3.0), 1.0);
    b.start.angularVelocity = Vec3(0.3, 8.0, 0.2);
    model.bodies.push_back(b);
    rigid::WorldData data = rigid::initialData(model);
    std::vector<rigid::BodyState> next(1);
    double drift = 0.0;
    for (int k = 0; k < 1000; ++k) {
      rigid::integrate(model, data, {0}, 1e-2, next);  // q as the method leaves it
      drift = std::max(drift, std::abs(next[0].q.norm() - 1.0));
      data.Y = next;
      data.Y[0].q.normalize();
    }
    if (method == rigid::Method::LieRK4)
      EXPECT_LT(drift, 1e-14);
    else
      EXPECT_GT(drift, 1e-12);  // the contrast that shows the check can fail
  }
}

// The splitting method keeps world L bitwise in a torque-free motion, whatever the
// orientation of the principal axes in the body frame (a non-diagonal Ibody).
TEST(Integrator, SplittingKeepsAngularMomentumWithNonDiagonalInertia) {
  rigid::WorldModel model = world(rigid::Method::Splitting, Vec3::Zero());
  rigid::BodyConstants b = asymmetricBody(Vec3(1.0, 2.0, 3.0), 1.0);
  Mat3 I;
  I << 1.5, 0.2, -0.1, 0.2, 2.0, 0.3, -0.1, 0.3, 2.5;
  rigid::setInertia(b, I);
  b.start.angularVelocity = Vec3(1.0, -2.0, 0.5);
  model.bodies.push_back(b);
  rigid::WorldData data = rigid::initialData(model);
  const Vec3 L0 = data.Y[0].L;
  const double E0 = 0.5 * L0.dot(data.aux[0].omega);
  double worstE = 0.0;
  for (int k = 0; k < 5000; ++k) {
    ASSERT_TRUE(rigid::step(model, data, 1e-2).ok);
    EXPECT_EQ(data.Y[0].L, L0);
    worstE = std::max(worstE, std::abs(0.5 * data.Y[0].L.dot(data.aux[0].omega) / E0 - 1.0));
  }
  EXPECT_LT(worstE, 1e-3);  // bounded at h |omega| ~ 0.03 over 50 s
}
