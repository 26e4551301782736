// Four bodies side by side: the body formulas on packs holding one value of each body
// per lane (structure of arrays). Written as the scalar formulas, they compile to SIMD,
// and four independent bodies hide each other's latencies (a rotation is a chain of
// dependent products and one division). Used where every body of a world takes the
// same formula: free bodies' Runge-Kutta stages and the auxiliaries after a step.
// The small functions are forced inline (EIGEN_STRONG_INLINE): a call would spill the
// packs to memory, which costs more than the arithmetic.
#pragma once

#include <algorithm>
#include <vector>

#include "body.h"

namespace rigid {

using Pack = Eigen::Array4d;
constexpr int kLanes = 4;

struct QuatPack {
  Pack w, x, y, z;
};

// A rotation matrix per lane, row by row.
struct RotationPack {
  Pack r[9];
};

// The lane's body for pack `first`: a last, partial pack repeats its last body in the
// spare lanes (computed, never stored).
inline size_t laneBody(size_t first, int lane, size_t n) { return std::min(first + lane, n - 1); }

// R of q / |q| for q of any norm, as rotationOf().
EIGEN_STRONG_INLINE RotationPack rotationOf(const QuatPack& q) {
  const Pack s = 2.0 / (q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  const Pack xs = q.x * s, ys = q.y * s, zs = q.z * s;
  const Pack wx = q.w * xs, wy = q.w * ys, wz = q.w * zs;
  const Pack xx = q.x * xs, xy = q.x * ys, xz = q.x * zs;
  const Pack yy = q.y * ys, yz = q.y * zs, zz = q.z * zs;
  // the matrix row by row
  // clang-format off
  return {{1.0 - (yy + zz), xy - wz, xz + wy,
           xy + wz, 1.0 - (xx + zz), yz - wx,
           xz - wy, yz + wx, 1.0 - (xx + yy)}};
  // clang-format on
}

// M v and M^T v for a 3x3 matrix given row by row.
EIGEN_STRONG_INLINE void multiply(const Pack (&M)[9], const Pack (&v)[3], Pack (&out)[3]) {
  for (int i = 0; i < 3; ++i) out[i] = M[3 * i] * v[0] + M[3 * i + 1] * v[1] + M[3 * i + 2] * v[2];
}
EIGEN_STRONG_INLINE void multiplyTransposed(const Pack (&M)[9], const Pack (&v)[3], Pack (&out)[3]) {
  for (int i = 0; i < 3; ++i) out[i] = M[i] * v[0] + M[3 + i] * v[1] + M[6 + i] * v[2];
}

// One lane of a pack: a 3x3 matrix (row by row), a quaternion, a vector.
inline void setLane(Pack (&M)[9], int lane, const Mat3& m) {
  for (int e = 0; e < 9; ++e) M[e][lane] = m(e / 3, e % 3);
}
inline void setLane(QuatPack& q, int lane, const Quat& v) {
  q.w[lane] = v.w(), q.x[lane] = v.x(), q.y[lane] = v.y(), q.z[lane] = v.z();
}
inline void setLane(Pack (&p)[3], int lane, const Vec3& v) {
  for (int c = 0; c < 3; ++c) p[c][lane] = v[c];
}

}  // namespace rigid
