// The Newton velocity stage (solver.contacts = "newton", experimental): the contact
// solver's velocities found by Newton's method on one convex problem over every body at
// once, in place of the Gauss-Seidel passes (contact_solver.cpp). Internal to the
// contact solver; the impacts before it and the position correction after it are the
// default solver's.
//
// The velocities u minimise
//   1/2 (u - u_free)^T M (u - u_free) + the points' costs, whose slopes are the impulses
//     lambda_n = max(c_n - Dn x_n, 0)          x_n = J_n u - target, the approach
//     lambda_t = c_t - Dt x_t, clipped to the disc |lambda_t| <= rho    x_t = J_t u, the slip
// c being the point's remembered impulses (0 for a new point) and D = (the axis'
// effective mass) / kNewtonSoftness: a point's impulse changes from what held it last
// step only as far as its velocity error asks, so a resting pile is held at x = 0
// exactly (no sinking, no creep) and a column of cubes rests still. Each iteration
// solves H d = -g by a sparse Cholesky factorisation of the Hessian (bodies joined by
// points), then takes the cost's exact minimum along d: a column's load reaches its
// foot in one iteration whatever its height, where a Gauss-Seidel pass carries it down
// one cube. Each island (bodies joined by points) is solved on its own, so that the
// iterations stop where they have converged. The discs' radii rho = mu lambda_n are
// held while Newton converges and then follow the normal impulses, until they stop
// changing (Coulomb's disc; updated within the iterations, the cost would change under
// the line search).
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Sparse>

#include "contact_solver.h"

namespace rigid {

namespace contact_solver {
// 1: a point's compliance over its effective mass's. A column of 10 dropped onto the
// floor (h = 2 ms, 3 s): 1e-6 took twice the iterations (12.8 per solve against 6.6;
// the impulses are D times velocity errors, and a stiffer D needs them nearer
// round-off), 1e-2 left the column moving at 6.6e-6 m/s at the end (1e-4: 2e-17).
constexpr double kNewtonSoftness = 1e-4;
constexpr int kMaxNewtonIterations = 30;   // cap of the Newton iterations for one set of friction discs
constexpr int kMaxDiscUpdates = 10;        // cap of the friction discs' updates from the normal impulses
constexpr double kNewtonTolerance = 1e-7;  // m/s: stop when no impulse changes a point's velocity more
}  // namespace contact_solver

// The Newton stage's work buffers (part of ContactScratch): nothing in them outlives a
// solve.
struct NewtonScratch {
  std::vector<size_t> islandRows;                     // the rows grouped by island
  std::vector<std::pair<size_t, size_t>> islands;     // each island's range in islandRows
  std::vector<size_t> rows;                           // the island being solved: its rows
  std::vector<int> unknown;                           // each solver body's unknown block in it, -1: not one
  std::vector<int> bodyOf;                            // each unknown block's solver body
  std::vector<double> mass;                           // each unknown block's body: kg
  std::vector<Mat3> inertia;                          // and kg m^2, world frame
  std::vector<Eigen::Matrix<double, 6, 6>> diagonal;  // the Hessian's blocks of each body
  Eigen::VectorXd free, u, g, d;                      // (v, w) per body: free motion, iterate, gradient, step
  Eigen::VectorXd Md;                                 // M d
  std::vector<double> radius;                         // each row's friction disc, N s
  std::vector<double> Dn, Dt;                         // each row's stiffness along its normal and its slip, kg
  std::vector<double> cn, ln;                         // each row's remembered normal impulse and its present one, N s
  std::vector<Eigen::Vector2d> ct, lt;                // the same of its friction (t1, t2)
  std::vector<double> xn, dn;                         // each row's approach and its change along d, m/s
  std::vector<Eigen::Vector2d> xt, dt;                // each row's slip and its change along d, m/s
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::SparseMatrix<double> H;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factors;
};

struct ContactScratch;

// The velocities of s's bodies and the impulses of its rows, from the bodies' velocities
// after the impacts and the rows' remembered impulses (the warm start, applied here).
void solveNewton(ContactScratch& s, ContactSolveReport& report);

}  // namespace rigid
