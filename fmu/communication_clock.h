// The FMU's own time. Importers reach the same communication point in different ways
// (fmpy's t0 + n h, a loop's t += h, (t + h) - t as the step), which differ in the last
// bits; a resting contact would turn those bits into different results. So the FMU
// keeps its time as origin + count * step and takes any step within a few ulps of its
// grid as the grid's own: every importer then integrates the same steps, bitwise.
#pragma once

#include <cfloat>
#include <cmath>
#include <cstdint>

namespace rigidfmu {

struct CommunicationClock {
  double origin = 0.0;  // s, where the grid began (the start, or where the step size changed)
  double step = 0.0;    // s, the grid's communication step (0: no step taken on it yet)
  int64_t count = 0;    // steps taken on the grid

  double now() const { return origin + static_cast<double>(count) * step; }  // s

  // Whether an importer's step h is the grid's, up to the rounding of the importer's
  // own time arithmetic (a few ulps of the time reached).
  bool onGrid(double h) const {
    if (step <= 0.0) return false;
    const double ulps = 8.0 * DBL_EPSILON * (std::abs(now()) + std::abs(h));
    return std::abs(h - step) <= ulps;
  }

  // The step to integrate for the importer's h: the grid's when h is on it, else h,
  // which starts a new grid at now().
  double take(double h) const { return onGrid(h) ? step : h; }

  // After a full step of take(h).
  void advance(double h) {
    if (!onGrid(h)) *this = {now(), h, 0};
    ++count;
  }

  // Stops off the grid, at t (an early return, a failed step, the start): the next
  // step begins a new grid there.
  void restartAt(double t) { *this = {t, 0.0, 0}; }
};

}  // namespace rigidfmu
