// The contact solver's rows and bodies, and its work buffers (ContactScratch): what
// contact_solver.cpp (the solve) and its stages (block_solve, coarse_correction,
// contact_impacts, shock_propagation) share. Internal to the contact solver; nothing
// outside it sees these types.
#pragma once

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "coarse_correction.h"
#include "collision_detection.h"
#include "contact_solver.h"
#include "islands.h"

namespace rigid {
namespace contact_rows {

using namespace contact_solver;

// Points closer than this count as touching (a located impact leaves a gap of about
// 1e-15 of the step's travel); farther ones are speculative.
constexpr double kTouching = 1e-6;  // m
constexpr int kMaxImpactPasses = 500;

// A body as the solver sees it; the last slot of the solver's bodies stands for every
// surface: no inverse mass, no inverse inertia, never moves.
struct SolverBody {
  double invMass = 0.0;
  Mat3 Iinv = Mat3::Zero();                   // 1/(kg m^2), world frame, at the end-of-step pose
  Vec3 v = Vec3::Zero(), w = Vec3::Zero();    // velocity and angular velocity
  Vec3 vp = Vec3::Zero(), wp = Vec3::Zero();  // pseudo-velocities of the position correction
  Vec3 v0 = Vec3::Zero(), w0 = Vec3::Zero();  // velocities before the impacts and the solve's impulses
  unsigned version = 0;  // counts the impulses that changed its velocities by more than kNegligible
};

// A velocity change below this (m/s) at a point leaves the bodies' versions as they
// were: the rows found settled stay settled (solveVelocities).
constexpr double kNegligible = 0.1 * kVelocityTolerance;

// One direction d of a contact point: an impulse lambda acts +lambda d on b and
// -lambda d on a.
struct Axis {
  Vec3 d = Vec3::Zero();
  Vec3 raXd = Vec3::Zero(), rbXd = Vec3::Zero();    // r x d of each side
  Vec3 spinA = Vec3::Zero(), spinB = Vec3::Zero();  // I^-1 (r x d): spin per unit impulse
  double mass = 0.0;  // 1 / (1/Ma + 1/Mb + (r_a x d).Ia^-1 (r_a x d) + (r_b x d).Ib^-1 (r_b x d))
};

// One contact point: its normal and two tangents, the impulses accumulated along them.
struct Row {
  int a = 0, b = 0;  // solver bodies
  Vec3 ra = Vec3::Zero(), rb = Vec3::Zero();
  Axis n, t1, t2;
  Coefficients k;
  double depth = 0.0;
  double target = 0.0;  // m/s, the normal velocity the solve aims at (< 0: a gap may close)
  double lambdaN = 0.0, lambdaT1 = 0.0, lambdaT2 = 0.0, lambdaP = 0.0;
  double pushOut = 0.0;                 // m/s, the position correction's target normal pseudo-velocity
  unsigned versionA = 0, versionB = 0;  // the bodies' versions when the row was found settled
  bool settled = false;
  bool held = false;           // solveBlock: its friction is not an unknown of the block
  bool sliding = false;        // friction limited by mu_k (else mu_s), for the whole solve
  bool remembered = false;     // matched to a point of last step
  bool atLimit = false;        // its friction on the edge of its disc when the solve ended (markLimits)
  Vec3 localA = Vec3::Zero();  // m, the point in body a's frame (matches last step's points)
  const Contact* contact = nullptr;
};

}  // namespace contact_rows

// The solver's work buffers, kept between solves (CollisionCache) so that a step
// allocates nothing once the contacts have been seen.
struct ContactScratch {
  using SolverBody = contact_rows::SolverBody;
  using Row = contact_rows::Row;
  std::vector<SolverBody> bodies;  // one per body, then the static slot
  std::vector<char> involved;      // bodies that some row touches
  std::vector<Row> rows;
  std::vector<Row> impacts;                            // impactRows: the merged pairs
  std::vector<std::pair<size_t, size_t>> impactPairs;  // impactRows: the rows of each
  std::vector<size_t> deep;                            // rows overlapping by more than the slop
  std::vector<double> moveScale;                       // limitMoves: each body's share of the solve's move
  std::vector<char> used;                              // warmStart: memory points already matched
  std::vector<int> island;                             // groupRowsByIsland: each body's island (union-find)
  std::vector<size_t> islandRows;                      // findBlockIslands: rows grouped by island
  std::vector<std::pair<size_t, size_t>> blocks;       // findBlockIslands: islands for solveBlock
  std::vector<size_t> block;                           // solveBlockIslands: one island's rows
  std::vector<size_t> active;                          // solveBlock: the rows whose impulses are solved
  std::vector<std::pair<size_t, int>> unknowns;        // solveBlock: (row, axis) of each unknown
  Eigen::MatrixXd K, regular;                          // solveBlock: its matrix, and that matrix made regular
  Eigen::VectorXd residual, delta;                     // solveBlock: velocity errors, impulse changes
  Eigen::LDLT<Eigen::MatrixXd> factors;                // solveBlock: of `regular`
  std::vector<int> level;                              // shockPass: each body's height in the support graph
  std::vector<size_t> climb;                           // shockPass: the rows between levels, lowest first
  contact_rows::CoarseScratch coarse;                  // coarse_correction: its islands, pairs and factors
  int staticSlot() const { return static_cast<int>(bodies.size()) - 1; }
};

namespace contact_rows {

using Solver = ContactScratch;

// |(x, y)|: std::hypot guards against overflow at a cost that showed as a quarter of a
// pile's solve; impulses are nowhere near overflowing.
inline double length(double x, double y) { return std::sqrt(x * x + y * y); }

// The end of the rows of the pair that row i belongs to (rows come grouped by pair).
inline size_t pairEnd(const Solver& s, size_t i) {
  size_t end = i;
  while (end < s.rows.size() && s.rows[end].a == s.rows[i].a && s.rows[end].b == s.rows[i].b &&
         s.rows[end].contact->surface == s.rows[i].contact->surface)
    ++end;
  return end;
}

// The rows grouped by island (bodies joined by rows; a surface joins none), by
// union-find in s.island: `order` takes every row index, island after island, each
// island's rows in their order, and `islands` each island's [begin, end) in `order`.
inline void groupRowsByIsland(Solver& s, std::vector<size_t>& order, std::vector<std::pair<size_t, size_t>>& islands) {
  std::vector<int>& parent = s.island;
  parent.resize(s.bodies.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (const Row& r : s.rows)
    if (r.b != s.staticSlot()) parent[islandRoot(parent, r.a)] = islandRoot(parent, r.b);
  for (int& p : parent) p = islandRoot(parent, p);
  order.resize(s.rows.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t x, size_t y) { return parent[s.rows[x].a] < parent[s.rows[y].a]; });
  islands.clear();
  for (size_t begin = 0; begin < order.size();) {
    size_t end = begin + 1;
    while (end < order.size() && parent[s.rows[order[end]].a] == parent[s.rows[order[begin]].a]) ++end;
    islands.emplace_back(begin, end);
    begin = end;
  }
}

inline Axis axisOf(const SolverBody& A, const SolverBody& B, const Vec3& ra, const Vec3& rb, const Vec3& d) {
  Axis x;
  x.d = d;
  x.raXd = ra.cross(d);
  x.rbXd = rb.cross(d);
  x.spinA = A.Iinv * x.raXd;
  x.spinB = B.Iinv * x.rbXd;
  x.mass = 1.0 / (A.invMass + B.invMass + x.raXd.dot(x.spinA) + x.rbXd.dot(x.spinB));
  return x;
}

// Velocity of b relative to a at the point, along the axis.
inline double relativeVelocity(const Solver& s, const Row& r, const Axis& x) {
  const SolverBody& A = s.bodies[r.a];
  const SolverBody& B = s.bodies[r.b];
  return x.d.dot(B.v - A.v) + x.rbXd.dot(B.w) - x.raXd.dot(A.w);
}

// The impulse lambda along the axis, on the bodies' velocities (storeMomenta hands the
// change to Y's momenta once the solve is done).
inline void applyImpulse(Solver& s, const Row& r, const Axis& x, double lambda) {
  if (lambda == 0.0) return;
  SolverBody& A = s.bodies[r.a];
  SolverBody& B = s.bodies[r.b];
  A.v -= lambda * A.invMass * x.d;
  A.w -= lambda * x.spinA;
  if (r.b == s.staticSlot()) return;
  B.v += lambda * B.invMass * x.d;
  B.w += lambda * x.spinB;
}

// The impulses (lambda_n, lambda_t1, lambda_t2) of one row at once.
inline void applyRowImpulse(Solver& s, const Row& r, double ln, double l1, double l2) {
  const Vec3 J = ln * r.n.d + l1 * r.t1.d + l2 * r.t2.d;
  SolverBody& A = s.bodies[r.a];
  A.v -= A.invMass * J;
  A.w -= ln * r.n.spinA + l1 * r.t1.spinA + l2 * r.t2.spinA;
  if (r.b == s.staticSlot()) return;
  SolverBody& B = s.bodies[r.b];
  B.v += B.invMass * J;
  B.w += ln * r.n.spinB + l1 * r.t1.spinB + l2 * r.t2.spinB;
}

// (l1, l2) scaled onto the disc |l| <= limit when it is outside.
inline void clampToDisc(double& l1, double& l2, double limit) {
  const double magnitude = length(l1, l2);
  if (!(magnitude > limit)) return;
  const double scale = magnitude > 0.0 ? limit / magnitude : 0.0;
  l1 *= scale, l2 *= scale;
}

// The friction disc's radius: mu lambda_n, mu = mu_s for a sticking point and mu_k for
// a sliding one.
inline double frictionLimit(const Row& r) { return (r.sliding ? r.k.muk : r.k.mus) * r.lambdaN; }

// Each row's friction marked on the edge of its disc or inside it, from the impulses of
// the solve's last pass.
inline void markLimits(Solver& s) {
  for (Row& r : s.rows) r.atLimit = length(r.lambdaT1, r.lambdaT2) >= (1.0 - 1e-9) * frictionLimit(r);
}

// Friction: the impulse that stops the slip, projected onto the disc |lambda_t| <=
// mu lambda_n, mu = mu_s for a sticking point and mu_k for a sliding one. (Switching
// between the two within the passes would make the projection jump and never settle:
// a point's state changes between steps, in store().) Returns the velocity change it
// made at the point (m/s).
inline double solveFriction(Solver& s, Row& r) {
  const double v1 = relativeVelocity(s, r, r.t1), v2 = relativeVelocity(s, r, r.t2);
  double l1 = r.lambdaT1 - r.t1.mass * v1, l2 = r.lambdaT2 - r.t2.mass * v2;
  clampToDisc(l1, l2, frictionLimit(r));
  const double d1 = l1 - r.lambdaT1, d2 = l2 - r.lambdaT2;
  r.lambdaT1 = l1, r.lambdaT2 = l2;
  applyImpulse(s, r, r.t1, d1);
  applyImpulse(s, r, r.t2, d2);
  return std::max(std::abs(d1) / r.t1.mass, std::abs(d2) / r.t2.mass);
}

}  // namespace contact_rows
}  // namespace rigid
