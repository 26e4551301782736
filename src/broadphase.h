// Candidate pairs of a step: the axis-aligned boxes that overlap, by sort and sweep in
// the rows of a grid.
#pragma once

#include <utility>
#include <vector>

#include "math_types.h"

namespace rigid {

// One sweep axis (the one along which the boxes' centres spread most) and, across it, a
// grid of square cells as wide as the widest box: each box belongs to the row of cells
// holding its lower corner, so two boxes can overlap only in the same or neighbouring
// rows. Each row's boxes are sorted by their lower bound on the sweep axis, and a box is
// compared only with the boxes of its row and the four rows after it that start before
// it ends there. The order is kept between calls and sorted again by insertion: bodies
// move little in a step, so that sort is close to linear.
//
// A single sweep compares each box with every box of its slab across the sweep axis:
// about N^(2/3) boxes in a pile, which made the pile of 1000 cubes cost 35 times the
// pile of 100. In rows, each box meets a bounded number of neighbours.
//
// Boxes more than four times as wide as the median box (floors, slabs) would widen
// every cell: they are kept out of the grid and tested against every box.
//
// (On the benchmark's pile of 1000 cubes, FCL's dynamic AABB tree took 0.7-0.9 ms a
// step, its SSaP and interval-tree managers 1.4 and 4.5 ms, its SaP did not finish a
// run, one sweep along one axis 0.3-0.5 ms.)
class SweepAndPrune {
 public:
  // The pairs (i, j), i < j, of boxes [lo, hi] that overlap on all three axes
  // (touching counts), into out (cleared first), in no particular order.
  void overlaps(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi, std::vector<std::pair<int, int>>& out);

 private:
  struct Row {
    long long v, u;  // cell indices across the sweep axis
    int begin;       // where its boxes start in order_
  };
  void chooseCells(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi);
  void sortIntoRows(const std::vector<Vec3>& lo);
  void sweepRow(int begin, int end, std::vector<std::pair<int, int>>& out) const;
  void sweepRows(int beginA, int endA, int beginB, int endB, std::vector<std::pair<int, int>>& out) const;
  void testLarge(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi, std::vector<std::pair<int, int>>& out) const;
  void test(int k, int m, std::vector<std::pair<int, int>>& out) const;

  int axis_ = -1;                       // the sweep axis
  double cell_ = 0.0;                   // width of a cell across it
  std::vector<int> large_;              // boxes kept out of the grid, ascending
  std::vector<char> isLarge_;           // per box
  std::vector<long long> rowV_, rowU_;  // per box: its row's cell indices
  std::vector<int> order_;              // the boxes of the grid, by row, then lower bound on the sweep axis
  std::vector<Row> rows_;               // the rows in that order, then one past the last
  std::vector<double> width_;           // scratch: the boxes' widest extents, for their median
  double median_ = 0.0;                 // the median box's widest extent when last found
  int sinceMedian_ = 0;                 // calls since
  // in order_'s order: lower and upper bounds on the sweep axis, then on the other two
  std::vector<double> sorted_[6];
};

// Boxes that do not move (the sleeping bodies'), asked which of them a moving box
// overlaps: Box2D keeps sleeping bodies' proxies in its tree and only moving proxies
// query it; this is that, in a hash grid. Each box sits in the cell of its lower corner
// (cells as wide as the widest box), so a query visits the cells from its lower corner
// less one cell to its upper corner. Boxes wider than four median boxes are kept apart
// and tested by every query. Built once when the set changes (an island falls asleep or
// wakes); a query costs the boxes near it, whatever the number asleep elsewhere.
class FixedBoxes {
 public:
  // The boxes [lo[k], hi[k]] named ids[k].
  FixedBoxes(const std::vector<int>& ids, const std::vector<Vec3>& lo, const std::vector<Vec3>& hi);
  // Appends to out the ids of the boxes that overlap [lo, hi] (touching counts).
  void overlapping(const Vec3& lo, const Vec3& hi, std::vector<int>& out) const;

 private:
  struct Entry {
    long long x, y, z;  // the cell of the box's lower corner
    int box;
    bool operator<(const Entry& o) const;
  };
  void test(int box, const Vec3& lo, const Vec3& hi, std::vector<int>& out) const;

  double cell_ = 1.0;
  std::vector<int> ids_;
  std::vector<Vec3> lo_, hi_;
  std::vector<Entry> grid_;  // sorted by cell
  std::vector<int> large_;   // boxes out of the grid
};

}  // namespace rigid
