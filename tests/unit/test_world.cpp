// The world's step (src/world.cpp): the energy audit that refuses a method's own
// energy gain, and the refusal of a state that is not finite.
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
using rigid::test::bodyOf;
using rigid::test::sphere;
using rigid::test::world;

}  // namespace

// 2 E = L . I(t)^-1 L, from the auxiliaries (independent of the audit's body-frame form).
namespace {
double twiceEnergy(const rigid::WorldData& data) { return data.Y[0].L.dot(data.aux[0].omega); }
}  // namespace

// The energy audit: explicit Euler's torque-free tumbling gains energy step by step
// (Lie-Euler); the step that would take the gain beyond the limit is refused with the
// body, the gain and a smaller step, and the state is left as it was. The methods that
// keep a free rotation's energy run 1e4 steps under the same limit.
TEST(World, EnergyAuditRefusesExplicitEulersGainOnAFreeRotation) {
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
      EXPECT_EQ(n, 10000) << rigid::causeName(r.cause);
      continue;
    }
    ASSERT_LT(n, 10000) << "explicit Euler was expected to gain energy";
    EXPECT_EQ(r.cause, rigid::StepCause::EnergyGain);
    EXPECT_EQ(r.body, 0);
    EXPECT_GT(r.energyGain, limit);
    EXPECT_GT(r.stableStep, 0.0);
    EXPECT_LT(r.stableStep, 1e-3);
    // Refused, not taken: the state is that of the last accepted step, within the limit.
    const rigid::BodyState before = data.Y[0];
    EXPECT_FALSE(rigid::step(model, data, 1e-3).ok);
    EXPECT_TRUE(before.X == data.Y[0].X && before.q.coeffs() == data.Y[0].q.coeffs() && before.P == data.Y[0].P &&
                before.L == data.Y[0].L);
    EXPECT_LE(twiceEnergy(data) / E0 - 1.0, limit * (1 + 1e-9));
    // Unchecked (0), the same run goes on.
    model.energyGainLimit = 0.0;
    EXPECT_TRUE(rigid::step(model, data, 1e-3).ok);
  }
}

// A torque changes L: those steps are the torque's work, not the method's, and are
// not audited (a spin-up by a constant torque quadruples the energy and is fine).
TEST(World, EnergyAuditLeavesTorquedBodiesAlone) {
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

bool sameState(const rigid::BodyState& a, const rigid::BodyState& b) {
  return a.X == b.X && a.q.coeffs() == b.q.coeffs() && a.P == b.P && a.L == b.L;
}

}  // namespace

// A huge force on a tiny mass: P stays finite but V = P/M overflows, and with it X.
TEST(World, OverflowIsRefusedWithBodyIndexAndStateUnchanged) {
  for (rigid::Method method : {rigid::Method::RK4, rigid::Method::Euler}) {
    SCOPED_TRACE(rigid::methodName(method));
    rigid::WorldModel model = world(method, Vec3(0, 0, -9.81));
    rigid::BodyConstants fine = bodyOf(sphere(0.1), 1.0, "fine");
    fine.start.velocity = Vec3(1.0, 0.0, 0.0);
    fine.start.angularVelocity = Vec3(0.0, 1.0, 0.0);
    model.bodies.push_back(fine);
    model.bodies.push_back(bodyOf(sphere(0.1), 1e-300, "tiny"));
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
TEST(World, Rk4TakesAFiniteStepUnderAHugeForce) {
  for (rigid::Method method : {rigid::Method::RK4, rigid::Method::Euler}) {
    SCOPED_TRACE(rigid::methodName(method));
    rigid::WorldModel model = world(method, Vec3::Zero());
    model.bodies.push_back(bodyOf(sphere(0.1), 1.0, "b"));
    rigid::WorldData data = rigid::initialData(model);
    data.input[0].force = Vec3(1e308, 0.0, 0.0);
    const rigid::StepResult r = rigid::step(model, data, 1e-150);
    ASSERT_TRUE(r.ok);
    EXPECT_NEAR(data.Y[0].P.x() / 1e158, 1.0, 1e-12);
  }
}
