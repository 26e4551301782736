// Dynamics through the public API: rigid::WorldModel, rigid::initialData, rigid::step.
// Expected values are closed-form physics computed here.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <vector>

#include "world.h"

namespace {

using rigid::Mat3;
using rigid::Quat;
using rigid::Vec3;

constexpr double kPi = 3.14159265358979323846;

rigid::BodyConstants sphereBody(const std::string& name, double r, double m) {
  rigid::BodyConstants b;
  b.name = name;
  b.shape.type = rigid::ShapeType::Sphere;
  b.shape.radius = r;
  rigid::setMass(b, m);
  return b;
}

// An asymmetric body: a box whose inertia is replaced by a given diagonal tensor.
rigid::BodyConstants asymmetricBody(const Vec3& principal, double m) {
  rigid::BodyConstants b;
  b.name = "a";
  b.shape.type = rigid::ShapeType::Box;
  b.shape.size = Vec3(0.1, 0.2, 0.3);
  rigid::setMass(b, m);
  rigid::setInertia(b, principal.asDiagonal());
  return b;
}

rigid::WorldModel world(rigid::Method method, const Vec3& g) {
  rigid::WorldModel m;
  m.name = "w";
  m.gravity = g;
  m.method = method;
  return m;
}

// Rotation matrix of a unit quaternion (w, x, y, z), body -> world, written out here.
Mat3 rotationOf(double w, double x, double y, double z) {
  Mat3 R;
  R << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
       2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
       2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
  return R;
}

Quat unitQuat(double w, double x, double y, double z) {
  const double n = std::sqrt(w * w + x * x + y * y + z * z);
  return Quat(w / n, x / n, y / n, z / n);
}

double maxAbs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

}  // namespace

TEST(Dynamics, FreeFallRk4MatchesClosedForm) {
  const Vec3 g(0.3, -0.2, -9.81);
  rigid::WorldModel model = world(rigid::Method::RK4, g);
  rigid::BodyConstants b = sphereBody("ball", 0.1, 1.3);
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
    rigid::BodyConstants b = sphereBody("ball", 0.2, m);
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
    rigid::BodyConstants b = sphereBody("ball", r, m);
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
  rigid::BodyConstants b = sphereBody("ball", 0.3, 2.0);
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
    const Quat turn(std::cos(half), std::sin(half) * axis.x(), std::sin(half) * axis.y(),
                    std::sin(half) * axis.z());
    const Quat q = turn * q0;  // world-frame rotation multiplies from the left
    ASSERT_LT((data.Y[0].q.coeffs() - q.coeffs()).cwiseAbs().maxCoeff(), 1e-10) << "step " << n;
  }
  // Independent check of the frame convention: the body x axis, mapped to the world.
  const double half = 0.5 * rate * 1.0;
  const Mat3 Rturn = Eigen::AngleAxisd(2 * half, axis).toRotationMatrix();
  const Mat3 R0 = rotationOf(q0.w(), q0.x(), q0.y(), q0.z());
  EXPECT_LT(maxAbs(data.aux[0].R - Rturn * R0), 1e-9);
}

TEST(Dynamics, TorqueFreeAsymmetricBodyKeepsLBitwiseAndUnitQuaternion) {
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
double twiceEnergy(const rigid::WorldData& data) { return data.Y[0].L.dot(data.aux[0].omega); }
}  // namespace

