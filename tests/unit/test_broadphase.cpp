// The broadphase (sort and sweep in the rows of a grid) against the brute-force test of
// every pair of boxes, over calls in which the boxes move (the kept order is sorted
// again), the axis of largest spread changes and the boxes grow (the cells change),
// with large boxes (a floor, slabs) kept out of the grid, boxes touching exactly across
// cell boundaries, and boxes so far away that their cell indices are clamped; and the
// sleeping bodies' fixed boxes asked by moving ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <tuple>
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

TEST(Broadphase, LatticeTouchingAcrossCellsAndFarBoxes) {
  // a lattice of cubes touching face to face, edge to edge and corner to corner, as a
  // settled pile: every neighbour pair lies across a row boundary somewhere
  const double pitch = 0.125;  // binary: the touching faces meet exactly
  std::vector<Vec3> lo, hi;
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 5; ++k) {
        const Vec3 c(i * pitch - 0.375, j * pitch + 0.0625, k * pitch);
        lo.push_back(c - Vec3::Constant(pitch / 2));
        hi.push_back(c + Vec3::Constant(pitch / 2));
      }
  const int lattice = static_cast<int>(lo.size());
  // far away: beyond the clamped cell indices (1e9 cells of about 0.125 m) and beyond
  // what a 64-bit cell index holds, on both sides; the first two overlap each other
  for (const double x : {1e20, 1e20 + 0.05, -3e19, 5e8}) {
    lo.push_back(Vec3(x, x, 1.0));
    hi.push_back(Vec3(x + 0.1, x + 0.1, 1.1));
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  rigid::SweepAndPrune sap;
  std::vector<std::pair<int, int>> found;
  for (int call = 0; call < 40; ++call) {
    // from call 10 on the lattice jitters and its boxes grow (the cell widens in steps),
    // from call 25 a third of it drifts across rows each call
    for (int b = 0; call >= 10 && b < lattice; ++b) {
      const Vec3 move = 0.002 * Vec3(unit(rng), unit(rng), unit(rng)) +
                        (call >= 25 && b % 3 == 0 ? Vec3(0.03, 0.0, -0.04) : Vec3::Zero());
      lo[b] += move - Vec3::Constant(0.001 * (call - 9));
      hi[b] += move + Vec3::Constant(0.001 * (call - 9));
    }
    sap.overlaps(lo, hi, found);
    std::sort(found.begin(), found.end());
    ASSERT_EQ(found, bruteForce(lo, hi)) << "call " << call;
    if (call == 0) {
      // the settled lattice: every pair of cubes whose lattice indices differ by at most
      // one on each axis touches, Σ over the 13 directions d of Π (size - |d|) pairs;
      // and the one far pair
      const int size[3] = {7, 6, 5};
      int touching = 0;
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz)
            if (std::make_tuple(dx, dy, dz) > std::make_tuple(0, 0, 0))
              touching += (size[0] - std::abs(dx)) * (size[1] - std::abs(dy)) * (size[2] - std::abs(dz));
      EXPECT_EQ(static_cast<int>(found.size()), touching + 1);
      EXPECT_TRUE(std::binary_search(found.begin(), found.end(), std::make_pair(lattice, lattice + 1)));
    }
  }
}

TEST(Broadphase, FewerThanTwoBoxesHaveNoPairs) {
  rigid::SweepAndPrune sap;
  std::vector<std::pair<int, int>> found = {{0, 1}};
  sap.overlaps({}, {}, found);
  EXPECT_TRUE(found.empty());
  sap.overlaps({Vec3::Zero()}, {Vec3::Ones()}, found);
  EXPECT_TRUE(found.empty());
}

// Fixed boxes (the sleeping bodies') asked by moving ones: exactly the brute force's
// overlaps, for queries of every size (a small box, one spanning many cells, one wider
// than the whole set), boxes touching exactly, a large fixed slab kept out of the grid,
// and boxes far enough away that their cells are clamped.
TEST(Broadphase, FixedBoxesAnswerEveryQueryAsTheBruteForceDoes) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int n = 300;
  std::vector<int> ids(n);
  std::vector<Vec3> lo(n), hi(n);
  for (int k = 0; k < n; ++k) {
    ids[k] = 1000 + 3 * k;
    const Vec3 c(unit(rng), unit(rng), unit(rng));
    const Vec3 half(0.01 + 0.03 * unit(rng), 0.01 + 0.03 * unit(rng), 0.01 + 0.03 * unit(rng));
    lo[k] = c - half, hi[k] = c + half;
  }
  lo[0] = Vec3(-5, -5, -1), hi[0] = Vec3(5, 5, 0.02);               // a slab under everything
  lo[1] = Vec3(1e12, 0, 0), hi[1] = Vec3(1e12 + 0.05, 0.05, 0.05);  // clamped cells
  const rigid::FixedBoxes fixed(ids, lo, hi);
  std::vector<int> found;
  size_t total = 0;
  for (int q = 0; q < 400; ++q) {
    const double size = q < 300 ? 0.05 * unit(rng) : q < 390 ? 0.5 * unit(rng) : 10.0;
    const Vec3 c(1.2 * unit(rng) - 0.1, 1.2 * unit(rng) - 0.1, 1.2 * unit(rng) - 0.1);
    Vec3 qlo = c - Vec3::Constant(size), qhi = c + Vec3::Constant(size);
    if (q == 0) qlo = Vec3(hi[5].x(), lo[5].y(), lo[5].z()), qhi = qlo + Vec3::Constant(0.01);  // touching
    if (q == 1) qlo = Vec3(1e12 - 1, -1, -1), qhi = Vec3(1e12 + 1, 1, 1);
    found.clear();
    fixed.overlapping(qlo, qhi, found);
    std::sort(found.begin(), found.end());
    std::vector<int> expected;
    for (int k = 0; k < n; ++k)
      if ((lo[k].array() <= qhi.array()).all() && (qlo.array() <= hi[k].array()).all()) expected.push_back(ids[k]);
    ASSERT_EQ(found, expected) << "query " << q;
    total += expected.size();
  }
  EXPECT_GT(total, 400u);  // the queries met boxes, not an empty world
}
