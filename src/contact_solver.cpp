#include "contact_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>

#include <Eigen/Dense>

#include "block_solve.h"
#include "coarse_correction.h"
#include "contact_impacts.h"
#include "contact_rows.h"
#include "contact_rules.h"
#include "shock_propagation.h"

namespace rigid {

using namespace contact_solver;

void ContactScratchDeleter::operator()(ContactScratch* s) const { delete s; }

namespace {

using namespace contact_rows;

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

// Impacts as the seed answers them, before the solve and outside its accumulated
// impulses (which would take a bounce back): passes over the pairs while one of them
// approaches faster than a resting body can, so that a chain of touching bodies passes
// an impact on (Newton's cradle). Returns the passes taken.
int answerImpacts(Solver& s, const ContactStep& step, std::vector<SurfacePush>& pushes) {
  auto striking = [&](double vrel) { return vrel < -step.restingSpeed; };
  const bool any = std::any_of(s.rows.begin(), s.rows.end(), [&](const Row& r) {
    return r.depth >= -kTouching && striking(relativeVelocity(s, r, r.n));
  });
  if (!any) return 0;
  impactRows(s, s.impacts, s.impactPairs);
  const std::vector<Row>& rows = s.impacts;
  int passes = 0;
  for (bool struck = true; struck && passes < kMaxImpactPasses;) {
    struck = false;
    for (const Row& r : rows) {
      const double vrel = relativeVelocity(s, r, r.n);
      if (!striking(vrel)) continue;
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
// frame, within kMatchDistance), each old point used once (applyWarmStart applies them).
// Rows and memory are both in the detector's pair order: one search per pair. A body
// sticks or slides as a whole, so a pair's new points take its remembered state.
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

// A row whose bodies took no impulse worth noting since it was found settled is settled
// still, and skipped: a pile converges where it moves, not everywhere.
bool settledStill(const Solver& s, const Row& r) {
  return r.settled && r.versionA == s.bodies[r.a].version && r.versionB == s.bodies[r.b].version;
}

// One row: normal, then friction with the new normal impulse. Returns the velocity
// change it made.
double solveRow(Solver& s, Row& r) {
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
    for (size_t k = 0; k < n; ++k) {
      Row& r = s.rows[backwards ? n - 1 - k : k];
      if (settledStill(s, r)) continue;
      ++report.rowSolves;
      change = std::max(change, solveRow(s, r));
    }
    ++report.iterations;
    report.residual = change;
    if (change <= kVelocityTolerance) break;
    if (report.iterations < kBlockAfter) continue;
    if (report.iterations == kBlockAfter) findBlockIslands(s);
    solveBlockIslands(s);
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
  warmStart(memory, s);
  applyWarmStart(s);
  coarseCorrection(s, step.restingSpeed);
  solveVelocities(s, report);
  shockPass(s);
  storeMomenta(model, s, Y);
  correctPositions(s, step, Y);
  markLimits(s);
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
