#include "broadphase.h"

#include <algorithm>
#include <numeric>

namespace rigid {

namespace {

// The axis along which the boxes' centres spread most (largest variance).
int sweepAxis(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi) {
  Vec3 sum = Vec3::Zero(), sum2 = Vec3::Zero();
  for (size_t i = 0; i < lo.size(); ++i) {
    const Vec3 c = 0.5 * (lo[i] + hi[i]);
    sum += c;
    sum2 += c.cwiseProduct(c);
  }
  const double n = static_cast<double>(lo.size());
  const Vec3 variance = sum2 / n - (sum / n).cwiseProduct(sum / n);
  int axis = 0;
  variance.maxCoeff(&axis);
  return axis;
}

}  // namespace

void SweepAndPrune::overlaps(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi,
                             std::vector<std::pair<int, int>>& out) {
  out.clear();
  const int n = static_cast<int>(lo.size());
  if (n < 2) return;
  const int axis = sweepAxis(lo, hi);
  auto before = [&](int a, int b) { return lo[a][axis] < lo[b][axis]; };
  if (static_cast<int>(order_.size()) != n || axis != axis_) {
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0);
    std::sort(order_.begin(), order_.end(), before);
    axis_ = axis;
  } else {
    for (int k = 1; k < n; ++k) {  // insertion sort: nearly sorted already
      const int box = order_[k];
      int j = k - 1;
      for (; j >= 0 && before(box, order_[j]); --j) order_[j + 1] = order_[j];
      order_[j + 1] = box;
    }
  }
  // The boxes in sweep order, contiguous: the inner loop streams through them.
  sorted_.resize(n);
  for (int k = 0; k < n; ++k) sorted_[k] = Interval{lo[order_[k]], hi[order_[k]]};
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  for (int k = 0; k < n; ++k) {
    const Interval& a = sorted_[k];
    const double end = a.hi[axis];
    for (int m = k + 1; m < n && sorted_[m].lo[axis] <= end; ++m) {
      const Interval& b = sorted_[m];
      if ((a.lo[u] <= b.hi[u]) & (b.lo[u] <= a.hi[u]) & (a.lo[v] <= b.hi[v]) & (b.lo[v] <= a.hi[v]))
        out.emplace_back(std::min(order_[k], order_[m]), std::max(order_[k], order_[m]));
    }
  }
}

}  // namespace rigid
