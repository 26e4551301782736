// Sleeping islands (sleep.h): a pile at rest falls asleep and holds its pose exactly;
// it wakes, with the closed form's motion, when an awake body strikes it or an input
// drives it; bodies that do not rest on a surface never sleep.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "contact_scenes.h"
#include "sleep.h"

namespace {

using namespace test_scenes;

json sleeping(json scene) {
  scene["solver"]["sleep"] = true;
  return scene;
}

int asleep(const Sim& sim) { return sim.data.sleep.sleeping; }

TEST(Sleep, AStackAtRestFallsAsleepAndHoldsItsPoseExactly) {
  json bodies = json::array();
  for (int i = 0; i < 3; ++i)
    bodies.push_back(box("c" + std::to_string(i), Vec3::Constant(kEdge), Vec3(0, 0, kEdge * (0.5 + i))));
  Sim sim(sleeping(sceneOf(bodies, {floorSurface()})));
  sim.run(0.45);
  EXPECT_EQ(asleep(sim), 0);  // still for less than the sleep time (0.5 s)
  sim.run(0.1);
  ASSERT_EQ(asleep(sim), 3);
  const std::vector<rigid::BodyState> held = sim.data.Y;
  const std::vector<int> contacts = sim.data.contacts;
  sim.run(10.0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(sim.data.Y[i].X, held[i].X) << i;  // bitwise: no drift at all
    EXPECT_EQ(sim.data.Y[i].q.coeffs(), held[i].q.coeffs()) << i;
    EXPECT_TRUE(sim.data.Y[i].P.isZero(0.0) && sim.data.Y[i].L.isZero(0.0)) << i;
    EXPECT_NEAR(sim.data.Y[i].X.z(), kEdge * (0.5 + i), 3e-4) << i;  // on its seats (sinking under 0.1 mm each)
    EXPECT_EQ(sim.data.contacts[i], contacts[i]) << i;
    EXPECT_GT(contacts[i], 0) << i;
  }
}

// Box B slides on a frictionless floor at v0 into box A, asleep: A wakes and the
// inelastic impact of equal masses leaves both at v0 / 2 (momentum conservation).
TEST(Sleep, ASleepingBodyStruckByAnAwakeOneWakesAndTakesTheImpact) {
  const double v0 = 1.0;
  json a = box("a", Vec3::Constant(kEdge), Vec3(0, 0, 0.5 * kEdge), Quat::Identity(), 0.0, 0.0, 0.0);
  json b = box("b", Vec3::Constant(kEdge), Vec3(-1.0, 0, 0.5 * kEdge), Quat::Identity(), 0.0, 0.0, 0.0);
  b["velocity"] = {v0, 0, 0};
  Sim sim(sleeping(sceneOf(json::array({a, b}), {floorSurface(0.0, 0.0)})));
  sim.run(0.8);  // b is 0.1 m from a
  ASSERT_TRUE(sim.data.sleep.asleep[0]);
  ASSERT_FALSE(sim.data.sleep.asleep[1]);
  sim.run(0.4);
  EXPECT_FALSE(sim.data.sleep.asleep[0]);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(sim.data.aux[i].V.x(), 0.5 * v0, 1e-6) << i;
    EXPECT_NEAR(sim.data.aux[i].V.y(), 0.0, 1e-9) << i;
    EXPECT_LT(sim.data.aux[i].omega.norm(), 1e-6) << i;
  }
}

// A sleeping box on a floor of mu = 0.5 driven by a force above static friction's limit
// wakes at the next step and accelerates at a = (F - mu m g) / m from where it slept,
// moved by the sub-steps of h/4 as every body in contact (symplectic Euler, first
// order): x = a t (t + h/4) / 2.
TEST(Sleep, AnInputForceWakesASleepingBodyWhichThenSlidesAsTheClosedFormSays) {
  const double mu = 0.5, F = 10.0, t = 0.5;
  Sim sim(sleeping(sceneOf(box("cube", Vec3::Constant(kEdge), Vec3(0, 0, 0.5 * kEdge), Quat::Identity(), 0.0, mu, mu),
                           {floorSurface(mu, mu)})));
  sim.run(1.0);
  ASSERT_EQ(asleep(sim), 1);
  const double x0 = sim.data.Y[0].X.x();
  sim.data.input[0].force = Vec3(F, 0, 0);
  sim.run(t);
  EXPECT_EQ(asleep(sim), 0);
  const double a = F - mu * kG;
  EXPECT_NEAR(sim.data.Y[0].X.x() - x0, 0.5 * a * t * (t + 0.25 * sim.model.maxStep), 1e-6);
  EXPECT_NEAR(sim.data.aux[0].V.x(), a * t, 1e-6);
}

