// Coarse correction (the second level of a two-level solve, as in multigrid): before
// the passes, in each resting island, every pair that sticks with a load is taken as
// welded, its points' impulses as one wrench, and the wrenches that stop every welded
// pair's relative motion are solved at once. A column's load and lean travel through it
// in one solve, where the passes carry them down a few cubes per pass and leave a
// resting column of 10 jittering at ~1e-4 m/s; the passes then answer what the welds
// do not (a point that slides, parts or pulls). Internal to the contact solver.
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "math_types.h"

namespace rigid {

struct ContactScratch;

namespace contact_rows {

// One welded pair: its rows [begin, end), its bodies, the reference point on each (the
// mean of its points' arms), its plane (n, e1, e2), the spread of its points in that
// plane (the pseudo-inverse of its second moments, and their trace), and the wrench
// directions its points can carry, the first m columns of basis: the force, then the
// moments their spread allows (none for one point, no tipping about the line of two).
struct CoarsePair {
  size_t begin = 0, end = 0;
  int a = 0, b = 0;
  Vec3 ca = Vec3::Zero(), cb = Vec3::Zero(), n = Vec3::Zero(), e1 = Vec3::Zero(), e2 = Vec3::Zero();
  Eigen::Matrix2d spreadInverse = Eigen::Matrix2d::Zero();
  double polar = 0.0;  // m^2, the sum of the points' squared distances from their centroid
  Eigen::Matrix<double, 6, 6> basis = Eigen::Matrix<double, 6, 6>::Zero();
  int m = 0, offset = 0;  // its unknowns, and the first one's index in the island's
};

struct CoarseScratch {
  std::vector<size_t> islandRows;                         // the rows grouped by island
  std::vector<std::pair<size_t, size_t>> islands;         // each island's range in islandRows
  std::vector<std::pair<size_t, size_t>> welds;           // one island's weldable pairs: their rows
  std::vector<CoarsePair> pairs;                          // and those pairs, welded
  std::vector<std::vector<std::pair<int, int>>> pairsOf;  // each body's welded pairs, with its side (+1: b)
  std::vector<int> bodies;                                // the island's bodies that welded pairs join
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::SparseMatrix<double> K;  // the wrenches' Delassus matrix
  // in the rows' order: a column's pairs come bottom up, and its matrix, block
  // tridiagonal, factors without fill
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> factors;
  Eigen::VectorXd motion, wrench;  // the welded pairs' relative motions, and the wrenches that stop them
};

// The coarse correction of every island of at most kMaxCoarsePairs touching pairs whose
// welded pairs all move slower than restingSpeed (m/s, what a resting body can gain in
// a step) and not all still: the wrenches onto its welded pairs' points (least-norm over
// each pair's points), each point's normal impulse kept >= 0 and its friction in its
// disc.
void coarseCorrection(ContactScratch& s, double restingSpeed);

}  // namespace contact_rows
}  // namespace rigid
