// Rules every contact follows, body-body and body-surface alike.
#pragma once

#include <cmath>

#include "math_types.h"

namespace rigid {

// Normal speed (m/s) below which an impact does not bounce and a body may rest: what
// gravity adds in two steps, so that a resting body's per-step sinking never bounces.
inline double restingNormalSpeed(const Vec3& gravity, double h) { return 2.0 * gravity.norm() * h + 1e-9; }

// Combination rule of two partners' coefficients (xi, mu_s, mu_k): the geometric mean,
// so that equal values combine to that value and a frictionless partner gives none.
inline double combineCoefficients(double a, double b) { return std::sqrt(a * b); }

}  // namespace rigid
