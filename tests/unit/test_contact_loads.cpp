// The contact loads (WorldData::contactLoads): the contact impulses over a stretch of
// steps divided by its length are, at rest, each body's support and the weight on the
// floor (statics), asleep or awake; sliding, the kinetic friction mu_k N.
#include <gtest/gtest.h>

#include <string>

#include "contact_scenes.h"

namespace {

using namespace test_scenes;

Vec3 meanForce(const Sim& sim, int body) {
  return sim.data.contactLoads.impulse[body] / sim.data.contactLoads.duration;
}
Vec3 meanTorque(const Sim& sim, int body) {
  return sim.data.contactLoads.angularImpulse[body] / sim.data.contactLoads.duration;
}
Vec3 floorForce(const Sim& sim) { return sim.data.contactLoads.surfaceImpulse[0] / sim.data.contactLoads.duration; }

// Two cubes of 2 and 3 kg stacked on the floor: the lower one's contacts give it
// (m1 + m2) g up from the floor and m2 g down from the upper, net m1 g; the upper's m2 g;
// the floor bears (m1 + m2) g. Awake, and asleep (the loads of their last awake step).
TEST(ContactLoads, AStackAtRestIsHeldByItsWeightAwakeAndAsleep) {
  for (bool sleep : {false, true}) {
    SCOPED_TRACE(sleep);
    json lower = box("lower", Vec3::Constant(kEdge), Vec3(0, 0, 0.5 * kEdge));
    json upper = box("upper", Vec3::Constant(kEdge), Vec3(0, 0, 1.5 * kEdge));
    lower["mass"] = 2.0;
    upper["mass"] = 3.0;
    json scene = sceneOf(json::array({lower, upper}), {floorSurface()});
    scene["solver"]["sleep"] = sleep;
    Sim sim(scene);
    sim.run(1.0);
    EXPECT_EQ(sim.data.sleep.sleeping, sleep ? 2 : 0);
    rigid::clearContactLoads(sim.data);
    sim.run(0.2);
    EXPECT_NEAR(sim.data.contactLoads.duration, 0.2, 1e-12);
    const double w1 = 2.0 * kG, w2 = 3.0 * kG;
    EXPECT_LT((meanForce(sim, 0) - Vec3(0, 0, w1)).norm(), 1e-6 * w1);
    EXPECT_LT((meanForce(sim, 1) - Vec3(0, 0, w2)).norm(), 1e-6 * w2);
    EXPECT_LT((floorForce(sim) - Vec3(0, 0, -(w1 + w2))).norm(), 1e-6 * (w1 + w2));
    for (int i = 0; i < 2; ++i) EXPECT_LT(meanTorque(sim, i).norm(), 1e-6 * w2 * kEdge) << i;
  }
}

// A cube sliding at 2 m/s on a floor (mu_k 0.3 both sides, so 0.3): over 0.1 s of the
// slide the contacts give it mu_k m g against the motion and m g up.
TEST(ContactLoads, ASlidingBoxFeelsKineticFrictionAgainstItsMotion) {
  const double mu = 0.3, m = 1.0;
  json cube = box("cube", Vec3::Constant(kEdge), Vec3(0, 0, 0.5 * kEdge), Quat::Identity(), 0.0, 0.5, mu);
  cube["velocity"] = {2.0, 0, 0};
  Sim sim(sceneOf(cube, {floorSurface(0.5, mu)}));
  sim.run(0.05);
  rigid::clearContactLoads(sim.data);
  sim.run(0.1);
  ASSERT_GT(sim.data.aux[0].V.x(), 1.0);  // still sliding
  EXPECT_LT((meanForce(sim, 0) - Vec3(-mu * m * kG, 0, m * kG)).norm(), 1e-6 * m * kG);
  EXPECT_LT((floorForce(sim) - Vec3(mu * m * kG, 0, -m * kG)).norm(), 1e-6 * m * kG);
}

}  // namespace
