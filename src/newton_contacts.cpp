#include "newton_contacts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact_rows.h"

namespace rigid {

using namespace contact_solver;

namespace {

using namespace contact_rows;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat63 = Eigen::Matrix<double, 6, 3>;

// ---- unknowns ---------------------------------------------------------------------

// One block of six unknowns (v, w) per body of the island, in the order its rows
// reach them. (`unknown` is -1 for every body on entry and left so for the next island.)
void numberBodies(Solver& s, NewtonScratch& n) {
  n.bodyOf.clear();
  for (size_t i : n.rows)
    for (int body : {s.rows[i].a, s.rows[i].b}) {
      if (body == s.staticSlot() || n.unknown[body] >= 0) continue;
      n.unknown[body] = static_cast<int>(n.bodyOf.size());
      n.bodyOf.push_back(body);
    }
  const size_t blocks = n.bodyOf.size();
  n.mass.resize(blocks);
  n.inertia.resize(blocks);
  n.diagonal.resize(blocks);
  for (size_t k = 0; k < blocks; ++k) {
    const SolverBody& b = s.bodies[n.bodyOf[k]];
    n.mass[k] = 1.0 / b.invMass;
    n.inertia[k] = b.Iinv.inverse();
  }
}

void readVelocities(const Solver& s, const NewtonScratch& n, Eigen::VectorXd& u) {
  u.resize(6 * static_cast<Eigen::Index>(n.bodyOf.size()));
  for (size_t k = 0; k < n.bodyOf.size(); ++k) {
    const SolverBody& b = s.bodies[n.bodyOf[k]];
    u.segment<3>(6 * k) = b.v;
    u.segment<3>(6 * k + 3) = b.w;
  }
}

// M x, block by block.
void applyMass(const NewtonScratch& n, const Eigen::VectorXd& x, Eigen::VectorXd& out) {
  out.resize(x.size());
  for (size_t k = 0; k < n.bodyOf.size(); ++k) {
    out.segment<3>(6 * k) = n.mass[k] * x.segment<3>(6 * k);
    out.segment<3>(6 * k + 3) = n.inertia[k] * x.segment<3>(6 * k + 3);
  }
}

// ---- a row's Jacobian --------------------------------------------------------------

// J x along the axis: the velocity of b relative to a at the point for the body
// velocities x.
double along(const NewtonScratch& n, const Row& r, const Axis& x, const Eigen::VectorXd& u) {
  const int a = n.unknown[r.a], b = n.unknown[r.b];
  double v = -x.d.dot(u.segment<3>(6 * a)) - x.raXd.dot(u.segment<3>(6 * a + 3));
  if (b >= 0) v += x.d.dot(u.segment<3>(6 * b)) + x.rbXd.dot(u.segment<3>(6 * b + 3));
  return v;
}

// The row's three axes as columns, body a's side and body b's.
void jacobians(const Row& r, Mat63& A, Mat63& B) {
  const Axis* axes[3] = {&r.n, &r.t1, &r.t2};
  for (int j = 0; j < 3; ++j) {
    A.col(j) << -axes[j]->d, -axes[j]->raXd;
    B.col(j) << axes[j]->d, axes[j]->rbXd;
  }
}

// ---- the point's cost --------------------------------------------------------------

// The impulses of a point at approach xn and slip xt, each about its centre (the
// remembered impulse): lambda_n = c_n - Dn xn while that is positive, the friction
// c_t - Dt xt clipped to the disc. Centred so, a point whose remembered impulses hold
// it is held at x = 0 exactly: a resting pile neither sinks nor creeps by the
// compliance.
double normalImpulse(double Dn, double centre, double xn) { return std::max(centre - Dn * xn, 0.0); }

Eigen::Vector2d frictionImpulse(double Dt, double radius, const Eigen::Vector2d& centre, const Eigen::Vector2d& xt) {
  const Eigen::Vector2d l = centre - Dt * xt;
  const double m = l.norm();
  if (!(m > radius)) return l;
  return radius > 0.0 ? Eigen::Vector2d(l * (radius / m)) : Eigen::Vector2d::Zero();
}

// The friction's curvature (the derivative of -lambda_t by x_t): Dt inside the disc;
// on its edge Dt rho / |l| across the impulse l and none along it (its size is held,
// its direction turns).
Eigen::Matrix2d frictionCurvature(double Dt, double radius, const Eigen::Vector2d& centre, const Eigen::Vector2d& xt) {
  const Eigen::Vector2d l = centre - Dt * xt;
  const double m = l.norm();
  if (!(m > radius)) return Dt * Eigen::Matrix2d::Identity();
  const Eigen::Vector2d e = l / m;
  return (Dt * radius / m) * (Eigen::Matrix2d::Identity() - e * e.transpose());
}

// ---- gradient and Hessian ----------------------------------------------------------

// Each row's approach and slip at the iterate.
void measure(const Solver& s, NewtonScratch& n) {
  for (size_t i = 0; i < n.rows.size(); ++i) {
    const Row& r = s.rows[n.rows[i]];
    n.xn[i] = along(n, r, r.n, n.u) - r.target;
    n.xt[i] = {along(n, r, r.t1, n.u), along(n, r, r.t2, n.u)};
  }
}

// The friction discs from the normal impulses at the iterate. Returns their largest
// change as a velocity (m/s).
double followDiscs(const Solver& s, NewtonScratch& n) {
  measure(s, n);
  double change = 0.0;
  for (size_t i = 0; i < n.rows.size(); ++i) {
    const Row& r = s.rows[n.rows[i]];
    const double mu = r.sliding ? r.k.muk : r.k.mus;
    const double radius = mu * normalImpulse(n.Dn[i], n.cn[i], n.xn[i]);
    change = std::max(change, std::abs(radius - n.radius[i]) / r.t1.mass);
    n.radius[i] = radius;
  }
  return change;
}

// A 6x6 block at block row `row`, column `col`; of a diagonal block, its lower triangle.
void addBlock(NewtonScratch& n, int row, int col, const Mat6& block, bool lowerOnly) {
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < (lowerOnly ? i + 1 : 6); ++j) n.entries.emplace_back(6 * row + i, 6 * col + j, block(i, j));
}

// g = M (u - u_free) - J^T lambda and the Hessian M + J^T W J (lower triangle), W the
// points' curvatures; every pair's blocks are entered, zero or not, so that the pattern
// is the same in every iteration of the solve.
void gradientAndHessian(const Solver& s, NewtonScratch& n) {
  applyMass(n, n.u - n.free, n.g);
  for (size_t k = 0; k < n.bodyOf.size(); ++k) {
    n.diagonal[k].setZero();
    n.diagonal[k].topLeftCorner<3, 3>() = n.mass[k] * Mat3::Identity();
    n.diagonal[k].bottomRightCorner<3, 3>() = n.inertia[k];
  }
  n.entries.clear();
  Mat6 between = Mat6::Zero();
  Mat63 A, B;
  for (size_t i = 0; i < n.rows.size(); ++i) {
    const Row& r = s.rows[n.rows[i]];
    const int a = n.unknown[r.a], b = n.unknown[r.b];
    jacobians(r, A, B);
    const Eigen::Vector2d lt = frictionImpulse(n.Dt[i], n.radius[i], n.ct[i], n.xt[i]);
    const Eigen::Vector3d lambda(normalImpulse(n.Dn[i], n.cn[i], n.xn[i]), lt.x(), lt.y());
    Eigen::Matrix3d W = Eigen::Matrix3d::Zero();
    W(0, 0) = lambda.x() > 0.0 ? n.Dn[i] : 0.0;
    W.bottomRightCorner<2, 2>() = frictionCurvature(n.Dt[i], n.radius[i], n.ct[i], n.xt[i]);
    n.g.segment<6>(6 * a) -= A * lambda;
    n.diagonal[a] += A * W * A.transpose();
    if (b < 0) continue;
    n.g.segment<6>(6 * b) -= B * lambda;
    n.diagonal[b] += B * W * B.transpose();
    between += B * W * A.transpose();  // rows of b, columns of a
    if (i + 1 < n.rows.size() && s.rows[n.rows[i + 1]].a == r.a && s.rows[n.rows[i + 1]].b == r.b) continue;
    if (b > a)
      addBlock(n, b, a, between, false);
    else
      addBlock(n, a, b, between.transpose(), false);
    between.setZero();
  }
  for (size_t k = 0; k < n.bodyOf.size(); ++k)
    addBlock(n, static_cast<int>(k), static_cast<int>(k), n.diagonal[k], true);
  const Eigen::Index size = n.u.size();
  n.H.resize(size, size);
  n.H.setFromTriplets(n.entries.begin(), n.entries.end());
}

// ---- line search -------------------------------------------------------------------

// The cost's slope and curvature along d at u + alpha d.
std::pair<double, double> slopeAlong(const NewtonScratch& n, double alpha, double dMr, double dMd) {
  double slope = dMr + alpha * dMd, curvature = dMd;
  for (size_t i = 0; i < n.rows.size(); ++i) {
    const double xn = n.xn[i] + alpha * n.dn[i];
    const Eigen::Vector2d xt = n.xt[i] + alpha * n.dt[i];
    const double ln = normalImpulse(n.Dn[i], n.cn[i], xn);
    slope -= ln * n.dn[i] + frictionImpulse(n.Dt[i], n.radius[i], n.ct[i], xt).dot(n.dt[i]);
    if (ln > 0.0) curvature += n.Dn[i] * n.dn[i] * n.dn[i];
    curvature += n.dt[i].dot(frictionCurvature(n.Dt[i], n.radius[i], n.ct[i], xt) * n.dt[i]);
  }
  return {slope, curvature};
}

// The exact minimum of the convex cost along d: Newton's method on its slope, kept
// within the bracket where the slope changes sign (the slope is piecewise linear, its
// kinks where a point starts or stops approaching or reaches its disc's edge).
double lineSearch(NewtonScratch& n) {
  applyMass(n, n.d, n.Md);
  const double dMr = n.Md.dot(n.u - n.free), dMd = n.Md.dot(n.d);
  const double slope0 = slopeAlong(n, 0.0, dMr, dMd).first;
  if (!(slope0 < 0.0)) return 0.0;
  double lo = 0.0, hi = std::numeric_limits<double>::infinity(), alpha = 1.0;
  for (int k = 0; k < 50; ++k) {
    const auto [slope, curvature] = slopeAlong(n, alpha, dMr, dMd);
    if (std::abs(slope) <= 1e-12 * std::abs(slope0)) break;
    (slope < 0.0 ? lo : hi) = alpha;
    double next = alpha - slope / curvature;
    if (!(next > lo && next < hi)) next = std::isinf(hi) ? 2.0 * alpha : 0.5 * (lo + hi);
    alpha = next;
  }
  return alpha;
}

// The largest change of a row's impulses since the last call, as the velocity it makes
// at the point (m/s).
double impulseChange(const Solver& s, NewtonScratch& n) {
  measure(s, n);
  double change = 0.0;
  for (size_t i = 0; i < n.rows.size(); ++i) {
    const Row& r = s.rows[n.rows[i]];
    const double ln = normalImpulse(n.Dn[i], n.cn[i], n.xn[i]);
    const Eigen::Vector2d lt = frictionImpulse(n.Dt[i], n.radius[i], n.ct[i], n.xt[i]);
    change = std::max({change, std::abs(ln - n.ln[i]) / r.n.mass, (lt - n.lt[i]).norm() / r.t1.mass});
    n.ln[i] = ln, n.lt[i] = lt;
  }
  return change;
}

// One Newton iteration: the step d from H d = -g, then the cost's minimum along it.
// The island's first orders the factorisation (the Hessian's pattern is the same in
// all of them). Returns the largest change of a row's impulses as a velocity at the
// point (m/s).
double newtonIteration(const Solver& s, NewtonScratch& n, bool first) {
  measure(s, n);
  gradientAndHessian(s, n);
  if (first) n.factors.analyzePattern(n.H);
  n.factors.factorize(n.H);
  if (n.factors.info() != Eigen::Success) return 0.0;
  n.d = n.factors.solve(-n.g);
  for (size_t i = 0; i < n.rows.size(); ++i) {
    const Row& r = s.rows[n.rows[i]];
    n.dn[i] = along(n, r, r.n, n.d);
    n.dt[i] = {along(n, r, r.t1, n.d), along(n, r, r.t2, n.d)};
  }
  n.u += lineSearch(n) * n.d;
  return impulseChange(s, n);
}

// Newton iterations on the cost with the discs held, until no impulse changes by more
// than kNewtonTolerance (as a velocity at its point) or the cap. Returns the last change.
double minimise(const Solver& s, NewtonScratch& n, ContactSolveReport& report) {
  double change = 0.0;
  for (int k = 0; k < kMaxNewtonIterations; ++k) {
    change = newtonIteration(s, n, report.iterations == 0);
    ++report.iterations;
    report.rowSolves += static_cast<long>(n.rows.size());
    report.residual = change;
    if (change <= kNewtonTolerance) break;
  }
  return change;
}

// ---- the solve ---------------------------------------------------------------------

// Each row's stiffnesses and starting disc (the remembered normal impulse's).
void prepareNewton(const Solver& s, NewtonScratch& n) {
  const size_t rows = n.rows.size();
  n.Dn.resize(rows), n.Dt.resize(rows), n.radius.resize(rows), n.cn.resize(rows), n.ct.resize(rows);
  n.ln.resize(rows), n.lt.resize(rows);
  n.xn.resize(rows), n.dn.resize(rows), n.xt.resize(rows), n.dt.resize(rows);
  for (size_t i = 0; i < rows; ++i) {
    const Row& r = s.rows[n.rows[i]];
    n.Dn[i] = r.n.mass / kNewtonSoftness;
    n.Dt[i] = 0.5 * (r.t1.mass + r.t2.mass) / kNewtonSoftness;
    n.radius[i] = (r.sliding ? r.k.muk : r.k.mus) * r.lambdaN;
    n.cn[i] = r.lambdaN;
    n.ct[i] = {r.lambdaT1, r.lambdaT2};
  }
}

// The unknowns, the free velocities (after the impacts), and the first iterate: those
// velocities with the remembered impulses applied.
void startFromWarmStart(Solver& s, NewtonScratch& n) {
  numberBodies(s, n);
  readVelocities(s, n, n.free);
  for (size_t i : n.rows)
    if (s.rows[i].remembered) applyRowImpulse(s, s.rows[i], s.rows[i].lambdaN, s.rows[i].lambdaT1, s.rows[i].lambdaT2);
  readVelocities(s, n, n.u);
  prepareNewton(s, n);
  impulseChange(s, n);
}

// The rows' impulses at the solution onto the free velocities: the velocities and the
// impulses then agree exactly (momentum), whatever is left of the iterations' error.
void applySolution(Solver& s, NewtonScratch& n) {
  followDiscs(s, n);
  for (size_t k = 0; k < n.bodyOf.size(); ++k) {
    SolverBody& b = s.bodies[n.bodyOf[k]];
    b.v = n.free.segment<3>(6 * k);
    b.w = n.free.segment<3>(6 * k + 3);
  }
  for (size_t i = 0; i < n.rows.size(); ++i) {
    Row& r = s.rows[n.rows[i]];
    const Eigen::Vector2d lt = frictionImpulse(n.Dt[i], n.radius[i], n.ct[i], n.xt[i]);
    r.lambdaN = normalImpulse(n.Dn[i], n.cn[i], n.xn[i]);
    r.lambdaT1 = lt.x(), r.lambdaT2 = lt.y();
    applyRowImpulse(s, r, r.lambdaN, r.lambdaT1, r.lambdaT2);
  }
}

// One island's velocities and impulses: the iterations stop where it has converged,
// whatever the others still need.
int solveIsland(Solver& s, NewtonScratch& n, ContactSolveReport& report) {
  ContactSolveReport own;
  startFromWarmStart(s, n);
  for (int update = 0; update < kMaxDiscUpdates; ++update) {
    const double change = minimise(s, n, own);
    if (followDiscs(s, n) <= kVelocityTolerance && change <= kNewtonTolerance) break;
    impulseChange(s, n);  // the impulses under the new discs, that the next iterations change
  }
  applySolution(s, n);
  for (int body : n.bodyOf) n.unknown[body] = -1;
  report.rowSolves += own.rowSolves;
  report.residual = std::max(report.residual, own.residual);
  return own.iterations;
}

}  // namespace

void solveNewton(ContactScratch& s, ContactSolveReport& report) {
  if (s.rows.empty()) return;
  NewtonScratch& n = s.newton;
  n.unknown.assign(s.bodies.size(), -1);
  groupRowsByIsland(s, n.islandRows, n.islands);
  for (const auto& [begin, end] : n.islands) {
    n.rows.assign(n.islandRows.begin() + static_cast<std::ptrdiff_t>(begin),
                  n.islandRows.begin() + static_cast<std::ptrdiff_t>(end));
    report.iterations = std::max(report.iterations, solveIsland(s, n, report));
  }
}

}  // namespace rigid
