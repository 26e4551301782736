#include "shock_propagation.h"

#include <algorithm>
#include <limits>

namespace rigid {
namespace contact_rows {

namespace {

// Each body's level in the support graph: 1 on a surface, k + 1 on a body of level k
// through a row that bears a load; a body supported by nothing (a stack in space) keeps
// kUnsupported. Relaxed over the rows, forwards and backwards, until no level drops.
constexpr int kUnsupported = std::numeric_limits<int>::max() / 2;

void findLevels(Solver& s) {
  const int statics = s.staticSlot();
  s.level.assign(s.bodies.size(), kUnsupported);
  s.level[statics] = 0;
  const size_t n = s.rows.size();
  for (bool lowered = true; lowered;) {
    lowered = false;
    for (size_t k = 0; k < 2 * n; ++k) {
      const Row& r = s.rows[k < n ? k : 2 * n - 1 - k];
      if (r.lambdaN <= 0.0) continue;
      int &la = s.level[r.a], &lb = s.level[r.b];
      if (lb + 1 < la) la = lb + 1, lowered = true;
      if (r.b != statics && la + 1 < lb) lb = la + 1, lowered = true;
    }
  }
}

// The side of row r that the shock pass moves (+1: b, -1: a): the upper one.
int upperSide(const Solver& s, const Row& r) { return s.level[r.a] < s.level[r.b] ? 1 : -1; }

// The effective mass along x of the moving side alone, the other side held.
double heldMass(const Solver& s, const Row& r, const Axis& x, int side) {
  const SolverBody& M = s.bodies[side > 0 ? r.b : r.a];
  return 1.0 / (M.invMass + (side > 0 ? x.rbXd.dot(x.spinB) : x.raXd.dot(x.spinA)));
}

// The impulse lambda along x on one side only (+lambda d on b, -lambda d on a).
void applyOneSided(Solver& s, const Row& r, const Axis& x, int side, double lambda) {
  if (lambda == 0.0) return;
  const int i = side > 0 ? r.b : r.a;
  SolverBody& M = s.bodies[i];
  M.v += side * lambda * M.invMass * x.d;
  M.w += side * lambda * (side > 0 ? x.spinB : x.spinA);
}

// solveRow with the lower body held: the normal (>= 0 accumulated) and the friction in
// its disc, with the upper body's masses alone. Returns the velocity change it made.
double solveRowHeld(Solver& s, Row& r, int side) {
  const double mn = heldMass(s, r, r.n, side);
  const double ln = std::max(r.lambdaN - mn * (relativeVelocity(s, r, r.n) - r.target), 0.0);
  const double dn = ln - r.lambdaN;
  r.lambdaN = ln;
  applyOneSided(s, r, r.n, side, dn);
  const double m1 = heldMass(s, r, r.t1, side), m2 = heldMass(s, r, r.t2, side);
  double l1 = r.lambdaT1 - m1 * relativeVelocity(s, r, r.t1), l2 = r.lambdaT2 - m2 * relativeVelocity(s, r, r.t2);
  clampToDisc(l1, l2, frictionLimit(r));
  const double d1 = l1 - r.lambdaT1, d2 = l2 - r.lambdaT2;
  r.lambdaT1 = l1, r.lambdaT2 = l2;
  applyOneSided(s, r, r.t1, side, d1);
  applyOneSided(s, r, r.t2, side, d2);
  return std::max({std::abs(dn) / mn, std::abs(d1) / m1, std::abs(d2) / m2});
}

}  // namespace

// Shock propagation (Guendelman, Bridson and Fedkiw, 2003): one sweep over the touching
// rows between bodies of different levels, lowest first, each row's lower body held.
// The passes carry a column's load down at a rate of a few levels per pass, and what
// they leave unconverged in a tall column is a slow rocking that keeps it awake for
// seconds (a pile of 1000 in columns of 10); here each level is made to rest on the
// one below before the next is taken. Rows on surfaces, between bodies of one level
// (dominoes, a row of boxes) and in unsupported stacks are left as the passes made
// them. The impulses accumulate into the rows' and so start the next step.
void shockPass(Solver& s) {
  findLevels(s);
  const int statics = s.staticSlot();
  s.climb.clear();
  for (size_t i = 0; i < s.rows.size(); ++i) {
    const Row& r = s.rows[i];
    if (r.depth >= -kTouching && r.b != statics && s.level[r.a] != s.level[r.b] &&
        std::min(s.level[r.a], s.level[r.b]) < kUnsupported)
      s.climb.push_back(i);
  }
  auto lower = [&](size_t i) { return std::min(s.level[s.rows[i].a], s.level[s.rows[i].b]); };
  std::stable_sort(s.climb.begin(), s.climb.end(), [&](size_t x, size_t y) { return lower(x) < lower(y); });
  for (size_t begin = 0; begin < s.climb.size();) {
    const Row& first = s.rows[s.climb[begin]];
    size_t end = begin;
    while (end < s.climb.size() && s.rows[s.climb[end]].a == first.a && s.rows[s.climb[end]].b == first.b) ++end;
    const int side = upperSide(s, first);
    for (int pass = 0; pass < kShockPairPasses; ++pass) {
      double change = 0.0;
      for (size_t k = begin; k < end; ++k) change = std::max(change, solveRowHeld(s, s.rows[s.climb[k]], side));
      if (change <= kVelocityTolerance) break;
    }
    begin = end;
  }
}

}  // namespace contact_rows
}  // namespace rigid
