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
  // The boxes in sweep order, one contiguous array per bound: the inner loop streams
  // through the sweep axis's bounds and reads the other two only for boxes it meets.
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  for (Bounds& b : sorted_) b.resize(n);
  for (int k = 0; k < n; ++k) {
    const Vec3& l = lo[order_[k]];
    const Vec3& h = hi[order_[k]];
    sorted_[0][k] = l[axis], sorted_[1][k] = h[axis];
    sorted_[2][k] = l[u], sorted_[3][k] = h[u];
    sorted_[4][k] = l[v], sorted_[5][k] = h[v];
  }
  const double* loA = sorted_[0].data();
  const double* hiA = sorted_[1].data();
  const double* loU = sorted_[2].data();
  const double* hiU = sorted_[3].data();
  const double* loV = sorted_[4].data();
  const double* hiV = sorted_[5].data();
  for (int k = 0; k < n; ++k) {
    const double end = hiA[k];
    for (int m = k + 1; m < n && loA[m] <= end; ++m) {
      if ((loU[k] <= hiU[m]) & (loU[m] <= hiU[k]) & (loV[k] <= hiV[m]) & (loV[m] <= hiV[k]))
        out.emplace_back(std::min(order_[k], order_[m]), std::max(order_[k], order_[m]));
    }
  }
}

}  // namespace rigid
