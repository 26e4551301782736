// The Newton velocity stage (solver.contacts = "newton", src/newton_contacts.h), an
// experimental contact solver beside the default: what it does that the passes do not.
// The default's whole contact suite also runs with it (ctest newton_contact_suite,
// RIGID_CONTACTS=newton), less the two tests it does not pass yet (CMakeLists.txt).
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>

#include "contact_scenes.h"
#include "world.h"

namespace {

using namespace test_scenes;

constexpr double kPileStep = 2e-3;  // s, the benchmark's piles' step

// A column of ten cubes set down touching rests still: at rest the answer is every
// cube at 0 m/s, and the solve reaches it (as the default's coarse correction does,
// test_contact_solver.cpp). Once the warm start holds the column, each solve takes one
// Newton iteration.
TEST(NewtonContacts, ColumnOfTenRestsStillInOneIterationPerSolve) {
  Sim sim(withContacts(sceneOf(column(10), {floorSurface()}, kPileStep), "newton"));
  sim.data.profiling = true;
  sim.run(1.0);
  const rigid::StepProfile before = sim.data.profile;
  double fastest = 0.0;
  sim.run(1.0, [&] { fastest = std::max(fastest, sim.fastest()); });
  const rigid::StepProfile& after = sim.data.profile;
  EXPECT_LT(fastest, 1e-12);
  EXPECT_EQ(after.iterations - before.iterations, after.solves - before.solves);
  for (int i = 0; i < 10; ++i) EXPECT_NEAR(sim.data.Y[i].X.z(), kEdge * (0.5 + i), 1e-4) << i;  // the slop
}

// Dropped as in the benchmark (columns of 4, each cube tilted to land on an edge), a
// pile of 16 lands and comes to rest: no overlap beyond 1 mm, every cube below 1 mm/s
// after 2 s.
TEST(NewtonContacts, PileOfSixteenLandsAndRests) {
  Sim sim(withContacts(sceneOf(pile(16, 2), {floorSurface()}, kPileStep), "newton"));
  double deepest = 0.0;
  sim.run(2.0, [&] { deepest = std::max(deepest, sim.deepestOverlap()); });
  EXPECT_LT(deepest, 1e-3);
  EXPECT_LT(sim.fastest(), 1e-3);
}

}  // namespace
