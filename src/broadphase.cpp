#include "broadphase.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace rigid {

namespace {

// Boxes wider than this many median boxes stay out of the grid.
constexpr double kLargeOverMedian = 4.0;
// Calls between two searches for the median box.
constexpr int kMedianCalls = 64;
// Cell widths are powers of 2^(1/4), so that a cell stays the same from step to step
// while the widest box turns (which would regroup the rows and undo the kept order).
constexpr double kCellSteps = 4.0;
// Cell indices are clamped here: far-away boxes share the outermost rows, which is
// slower but still exact (the clamp keeps neighbouring cells neighbours).
constexpr double kMaxCell = 1e9;

// (compares and a cast rather than fmin, fmax and floor: no calls into libm for the two
// cells of every box of every step; NaN lands in the outermost cell, as fmin sends it)
long long cellOf(double x, double cell) {
  double t = x / cell;
  if (!(t < kMaxCell)) t = kMaxCell;
  if (t < -kMaxCell) t = -kMaxCell;
  const auto k = static_cast<long long>(t);  // towards zero
  return static_cast<double>(k) > t ? k - 1 : k;
}

}  // namespace

// Which boxes are large, the cell width and the sweep axis; whatever changed among them
// invalidates the kept order.
void SweepAndPrune::chooseCells(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi) {
  const int n = static_cast<int>(lo.size());
  bool regroup = static_cast<int>(isLarge_.size()) != n;
  // The median box: boxes change width only as they turn (by sqrt 3 at most), so it is
  // found again every kMedianCalls calls, or when the number of boxes changes. Which
  // boxes count as large changes how pairs are found, not which.
  if (regroup || ++sinceMedian_ >= kMedianCalls) {
    width_.resize(n);
    for (int i = 0; i < n; ++i) width_[i] = (hi[i] - lo[i]).maxCoeff();
    std::nth_element(width_.begin(), width_.begin() + n / 2, width_.end());
    median_ = width_[n / 2];
    sinceMedian_ = 0;
  }
  const double limit = kLargeOverMedian * median_;

  isLarge_.resize(n);
  large_.clear();
  double widest = 0.0;
  Vec3 sum = Vec3::Zero(), sum2 = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    const double width = (hi[i] - lo[i]).maxCoeff();
    const char large = width > limit;
    regroup |= large != isLarge_[i];
    isLarge_[i] = large;
    if (large) {
      large_.push_back(i);
      continue;
    }
    widest = std::max(widest, width);
    const Vec3 c = 0.5 * (lo[i] + hi[i]);
    sum += c;
    sum2 += c.cwiseProduct(c);
  }
  // the cell: the widest box rounded up to a step, kept until it is two steps too wide
  // (one would let a box turning across a step's boundary regroup every step)
  widest = std::max(widest, 1e-9);
  if (widest > cell_ || widest * std::exp2(2.0 / kCellSteps) < cell_) {
    cell_ = std::exp2(std::ceil(kCellSteps * std::log2(widest)) / kCellSteps);
    regroup = true;
  }
  // the sweep axis: the one along which the grid's boxes spread most (largest variance)
  const double m = static_cast<double>(std::max<size_t>(1, n - large_.size()));
  const Vec3 variance = sum2 / m - (sum / m).cwiseProduct(sum / m);
  int axis = 0;
  variance.maxCoeff(&axis);
  regroup |= axis != axis_;
  axis_ = axis;
  if (regroup) order_.clear();
}

