#include "soft_contacts.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "block_solve.h"
#include "contact_impacts.h"
#include "shock_propagation.h"

namespace rigid {

using namespace contact_rows;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A soft constraint's coefficients for a sub-step h (Catto, "Solver2D"): the bias
// rate (1/s) that turns an overlap into a push-out speed, and the shares of the rigid
// impulse and of the accumulated impulse that make the constraint a spring of natural
// frequency f and damping ratio zeta rather than a rigid one.
struct Softness {
  double biasRate = 0.0, massScale = 1.0, impulseScale = 0.0;
};

Softness softness(double frequency, double zeta, double h) {
  const double omega = 2.0 * kPi * frequency;
  const double a1 = 2.0 * zeta + h * omega, a2 = h * omega * a1, a3 = 1.0 / (1.0 + a2);
  return {omega / a1, a2 * a3, a3};
}

// The normal component at row r of what bodies a and b moved by (m along the normal).
double normalMove(const Row& r, const Vec3& moveA, const Vec3& turnA, const Vec3& moveB, const Vec3& turnB) {
  return r.n.d.dot(moveB - moveA) + r.n.rbXd.dot(turnB) - r.n.raXd.dot(turnA);
}

// The row's separation (m, < 0: overlap) after `done` of the kSoftSubsteps sub-steps:
// the detected one (at the step's end, after the whole free motion) less the free
// motion still to come, plus what the contact impulses have moved the bodies so far.
// Sub-step j's free motion is h_sub (v + (j - 1/2) dv) + drift: the velocity at its
// middle, and the drift that makes the sub-steps' motion add up to the integrator's
// (none for RK4 under constant forces; explicit Euler's h v lacks h dv_total / 2).
// moveBodies counts it the same way, so that a point's separation changes by exactly
// h_sub times its normal velocity in each sub-step and a resting point sees neither a
// gap it could close nor an overlap.
double separation(const Solver& s, const Row& r, double hs, int done) {
  const SubstepBody& A = s.substep[r.a];
  const SubstepBody& B = s.substep[r.b];
  const int n = kSoftSubsteps, left = n - done;
  const double steps = hs * left, ramp = hs * 0.5 * (n * n - done * done);
  auto rest = [&](const Vec3& v, const Vec3& dv, const Vec3& drift) {
    return Vec3(steps * v + ramp * dv + left * drift);
  };
  const double toCome = normalMove(r, rest(A.v, A.dv, A.drift), rest(A.w, A.dw, A.twist), rest(B.v, B.dv, B.drift),
                                   rest(B.w, B.dw, B.twist));
  return -r.depth - toCome + normalMove(r, A.move, A.turn, B.move, B.turn);
}

// The normal impulse of one row in one pass. Apart (a speculative point): it may close
// its gap within the sub-step. Overlapping beyond kSoftSlop, with the bias: the soft
// push-out, a spring from kSoftSlop on. Otherwise (relax, or within kSoftSlop) it stops
// the approach rigidly: a damper there (the spring's coefficients without its push)
// let a body set down touching sink over seconds, and a box on a ramp just below its
// static limit creep down it as it sank.
void solveSoftNormal(Solver& s, Row& r, double gap, double hs, const Softness* bias) {
  double push = 0.0;
  Softness k;
  if (gap > 0.0) {
    push = gap / hs;
  } else if (bias && gap + kSoftSlop < 0.0) {
    k = *bias;
    push = std::max(bias->biasRate * (gap + kSoftSlop), -kMaxPushOut);
  }
  const double vn = relativeVelocity(s, r, r.n);
  const double total = std::max(r.lambdaN - r.n.mass * k.massScale * (vn + push) - k.impulseScale * r.lambdaN, 0.0);
  applyImpulse(s, r, r.n, total - r.lambdaN);
  r.lambdaN = total;
}

// The normal velocity the soft solve aims a row at, taken rigidly (the block solve's
// target): closing the gap in the sub-step, the bias's push-out, or none.
double softTarget(const Solver& s, const Row& r, double hs, int done, const Softness* bias) {
  const double gap = separation(s, r, hs, done);
  if (gap > 0.0) return -gap / hs;
  if (bias && gap + kSoftSlop < 0.0) return std::min(-bias->biasRate * (gap + kSoftSlop), kMaxPushOut);
  return 0.0;
}

// The islands of unlike masses (block_solve.h) solved at once after the passes, each
// row aimed at its soft target taken rigidly: two passes carry a heavy box's load onto
// a light one below it by a share of the mass ratio only, and the light box was crushed.
void solveUnlikeMasses(Solver& s, double hs, int done, const Softness* bias) {
  if (s.blocks.empty()) return;
  for (const auto& [begin, end] : s.blocks)
    for (size_t k = begin; k < end; ++k) {
      Row& r = s.rows[s.islandRows[k]];
      r.target = softTarget(s, r, hs, done, bias);
    }
  solveBlockIslands(s);
}

// One row's normal and friction in a pass; returns the velocity change it made.
double softRow(Solver& s, Row& r, double hs, int done, const Softness* bias) {
  const double before = r.lambdaN;
  solveSoftNormal(s, r, separation(s, r, hs, done), hs, bias);
  return std::max(std::abs(r.lambdaN - before) / r.n.mass, solveFriction(s, r));
}

// One pass over the rows (forwards or backwards) at the bodies' positions after `done`
// sub-steps; `bias` null for the relax pass. Returns the largest velocity change.
double softPass(Solver& s, double hs, int done, const Softness* bias, bool backwards) {
  const size_t n = s.rows.size();
  double change = 0.0;
  for (size_t k = 0; k < n; ++k)
    change = std::max(change, softRow(s, s.rows[backwards ? n - 1 - k : k], hs, done, bias));
  return change;
}

// The points new this step (s.fresh) relaxed further in the first sub-step, until no
// pass changes a velocity by more than the tolerance or kSoftFreshRelaxPasses passes in
// all: a new contact's first passes, from nothing, left a box on a ramp just below its
// static limit slipping at 1e-4 m/s with every point at its limit, and the pair was
// taken as sliding for good. Only the new points: over every row, the falling pile of
// 1000 cost 1.4x. Returns the passes taken.
int relaxFresh(Solver& s, double hs, ContactSolveReport& report) {
  int taken = 0;
  for (; taken + kSoftRelaxPasses < kSoftFreshRelaxPasses && report.residual > kVelocityTolerance; ++taken) {
    double change = 0.0;
    const size_t n = s.fresh.size();
    for (size_t k = 0; k < n; ++k)
      change = std::max(change, softRow(s, s.rows[s.fresh[taken % 2 ? k : n - 1 - k]], hs, 1, nullptr));
    report.residual = change;
    report.rowSolves += static_cast<long>(n);
  }
  return taken;
}

// Half of each moving body's velocity change by the applied forces over one sub-step,
// with half of each row's remembered sub-step impulse (`warm`, the last sub-step's).
// The sub-step takes one half before its solve and the other after its move, so that
// the move sees the velocity at mid-sub-step, as the free motion counts it: with the
// whole change before it, a body sliding at a net acceleration a moved a h^2 / 8 a step
// too far (a slider woken by a force 0.3 mm off in 0.5 s). Each half brings half of the
// impulses that held it last time, so that a resting stack's passes start balanced.
void addHalfStep(Solver& s) {
  for (size_t i = 0; i + 1 < s.bodies.size(); ++i) {
    if (!s.involved[i]) continue;
    s.bodies[i].v += 0.5 * s.substep[i].dv;
    s.bodies[i].w += 0.5 * s.substep[i].dw;
  }
  for (Row& r : s.rows) {
    const double n = 0.5 * r.warmN, t1 = 0.5 * r.warmT1, t2 = 0.5 * r.warmT2;
    r.lambdaN += n, r.lambdaT1 += t1, r.lambdaT2 += t2;
    applyRowImpulse(s, r, n, t1, t2);
  }
}

// Impacts within the sub-step: each pair whose points could close their gap (the
// nearest's, at the positions after `done` sub-steps) and approach faster than a
// resting body can takes one impulse at its merged point (contact_impacts.h) before the
// sub-step's passes, pass after pass as a chain passes an impact on: the seed's j with
// restitution xi when it touches, and the impulse that leaves it closing the gap in the
// sub-step and no faster when it is apart. Taken by the passes at its corner points, a
// face's impact left a spurious spin (a box struck face on at 1 m/s turned at 0.1
// rad/s); taken before the solve at the step's end, it left a landing body sunk by the
// step's travel (2 mm in a falling pile of 100). Here the body moves by the stopped
// velocity in the sub-step.
void stopImpacts(Solver& s, const ContactStep& step, double hs, int done, std::vector<SurfacePush>& pushes) {
  for (int pass = 0; pass < kMaxImpactPasses; ++pass) {
    bool struck = false;
    for (size_t m = 0; m < s.impacts.size(); ++m) {
      Row& r = s.impacts[m];
      const auto [begin, end] = s.impactPairs[m];
      double gap = std::numeric_limits<double>::infinity();
      for (size_t k = begin; k < end; ++k) gap = std::min(gap, separation(s, s.rows[k], hs, done));
      const bool touching = gap <= kTouching;
      const double closing = touching ? 0.0 : -gap / hs;  // the normal velocity that just closes the gap
      const double vrel = relativeVelocity(s, r, r.n);
      if (!(vrel < closing - step.restingSpeed)) continue;
      const double xi = r.k.xi;
      if (!touching) r.k.xi = 0.0;
      impact(s, r, vrel - closing, pushes);
      r.k.xi = xi;
      struck = true;
    }
    if (!struck) return;
  }
}

// Each moving body moved by what the contact impulses made of its velocities over the
// k-th sub-step: its velocity less that of the free motion and of the share of the
// impacts' kick that does not move it (limitKicks).
void moveBodies(Solver& s, double hs, int k) {
  for (size_t i = 0; i + 1 < s.bodies.size(); ++i) {
    if (!s.involved[i]) continue;
    SubstepBody& x = s.substep[i];
    const SolverBody& b = s.bodies[i];
    const double still = 1.0 - x.kickMoves;
    x.move += hs * (b.v - x.v - still * x.kick - (k - 0.5) * x.dv) - x.drift;
    x.turn += hs * (b.w - x.w - still * x.spin - (k - 0.5) * x.dw) - x.twist;
  }
}

// The impacts (answerImpacts: bouncing pairs only, with the soft sub-steps) stop an
// approach at the step's end; taken over the whole step, their kick would move the body.
// A located impact leaves no overlap, so its kick moves nothing; one that is not located
// (the step's cap of impacts reached) has sunk the body by the free motion. A point
// whose normal velocity the kick changed by more than the resting speed may be closed by
// the kick's move but not opened beyond touching, as limitMoves does for the passes.
void limitKicks(Solver& s, const ContactStep& step) {
  for (const Row& r : s.rows) {
    if (r.depth < -kTouching) continue;
    SubstepBody& A = s.substep[r.a];
    SubstepBody& B = s.substep[r.b];
    const double kicked = normalMove(r, A.kick, A.spin, B.kick, B.spin);
    if (!(kicked > step.restingSpeed)) continue;
    const double opening = step.h * kicked, allowed = std::max(r.depth, 0.0);
    if (!(opening > allowed)) continue;
    A.kickMoves = std::min(A.kickMoves, allowed / opening);
    B.kickMoves = std::min(B.kickMoves, allowed / opening);
  }
}

// Passes over the rows, forwards and backwards in turn (`backwards` first or not), at
// the positions after `done` sub-steps: at most `most`, fewer once a pass changes no
// velocity by more than the tolerance (a resting pile's warm-started rows). Returns the
// passes taken.
int passes(Solver& s, double hs, int done, const Softness* bias, int most, bool backwards, ContactSolveReport& report) {
  for (int pass = 0; pass < most; ++pass) {
    report.residual = softPass(s, hs, done, bias, backwards == (pass % 2 == 0));
    report.rowSolves += static_cast<long>(s.rows.size());
    if (report.residual <= kVelocityTolerance) return pass + 1;
  }
  return most;
}

// The sub-steps' start: the velocities back to the step's start (the applied forces'
// change is re-added sub-step by sub-step), each row's remembered step impulse cut into
// the sub-steps' shares, the merged pairs of the sub-steps' impacts and the islands of
// unlike masses.
void startSubsteps(Solver& s) {
  for (size_t i = 0; i + 1 < s.bodies.size(); ++i) {
    if (!s.involved[i]) continue;
    s.bodies[i].v = s.substep[i].v + s.substep[i].kick;
    s.bodies[i].w = s.substep[i].w + s.substep[i].spin;
  }
  for (Row& r : s.rows) {
    r.warmN = r.lambdaN / kSoftSubsteps, r.warmT1 = r.lambdaT1 / kSoftSubsteps, r.warmT2 = r.lambdaT2 / kSoftSubsteps;
    r.sumN = r.sumT1 = r.sumT2 = 0.0;
  }
  s.fresh.clear();
  for (size_t i = 0; i < s.rows.size(); ++i)
    if (!s.rows[i].remembered && !s.rows[i].sliding) s.fresh.push_back(i);
  impactRows(s, s.impacts, s.impactPairs);
  findBlockIslands(s);
}

// A point new this step remembers nothing: the first sub-step's second half starts it
// from what its first half took. (From nothing, the relax passes left a box on a ramp
// just below its static limit slipping at 1e-4 m/s at every point's limit, and the pair
// was taken as sliding.)
void takeFirstHalf(Solver& s) {
  for (Row& r : s.rows)
    if (!r.remembered) r.warmN = 2.0 * r.lambdaN, r.warmT1 = 2.0 * r.lambdaT1, r.warmT2 = 2.0 * r.lambdaT2;
}

// The rotation vector (rad) that turns q0 into q1.
Vec3 rotationBetween(const Quat& q0, const Quat& q1) {
  Quat d = q1.normalized() * q0.normalized().conjugate();
  if (d.w() < 0.0) d.coeffs() = -d.coeffs();  // the short way round
  const Eigen::AngleAxisd turn(d);
  return turn.angle() * turn.axis();
}

}  // namespace

