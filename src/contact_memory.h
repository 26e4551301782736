// What the contact solver keeps from one step to the next: each contact point of the
// last step, where it was on the bodies and the impulses it took, so that the next
// step's solve starts from them (warm start). It is part of a run's state: an FMU
// state saved and restored carries it, and a restored run continues bitwise.
#pragma once

#include <algorithm>
#include <cstddef>
#include <tuple>
#include <vector>

#include "math_types.h"

namespace rigid {

struct ContactMemory {
  int a = -1;                          // body
  int b = -1;                          // other body, or -1 with `surface` set
  int surface = -1;                    // surface index when b == -1
  Vec3 localA = Vec3::Zero();          // m, the point in body a's frame, from its centre of mass
  double normalImpulse = 0.0;          // N s, accumulated lambda_n >= 0 along the normal from a to b
  Vec3 tangentImpulse = Vec3::Zero();  // N s, accumulated friction impulse on b (world frame)
  double twistImpulse = 0.0;           // N m s, friction's moment on b about the normal (its share of the pair's)
  // The point slid at the end of the last solve (its friction reached the cone's edge):
  // the next solve limits its friction by mu_k, a sticking point's by mu_s.
  bool sliding = false;
};

// The order of the detector's pairs (a, bodies before surfaces, b or surface), which
// the contacts and the contact memory keep.
inline std::tuple<int, int, int> pairKey(int a, int b, int surface) {
  return std::make_tuple(a, b < 0 ? 1 : 0, b >= 0 ? b : surface);
}

// Moves the points of `from` for which `moves(point)` holds into `into`, both kept in
// pair order (each pair's points lie wholly in one of them).
template <class Moves>
void movePoints(std::vector<ContactMemory>& from, std::vector<ContactMemory>& into, Moves moves) {
  const auto kept = std::stable_partition(from.begin(), from.end(), [&](const ContactMemory& m) { return !moves(m); });
  if (kept == from.end()) return;
  const auto middle = static_cast<std::ptrdiff_t>(into.size());
  into.insert(into.end(), kept, from.end());
  from.erase(kept, from.end());
  std::inplace_merge(into.begin(), into.begin() + middle, into.end(),
                     [](const ContactMemory& x, const ContactMemory& y) {
                       return pairKey(x.a, x.b, x.surface) < pairKey(y.a, y.b, y.surface);
                     });
}

}  // namespace rigid