// order_ by row, then lower bound on the sweep axis; rows_ the rows in that order.
void SweepAndPrune::sortIntoRows(const std::vector<Vec3>& lo) {
  const int n = static_cast<int>(lo.size());
  const int u = (axis_ + 1) % 3, v = (axis_ + 2) % 3;
  rowV_.resize(n);
  rowU_.resize(n);
  for (int i = 0; i < n; ++i) {
    rowV_[i] = cellOf(lo[i][v], cell_);
    rowU_[i] = cellOf(lo[i][u], cell_);
  }
  auto before = [&](int a, int b) {
    return std::tie(rowV_[a], rowU_[a], lo[a][axis_]) < std::tie(rowV_[b], rowU_[b], lo[b][axis_]);
  };
  if (order_.empty()) {
    for (int i = 0; i < n; ++i)
      if (!isLarge_[i]) order_.push_back(i);
    std::sort(order_.begin(), order_.end(), before);
  } else {
    // insertion sort, nearly sorted already; many boxes changing rows at once (a
    // stream of boxes crossing a row) fall back to a full sort
    const int m = static_cast<int>(order_.size());
    long long moves = 0;
    for (int k = 1; k < m && moves <= 8LL * m; ++k) {
      const int box = order_[k];
      int j = k - 1;
      for (; j >= 0 && before(box, order_[j]); --j) order_[j + 1] = order_[j];
      order_[j + 1] = box;
      moves += k - 1 - j;
    }
    if (moves > 8LL * m) std::sort(order_.begin(), order_.end(), before);
  }
  rows_.clear();
  for (int k = 0; k < static_cast<int>(order_.size()); ++k) {
    const int box = order_[k];
    if (rows_.empty() || rows_.back().v != rowV_[box] || rows_.back().u != rowU_[box])
      rows_.push_back(Row{rowV_[box], rowU_[box], k});
  }
  rows_.push_back(Row{0, 0, static_cast<int>(order_.size())});
}

void SweepAndPrune::overlaps(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi,
                             std::vector<std::pair<int, int>>& out) {
  out.clear();
  const int n = static_cast<int>(lo.size());
  if (n < 2) return;
  chooseCells(lo, hi);
  sortIntoRows(lo);
  // The grid's boxes in sweep order, one contiguous array per bound: the inner loops
  // stream through the sweep axis's bounds and read the other two only for boxes they meet.
  const int m = static_cast<int>(order_.size());
  const int u = (axis_ + 1) % 3, v = (axis_ + 2) % 3;
  for (std::vector<double>& b : sorted_) b.resize(m);
  for (int k = 0; k < m; ++k) {
    const Vec3& l = lo[order_[k]];
    const Vec3& h = hi[order_[k]];
    sorted_[0][k] = l[axis_], sorted_[1][k] = h[axis_];
    sorted_[2][k] = l[u], sorted_[3][k] = h[u];
    sorted_[4][k] = l[v], sorted_[5][k] = h[v];
  }
  // Each row with itself, with the next cell in its line, and with the (up to) three
  // cells of the next line beside it: every pair of neighbouring rows once.
  const int nRows = static_cast<int>(rows_.size()) - 1;
  int next = 0;  // the first row of the next line not before the cell diagonally behind
  for (int r = 0; r < nRows; ++r) {
    const Row& row = rows_[r];
    const int end = rows_[r + 1].begin;
    sweepRow(row.begin, end, out);
    if (r + 1 < nRows && rows_[r + 1].v == row.v && rows_[r + 1].u == row.u + 1)
      sweepRows(row.begin, end, rows_[r + 1].begin, rows_[r + 2].begin, out);
    while (next < nRows && std::tie(rows_[next].v, rows_[next].u) < std::make_tuple(row.v + 1, row.u - 1)) ++next;
    for (int q = next; q < nRows && rows_[q].v == row.v + 1 && rows_[q].u <= row.u + 1; ++q)
      sweepRows(row.begin, end, rows_[q].begin, rows_[q + 1].begin, out);
  }
  testLarge(lo, hi, out);
}

// The pair (k, m) of sweep positions whose bounds overlap on the sweep axis: kept when
// they overlap across it too.
inline void SweepAndPrune::test(int k, int m, std::vector<std::pair<int, int>>& out) const {
  const double* loU = sorted_[2].data();
  const double* hiU = sorted_[3].data();
  const double* loV = sorted_[4].data();
  const double* hiV = sorted_[5].data();
  if ((loU[k] <= hiU[m]) & (loU[m] <= hiU[k]) & (loV[k] <= hiV[m]) & (loV[m] <= hiV[k]))
    out.emplace_back(std::min(order_[k], order_[m]), std::max(order_[k], order_[m]));
}

