// Candidate pairs of a step: the axis-aligned boxes that overlap, by sort and sweep.
#pragma once

#include <utility>
#include <vector>

#include "math_types.h"

namespace rigid {

// Boxes are sorted by their lower bound on one axis, the one along which their centres
// spread most, and each box is compared only with the boxes that start before it ends
// there. The order is kept between calls and sorted again by insertion: bodies move
// little in a step, so that sort is close to linear. (On the benchmark's pile of 1000
// cubes, with the rest of the code as it was, FCL's dynamic AABB tree took 0.7-0.9 ms
// a step, its SSaP and interval-tree managers 1.4 and 4.5 ms, its SaP did not finish a
// run, and this sweep took 0.5 ms.)
class SweepAndPrune {
 public:
  // The pairs (i, j), i < j, of boxes [lo, hi] that overlap on all three axes
  // (touching counts), into out (cleared first), in no particular order.
  void overlaps(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi, std::vector<std::pair<int, int>>& out);

 private:
  using Bounds = std::vector<double>;
  std::vector<int> order_;   // box indices by lower bound on axis_
  // in that order: lower and upper bounds on the sweep axis, then on the other two
  Bounds sorted_[6];
  int axis_ = -1;
};

}  // namespace rigid