// A box asleep on a conveyor at rest wakes at the next step once the belt is set
// moving, and is carried: it rides at the belt's speed. On a belt slower than the sleep
// speed it never falls asleep: it moves.
TEST(Sleep, ABoxOnAConveyorWakesWhenTheBeltStartsAndNeverSleepsOnAMovingOne) {
  const double mu = 0.5;
  json floor = floorSurface(mu, mu);
  floor["beltVelocity"] = {0, 0, 0};
  json cube = box("cube", Vec3::Constant(kEdge), Vec3(0, 0, 0.5 * kEdge), Quat::Identity(), 0.0, mu, mu);
  Sim sim(sleeping(sceneOf(cube, {floor})));
  sim.run(1.0);
  ASSERT_EQ(asleep(sim), 1);
  sim.data.beltVelocity[0] = Vec3(0.5, 0, 0);
  sim.run(sim.model.maxStep);
  EXPECT_EQ(asleep(sim), 0);
  sim.run(0.5);  // it reaches the belt's speed after 0.5 / (mu g) = 0.1 s
  EXPECT_NEAR(sim.data.aux[0].V.x(), 0.5, 1e-9);
  const double slow = 0.5 * sim.model.sleep.speed, x0 = sim.data.Y[0].X.x();
  sim.data.beltVelocity[0] = Vec3(slow, 0, 0);
  sim.run(5.0, [&] { ASSERT_EQ(asleep(sim), 0); });
  // carried 5 s at the slow speed, having slid (0.5 - slow)^2 / (2 mu g) as it slowed
  const double slid = (0.5 - slow) * (0.5 - slow) / (2.0 * mu * kG);
  EXPECT_NEAR(sim.data.Y[0].X.x() - x0, 5.0 * slow + slid, 0.01 * slid);
}

// A cube turning slowly in space (its points at 4.3 mm/s, below the sleep speed) turns
// on at its rate: only what rests on a surface sleeps.
TEST(Sleep, ABodyFloatingFreeNeverSleepsHoweverSlowly) {
  const double w = 0.05;  // rad/s about z; a cube's inertia is spherical, so w stays
  json cube = box("cube", Vec3::Constant(kEdge), Vec3(0, 0, 1.0));
  cube["angularVelocity"] = {0, 0, w};
  json scene = sleeping(sceneOf(cube, {floorSurface()}));
  scene["gravity"] = {0, 0, 0};
  Sim sim(scene);
  sim.run(2.0);
  EXPECT_EQ(asleep(sim), 0);
  const Quat expected(Eigen::AngleAxisd(w * 2.0, Vec3::UnitZ()));
  EXPECT_LT(sim.data.Y[0].q.angularDistance(expected), 1e-9);
}

// Sleeping islands cost nothing: once a pile sleeps, a step neither integrates its
// bodies nor places their boxes; a box sliding far from it is the only body integrated
// and detected, and the pile's contact memory waits in the sleep state.
TEST(Sleep, ASleepingPileIsNeitherIntegratedNorBoxed) {
  json bodies = pile(8, 2);
  json slider = box("slider", Vec3::Constant(kEdge), Vec3(5.0, 0, 0.5 * kEdge), Quat::Identity(), 0.0, 0.0, 0.0);
  slider["velocity"] = {0.5, 0, 0};
  bodies.push_back(slider);  // frictionless: the pair's friction is the partners' geometric mean
  Sim sim(sleeping(sceneOf(bodies, {floorSurface()}, 2e-3)));
  sim.run(3.0);
  ASSERT_EQ(asleep(sim), 8);
  EXPECT_TRUE(sim.data.contactMemory.empty() || sim.data.contactMemory.front().a == 8);
  EXPECT_FALSE(sim.data.sleep.memory.empty());
  sim.data.profiling = true;
  sim.run(1.0);
  const rigid::StepProfile& p = sim.data.profile;
  EXPECT_EQ(p.integrated, p.steps);  // the slider alone
  EXPECT_EQ(p.boxes, p.steps);       // its box alone, once a step (nothing bounces)
  EXPECT_EQ(asleep(sim), 8);
  for (const rigid::ContactMemory& m : sim.data.contactMemory) EXPECT_EQ(m.a, 8);
}

// A world whose every body that meets something sleeps has nothing to detect or solve.
TEST(Sleep, AWorldAsleepDetectsAndSolvesNothing) {
  Sim sim(sleeping(sceneOf(pile(8, 2), {floorSurface()}, 2e-3)));
  sim.run(3.0);
  ASSERT_EQ(asleep(sim), 8);
  sim.data.profiling = true;
  sim.run(0.5);
  const rigid::StepProfile& p = sim.data.profile;
  EXPECT_EQ(p.integrated, 0);
  EXPECT_EQ(p.broadphase, 0.0);
  EXPECT_EQ(p.solves, 0);
}

TEST(Sleep, WithSleepOffABodyAtRestStaysAwake) {
  Sim sim(sceneOf(box("cube", Vec3::Constant(kEdge), Vec3(0, 0, 0.5 * kEdge)), {floorSurface()}));
  sim.run(2.0);
  EXPECT_EQ(asleep(sim), 0);
}

// A copy of the data taken while the island is growing still continues bitwise as the
// original does, through falling asleep and a wake by an input.
TEST(Sleep, ACopyContinuesBitwiseThroughSleepAndWaking) {
  Sim sim(sleeping(sceneOf(pile(8, 2), {floorSurface()}, 2e-3)));
  sim.run(0.5);
  Sim copy = sim;
  auto drive = [](Sim& s) {
    s.run(2.5);
    EXPECT_GT(asleep(s), 0);
    s.data.input[0].force = Vec3(0, 0, 30.0);
    s.run(0.5);
  };
  drive(sim);
  drive(copy);
  for (size_t i = 0; i < sim.data.Y.size(); ++i) {
    EXPECT_EQ(sim.data.Y[i].X, copy.data.Y[i].X) << i;
    EXPECT_EQ(sim.data.Y[i].L, copy.data.Y[i].L) << i;
    EXPECT_EQ(sim.data.sleep.asleep[i], copy.data.sleep.asleep[i]) << i;
  }
}

}  // namespace