void SweepAndPrune::sweepRow(int begin, int end, std::vector<std::pair<int, int>>& out) const {
  const double* loA = sorted_[0].data();
  const double* hiA = sorted_[1].data();
  for (int k = begin; k < end; ++k)
    for (int m = k + 1; m < end && loA[m] <= hiA[k]; ++m) test(k, m, out);
}

// Two rows, both sorted on the sweep axis: whichever box starts first meets the other
// row's boxes that start before it ends, so each overlapping pair is met once.
void SweepAndPrune::sweepRows(int beginA, int endA, int beginB, int endB, std::vector<std::pair<int, int>>& out) const {
  const double* loA = sorted_[0].data();
  const double* hiA = sorted_[1].data();
  int i = beginA, j = beginB;
  while (i < endA && j < endB) {
    if (loA[i] <= loA[j]) {
      for (int m = j; m < endB && loA[m] <= hiA[i]; ++m) test(i, m, out);
      ++i;
    } else {
      for (int m = i; m < endA && loA[m] <= hiA[j]; ++m) test(j, m, out);
      ++j;
    }
  }
}

// The large boxes against every box (two large boxes once).
void SweepAndPrune::testLarge(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi,
                              std::vector<std::pair<int, int>>& out) const {
  const int n = static_cast<int>(lo.size());
  for (const int a : large_) {
    for (int b = 0; b < n; ++b) {
      if (b == a || (isLarge_[b] && b < a)) continue;
      if ((lo[a].array() <= hi[b].array()).all() && (lo[b].array() <= hi[a].array()).all())
        out.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
}

bool FixedBoxes::Entry::operator<(const Entry& o) const {
  return std::tie(x, y, z, box) < std::tie(o.x, o.y, o.z, o.box);
}

FixedBoxes::FixedBoxes(const std::vector<int>& ids, const std::vector<Vec3>& lo, const std::vector<Vec3>& hi)
    : ids_(ids), lo_(lo), hi_(hi) {
  const int n = static_cast<int>(ids.size());
  if (n == 0) return;
  std::vector<double> width(n);
  for (int k = 0; k < n; ++k) width[k] = (hi[k] - lo[k]).maxCoeff();
  std::vector<double> sorted = width;
  std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
  const double limit = kLargeOverMedian * sorted[n / 2];
  double widest = 1e-9;
  for (int k = 0; k < n; ++k)
    if (width[k] <= limit) widest = std::max(widest, width[k]);
  cell_ = widest;
  for (int k = 0; k < n; ++k) {
    if (width[k] > limit) {
      large_.push_back(k);
      continue;
    }
    grid_.push_back(Entry{cellOf(lo[k].x(), cell_), cellOf(lo[k].y(), cell_), cellOf(lo[k].z(), cell_), k});
  }
  std::sort(grid_.begin(), grid_.end());
}

inline void FixedBoxes::test(int box, const Vec3& lo, const Vec3& hi, std::vector<int>& out) const {
  if ((lo_[box].array() <= hi.array()).all() && (lo.array() <= hi_[box].array()).all()) out.push_back(ids_[box]);
}

void FixedBoxes::overlapping(const Vec3& lo, const Vec3& hi, std::vector<int>& out) const {
  for (int box : large_) test(box, lo, hi, out);
  if (grid_.empty()) return;
  long long first[3], last[3];
  double cells = 1.0;
  for (int a = 0; a < 3; ++a) {
    first[a] = cellOf(lo[a] - cell_, cell_);
    last[a] = cellOf(hi[a], cell_);
    cells *= static_cast<double>(last[a] - first[a] + 1);
  }
  // a query wider than the grid's boxes many times over reads them all instead
  if (cells > static_cast<double>(grid_.size())) {
    for (const Entry& e : grid_) test(e.box, lo, hi, out);
    return;
  }
  for (long long x = first[0]; x <= last[0]; ++x) {
    for (long long y = first[1]; y <= last[1]; ++y) {
      // the cells (x, y, first[2] .. last[2]) lie together in the sorted grid
      auto it = std::lower_bound(grid_.begin(), grid_.end(), Entry{x, y, first[2], -1});
      for (; it != grid_.end() && it->x == x && it->y == y && it->z <= last[2]; ++it) test(it->box, lo, hi, out);
    }
  }
}

}  // namespace rigid
