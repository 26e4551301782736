#include "constraint_solver.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "contact_rules.h"
#include "dynamics.h"
#include "solver_rows.h"

namespace rigid {

using namespace constraint_solver;
using namespace solver;

namespace {

// Points closer than this count as touching (a located impact leaves a gap of about
// 1e-15 of the step's travel); farther ones are speculative.
constexpr double kTouching = 1e-6;       // m
constexpr double kMatchDistance = 0.01;  // m: a point within this of last step's (body a's frame) is the same
constexpr int kMaxImpactPasses = 500;

// One contact point's normal row.
struct Point {
  Jacobian n;
  double mass = 0.0;  // 1 / (J M^-1 J^T)
  // m, the point from each centre of mass: at the step's start, and now (followPoint:
  // one point for both bodies, so that the impulse has no moment about any point and
  // momenta are kept)
  Vec3 rA0 = Vec3::Zero(), rB0 = Vec3::Zero(), rA = Vec3::Zero(), rB = Vec3::Zero();
  double separation = 0.0;  // m, at the step's start (< 0: overlap)
  double lambda = 0.0;      // N s, the sub-step's accumulated impulse (>= 0)
  double total = 0.0;       // N s, over the step's sub-steps
  Vec3 localA = Vec3::Zero();
  bool touching = false;
};

// One touching pair: its points, and its friction at the centre of the patch.
struct Manifold {
  int a = 0, b = 0, surface = -1;               // solver bodies; b is the static slot on a surface
  size_t first = 0, count = 0;                  // its points in ConstraintScratch::points
  Vec3 normal = Vec3::Zero();                   // unit, from a to b
  Vec3 rA0 = Vec3::Zero(), rB0 = Vec3::Zero();  // m, the patch's centre from each centre of mass, at the start
  Vec3 rA = Vec3::Zero(), rB = Vec3::Zero();    // m, and now (as Point's)
  Vec3 t1 = Vec3::Zero(), t2 = Vec3::Zero();    // the tangents, fixed over the step
  Jacobian friction[3];                         // two tangents at the centre, and the twist about the normal
  Mat3 frictionMass = Mat3::Zero();             // (J M^-1 J^T)^-1 over the three
  double radius = 0.0;                          // m, the patch radius (Contact::patchRadius): the twist's lever
  // m/s, the velocity of B's material beyond B's own motion, along the contact plane:
  // a conveyor's belt (WorldData::beltVelocity), zero elsewhere. The friction tangents
  // drift with it and slipOf counts it, so friction acts against the slip relative to
  // the belt.
  Vec3 belt = Vec3::Zero();
  Coefficients k;
  Softness soft;
  bool sliding = false;                              // friction bounded by mu_k (else mu_s) for the whole step
  bool atLimit = false;                              // its friction on the edge of its bound after the last pass
  Vec3 lambda = Vec3::Zero(), total = Vec3::Zero();  // (t1, t2, twist) impulses, as the points'
  // Rolling resistance (k.rolling > 0): the pair's relative turn about t1 and t2, its
  // moment bounded by k.rolling lambda_N; it starts each step from none (not remembered)
  Jacobian rolling[2];
  Eigen::Matrix2d rollingMass = Eigen::Matrix2d::Zero();
  Eigen::Vector2d rollingLambda = Eigen::Vector2d::Zero();  // N m s
};

// The velocity of B's material relative to A's along the contact plane, at the points
// rA and rB from their centres of mass (m/s): the slip that friction acts against.
Vec3 slipOf(const Manifold& m, const Body& A, const Body& B, const Vec3& rA, const Vec3& rB) {
  const Vec3 u = B.v + B.w.cross(rB) + m.belt - A.v - A.w.cross(rA);
  return u - u.dot(m.normal) * m.normal;
}

}  // namespace

struct ConstraintScratch {
  std::vector<Body> bodies;  // one per body, then the static slot
  std::vector<char> involved;
  std::vector<int> moving;  // the bodies some row touches
  std::vector<Point> points;
  std::vector<Manifold> manifolds;
  std::vector<char> used;  // warm start: memory points already matched
  std::vector<int> held;   // the bodies the extra rows (joints) hold
  int staticSlot() const { return static_cast<int>(bodies.size()) - 1; }
};

void ConstraintScratchDeleter::operator()(ConstraintScratch* s) const { delete s; }

namespace {

using Solver = ConstraintScratch;

// ---- prepare ---------------------------------------------------------------------

void prepareBody(const WorldModel& model, const WorldData& data, double hSub, int i, Solver& s) {
  if (s.involved[i]) return;
  s.involved[i] = 1;
  s.moving.push_back(i);
  const BodyConstants& constants = model.bodies[i];
  const BodyState& y = data.Y[i];
  BodyAux aux;
  computeVelocities(constants, y, aux);
  Body& b = s.bodies[i];
  b = Body{};
  if (driven(constants)) {  // infinitely heavy, at its velocities, no force acting
    b.driven = true;
    b.v = b.v0 = aux.V;
    b.w = b.w0 = aux.omega;
    b.x0 = y.X;
    b.q = b.q0 = y.q.normalized();
    return;
  }
  accumulateAppliedForces(model, constants, data.input[i], y, aux);
  b.invMass = 1.0 / constants.mass;
  b.invInertia = aux.R * constants.IbodyInv * aux.R.transpose();
  b.v = b.v0 = aux.V;
  b.w = b.w0 = aux.omega;
  b.dv = hSub * b.invMass * aux.F;
  b.dw = hSub * (b.invInertia * aux.T);
  b.x0 = y.X;
  b.q = b.q0 = y.q.normalized();
}

void frictionJacobians(Manifold& m, const Body& A, const Body& B) {
  m.friction[0] = jacobian(A, B, m.t1, m.rA.cross(m.t1), m.rB.cross(m.t1));
  m.friction[1] = jacobian(A, B, m.t2, m.rA.cross(m.t2), m.rB.cross(m.t2));
  m.friction[0].drift = m.t1.dot(m.belt);
  m.friction[1].drift = m.t2.dot(m.belt);
}

// The friction rows of a manifold at its centre: the first tangent along the slip, so
// that a sliding pair's friction opposes it from the first pass.
void prepareFriction(Manifold& m, const Solver& s) {
  const Body& A = s.bodies[m.a];
  const Body& B = s.bodies[m.b];
  const Vec3& n = m.normal;
  const Vec3 slip = slipOf(m, A, B, m.rA, m.rB);
  m.t1 = slip.norm() > 1e-9 ? Vec3(slip.normalized()) : anyPerpendicular(n);
  m.t2 = n.cross(m.t1);
  frictionJacobians(m, A, B);
  // without a patch (a point or an edge) there is no twist row: a zero row of unit mass
  m.friction[2] = m.radius > 0.0 ? jacobian(A, B, Vec3::Zero(), n, n) : Jacobian{};
  Mat3 K = Mat3::Identity();
  for (int x = 0; x < 3; ++x)
    for (int y = 0; y < 3; ++y)
      if (m.radius > 0.0 || (x < 2 && y < 2)) K(x, y) = coupling(A, B, m.friction[x], m.friction[y]);
  m.frictionMass = K.inverse();
  if (m.k.rolling > 0.0) {
    m.rolling[0] = jacobian(A, B, Vec3::Zero(), m.t1, m.t1);
    m.rolling[1] = jacobian(A, B, Vec3::Zero(), m.t2, m.t2);
    Eigen::Matrix2d R;
    for (int x = 0; x < 2; ++x)
      for (int y = 0; y < 2; ++y) R(x, y) = coupling(A, B, m.rolling[x], m.rolling[y]);
    m.rollingMass = R.inverse();
  }
}

// How fast a contact point of Y approaches (m/s, > 0: closing).
double approachSpeed(const WorldModel& model, const std::vector<BodyState>& Y, const Contact& c) {
  auto pointVelocity = [&](int i) {
    if (i < 0) return Vec3(Vec3::Zero());
    BodyAux aux;
    computeVelocities(model.bodies[i], Y[i], aux);
    return Vec3(aux.V + aux.omega.cross(c.point - Y[i].X));
  };
  return -c.normal.dot(pointVelocity(c.b) - pointVelocity(c.a));
}

// The rows of one pair's points contacts[first, end) into s.points. A speculative point
// (apart by a gap) of a bouncing pair that closes faster than a resting body can is left
// out: its impact is located in time, and slowing it early would take energy from the
// bounce. A slower one is held at its gap as any other (it would not bounce).
void addPoints(const WorldModel& model, const WorldData& data, const std::vector<Contact>& contacts, size_t first,
               size_t end, double restingSpeed, Manifold& m, Solver& s) {
  const Contact& c = contacts[first];
  Vec3 centre = Vec3::Zero(), normal = Vec3::Zero();
  m.first = s.points.size();
  for (size_t k = first; k < end; ++k) {
    const bool touching = contacts[k].depth >= -kTouching;
    if (!touching && m.k.xi > 0.0 && approachSpeed(model, data.Y, contacts[k]) > restingSpeed) continue;
    Point p;
    p.touching = touching;
    p.separation = -contacts[k].depth;
    p.rA = p.rA0 = contacts[k].point - data.Y[c.a].X;
    p.rB = p.rB0 = c.b >= 0 ? Vec3(contacts[k].point - data.Y[c.b].X) : Vec3::Zero();
    p.localA = data.Y[c.a].q.normalized().conjugate() * p.rA;
    centre += contacts[k].point;
    normal += contacts[k].normal;
    s.points.push_back(p);
  }
  m.count = s.points.size() - m.first;
  if (m.count == 0) return;
  m.normal = normal.normalized();
  centre /= static_cast<double>(m.count);
  m.rA = m.rA0 = centre - data.Y[c.a].X;
  m.rB = m.rB0 = c.b >= 0 ? Vec3(centre - data.Y[c.b].X) : Vec3::Zero();
}

// A manifold per touching pair (the detector's points come grouped by pair), a normal
// row per point, the pair's friction rows. The springs and the resting speed are
// solver.step's (solveConstraints), the sub-steps h's.
void prepareRows(const WorldModel& model, const WorldData& data, const std::vector<Contact>& contacts, double h,
                 Solver& s) {
  const double hSub = h / kSubsteps;
  const double hertz = kContactHertzShare * kSubsteps / model.maxStep;
  const Softness soft = makeSoft(hertz, kDampingRatio, hSub), stiff = makeSoft(2.0 * hertz, kDampingRatio, hSub);
  const double restingSpeed = restingNormalSpeed(model.gravity, model.maxStep);
  s.points.clear();
  s.manifolds.clear();
  for (size_t i = 0; i < contacts.size();) {
    size_t end = i + 1;
    while (end < contacts.size() && contacts[end].a == contacts[i].a && contacts[end].b == contacts[i].b &&
           contacts[end].surface == contacts[i].surface)
      ++end;
    const Contact& c = contacts[i];
    Manifold m;
    m.k = coefficientsOf(model, c);
    m.a = c.a;
    m.b = c.b >= 0 ? c.b : s.staticSlot();
    m.surface = c.surface;
    const bool immovable = c.b < 0 || driven(model.bodies[c.a]) || driven(model.bodies[c.b]);
    m.soft = immovable ? stiff : soft;
    m.radius = c.patchRadius;
    addPoints(model, data, contacts, i, end, restingSpeed, m, s);
    i = end;
    if (m.count == 0) continue;
    prepareBody(model, data, hSub, m.a, s);
    if (c.b >= 0) prepareBody(model, data, hSub, c.b, s);
    if (c.b < 0) {  // the surface's belt along the contact plane: its normal part does nothing
      const Vec3& belt = data.beltVelocity[c.surface];
      m.belt = belt - belt.dot(m.normal) * m.normal;
    }
    const Body& A = s.bodies[m.a];
    const Body& B = s.bodies[m.b];
    for (size_t k = m.first; k < m.first + m.count; ++k) {
      Point& p = s.points[k];
      p.n = jacobian(A, B, m.normal, p.rA.cross(m.normal), p.rB.cross(m.normal));
      p.mass = 1.0 / coupling(A, B, p.n, p.n);
    }
    prepareFriction(m, s);
    m.sliding = slipOf(m, A, B, m.rA, m.rB).norm() > restingSpeed;  // a new pair; a kept one takes its memory's
    s.manifolds.push_back(m);
  }
}

// ---- warm start ------------------------------------------------------------------

// Each point takes the impulse of last step's nearest point of the same pair (body a's
// frame, within kMatchDistance), each old point used once; the pair takes the friction
// of the points it matched and their sliding state. Memory holds impulses over a step;
// the sub-steps take their share. Rows and memory come in the detector's pair order.
void warmStart(const std::vector<ContactMemory>& memory, Solver& s) {
  s.used.assign(memory.size(), 0);
  auto before = [](const ContactMemory& m, const std::tuple<int, int, int>& key) {
    return pairKey(m.a, m.b, m.surface) < key;
  };
  auto from = memory.begin();
  for (Manifold& m : s.manifolds) {
    const int b = m.b == s.staticSlot() ? -1 : m.b;
    const auto key = pairKey(m.a, b, m.surface);
    from = std::lower_bound(from, memory.end(), key, before);
    auto to = from;
    while (to != memory.end() && pairKey(to->a, to->b, to->surface) == key) ++to;
    Vec3 tangent = Vec3::Zero();
    double twist = 0.0;
    bool matched = false;
    for (size_t k = m.first; k < m.first + m.count; ++k) {
      Point& p = s.points[k];
      size_t best = memory.size();
      double nearest = kMatchDistance * kMatchDistance;
      for (auto it = from; it != to; ++it) {
        const size_t i = static_cast<size_t>(it - memory.begin());
        const double d2 = (it->localA - p.localA).squaredNorm();
        if (!s.used[i] && d2 < nearest) nearest = d2, best = i;
      }
      if (best == memory.size()) continue;
      s.used[best] = 1;
      const ContactMemory& old = memory[best];
      p.lambda = old.normalImpulse / kSubsteps;
      tangent += old.tangentImpulse;
      twist += old.twistImpulse;
      m.sliding = old.sliding;
      matched = true;
    }
    if (!matched) continue;
    m.lambda =
        Vec3(tangent.dot(m.friction[0].linear), tangent.dot(m.friction[1].linear), m.radius > 0.0 ? twist : 0.0) /
        kSubsteps;
  }
}

// ---- the seed's impacts ------------------------------------------------------------

// The seed's impulse at a pair's striking points merged into one (their centre): j =
// -(1 + xi) v_n m_eff, then a Coulomb friction impulse against the slip, |j_t| <= mu j
// (static when it stops the slip). A point strikes when it approaches faster than a
// resting body can and touches or would close its gap within the step (a rocking
// cube's falling edge, not the edge it pivots on). A bouncing pair's impact
// was located in time (its gap is closed); an inelastic one is taken at the step's
// start, up to a step early: it then stops where it is instead of sinking in. One
// impulse through the patch's centre keeps a face-on impact free of the spin that
// corner impulses taken in turn would leave. Returns whether the pair struck.
bool impact(const Manifold& m, const std::vector<Point>& points, double restingSpeed, double h, Solver& s,
            ContactImpulses& out) {
  Body& A = s.bodies[m.a];
  Body& B = s.bodies[m.b];
  Vec3 centre = Vec3::Zero();
  int count = 0;
  for (size_t k = m.first; k < m.first + m.count; ++k) {
    const double approach = velocityAlong(A, B, points[k].n);
    if (approach < -restingSpeed && points[k].separation <= std::max(kTouching, -approach * h))
      centre += points[k].rA, ++count;
  }
  if (count == 0) return false;
  const Vec3 rA = centre / count, rB = m.rB + (rA - m.rA);
  const Jacobian n = jacobian(A, B, m.normal, rA.cross(m.normal), rB.cross(m.normal));
  const double vn = velocityAlong(A, B, n);
  if (!(vn < -restingSpeed)) return false;
  const double j = -(1.0 + m.k.xi) * vn / coupling(A, B, n, n);
  applyImpulse(A, B, n, j);
  Vec3 push = j * m.normal;
  const Vec3 slip = slipOf(m, A, B, rA, rB);
  if (slip.norm() >= 1e-15) {
    const Vec3 d = -slip.normalized();
    const Jacobian t = jacobian(A, B, d, rA.cross(d), rB.cross(d));
    const double stick = slip.norm() / coupling(A, B, t, t);
    const double jt = stick <= m.k.mus * j ? stick : m.k.muk * j;
    applyImpulse(A, B, t, jt);
    push += jt * d;
  }
  if (m.b == s.staticSlot()) out.pushes.push_back({m.a, m.surface, push});
  return true;
}

// Passes over the pairs (and the extra rows' stops) while one of them strikes, so that
// a chain of touching bodies passes an impact on (Newton's cradle). Returns the passes
// taken.
int answerImpacts(Solver& s, double restingSpeed, double h, ContactImpulses& out, ExtraRows* extra) {
  int passes = 0;
  for (bool struck = true; struck && passes < kMaxImpactPasses;) {
    struck = extra && extra->impact(s.bodies, restingSpeed, h);
    for (const Manifold& m : s.manifolds)
      if (impact(m, s.points, restingSpeed, h, s, out)) struck = true;
    if (struck) ++passes;
  }
  return passes;
}

// ---- sub-steps -------------------------------------------------------------------

void integrateVelocities(Solver& s) {
  for (int i : s.moving) {
    Body& b = s.bodies[i];
    b.v += b.dv;
    b.w += b.dw;
  }
}

void applyWarmStart(Solver& s) {
  for (const Manifold& m : s.manifolds) {
    Body& A = s.bodies[m.a];
    Body& B = s.bodies[m.b];
    for (size_t k = m.first; k < m.first + m.count; ++k) applyImpulse(A, B, s.points[k].n, s.points[k].lambda);
    for (int x = 0; x < 3; ++x) applyImpulse(A, B, m.friction[x], m.lambda[x]);
    for (int x = 0; x < 2; ++x) applyImpulse(A, B, m.rolling[x], m.rollingLambda[x]);
  }
}

// How far the point has closed since the step's start, along the normal (m): the
// sub-steps' motion of the two bodies at the point, to first order in their turns, as
// the rows' velocities see it. (The turned material point would rise off a rolling
// sphere by R (1 - cos theta), which the sphere's surface never does.)
double closing(const Body& A, const Body& B, const Point& p, const Vec3& n) {
  const Vec3 pa = A.moved + A.turned.cross(p.rA0), pb = B.moved + B.turned.cross(p.rB0);
  return n.dot(pb - pa);
}

// The lever arms of a point that was at rA0 and rB0 at the step's start, carried by
// the two bodies' moves weighted by their inverse masses: on a surface it moves with
// the body (a rolling or sliding body's contact point travels with it), between two
// bodies with the lighter one more; both bodies take the impulse at that one point.
void followPoint(const Body& A, const Body& B, const Vec3& rA0, const Vec3& rB0, Vec3& rA, Vec3& rB) {
  const double share = B.invMass / (A.invMass + B.invMass);  // of B's move relative to A's
  const Vec3 apart = B.moved - A.moved;
  rA = rA0 + share * apart;
  rB = rB0 - (1.0 - share) * apart;
}

// Each row's directions at the points as the bodies have moved them (effective masses
// are kept from the step's start: they only scale the passes' steps).
void followBodies(Solver& s) {
  for (Manifold& m : s.manifolds) {
    const Body& A = s.bodies[m.a];
    const Body& B = s.bodies[m.b];
    for (size_t k = m.first; k < m.first + m.count; ++k) {
      Point& p = s.points[k];
      followPoint(A, B, p.rA0, p.rB0, p.rA, p.rB);
      p.n = jacobian(A, B, m.normal, p.rA.cross(m.normal), p.rB.cross(m.normal));
    }
    followPoint(A, B, m.rA0, m.rB0, m.rA, m.rB);
    frictionJacobians(m, A, B);
  }
}

// Normal rows: lambda_n += the soft impulse toward the target, clamped at 0 accumulated.
// A gap may close within the step and no more (speculative); an overlap is pushed apart
// at the soft bias's rate with the soft mass, and without bias when relaxing.
void solveNormals(Solver& s, Manifold& m, double hSub, bool useBias) {
  Body& A = s.bodies[m.a];
  Body& B = s.bodies[m.b];
  for (size_t k = m.first; k < m.first + m.count; ++k) {
    Point& p = s.points[k];
    const double separation = p.separation + closing(A, B, p, m.normal);
    double bias = 0.0, massScale = 1.0, impulseScale = 0.0;
    if (separation > 0.0) {
      bias = separation / hSub;
    } else if (useBias) {
      bias = std::max(m.soft.biasRate * separation, -kMaxPushOut);
      massScale = m.soft.massScale;
      impulseScale = m.soft.impulseScale;
    }
    const double vn = velocityAlong(A, B, p.n);
    const double impulse = -p.mass * massScale * (vn + bias) - impulseScale * p.lambda;
    const double total = std::max(p.lambda + impulse, 0.0);
    applyImpulse(A, B, p.n, total - p.lambda);
    p.lambda = total;
  }
}

// Friction at the patch: the impulses (t1, t2, twist) that stop its slip and spin,
// projected onto the ellipsoid |(l1, l2, l_twist / r)| <= mu lambda_N (mu_s while the
// pair sticks, mu_k once it slides), lambda_N the sum of its points' normal impulses:
// slip and spin share one bound, so that a puck sliding and spinning stops both at once.
void solveFriction(Solver& s, Manifold& m) {
  Body& A = s.bodies[m.a];
  Body& B = s.bodies[m.b];
  double normal = 0.0;
  for (size_t k = m.first; k < m.first + m.count; ++k) normal += s.points[k].lambda;
  const double bound = (m.sliding ? m.k.muk : m.k.mus) * normal;
  const Vec3 velocity(velocityAlong(A, B, m.friction[0]), velocityAlong(A, B, m.friction[1]),
                      velocityAlong(A, B, m.friction[2]));
  Vec3 lambda = m.lambda - m.frictionMass * velocity;
  const double r = m.radius > 0.0 ? m.radius : 1.0;
  const double size =
      std::sqrt(lambda.x() * lambda.x() + lambda.y() * lambda.y() + (lambda.z() / r) * (lambda.z() / r));
  m.atLimit = size >= (1.0 - 1e-9) * bound;
  if (size > bound) lambda *= bound / size;
  for (int x = 0; x < 3; ++x) applyImpulse(A, B, m.friction[x], lambda[x] - m.lambda[x]);
  m.lambda = lambda;
}

// Rolling resistance: the moment that stops the pair's relative turn about the
// tangents, within the disc |moment| <= rolling lambda_N (a rolling sphere's speed then
// falls at 5 rolling g / (7 R)).
void solveRolling(Solver& s, Manifold& m) {
  if (!(m.k.rolling > 0.0)) return;
  Body& A = s.bodies[m.a];
  Body& B = s.bodies[m.b];
  double normal = 0.0;
  for (size_t k = m.first; k < m.first + m.count; ++k) normal += s.points[k].lambda;
  const Eigen::Vector2d turn(velocityAlong(A, B, m.rolling[0]), velocityAlong(A, B, m.rolling[1]));
  Eigen::Vector2d lambda = m.rollingLambda - m.rollingMass * turn;
  const double bound = m.k.rolling * normal, size = lambda.norm();
  if (size > bound) lambda *= bound / size;
  for (int x = 0; x < 2; ++x) applyImpulse(A, B, m.rolling[x], lambda[x] - m.rollingLambda[x]);
  m.rollingLambda = lambda;
}

void solvePass(Solver& s, double hSub, bool useBias) {
  for (Manifold& m : s.manifolds) {
    solveNormals(s, m, hSub, useBias);
    solveFriction(s, m);
    solveRolling(s, m);
  }
}

// Positions from the new velocities: X += h v, q += h/2 (0, omega) q.
void integratePositions(Solver& s, double hSub) {
  for (int i : s.moving) {
    Body& b = s.bodies[i];
    b.moved += hSub * b.v;
    b.turned += hSub * b.w;
    const Quat spin(0.0, 0.5 * hSub * b.w.x(), 0.5 * hSub * b.w.y(), 0.5 * hSub * b.w.z());
    b.q = Quat(b.q.coeffs() + (spin * b.q).coeffs()).normalized();
  }
}

void addSubstepImpulses(Solver& s) {
  for (Point& p : s.points) p.total += p.lambda;
  for (Manifold& m : s.manifolds) m.total += m.lambda;
}

// ---- store -----------------------------------------------------------------------

// A pair slides in the next step (kinetic bound) when its friction ended on its bound
// with the patch still slipping or spinning faster than slideSpeed; a body slides as a
// whole, so the state is the pair's.
bool slides(const Solver& s, const Manifold& m, double slideSpeed) {
  if (!m.atLimit) return false;
  const Body& A = s.bodies[m.a];
  const Body& B = s.bodies[m.b];
  const double v1 = velocityAlong(A, B, m.friction[0]), v2 = velocityAlong(A, B, m.friction[1]);
  const double spin = velocityAlong(A, B, m.friction[2]) * m.radius;
  return std::sqrt(v1 * v1 + v2 * v2 + spin * spin) > slideSpeed;
}

// Each point with its step's normal impulse and its share of the pair's friction.
void store(const Solver& s, double slideSpeed, std::vector<ContactMemory>& memory) {
  memory.clear();
  for (const Manifold& m : s.manifolds) {
    const bool sliding = slides(s, m, slideSpeed);
    const double share = 1.0 / static_cast<double>(m.count);
    const Vec3 tangent = m.total.x() * m.friction[0].linear + m.total.y() * m.friction[1].linear;
    for (size_t k = m.first; k < m.first + m.count; ++k) {
      const Point& p = s.points[k];
      ContactMemory c;
      c.a = m.a;
      c.b = m.b == s.staticSlot() ? -1 : m.b;
      c.surface = m.surface;
      c.localA = p.localA;
      c.normalImpulse = p.total;
      c.tangentImpulse = share * tangent;
      c.twistImpulse = share * m.total.z();
      c.sliding = sliding;
      memory.push_back(c);
    }
  }
}

// The sub-steps' impulses on the surfaces, one push per pair.
void pushSurfaces(const Solver& s, ContactImpulses& out) {
  for (const Manifold& m : s.manifolds) {
    if (m.b != s.staticSlot()) continue;
    Vec3 push = m.total.x() * m.friction[0].linear + m.total.y() * m.friction[1].linear;
    for (size_t k = m.first; k < m.first + m.count; ++k) push += s.points[k].total * m.normal;
    out.pushes.push_back({m.a, m.surface, push});
  }
}

// The bodies that some row pushed into next, and what contact gave each: the momenta
// change by the velocity change (I at the step's start, the inertia the solve used),
// less the applied forces' share. The others keep the integrator's motion.
void commitBodies(const WorldModel& model, const WorldData& data, const Solver& s, int substeps,
                  std::vector<BodyState>& next, ContactImpulses& out) {
  for (int i : s.moving) {
    const Body& b = s.bodies[i];
    if (b.driven) {  // it moves as driven (the integrator's step); what it felt is its load
      out.linear[i] = b.felt;
      out.angular[i] = b.feltMoment;
      continue;
    }
    if (!b.pushed) continue;
    const BodyConstants& constants = model.bodies[i];
    const BodyState& y = data.Y[i];
    const Mat3 inertia = b.q0.toRotationMatrix() * constants.Ibody * b.q0.toRotationMatrix().transpose();
    BodyState& out_ = next[i];
    out_.X = y.X + b.moved;
    out_.q = b.q;
    out_.P = y.P + constants.mass * (b.v - b.v0);
    out_.L = y.L + inertia * (b.w - b.w0);
    out.linear[i] = constants.mass * (b.v - b.v0 - substeps * b.dv);
    out.angular[i] = inertia * (b.w - b.w0 - substeps * b.dw);
  }
}

void countTouching(const std::vector<Contact>& contacts, std::vector<int>& count) {
  for (const Contact& c : contacts) {
    if (c.depth < -kTouching) continue;
    ++count[c.a];
    if (c.b >= 0) ++count[c.b];
  }
}

// The step's rows and the impacts at its start (both entry points begin so).
Solver& prepareAndAnswerImpacts(const WorldModel& model, const WorldData& data, const std::vector<Contact>& contacts,
                                double h, ConstraintScratchPtr& scratch, ContactImpulses& impulses,
                                ConstraintReport& report, ExtraRows* extra = nullptr) {
  const size_t n = data.Y.size();
  impulses.linear.assign(n, Vec3::Zero());
  impulses.angular.assign(n, Vec3::Zero());
  impulses.pushes.clear();
  if (!scratch) scratch.reset(new ConstraintScratch);
  Solver& s = *scratch;
  s.bodies.assign(n + 1, Body{});
  s.involved.assign(n, 0);
  s.moving.clear();
  prepareRows(model, data, contacts, h, s);
  if (extra) {  // a body that a joint holds moves as the solve says, whatever its rows' impulses
    s.held.clear();
    extra->prepare(model, data, h, s.held);
    for (int i : s.held) {
      prepareBody(model, data, h / kSubsteps, i, s);
      s.bodies[i].pushed = true;
    }
  }
  report.points = static_cast<int>(s.points.size());
  report.impactPasses = answerImpacts(s, restingNormalSpeed(model.gravity, model.maxStep), h, impulses, extra);
  return s;
}

}  // namespace

ConstraintReport answerImpactsNow(const WorldModel& model, const WorldData& data, const std::vector<Contact>& contacts,
                                  double h, std::vector<BodyState>& next, ConstraintScratchPtr& scratch,
                                  ContactImpulses& impulses) {
  ConstraintReport report;
  const Solver& s = prepareAndAnswerImpacts(model, data, contacts, h, scratch, impulses, report);
  commitBodies(model, data, s, 0, next, impulses);
  return report;
}

ConstraintReport solveConstraints(const WorldModel& model, const WorldData& data, const std::vector<Contact>& contacts,
                                  double h, const std::vector<ContactMemory>& remembered,
                                  std::vector<ContactMemory>& stored, std::vector<BodyState>& next,
                                  std::vector<int>& count, ConstraintScratchPtr& scratch, ContactImpulses& impulses,
                                  ExtraRows* extra) {
  ConstraintReport report;
  countTouching(contacts, count);
  Solver& s = prepareAndAnswerImpacts(model, data, contacts, h, scratch, impulses, report, extra);
  const double restingSpeed = restingNormalSpeed(model.gravity, model.maxStep);
  warmStart(remembered, s);
  const double hSub = h / kSubsteps;
  for (int k = 0; k < kSubsteps; ++k) {
    integrateVelocities(s);
    if (extra) extra->warmStart(s.bodies);
    applyWarmStart(s);
    if (extra) extra->solve(s.bodies, hSub, true);
    solvePass(s, hSub, true);
    integratePositions(s, hSub);
    followBodies(s);
    for (int pass = 0; pass < kRelaxPasses; ++pass) {
      if (extra) extra->solve(s.bodies, hSub, false);
      solvePass(s, hSub, false);
    }
    addSubstepImpulses(s);
  }
  store(s, std::max(1e-5, 0.01 * restingSpeed), stored);
  pushSurfaces(s, impulses);
  commitBodies(model, data, s, kSubsteps, next, impulses);
  return report;
}

bool anyBouncingImpact(const WorldModel& model, const std::vector<Contact>& contacts, const std::vector<BodyState>& Y,
                       double restingSpeed) {
  return std::any_of(contacts.begin(), contacts.end(), [&](const Contact& c) {
    return c.depth > 0.0 && coefficientsOf(model, c).xi > 0.0 && approachSpeed(model, Y, c) > restingSpeed;
  });
}

}  // namespace rigid
