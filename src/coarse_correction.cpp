#include "coarse_correction.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "contact_rows.h"

namespace rigid {
namespace contact_rows {

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Wrenches = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;
using Block = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

// A pair is welded when each of its points touches, sticks, and bears a load or does
// not part (a pair new this step has no load yet). Its friction may be on the edge of
// its disc: the passes build up friction that balances itself across a face, and a
// resting column's faces keep some of it there.
bool weldable(const Solver& s, size_t begin, size_t end) {
  for (size_t i = begin; i < end; ++i) {
    const Row& r = s.rows[i];
    if (r.depth < -kTouching || r.sliding) return false;
    if (r.lambdaN <= 0.0 && relativeVelocity(s, r, r.n) > kNegligible) return false;  // unloaded and parting
  }
  return true;
}

// The pair's reference point on each body: the mean of its points' arms.
std::pair<Vec3, Vec3> referencePoints(const Solver& s, size_t begin, size_t end) {
  const double k = static_cast<double>(end - begin);
  Vec3 ca = Vec3::Zero(), cb = Vec3::Zero();
  for (size_t i = begin; i < end; ++i) ca += s.rows[i].ra / k, cb += s.rows[i].rb / k;
  return {ca, cb};
}

// The speed of b relative to a at the pair's reference points, m/s.
double slipSpeed(const Solver& s, size_t begin, size_t end) {
  const auto [ca, cb] = referencePoints(s, begin, end);
  const SolverBody& A = s.bodies[s.rows[begin].a];
  const SolverBody& B = s.bodies[s.rows[begin].b];
  return (B.v + B.w.cross(cb) - A.v - A.w.cross(ca)).norm();
}

// The pair's plane, its points' spread in it and the wrenches they can carry.
CoarsePair pairOf(const Solver& s, size_t begin, size_t end) {
  CoarsePair p;
  p.begin = begin, p.end = end;
  p.a = s.rows[begin].a, p.b = s.rows[begin].b;
  std::tie(p.ca, p.cb) = referencePoints(s, begin, end);
  p.n = s.rows[begin].n.d;
  p.e1 = s.rows[begin].t1.d;
  p.e2 = p.n.cross(p.e1);
  Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
  for (size_t i = begin; i < end; ++i) {
    const Vec3 d = s.rows[i].ra - p.ca;
    const Eigen::Vector2d xy(d.dot(p.e1), d.dot(p.e2));
    spread += xy * xy.transpose();
  }
  p.polar = spread.trace();
  p.basis.topLeftCorner<3, 3>().setIdentity();  // the force
  p.m = 3;
  if (p.polar <= kCoarseSpread) return p;
  // normal loads growing along an eigenvector v of the spread tip the pair about R v,
  // R (x, y) = (y, -x); a direction without spread (the line of two points) carries none
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(spread);
  const double largest = eigen.eigenvalues()(1);
  for (int j = 0; j < 2; ++j) {
    const double mu = eigen.eigenvalues()(j);
    if (mu <= kCoarseSpreadRatio * largest) continue;
    const Eigen::Vector2d v = eigen.eigenvectors().col(j);
    p.spreadInverse += v * v.transpose() / mu;
    p.basis.block<3, 1>(3, p.m++) = v(1) * p.e1 - v(0) * p.e2;
  }
  p.basis.block<3, 1>(3, p.m++) = p.n;  // the twist, by the points' friction
  return p;
}

// The wrench at a body's centre per unit of the pair's unknowns, the body's reference
// point being c: (F, c x F + M).
Wrenches atCentre(const CoarsePair& p, const Vec3& c) {
  Wrenches G = p.basis.leftCols(p.m);
  for (int j = 0; j < p.m; ++j) G.block<3, 1>(3, j) += c.cross(Vec3(G.block<3, 1>(0, j)));
  return G;
}

// The pair's relative motion (b's less a's, at the reference points) along its unknowns.
Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1> relativeMotion(const Solver& s, const CoarsePair& p) {
  const SolverBody& A = s.bodies[p.a];
  const SolverBody& B = s.bodies[p.b];
  Vec6 xi;
  xi << B.v + B.w.cross(p.cb) - A.v - A.w.cross(p.ca), B.w - A.w;
  return p.basis.leftCols(p.m).transpose() * xi;
}

// The island's weldable pairs' rows into c.welds; whether it is to be corrected: at
// most kMaxCoarsePairs touching pairs, two or more of them weldable, none of those
// faster than restingSpeed and not all still.
bool findWelds(const Solver& s, size_t begin, size_t end, double restingSpeed, CoarseScratch& c) {
  c.welds.clear();
  int touching = 0;
  double fastest = 0.0;
  for (size_t k = begin; k < end;) {
    const size_t first = c.islandRows[k], last = pairEnd(s, first);
    k += last - first;  // a pair's rows are consecutive, in the island's order too
    if (s.rows[first].depth < -kTouching) continue;
    if (++touching > kMaxCoarsePairs) return false;
    if (!weldable(s, first, last)) continue;
    c.welds.emplace_back(first, last);
    fastest = std::max(fastest, slipSpeed(s, first, last));
  }
  return c.welds.size() >= 2 && fastest <= restingSpeed && fastest > kCoarseStill;
}

// The welded pairs of c.welds into c.pairs, their unknowns numbered.
void weldPairs(const Solver& s, CoarseScratch& c) {
  c.pairs.clear();
  int unknowns = 0;
  for (const auto& [first, last] : c.welds) {
    c.pairs.push_back(pairOf(s, first, last));
    c.pairs.back().offset = unknowns;
    unknowns += c.pairs.back().m;
  }
}

// The matrix of the wrenches: each body adds, for every two of its welded pairs q and p,
// the motion of q per unit wrench of p through it.
void assemble(const Solver& s, CoarseScratch& c) {
  c.entries.clear();
  for (int body : c.bodies) {
    const std::vector<std::pair<int, int>>& of = c.pairsOf[body];
    const SolverBody& X = s.bodies[body];
    for (const auto& [q, sideQ] : of) {
      const CoarsePair& Q = c.pairs[q];
      const Wrenches Gq = atCentre(Q, sideQ > 0 ? Q.cb : Q.ca);
      for (const auto& [p, sideP] : of) {
        const CoarsePair& P = c.pairs[p];
        Wrenches H = atCentre(P, sideP > 0 ? P.cb : P.ca);
        H.topRows<3>() *= X.invMass;
        H.bottomRows<3>() = (X.Iinv * H.bottomRows<3>()).eval();
        Block block = static_cast<double>(sideQ * sideP) * (Gq.transpose() * H);
        if (q == p) block.diagonal() *= 1.0 + kCoarseRegular;
        for (int i = 0; i < Q.m; ++i)
          for (int j = 0; j < P.m; ++j) c.entries.emplace_back(Q.offset + i, P.offset + j, block(i, j));
      }
    }
  }
}

// The wrench (F, M) of pair p onto its points, least-norm: F shared evenly, M's tipping
// by normal loads growing linearly across the points and its twist by friction about
// their centroid; each point's normal impulse kept >= 0 and its friction in its disc.
void distribute(Solver& s, const CoarsePair& p, const Vec6& W) {
  const Vec3 F = W.head<3>(), M = W.tail<3>();
  const double k = static_cast<double>(p.end - p.begin);
  const Eigen::Vector2d slope = p.spreadInverse * Eigen::Vector2d(-M.dot(p.e2), M.dot(p.e1));
  const double twist = p.polar > kCoarseSpread ? M.dot(p.n) / p.polar : 0.0;
  for (size_t i = p.begin; i < p.end; ++i) {
    Row& r = s.rows[i];
    const Vec3 d = r.ra - p.ca;
    const double x = d.dot(p.e1), y = d.dot(p.e2);
    const Vec3 g = F / k + (slope(0) * x + slope(1) * y) * p.n + twist * (x * p.e2 - y * p.e1);
    const double ln = std::max(r.lambdaN + g.dot(r.n.d), 0.0);
    double l1 = r.lambdaT1 + g.dot(r.t1.d), l2 = r.lambdaT2 + g.dot(r.t2.d);
    clampToDisc(l1, l2, (r.sliding ? r.k.muk : r.k.mus) * ln);
    applyRowImpulse(s, r, ln - r.lambdaN, l1 - r.lambdaT1, l2 - r.lambdaT2);
    r.lambdaN = ln, r.lambdaT1 = l1, r.lambdaT2 = l2;
  }
}

// The island's wrenches solved and handed to its points. A welded structure with a
// loop (a cube leaning on two) has more wrenches than motions: its matrix, made regular
// by kCoarseRegular of its diagonal, gives the least-norm ones.
void correctIsland(Solver& s, CoarseScratch& c) {
  const int unknowns = c.pairs.back().offset + c.pairs.back().m;
  c.pairsOf.resize(s.bodies.size());
  c.bodies.clear();
  c.motion.resize(unknowns);
  auto join = [&](int body, int q, int side) {
    if (c.pairsOf[body].empty()) c.bodies.push_back(body);
    c.pairsOf[body].emplace_back(q, side);
  };
  for (int q = 0; q < static_cast<int>(c.pairs.size()); ++q) {
    const CoarsePair& p = c.pairs[q];
    join(p.a, q, -1);
    if (p.b != s.staticSlot()) join(p.b, q, 1);
    c.motion.segment(p.offset, p.m) = relativeMotion(s, p);
  }
  assemble(s, c);
  for (int body : c.bodies) c.pairsOf[body].clear();
  c.K.resize(unknowns, unknowns);
  c.K.setFromTriplets(c.entries.begin(), c.entries.end());
  c.factors.compute(c.K);
  if (c.factors.info() != Eigen::Success) return;
  c.wrench = c.factors.solve(-c.motion);
  if (!c.wrench.allFinite()) return;
  for (const CoarsePair& p : c.pairs) distribute(s, p, p.basis.leftCols(p.m) * c.wrench.segment(p.offset, p.m));
}

}  // namespace

void coarseCorrection(Solver& s, double restingSpeed) {
  CoarseScratch& c = s.coarse;
  groupRowsByIsland(s, c.islandRows, c.islands);
  for (const auto& [begin, end] : c.islands) {
    if (!findWelds(s, begin, end, restingSpeed, c)) continue;
    weldPairs(s, c);
    correctIsland(s, c);
  }
}

}  // namespace contact_rows
}  // namespace rigid
