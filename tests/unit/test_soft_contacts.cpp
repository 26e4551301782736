// The soft sub-steps (solver.contacts = "soft", src/soft_contacts.h), an experimental
// contact solver beside the default: what it is already held to. Resting and landing
// cubes at their face-down height, a stack that stands and rests, kinetic and static
// friction on a ramp, next to no energy gained through contact (a looser bound than the
// default's), and a bound on the passes of every solve.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "contact_scenes.h"
#include "contact_solver.h"
#include "world.h"

namespace {

using namespace test_scenes;

json soft(json scene) {
  scene["solver"]["contacts"] = "soft";
  return scene;
}

constexpr double kStep = 2e-3;  // s, the benchmark's piles' step

// A cube set down touching the floor rests at its face-down height: an overlap within
// kSoftSlop is held rigidly, so it neither sinks nor rises.
TEST(SoftContacts, CubeSetDownRestsAtItsFaceDownHeight) {
  Sim sim(soft(sceneOf(box("cube", Vec3::Constant(kEdge), Vec3(0, 0, 0.5 * kEdge)), {floorSurface()}, kStep)));
  sim.run(1.0);
  EXPECT_NEAR(sim.data.Y[0].X.z(), 0.5 * kEdge, rigid::contact_solver::kSoftSlop);
  EXPECT_LT(sim.fastest(), 1e-3);
  EXPECT_LT(sim.data.aux[0].omega.norm(), 1e-2);
}

// Dropped from 0.3 m (2.4 m/s at the floor, 5 mm a step), a cube is caught by its
// speculative points: it neither sinks in nor bounces, and rests face down.
TEST(SoftContacts, CubeDroppedLandsWithoutSinkingAndRests) {
  Sim sim(soft(sceneOf(box("cube", Vec3::Constant(kEdge), Vec3(0, 0, 0.3 + 0.5 * kEdge)), {floorSurface()}, kStep)));
  double deepest = 0.0;
  sim.run(1.0, [&] { deepest = std::max(deepest, sim.deepestOverlap()); });
  EXPECT_LT(deepest, 1e-3);
  EXPECT_NEAR(sim.data.Y[0].X.z(), 0.5 * kEdge, rigid::contact_solver::kSoftSlop);
  EXPECT_LT(sim.fastest(), 1e-3);
  std::printf("deepest overlap %.3g m\n", deepest);
}

// A stack of ten cubes set down touching: every cube within 1 mm of where it was at
// 0.5 s after 10 s, no overlap deeper than 1 mm, and no cube faster than 1 mm/s at the
// end.
TEST(SoftContacts, StackOfTenCubesStands) {
  json bodies = json::array();
  for (int i = 0; i < 10; ++i)
    bodies.push_back(box("c" + std::to_string(i), Vec3::Constant(kEdge), Vec3(0, 0, kEdge * (0.5 + i))));
  Sim sim(soft(sceneOf(bodies, {floorSurface()}, kStep)));
  const double drift = driftAfterSettling(sim, 0.5, 9.5);
  EXPECT_LT(drift, 1e-3);
  EXPECT_LT(sim.deepestOverlap(), 1e-3);
  EXPECT_LT(sim.fastest(), 1e-3);
  std::printf("drift %.3g m, fastest %.3g m/s at 10 s\n", drift, sim.fastest());
}

// A cube on a 30 deg ramp (tan 30 deg > mu_s = 0.5) slides from the first steps with
// a = g (sin(theta) - mu_k cos(theta)): within 0.5 % over 2 s. Each step's impulses sum
// four sub-steps'; the pair is judged sliding from the last sub-step's friction, on the
// edge of its disc (the sum of sub-steps whose directions turn need not be).
TEST(SoftContacts, CubeDownARampSlidesWithKineticFriction) {
  const double theta = 30.0 * 3.14159265358979323846 / 180.0, T = 2.0;
  const Quat turn(Eigen::AngleAxisd(theta, Vec3::UnitY()));
  const Vec3 start = (0.5 + 0.1) * (turn * Vec3::UnitZ());
  Sim sim(soft(sceneOf(box("cube", Vec3::Constant(0.2), start, turn, 0.0, 0.5, 0.3), rampSurface(turn, 0.5, 0.3))));
  sim.run(T);
  const double expected = 0.5 * kG * (std::sin(theta) - 0.3 * std::cos(theta)) * T * T;
  EXPECT_NEAR((sim.data.Y[0].X - start).dot(turn * Vec3::UnitX()), expected, 5e-3 * expected);
}

// Just below the limit (tan(theta) = 0.499, mu_s = 0.5) static friction holds the cube:
// after it seats (0.5 s) it does not creep over 10 s. With the overlap within the slop
// soft too (a damper), it crept 53 um as it sank.
TEST(SoftContacts, StaticFrictionHoldsACubeOnARampJustBelowItsLimit) {
  const double theta = std::atan(0.5 - 1e-3);
  const Quat turn(Eigen::AngleAxisd(theta, Vec3::UnitY()));
  const Vec3 start = (0.5 + 0.1) * (turn * Vec3::UnitZ()), down = turn * Vec3::UnitX();
  Sim sim(soft(sceneOf(box("cube", Vec3::Constant(0.2), start, turn, 0.0, 0.5, 0.3), rampSurface(turn, 0.5, 0.3))));
  sim.run(0.5);
  const double seated = (sim.data.Y[0].X - start).dot(down);
  sim.run(10.0);
  EXPECT_LT(std::abs(seated), 1e-5);
  EXPECT_LT(std::abs((sim.data.Y[0].X - start).dot(down) - seated), 1e-9);
}

// Contact alone adds next to no mechanical energy: through a falling, tumbling pile of
// 27 (55.6 J) no step ends with more than the last one's plus 1e-3 J, and the run ends
// below its start. The default solver is held to 1e-5 J; this one measured 3.2e-4 J, a
// gap to close before it can be the default.
TEST(SoftContacts, MechanicalEnergyNeverRisesThroughContact) {
  Sim sim(soft(sceneOf(pile(27, 3), {floorSurface()}, kStep)));
  const EnergyRun e = runWatchingEnergy(sim, 1.5);
  EXPECT_LT(e.worstRise, 1e-3);
  EXPECT_LT(e.end, e.start);
}

// The cost of a solve does not grow with how hard it is: no solve of a falling pile
// takes more passes than kSoftSubsteps x (solve + relax passes), and the first
// sub-step's longer relax in a step with new points, where the default solver's passes
// run to their tolerance (up to 60 while a tall pile settles). A phase stops early only
// once a pass changes nothing: at rest, one pass a phase.
TEST(SoftContacts, NoSolveTakesMoreThanItsPasses) {
  using namespace rigid::contact_solver;
  Sim sim(soft(sceneOf(pile(27, 3), {floorSurface()}, kStep)));
  sim.data.profiling = true;
  const long most = kSoftSubsteps * (kSoftSolvePasses + kSoftRelaxPasses) + kSoftFreshRelaxPasses - kSoftRelaxPasses;
  long iterations = 0, solves = 0, busiest = 0;
  sim.run(1.0, [&] {
    const long taken = sim.data.profile.iterations - iterations, count = sim.data.profile.solves - solves;
    if (count > 0) busiest = std::max(busiest, taken / count);
    iterations = sim.data.profile.iterations, solves = sim.data.profile.solves;
  });
  ASSERT_GT(solves, 0);
  EXPECT_LE(busiest, most);
  EXPECT_GT(busiest, kSoftSubsteps * 2);  // a falling pile is not solved in one pass a phase
  std::printf("busiest solve %ld passes, %.1f per solve on average\n", busiest,
              static_cast<double>(iterations) / static_cast<double>(solves));
}

}  // namespace
