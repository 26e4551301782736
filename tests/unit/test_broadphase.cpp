// The sweep-and-prune broadphase against the brute-force test of every pair of boxes,
// over calls in which the boxes move (the kept order is sorted again) and in which
// the axis of largest spread changes, with a few large boxes (a floor, two slabs)
// among them and boxes on both sides of the origin.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "broadphase.h"

namespace {

using rigid::Vec3;

std::vector<std::pair<int, int>> bruteForce(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi) {
  std::vector<std::pair<int, int>> out;
  for (int a = 0; a < static_cast<int>(lo.size()); ++a)
    for (int b = a + 1; b < static_cast<int>(lo.size()); ++b)
      if ((lo[a].array() <= hi[b].array()).all() && (lo[b].array() <= hi[a].array()).all()) out.emplace_back(a, b);
  return out;
}

}  // namespace

TEST(Broadphase, SweepAndPruneFindsExactlyTheOverlappingPairs) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int n = 400;
  std::vector<Vec3> centre(n), half(n), lo(n), hi(n);
  for (int i = 0; i < n; ++i) {
    centre[i] = Vec3(unit(rng), unit(rng), unit(rng));
    half[i] = Vec3(0.01 + 0.04 * unit(rng), 0.01 + 0.04 * unit(rng), 0.01 + 0.04 * unit(rng));
  }
  rigid::SweepAndPrune sap;
  std::vector<std::pair<int, int>> found;
  size_t total = 0;
  for (int call = 0; call < 30; ++call) {
    // stretch the cloud along x, then along z: the sweep axis changes on the way
    const Vec3 stretch = call < 15 ? Vec3(1.0 + 0.3 * call, 1.0, 1.0) : Vec3(1.0, 1.0, 1.0 + 0.5 * call);
    for (int i = 0; i < n; ++i) {
      centre[i] += 0.01 * Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
      lo[i] = centre[i].cwiseProduct(stretch) - half[i];
      hi[i] = centre[i].cwiseProduct(stretch) + half[i];
    }
    // two boxes touching exactly count as overlapping
    lo[1] = Vec3(hi[0].x(), lo[0].y(), lo[0].z());
    hi[1] = lo[1] + Vec3::Constant(0.02);
    // large boxes: a floor under everything, two slabs crossing the cloud
    lo[2] = Vec3(-10, -10, -1), hi[2] = Vec3(10, 10, 0.05);
    lo[3] = Vec3(-0.5, 0.4, -0.5), hi[3] = Vec3(3.0, 0.45, 3.0);
    lo[4] = Vec3(0.2, -0.5, 0.2), hi[4] = Vec3(0.25, 2.0, 2.0);
    for (int i = 5; i < 40; ++i) lo[i] -= Vec3(0.6, 0.6, 0.6), hi[i] -= Vec3(0.6, 0.6, 0.6);
    sap.overlaps(lo, hi, found);
    std::sort(found.begin(), found.end());
    const std::vector<std::pair<int, int>> expected = bruteForce(lo, hi);
    ASSERT_EQ(found, expected) << "call " << call;
    total += expected.size();
  }
  EXPECT_GT(total, 30u * 20u);  // the check saw many pairs, not an empty world
}

TEST(Broadphase, FewerThanTwoBoxesHaveNoPairs) {
  rigid::SweepAndPrune sap;
  std::vector<std::pair<int, int>> found = {{0, 1}};
  sap.overlaps({}, {}, found);
  EXPECT_TRUE(found.empty());
  sap.overlaps({Vec3::Zero()}, {Vec3::Ones()}, found);
  EXPECT_TRUE(found.empty());
}