void beginSubsteps(const WorldModel& model, const ContactStep& step, const std::vector<BodyState>& Y,
                   ContactScratch& s) {
  s.substep.assign(s.bodies.size(), SubstepBody{});
  for (size_t i = 0; i + 1 < s.bodies.size(); ++i) {
    if (!s.involved[i]) continue;
    const SolverBody& b = s.bodies[i];
    SubstepBody& x = s.substep[i];
    x.kick = b.v - b.v0, x.spin = b.w - b.w0;
    x.v = b.v0, x.w = b.w0;
    if (step.start) {
      const BodyState& y0 = (*step.start)[i];
      const Mat3 R = y0.q.normalized().toRotationMatrix();
      x.v = y0.P / model.bodies[i].mass;
      x.w = R * model.bodies[i].IbodyInv * R.transpose() * y0.L;
      const int n = kSoftSubsteps;
      const double hs = step.h / n;
      x.dv = (b.v0 - x.v) / n, x.dw = (b.w0 - x.w) / n;
      x.drift = (Y[i].X - y0.X) / n - hs * (x.v + 0.5 * n * x.dv);
      x.twist = rotationBetween(y0.q, Y[i].q) / n - hs * (x.w + 0.5 * n * x.dw);
    }
  }
  limitKicks(s, step);
}