// The energy audit: explicit Euler's torque-free tumbling gains energy step by step
// (Lie-Euler); the step that would take the gain beyond the limit is refused with the
// body, the gain and a smaller step, and the state is left as it was. The methods that
// keep a free rotation's energy run 1e4 steps under the same limit.
TEST(Dynamics, EnergyAuditRefusesExplicitEulersGainOnAFreeRotation) {
  const double limit = 1e-3;
  for (rigid::Method method : {rigid::Method::Euler, rigid::Method::RK4, rigid::Method::SymplecticEuler,
                               rigid::Method::Splitting, rigid::Method::LieRK4}) {
    SCOPED_TRACE(rigid::methodName(method));
    rigid::WorldModel model = world(method, Vec3(0, 0, -9.81));
    model.energyGainLimit = limit;
    rigid::BodyConstants b = asymmetricBody(Vec3(1.0, 2.0, 2.5), 4.0);
    b.start.angularVelocity = Vec3(0.2, 4.0, -0.3);
    model.bodies.push_back(b);
    rigid::WorldData data = rigid::initialData(model);
    const double E0 = twiceEnergy(data);
    int n = 0;
    rigid::StepResult r;
    for (; n < 10000 && (r = rigid::step(model, data, 1e-3)).ok; ++n) {
      ASSERT_LE(twiceEnergy(data) / E0 - 1.0, limit * (1 + 1e-9)) << "step " << n;
    }
    if (method != rigid::Method::Euler) {
      EXPECT_EQ(n, 10000) << r.cause;
      continue;
    }
    ASSERT_LT(n, 10000) << "explicit Euler was expected to gain energy";
    EXPECT_EQ(r.cause, rigid::kEnergyGain);
    EXPECT_EQ(r.body, 0);
    EXPECT_GT(r.energyGain, limit);
    EXPECT_GT(r.stableStep, 0.0);
    EXPECT_LT(r.stableStep, 1e-3);
    // Refused, not taken: the state is that of the last accepted step, within the limit.
    const rigid::BodyState before = data.Y[0];
    EXPECT_FALSE(rigid::step(model, data, 1e-3).ok);
    EXPECT_TRUE(before.X == data.Y[0].X && before.q.coeffs() == data.Y[0].q.coeffs() &&
                before.P == data.Y[0].P && before.L == data.Y[0].L);
    EXPECT_LE(twiceEnergy(data) / E0 - 1.0, limit * (1 + 1e-9));
    // Unchecked (0), the same run goes on.
    model.energyGainLimit = 0.0;
    EXPECT_TRUE(rigid::step(model, data, 1e-3).ok);
  }
}

// A torque changes L: those steps are the torque's work, not the method's, and are
// not audited (a spin-up by a constant torque quadruples the energy and is fine).
TEST(Dynamics, EnergyAuditLeavesTorquedBodiesAlone) {
  rigid::WorldModel model = world(rigid::Method::Euler, Vec3(0, 0, -9.81));
  model.bodies.push_back(asymmetricBody(Vec3(1.0, 2.0, 2.5), 4.0));
  model.bodies[0].start.angularVelocity = Vec3(0.0, 0.0, 1.0);
  rigid::WorldData data = rigid::initialData(model);
  data.input[0].torque = Vec3(0.0, 0.0, 2.5);  // doubles omega_z in 1 s
  const double E0 = twiceEnergy(data);
  for (int n = 0; n < 1000; ++n) ASSERT_TRUE(rigid::step(model, data, 1e-3).ok) << n;
  EXPECT_NEAR(twiceEnergy(data) / E0, 4.0, 1e-9);
}

