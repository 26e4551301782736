#include "contact_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>

#include <Eigen/Dense>

#include "contact_rows.h"
#include "contact_rules.h"
#include "islands.h"
#include "soft_contacts.h"

namespace rigid {

using namespace contact_solver;

void ContactScratchDeleter::operator()(ContactScratch* s) const { delete s; }

namespace {

using namespace contact_rows;

// The end of the rows of the pair that row i belongs to (rows come grouped by pair).
size_t pairEnd(const Solver& s, size_t i) {
  size_t end = i;
  while (end < s.rows.size() && s.rows[end].a == s.rows[i].a && s.rows[end].b == s.rows[i].b &&
         s.rows[end].contact->surface == s.rows[i].contact->surface)
    ++end;
  return end;
}

Coefficients coefficientsOf(const WorldModel& model, const Contact& c) {
  const BodyConstants& a = model.bodies[c.a];
  const bool body = c.b >= 0;
  const double xi = body ? model.bodies[c.b].restitution : model.surfaces[c.surface].restitution;
  const double mus = body ? model.bodies[c.b].staticFriction : model.surfaces[c.surface].staticFriction;
  const double muk = body ? model.bodies[c.b].kineticFriction : model.surfaces[c.surface].kineticFriction;
  return {combineCoefficients(a.restitution, xi), combineCoefficients(a.staticFriction, mus),
          combineCoefficients(a.kineticFriction, muk)};
}

Vec3 anyPerpendicular(const Vec3& u) {
  const Vec3 other = std::abs(u.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return u.cross(other).normalized();
}

Axis axisOf(const SolverBody& A, const SolverBody& B, const Vec3& ra, const Vec3& rb, const Vec3& d) {
  Axis x;
  x.d = d;
  x.raXd = ra.cross(d);
  x.rbXd = rb.cross(d);
  x.spinA = A.Iinv * x.raXd;
  x.spinB = B.Iinv * x.rbXd;
  x.mass = 1.0 / (A.invMass + B.invMass + x.raXd.dot(x.spinA) + x.rbXd.dot(x.spinB));
  return x;
}

// ---- prepare ---------------------------------------------------------------------

void prepareBody(const WorldModel& model, const std::vector<BodyState>& Y, int i, Solver& s) {
  if (s.involved[i]) return;
  s.involved[i] = 1;
  SolverBody& b = s.bodies[i];
  b = SolverBody{};
  const Mat3 R = Y[i].q.normalized().toRotationMatrix();
  b.invMass = 1.0 / model.bodies[i].mass;
  b.Iinv = R * model.bodies[i].IbodyInv * R.transpose();
  b.v = Y[i].P * b.invMass;
  b.w = b.Iinv * Y[i].L;
}

// A row per contact point. A speculative point (apart by a gap) of a bouncing pair is
// left out: its impact is located in time, and slowing it early would take energy
// from the bounce.
void prepareRows(const WorldModel& model, const std::vector<Contact>& contacts, const ContactStep& step,
                 const std::vector<BodyState>& Y, Solver& s) {
  s.rows.clear();
  s.rows.reserve(contacts.size());
  for (const Contact& c : contacts) {
    Row r;
    r.k = coefficientsOf(model, c);
    const bool touching = c.depth >= -kTouching;
    if (!touching && r.k.xi > 0.0) continue;
    r.contact = &c;
    r.a = c.a;
    r.b = c.b >= 0 ? c.b : s.staticSlot();
    prepareBody(model, Y, c.a, s);
    if (c.b >= 0) prepareBody(model, Y, c.b, s);
    // Each body's lever arm to its own surface point (the detector's point is midway
    // in the overlap): a sphere sunk by the step's g h^2 / 2 is then turned by friction
    // about its radius R, not R - depth / 2.
    r.ra = c.point + 0.5 * c.depth * c.normal - Y[c.a].X;
    r.localA = Y[c.a].q.normalized().conjugate() * r.ra;
    r.rb = c.b >= 0 ? Vec3(c.point - 0.5 * c.depth * c.normal - Y[c.b].X) : Vec3::Zero();
    const SolverBody& A = s.bodies[r.a];
    const SolverBody& B = s.bodies[r.b];
    r.n = axisOf(A, B, r.ra, r.rb, c.normal);
    // First tangent along the slip, so that a sliding point's friction opposes it
    // exactly from the first pass; any direction when it does not slip.
    const Vec3 u = B.v + B.w.cross(r.rb) - A.v - A.w.cross(r.ra);
    const Vec3 slip = u - u.dot(c.normal) * c.normal;
    const Vec3 t1 = slip.norm() > 1e-9 ? Vec3(slip.normalized()) : anyPerpendicular(c.normal);
    r.sliding = slip.norm() > step.restingSpeed;  // a new point; a kept one takes its memory's
    r.t1 = axisOf(A, B, r.ra, r.rb, t1);
    r.t2 = axisOf(A, B, r.ra, r.rb, c.normal.cross(t1));
    r.depth = c.depth;
    r.target = touching ? 0.0 : c.depth / step.h;  // apart: may close the gap in the step
    s.rows.push_back(r);
  }
}

// ---- impacts ---------------------------------------------------------------------

// The touching points of one pair merged into one (centroid, mean normal): an impact
// on a face then takes one impulse through the patch's centre instead of corner
// impulses whose sequential order would leave a spurious spin.
void impactRows(const Solver& s, std::vector<Row>& out) {
  out.clear();
  for (size_t i = 0; i < s.rows.size();) {
    const size_t end = pairEnd(s, i);
    Vec3 point = Vec3::Zero(), normal = Vec3::Zero();
    int n = 0;
    for (size_t k = i; k < end; ++k) {
      if (s.rows[k].depth < -kTouching) continue;
      point += s.rows[k].ra;
      normal += s.rows[k].n.d;
      ++n;
    }
    if (n > 0) {
      Row r = s.rows[i];
      const Vec3 X = r.ra;  // a's lever arm of the first point: shift every arm by the same
      r.ra = point / n;
      r.rb = r.rb + (r.ra - X);
      r.n = axisOf(s.bodies[r.a], s.bodies[r.b], r.ra, r.rb, normal.normalized());
      out.push_back(r);
    }
    i = end;
  }
}

// The seed's impulse at one merged point, j = -(1 + xi) vrel m_eff, then a Coulomb
// friction impulse against the slip, |jt| <= mu j (static when it stops the slip).
void impact(Solver& s, const Row& r, double vrel, std::vector<SurfacePush>& pushes) {
  const double j = -(1.0 + r.k.xi) * vrel * r.n.mass;
  applyImpulse(s, r, r.n, j);
  const bool onSurface = r.b == s.staticSlot();
  if (onSurface) pushes.push_back({r.a, r.contact->surface, j * r.n.d});
  const SolverBody& A = s.bodies[r.a];
  const SolverBody& B = s.bodies[r.b];
  const Vec3 u = B.v + B.w.cross(r.rb) - A.v - A.w.cross(r.ra);
  const Vec3 ut = u - u.dot(r.n.d) * r.n.d;
  if (ut.norm() < 1e-15) return;
  const Axis t = axisOf(A, B, r.ra, r.rb, -ut.normalized());
  const double stick = ut.norm() * t.mass;
  const double jt = stick <= r.k.mus * j ? stick : r.k.muk * j;
  applyImpulse(s, r, t, jt);
  if (onSurface) pushes.back().impulse += jt * t.d;
}

// Impacts as the seed answers them, before the solve and outside its accumulated
// impulses (which would take a bounce back): passes over the pairs while one of them
// approaches faster than a resting body can, so that a chain of touching bodies passes
// an impact on (Newton's cradle). Returns the passes taken. The soft sub-steps answer
// only the bouncing pairs (xi > 0) here: an inelastic landing is stopped within their
// sub-steps, where the seed's impulse at the step's end left the body sunk by the
// step's travel (2 mm in a falling pile of 100, 0.4 mm without).
int answerImpacts(Solver& s, const ContactStep& step, std::vector<SurfacePush>& pushes) {
  const bool inelastic = step.model != ContactModel::Soft;
  auto striking = [&](const Row& r, double vrel) { return vrel < -step.restingSpeed && (inelastic || r.k.xi > 0.0); };
  const bool any = std::any_of(s.rows.begin(), s.rows.end(), [&](const Row& r) {
    return r.depth >= -kTouching && striking(r, relativeVelocity(s, r, r.n));
  });
  if (!any) return 0;
  impactRows(s, s.impacts);
  const std::vector<Row>& rows = s.impacts;
  int passes = 0;
  for (bool struck = true; struck && passes < kMaxImpactPasses;) {
    struck = false;
    for (const Row& r : rows) {
      const double vrel = relativeVelocity(s, r, r.n);
      if (!striking(r, vrel)) continue;
      impact(s, r, vrel, pushes);
      struck = true;
    }
    if (struck) ++passes;
  }
  return passes;
}

// ---- warm start ------------------------------------------------------------------

// The velocities that the impacts and the solve's impulses start from (correctPositions
// moves each body by what they change, within limitMoves).
void markVelocities(Solver& s) {
  for (SolverBody& b : s.bodies) b.v0 = b.v, b.w0 = b.w;
}

// One row takes the impulses of memory[m], clamped to its friction disc.
void remember(const ContactMemory& m, Row& r) {
  r.sliding = m.sliding;
  r.remembered = true;
  r.lambdaN = m.normalImpulse;
  r.lambdaT1 = m.tangentImpulse.dot(r.t1.d);
  r.lambdaT2 = m.tangentImpulse.dot(r.t2.d);
  const double limit = (r.sliding ? r.k.muk : r.k.mus) * r.lambdaN, t = length(r.lambdaT1, r.lambdaT2);
  if (t > limit) r.lambdaT1 *= limit / t, r.lambdaT2 *= limit / t;
}

// Each row takes the impulses of last step's nearest point of the same pair (body a's
// frame, within kMatchDistance), each old point used once (applyWarmStart applies them:
// the soft sub-steps apply their share in each sub-step instead). Rows and
// memory are both in the detector's pair order: one search per pair. A body sticks or
// slides as a whole, so a pair's new points take its remembered state.
void warmStart(const std::vector<ContactMemory>& memory, Solver& s) {
  s.used.assign(memory.size(), 0);
  auto before = [](const ContactMemory& m, const std::tuple<int, int, int>& key) {
    return pairKey(m.a, m.b, m.surface) < key;
  };
  auto from = memory.begin();
  for (size_t i = 0; i < s.rows.size();) {
    const size_t end = pairEnd(s, i);
    const Contact& c = *s.rows[i].contact;
    const auto key = pairKey(c.a, c.b, c.surface);
    from = std::lower_bound(from, memory.end(), key, before);
    auto to = from;
    while (to != memory.end() && pairKey(to->a, to->b, to->surface) == key) ++to;
    int state = -1;  // the pair's remembered sliding state, -1: none
    for (size_t k = i; k < end; ++k) {
      Row& r = s.rows[k];
      size_t best = memory.size();
      double nearest = kMatchDistance * kMatchDistance;
      for (auto it = from; it != to; ++it) {
        const size_t m = static_cast<size_t>(it - memory.begin());
        const double d2 = (it->localA - r.localA).squaredNorm();
        if (!s.used[m] && d2 < nearest) nearest = d2, best = m;
      }
      if (best == memory.size()) continue;
      s.used[best] = 1;
      remember(memory[best], r);
      state = r.sliding ? 1 : 0;
    }
    if (state >= 0)
      for (size_t k = i; k < end; ++k) s.rows[k].sliding = state == 1;
    i = end;
  }
}

// The remembered impulses onto the bodies' velocities, the passes' starting point.
void applyWarmStart(Solver& s) {
  for (const Row& r : s.rows)
    if (r.remembered) applyRowImpulse(s, r, r.lambdaN, r.lambdaT1, r.lambdaT2);
}

// ---- velocities ------------------------------------------------------------------

// Normal: lambda_n += -m_n (v_n - target), clamped at 0 accumulated. Returns the
// velocity change it made at the point (m/s).
double solveNormal(Solver& s, Row& r) {
  const double vn = relativeVelocity(s, r, r.n);
  const double total = std::max(r.lambdaN - r.n.mass * (vn - r.target), 0.0);
  const double delta = total - r.lambdaN;
  r.lambdaN = total;
  applyImpulse(s, r, r.n, delta);
  return std::abs(delta) / r.n.mass;
}

void noteChange(Solver& s, const Row& r, double change) {
  if (change <= kNegligible) return;
  ++s.bodies[r.a].version;
  ++s.bodies[r.b].version;
}

// One row: normal, then friction with the new normal impulse. A row whose bodies took
// no impulse worth noting since it was found settled is settled still, and skipped: a
// pile converges where it moves, not everywhere. Returns the velocity change it made.
double solveRow(Solver& s, Row& r) {
  if (r.settled && r.versionA == s.bodies[r.a].version && r.versionB == s.bodies[r.b].version) return 0.0;
  const double normal = solveNormal(s, r);
  noteChange(s, r, normal);
  const double friction = solveFriction(s, r);
  noteChange(s, r, friction);
  const double change = std::max(normal, friction);
  r.settled = change <= kVelocityTolerance;
  r.versionA = s.bodies[r.a].version;
  r.versionB = s.bodies[r.b].version;
  return change;
}

// ---- block solve of small islands ---------------------------------------------------

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

// The islands (bodies joined by rows) that the block solve may take: at most
// kMaxBlockRows rows whose masses differ by kBlockMassRatio or more. Their rows go to
// s.islandRows, island after island, and each island's [begin, end) to s.blocks. Rows
// do not change within a solve, so this is found once, at the first pass that wants it.
void findBlockIslands(Solver& s) {
  const int statics = s.staticSlot();
  std::vector<size_t>& order = s.islandRows;
  order.resize(s.rows.size());
  std::iota(order.begin(), order.end(), size_t{0});
  s.blocks.clear();
  if (massRatio(s, order, 0, order.size()) < kBlockMassRatio) return;  // like masses: none
  std::vector<int>& parent = s.island;
  parent.resize(s.bodies.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (const Row& r : s.rows)
    if (r.b != statics) parent[islandRoot(parent, r.a)] = islandRoot(parent, r.b);
  for (int& p : parent) p = islandRoot(parent, p);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t x, size_t y) { return parent[s.rows[x].a] < parent[s.rows[y].a]; });
  for (size_t begin = 0; begin < order.size();) {
    size_t end = begin;
    while (end < order.size() && parent[s.rows[order[end]].a] == parent[s.rows[order[begin]].a]) ++end;
    if (end - begin <= static_cast<size_t>(kMaxBlockRows) && massRatio(s, order, begin, end) >= kBlockMassRatio)
      s.blocks.emplace_back(begin, end);
    begin = end;
  }
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

// ---- velocities, iterated ---------------------------------------------------------

// Gauss-Seidel passes over the rows until no impulse changes a velocity by more than
// the tolerance, or the cap. The passes sweep forwards and backwards in turn
// (symmetric Gauss-Seidel): sweeps in one order only let a tall column of cubes rock,
// as a sweep from the bottom up builds a lean that the next one does not take back.
void solveVelocities(Solver& s, ContactSolveReport& report) {
  const size_t n = s.rows.size();
  for (report.iterations = 0; report.iterations < kMaxVelocityIterations;) {
    const bool backwards = report.iterations % 2 == 1;
    double change = 0.0;
    for (size_t k = 0; k < n; ++k) change = std::max(change, solveRow(s, s.rows[backwards ? n - 1 - k : k]));
    ++report.iterations;
    report.residual = change;
    if (change <= kVelocityTolerance) break;
    if (report.iterations < kBlockAfter) continue;
    if (report.iterations == kBlockAfter) findBlockIslands(s);
    solveBlockIslands(s);
  }
}

// ---- shock propagation -----------------------------------------------------------

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

// ---- momenta ---------------------------------------------------------------------

// The solve's velocity changes into Y's momenta, once: P += M dv, L += I dw, I = R Ibody
// R^T at the pose the solve saw (correctPositions turns the bodies after). Kept apart
// from each impulse, which then changes two vectors per body instead of four; a body
// the impulses left alone keeps its momenta bitwise.
void storeMomenta(const WorldModel& model, const Solver& s, std::vector<BodyState>& Y) {
  for (size_t i = 0; i + 1 < s.bodies.size(); ++i) {
    const SolverBody& b = s.bodies[i];
    if (!s.involved[i] || (b.v == b.v0 && b.w == b.w0)) continue;
    const Mat3 R = Y[i].q.normalized().toRotationMatrix();
    Y[i].P += model.bodies[i].mass * (b.v - b.v0);
    Y[i].L += R * model.bodies[i].Ibody * R.transpose() * (b.w - b.w0);
  }
}

// ---- positions -------------------------------------------------------------------

// The change of a row's normal velocity since markVelocities, each body's share of it
// scaled by sa and sb (limitMoves' move scales).
double normalChange(const Solver& s, const Row& r, double sa, double sb) {
  const SolverBody& A = s.bodies[r.a];
  const SolverBody& B = s.bodies[r.b];
  return r.n.d.dot(sb * (B.v - B.v0) - sa * (A.v - A.v0)) + sb * r.n.rbXd.dot(B.w - B.w0) -
         sa * r.n.raXd.dot(A.w - A.w0);
}

// Split impulse: pseudo-velocities that would remove kBaumgarte of each overlap beyond
// the slop in one step, solved like the normal impulses (accumulated, >= 0). They are
// integrated into the positions and dropped: velocities, and so the energy, are left as
// the solve made them.
void solvePseudoVelocities(Solver& s, double h, double share) {
  // the overlap each row has left after the solve's own move (correctPositions); only
  // rows deeper than the slop take part
  s.deep.clear();
  for (size_t i = 0; i < s.rows.size(); ++i) {
    Row& r = s.rows[i];
    const double depth = r.depth - share * h * normalChange(s, r, s.moveScale[r.a], s.moveScale[r.b]);
    if (depth <= kSlop) continue;
    r.pushOut = std::min(kBaumgarte * (depth - kSlop) / h, kMaxPushOut);
    s.deep.push_back(i);
  }
  for (int pass = 0; pass < kPositionIterations && !s.deep.empty(); ++pass) {
    double change = 0.0;
    for (size_t i : s.deep) {
      Row& r = s.rows[i];
      SolverBody& A = s.bodies[r.a];
      SolverBody& B = s.bodies[r.b];
      const double vn = r.n.d.dot(B.vp - A.vp) + r.n.rbXd.dot(B.wp) - r.n.raXd.dot(A.wp);
      const double total = std::max(r.lambdaP + r.n.mass * (r.pushOut - vn), 0.0);
      const double delta = total - r.lambdaP;
      r.lambdaP = total;
      change = std::max(change, std::abs(delta) / r.n.mass);
      A.vp -= delta * A.invMass * r.n.d;
      A.wp -= delta * r.n.spinA;
      if (r.b == s.staticSlot()) continue;
      B.vp += delta * B.invMass * r.n.d;
      B.wp += delta * r.n.spinB;
    }
    if (change <= kVelocityTolerance) return;
  }
}

// The share of the solve's move that each body takes (1: all of it). A ball landing at
// 2 m/s is stopped by an impulse of 2 m/s m; taken as a force over the step, it would
// lift the ball h/2 2 m/s above the floor, and every later step would keep it hovering
// at g h^2 / 2. The impulse that stops an approach acts at the step's end: a point
// whose normal velocity the solve changed by more than the step's forces can (more
// than the resting speed) may be closed by the move but not opened beyond touching.
// (Every point would be too strict: a resting body's move takes back its sinking at
// all its points, and one point's limit would leave the others sunk.)
void limitMoves(Solver& s, const ContactStep& step) {
  s.moveScale.assign(s.bodies.size(), 1.0);
  for (const Row& r : s.rows) {
    const double solved = normalChange(s, r, 1.0, 1.0);
    if (!(solved > step.restingSpeed)) continue;
    const double opening = step.moveShare * step.h * solved, allowed = std::max(r.depth, 0.0);
    if (!(opening > allowed)) continue;
    const double scale = allowed / opening;
    s.moveScale[r.a] = std::min(s.moveScale[r.a], scale);
    s.moveScale[r.b] = std::min(s.moveScale[r.b], scale);
  }
}

// The positions: the pseudo-velocities' move, and the move of the solve's impulses
// taken as a constant force over the step (`share` of h times the velocity change they
// made: h/2 for the methods exact on a constant force, as the integrator would move a
// body under one), within limitMoves. The integrator moved every body by the step's
// applied forces alone: a body resting on the floor sank g h^2 / 2 and a box held by
// static friction on a ramp slid g sin(theta) h^2 / 2; the solve's move takes both
// back, so that what contact holds does not creep.
void correctPositions(Solver& s, const ContactStep& step, std::vector<BodyState>& Y) {
  const double h = step.h, share = step.moveShare;
  limitMoves(s, step);
  solvePseudoVelocities(s, h, share);
  for (size_t i = 0; i + 1 < s.bodies.size(); ++i) {
    const SolverBody& b = s.bodies[i];
    if (!s.involved[i]) continue;
    const double moved = share * s.moveScale[i];
    const Vec3 move = h * b.vp + moved * h * (b.v - b.v0);
    const Vec3 turn = h * b.wp + moved * h * (b.w - b.w0);
    if (move.isZero(0.0) && turn.isZero(0.0)) continue;
    Y[i].X += move;
    const Quat& q = Y[i].q;
    const Quat spin(0.0, 0.5 * turn.x(), 0.5 * turn.y(), 0.5 * turn.z());
    Y[i].q = Quat(q.coeffs() + (spin * q).coeffs()).normalized();
  }
}

// ---- store -----------------------------------------------------------------------

// A pair slides in the next step (kinetic limit) when the friction of every point that
// bears a load ends on the edge of its disc with the slip not stopped: a body slides as
// a whole. Judged per pair, not per point: Gauss-Seidel shares a held body's friction
// among its points in no particular way, and one point at its limit while the others
// hold does not make the body slide (a box at tan(theta) = 0.999 mu_s on a ramp stays).
// One point inside its disc means the slip is stopped there: the pair sticks (static).
// The slip must exceed 1 % of a resting body's speed (2 g h): near the limit (0.1 % below
// it) the passes leave the first step's slip at 6e-5 m/s with every point at its limit,
// and the body is still held.
bool pairSlides(const Solver& s, size_t begin, size_t end, double slideSpeed) {
  bool loaded = false;
  double slip = 0.0;
  for (size_t k = begin; k < end; ++k) {
    const Row& r = s.rows[k];
    if (r.lambdaN <= 0.0) continue;
    loaded = true;
    if (!r.atLimit) return false;
    slip = std::max(slip, length(relativeVelocity(s, r, r.t1), relativeVelocity(s, r, r.t2)));
  }
  return loaded && slip > slideSpeed;
}

void store(const Solver& s, double slideSpeed, std::vector<ContactMemory>& memory) {
  memory.clear();
  for (size_t i = 0; i < s.rows.size();) {
    const size_t end = pairEnd(s, i);
    const bool sliding = pairSlides(s, i, end, slideSpeed);
    for (; i < end; ++i) {
      const Row& r = s.rows[i];
      const Contact& c = *r.contact;
      ContactMemory m;
      m.a = c.a, m.b = c.b, m.surface = c.surface;
      m.localA = r.localA;
      m.normalImpulse = r.lambdaN;
      m.tangentImpulse = r.lambdaT1 * r.t1.d + r.lambdaT2 * r.t2.d;
      m.sliding = sliding;
      memory.push_back(m);
    }
  }
}

// The accumulated impulses of the rows on surfaces, one push per body and surface
// (rows come grouped by pair).
void pushSurfaces(const Solver& s, std::vector<SurfacePush>& pushes) {
  for (size_t i = 0; i < s.rows.size();) {
    const size_t end = pairEnd(s, i);
    if (s.rows[i].b != s.staticSlot()) {
      i = end;
      continue;
    }
    SurfacePush p{s.rows[i].a, s.rows[i].contact->surface, Vec3::Zero()};
    for (; i < end; ++i) {
      const Row& r = s.rows[i];
      p.impulse += r.lambdaN * r.n.d + r.lambdaT1 * r.t1.d + r.lambdaT2 * r.t2.d;
    }
    pushes.push_back(p);
  }
}

void countTouching(const std::vector<Contact>& contacts, std::vector<int>& count) {
  for (const Contact& c : contacts) {
    if (c.depth < -kTouching) continue;
    ++count[c.a];
    if (c.b >= 0) ++count[c.b];
  }
}

}  // namespace

ContactSolveReport solveContacts(const WorldModel& model, const std::vector<Contact>& contacts, const ContactStep& step,
                                 std::vector<ContactMemory>& memory, std::vector<BodyState>& Y, std::vector<int>& count,
                                 ContactScratchPtr& scratch, std::vector<SurfacePush>& pushes) {
  ContactSolveReport report;
  pushes.clear();
  countTouching(contacts, count);
  if (!scratch) scratch.reset(new ContactScratch);
  Solver& s = *scratch;
  s.bodies.resize(Y.size() + 1);
  s.bodies.back() = SolverBody{};
  s.involved.assign(Y.size(), 0);
  prepareRows(model, contacts, step, Y, s);
  report.points = static_cast<int>(s.rows.size());
  markVelocities(s);
  report.impactPasses = answerImpacts(s, step, pushes);
  const bool soft = step.model == ContactModel::Soft;
  if (soft) beginSubsteps(model, step, Y, s);
  warmStart(memory, s);
  if (soft) {
    solveSubsteps(step, s, report);
    storeMomenta(model, s, Y);
    moveBySubsteps(s, Y);
  } else {
    applyWarmStart(s);
    solveVelocities(s, report);
    shockPass(s);
    storeMomenta(model, s, Y);
    correctPositions(s, step, Y);
    markLimits(s);
  }
  store(s, std::max(kVelocityTolerance, 0.01 * step.restingSpeed), memory);
  pushSurfaces(s, pushes);
  return report;
}

bool anyBouncingImpact(const WorldModel& model, const std::vector<Contact>& contacts, const std::vector<BodyState>& Y,
                       double restingSpeed) {
  for (const Contact& c : contacts) {
    if (c.depth <= 0.0 || coefficientsOf(model, c).xi <= 0.0) continue;
    auto pointVelocity = [&](int i) -> Vec3 {
      if (i < 0) return Vec3::Zero();
      const Mat3 R = Y[i].q.normalized().toRotationMatrix();
      const Vec3 w = R * (model.bodies[i].IbodyInv * (R.transpose() * Y[i].L));
      return Y[i].P / model.bodies[i].mass + w.cross(c.point - Y[i].X);
    };
    if (c.normal.dot(pointVelocity(c.b) - pointVelocity(c.a)) < -restingSpeed) return true;
  }
  return false;
}

}  // namespace rigid