void solveSubsteps(const ContactStep& step, ContactScratch& s, ContactSolveReport& report,
                   std::vector<SurfacePush>& pushes) {
  const double hs = step.h / kSoftSubsteps;
  const Softness soft = softness(kSoftFrequencyShare / hs, kSoftDampingRatio, hs);
  startSubsteps(s);
  report.iterations = 0;
  for (int k = 1; k <= kSoftSubsteps; ++k) {
    for (Row& r : s.rows) r.lambdaN = r.lambdaT1 = r.lambdaT2 = 0.0;
    addHalfStep(s);
    stopImpacts(s, step, hs, k - 1, pushes);
    report.iterations += passes(s, hs, k - 1, &soft, kSoftSolvePasses, false, report);
    solveUnlikeMasses(s, hs, k - 1, &soft);
    moveBodies(s, hs, k);
    if (k == 1) takeFirstHalf(s);
    addHalfStep(s);
    stopImpacts(s, step, hs, k, pushes);
    report.iterations += passes(s, hs, k, nullptr, kSoftRelaxPasses, true, report);
    if (k == 1) report.iterations += relaxFresh(s, hs, report);
    solveUnlikeMasses(s, hs, k, nullptr);
    if (k == kSoftSubsteps) shockPass(s);
    for (Row& r : s.rows) {
      r.sumN += r.lambdaN, r.sumT1 += r.lambdaT1, r.sumT2 += r.lambdaT2;
      r.warmN = r.lambdaN, r.warmT1 = r.lambdaT1, r.warmT2 = r.lambdaT2;
    }
  }
  markLimits(s);
  for (Row& r : s.rows) r.lambdaN = r.sumN, r.lambdaT1 = r.sumT1, r.lambdaT2 = r.sumT2;
}

void moveBySubsteps(const ContactScratch& s, std::vector<BodyState>& Y) {
  for (size_t i = 0; i + 1 < s.bodies.size(); ++i) {
    if (!s.involved[i]) continue;
    const SubstepBody& x = s.substep[i];
    if (x.move.isZero(0.0) && x.turn.isZero(0.0)) continue;
    Y[i].X += x.move;
    const Quat& q = Y[i].q;
    const Quat half(0.0, 0.5 * x.turn.x(), 0.5 * x.turn.y(), 0.5 * x.turn.z());
    Y[i].q = Quat(q.coeffs() + (half * q).coeffs()).normalized();
  }
}

}  // namespace rigid