namespace {

// Orientation after time T of a torque-free asymmetric body spinning near its major
// axis (a smooth, bounded nutation), integrated with steps of h.
Quat spinningBody(rigid::Method method, double h, double T, double spin) {
  rigid::WorldModel model = world(method, Vec3::Zero());
  rigid::BodyConstants b = asymmetricBody(Vec3(1.0, 1.6, 2.2), 1.0);
  b.start.orientation = unitQuat(0.9, 0.2, -0.3, 0.25);
  const Mat3 R = rotationOf(b.start.orientation.w(), b.start.orientation.x(),
                            b.start.orientation.y(), b.start.orientation.z());
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

TEST(Dynamics, Rk4GlobalErrorIsFourthOrder) {
  const double slope = orderOf(rigid::Method::RK4, 12.0);
  EXPECT_NEAR(slope, 4.0, 0.4);
}

TEST(Dynamics, EulerGlobalErrorIsFirstOrder) {
  const double slope = orderOf(rigid::Method::Euler, 2.0);
  EXPECT_NEAR(slope, 1.0, 0.2);
}

namespace {

bool sameState(const rigid::BodyState& a, const rigid::BodyState& b) {
  return a.X == b.X && a.q.coeffs() == b.q.coeffs() && a.P == b.P && a.L == b.L;
}

}  // namespace

// A huge force on a tiny mass: P stays finite but V = P/M overflows, and with it X.
TEST(Dynamics, OverflowIsRefusedWithBodyIndexAndStateUnchanged) {
  for (rigid::Method method : {rigid::Method::RK4, rigid::Method::Euler}) {
    SCOPED_TRACE(rigid::methodName(method));
    rigid::WorldModel model = world(method, Vec3(0, 0, -9.81));
    rigid::BodyConstants fine = sphereBody("fine", 0.1, 1.0);
    fine.start.velocity = Vec3(1.0, 0.0, 0.0);
    fine.start.angularVelocity = Vec3(0.0, 1.0, 0.0);
    model.bodies.push_back(fine);
    model.bodies.push_back(sphereBody("tiny", 0.1, 1e-300));
    for (rigid::BodyConstants& b : model.bodies) b.collides = false;  // both at the origin
    rigid::WorldData data = rigid::initialData(model);
    data.input[1].force = Vec3(1e308, 0.0, 0.0);
    bool refused = false;
    for (int n = 0; n < 10 && !refused; ++n) {
      const std::vector<rigid::BodyState> before = data.Y;
      const rigid::StepResult r = rigid::step(model, data, 1e-3);
      if (!r.ok) {
        refused = true;
        EXPECT_EQ(r.body, 1);
        ASSERT_EQ(data.Y.size(), before.size());
        for (size_t i = 0; i < before.size(); ++i)
          EXPECT_TRUE(sameState(data.Y[i], before[i])) << "body " << i << " changed";
        EXPECT_TRUE(rigid::isFinite(data.Y[1]));
      } else {
        EXPECT_EQ(r.body, -1);
        for (const rigid::BodyState& y : data.Y) ASSERT_TRUE(rigid::isFinite(y));
      }
    }
    EXPECT_TRUE(refused) << "the state never overflowed";
  }
}

// A derivative near the largest double must not overflow inside the RK4 combination
// when the step's result is finite: 1e308 N on 1 kg for 1e-150 s gives P = 1e158 kg m/s
// (and moves the body 5e7 m, inside the 1e12 m that a state may reach).
TEST(Dynamics, Rk4TakesAFiniteStepUnderAHugeForce) {
  for (rigid::Method method : {rigid::Method::RK4, rigid::Method::Euler}) {
    SCOPED_TRACE(rigid::methodName(method));
    rigid::WorldModel model = world(method, Vec3::Zero());
    model.bodies.push_back(sphereBody("b", 0.1, 1.0));
    rigid::WorldData data = rigid::initialData(model);
    data.input[0].force = Vec3(1e308, 0.0, 0.0);
    const rigid::StepResult r = rigid::step(model, data, 1e-150);
    ASSERT_TRUE(r.ok);
    EXPECT_NEAR(data.Y[0].P.x() / 1e158, 1.0, 1e-12);
  }
}

TEST(Dynamics, AuxiliariesFromState) {
  rigid::WorldModel model = world(rigid::Method::RK4, Vec3(0, 0, -9.81));
  rigid::BodyConstants b;
  b.name = "b";
  b.shape.type = rigid::ShapeType::Box;
  b.shape.size = Vec3(0.3, 0.5, 0.7);
  const double m = 2.5;
  rigid::setMass(b, m);
  Mat3 Ibody;
  Ibody << 0.9, 0.12, -0.05,
           0.12, 0.7, 0.08,
          -0.05, 0.08, 0.5;
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
TEST(Dynamics, LieRk4KeepsTheQuaternionUnitByConstruction) {
  for (rigid::Method method : {rigid::Method::LieRK4, rigid::Method::RK4}) {
    rigid::WorldModel model = world(method, Vec3::Zero());
    rigid::BodyConstants b = asymmetricBody(Vec3(1.0, 2.0, 3.0), 1.0);
    b.start.angularVelocity = Vec3(0.3, 8.0, 0.2);
    model.bodies.push_back(b);
    rigid::WorldData data = rigid::initialData(model);
    std::vector<rigid::BodyState> next(1);
    double drift = 0.0;
    for (int k = 0; k < 1000; ++k) {
      rigid::integrate(model, data, 1e-2, next);  // q as the method leaves it
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
TEST(Dynamics, SplittingKeepsAngularMomentumWithNonDiagonalInertia) {
  rigid::WorldModel model = world(rigid::Method::Splitting, Vec3::Zero());
  rigid::BodyConstants b = asymmetricBody(Vec3(1.0, 2.0, 3.0), 1.0);
  Mat3 I;
  I << 1.5, 0.2, -0.1,
       0.2, 2.0, 0.3,
      -0.1, 0.3, 2.5;
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
