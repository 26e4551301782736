#include "block_solve.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include <Eigen/Dense>

namespace rigid {
namespace contact_rows {

namespace {

// Velocity of row i along its axis x per unit impulse of row j along its axis y: an
// entry of the Delassus matrix, from the bodies the two rows share.
double coupling(const Solver& s, const Row& i, const Axis& x, const Row& j, const Axis& y) {
  auto response = [&](int body, double side, const Vec3& arm) {
    // side: +1 where body is row i's b, -1 where it is its a; arm: r x d of that side
    const SolverBody& X = s.bodies[body];
    double sum = 0.0;
    if (j.a == body) sum -= X.invMass * x.d.dot(y.d) + arm.dot(y.spinA);
    if (j.b == body) sum += X.invMass * x.d.dot(y.d) + arm.dot(y.spinB);
    return side * sum;
  };
  double k = response(i.a, -1.0, x.raXd);
  if (i.b != s.staticSlot()) k += response(i.b, 1.0, x.rbXd);
  return k;
}

// One unknown of a block: a row's impulse along one of its axes (0: normal, 1, 2: the
// tangents).
const Axis& axisNumber(const Row& r, int axis) { return axis == 0 ? r.n : axis == 1 ? r.t1 : r.t2; }
double& impulseNumber(Row& r, int axis) { return axis == 0 ? r.lambdaN : axis == 1 ? r.lambdaT1 : r.lambdaT2; }

// The block's matrix (Delassus entries of its unknowns) and its residual (velocity
// minus target along each unknown's axis).
void assembleBlock(const Solver& s, const std::vector<std::pair<size_t, int>>& unknowns, Eigen::MatrixXd& K,
                   Eigen::VectorXd& residual) {
  const Eigen::Index n = static_cast<Eigen::Index>(unknowns.size());
  for (Eigen::Index p = 0; p < n; ++p) {
    const Row& r = s.rows[unknowns[p].first];
    const Axis& x = axisNumber(r, unknowns[p].second);
    residual(p) = relativeVelocity(s, r, x) - (unknowns[p].second == 0 ? r.target : 0.0);
    for (Eigen::Index q = 0; q <= p; ++q) {
      const Row& o = s.rows[unknowns[q].first];
      K(p, q) = K(q, p) = coupling(s, r, x, o, axisNumber(o, unknowns[q].second));
    }
  }
}

// Friction outside its disc projected onto it and held there from now on. Returns
// whether some row's was.
bool projectFriction(Solver& s, const std::vector<size_t>& rows) {
  bool changed = false;
  for (size_t i : rows) {
    Row& r = s.rows[i];
    const double t = length(r.lambdaT1, r.lambdaT2), limit = frictionLimit(r);
    if (t <= limit) continue;
    const double scale = limit / t;
    applyImpulse(s, r, r.t1, r.lambdaT1 * (scale - 1.0));
    applyImpulse(s, r, r.t2, r.lambdaT2 * (scale - 1.0));
    r.lambdaT1 *= scale, r.lambdaT2 *= scale;
    r.held = changed = true;
  }
  return changed;
}

// The impulses of `rows` solved together, exactly: lambda_n >= 0 with v_n = target
// wherever lambda_n > 0, and the slip stopped at every sticking point whose friction
// stays inside its disc. An active set: rows that would pull are dropped, points whose
// friction would leave the disc are projected onto it and held there, and the rest is
// solved again. Sliding points keep their kinetic friction as the passes made it;
// speculative points are left to the passes (their targets, gap / h, need not agree
// with a touching point's 0 on the same pair, and the least-squares answer to that
// would be huge). A face's four points are redundant (one normal and one twist too
// many), so the matrix is made regular by 1e-9 of its diagonal: near the least-norm
// impulses, the load shared evenly.
void solveBlock(Solver& s, const std::vector<size_t>& rows) {
  std::vector<size_t>& active = s.active;
  active.clear();
  for (size_t i : rows) {
    Row& r = s.rows[i];
    r.held = r.sliding;
    if (r.depth < -kTouching) continue;
    if (r.lambdaN > 0.0 || relativeVelocity(s, r, r.n) < r.target) active.push_back(i);
  }
  std::vector<std::pair<size_t, int>>& unknowns = s.unknowns;
  constexpr int kMaxRounds = 8;
  for (int round = 0; round <= kMaxRounds && !active.empty(); ++round) {
    if (round == kMaxRounds)  // not settled: the normals alone, with the friction as it is
      for (size_t i : active) s.rows[i].held = true;
    unknowns.clear();
    for (size_t i : active)
      for (int axis = 0; axis < (s.rows[i].held ? 1 : 3); ++axis) unknowns.emplace_back(i, axis);
    const Eigen::Index n = static_cast<Eigen::Index>(unknowns.size());
    Eigen::MatrixXd& K = s.K;
    Eigen::VectorXd& residual = s.residual;
    Eigen::VectorXd& delta = s.delta;
    K.resize(n, n);
    residual.resize(n);
    assembleBlock(s, unknowns, K, residual);
    // regularised, then refined twice against the exact matrix: the regularisation's
    // own error (1e-9 of a 1e6 kg box's load) would otherwise be left in the velocities
    s.regular = K;
    s.regular.diagonal() *= 1.0 + 1e-9;
    s.factors.compute(s.regular);
    delta = s.factors.solve(-residual);
    for (int refine = 0; refine < 2; ++refine) delta += s.factors.solve(-(residual + K * delta));
    if (!delta.allFinite()) return;
    for (Eigen::Index p = 0; p < n; ++p) {
      Row& r = s.rows[unknowns[p].first];
      const int axis = unknowns[p].second;
      double& lambda = impulseNumber(r, axis);
      const double total = axis == 0 ? std::max(lambda + delta(p), 0.0) : lambda + delta(p);
      applyImpulse(s, r, axisNumber(r, axis), total - lambda);
      lambda = total;
    }
    const bool changed = projectFriction(s, active);
    const size_t before = active.size();
    active.erase(std::remove_if(active.begin(), active.end(), [&](size_t i) { return s.rows[i].lambdaN == 0.0; }),
                 active.end());
    if (!changed && active.size() == before) return;
  }
}

// The ratio of the heaviest to the lightest body that the rows [begin, end) of `order`
// touch (1 when they touch one body).
double massRatio(const Solver& s, const std::vector<size_t>& order, size_t begin, size_t end) {
  double lightest = 0.0, heaviest = std::numeric_limits<double>::infinity();  // in inverse masses
  for (size_t k = begin; k < end; ++k) {
    const Row& r = s.rows[order[k]];
    for (int body : {r.a, r.b}) {
      if (body == s.staticSlot()) continue;
      lightest = std::max(lightest, s.bodies[body].invMass);
      heaviest = std::min(heaviest, s.bodies[body].invMass);
    }
  }
  return lightest / heaviest;
}

}  // namespace

// The islands (bodies joined by rows) that the block solve may take: at most
// kMaxBlockRows rows whose masses differ by kBlockMassRatio or more. Their rows go to
// s.islandRows, island after island, and each island's [begin, end) to s.blocks. Rows
// do not change within a solve, so this is found once, at the first pass that wants it.
void findBlockIslands(Solver& s) {
  std::vector<size_t>& order = s.islandRows;
  order.resize(s.rows.size());
  std::iota(order.begin(), order.end(), size_t{0});
  s.blocks.clear();
  if (massRatio(s, order, 0, order.size()) < kBlockMassRatio) return;  // like masses: none
  groupRowsByIsland(s, order, s.blocks);
  s.blocks.erase(std::remove_if(s.blocks.begin(), s.blocks.end(),
                                [&](const std::pair<size_t, size_t>& b) {
                                  return b.second - b.first > static_cast<size_t>(kMaxBlockRows) ||
                                         massRatio(s, order, b.first, b.second) < kBlockMassRatio;
                                }),
                 s.blocks.end());
}

// Every island of findBlockIslands that the passes have not settled has its impulses
// solved at once (solveBlock). Its bodies' versions change, so that its rows are
// solved again.
void solveBlockIslands(Solver& s) {
  const std::vector<size_t>& order = s.islandRows;
  std::vector<size_t>& rows = s.block;
  for (const auto& [begin, end] : s.blocks) {
    const bool unsettled =
        std::any_of(order.begin() + static_cast<std::ptrdiff_t>(begin),
                    order.begin() + static_cast<std::ptrdiff_t>(end), [&](size_t i) { return !s.rows[i].settled; });
    if (!unsettled) continue;
    rows.assign(order.begin() + static_cast<std::ptrdiff_t>(begin), order.begin() + static_cast<std::ptrdiff_t>(end));
    solveBlock(s, rows);
    for (size_t i : rows) ++s.bodies[s.rows[i].a].version, ++s.bodies[s.rows[i].b].version;
  }
}

}  // namespace contact_rows
}  // namespace rigid
