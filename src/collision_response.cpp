#include "collision_response.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surface_contact.h"  // combineCoefficients

namespace rigid {

namespace {

// Contacts closer than this count as touching (the located impact leaves a gap of
// about 1e-15 of the step's travel).
constexpr double kTouching = 1e-6;  // m
constexpr int kMaxPasses = 500;

// One side of a contact, as the impulse sees it: a static surface has no inverse
// mass or inertia.
struct Side {
  const BodyState* y = nullptr;
  double invMass = 0.0;
  Mat3 Iinv = Mat3::Zero();
  Vec3 r = Vec3::Zero();  // m, from the centre of mass to the contact point

  Vec3 velocityAt() const {
    if (!y) return Vec3::Zero();
    return y->P * invMass + (Iinv * y->L).cross(r);
  }
  // An immovable side (shock propagation): it takes no impulse, and the body above
  // is stopped against it as against a static partner.
  void freeze() {
    invMass = 0.0;
    Iinv = Mat3::Zero();
  }
  // How the velocity at the contact point along d changes per unit impulse along d.
  double inverseEffectiveMass(const Vec3& d) const {
    return invMass + d.dot((Iinv * r.cross(d)).cross(r));
  }
};

// Applies the impulse J at the contact point of body `body` (none for a surface).
void applyImpulse(std::vector<BodyState>& Y, int body, const Side& s, const Vec3& J) {
  if (body < 0) return;
  Y[body].P += J;
  Y[body].L += s.r.cross(J);
}

// I(t)^-1 = R Ibody^-1 R^T of one body at its pose in Y.
Mat3 inverseInertia(const WorldModel& model, const std::vector<BodyState>& Y, int body) {
  const Mat3 R = Y[body].q.normalized().toRotationMatrix();
  return R * model.bodies[body].IbodyInv * R.transpose();
}

// The side of body `body` (-1: a surface) at a contact point, with its inverse
// inertia given (the response computes each body's once: impulses change no pose).
Side sideOf(const WorldModel& model, const std::vector<BodyState>& Y, int body, const Vec3& point,
            const Mat3& Iinv) {
  Side s;
  if (body < 0) return s;
  s.y = &Y[body];
  s.invMass = 1.0 / model.bodies[body].mass;
  s.Iinv = Iinv;
  s.r = point - Y[body].X;
  return s;
}

Side sideOf(const WorldModel& model, const std::vector<BodyState>& Y, int body, const Vec3& point) {
  return body < 0 ? Side{} : sideOf(model, Y, body, point, inverseInertia(model, Y, body));
}

struct Coefficients {
  double xi, mus, muk;
};

Coefficients coefficientsOf(const WorldModel& model, const Contact& c) {
  const BodyConstants& a = model.bodies[c.a];
  double xi = a.restitution, mus = a.staticFriction, muk = a.kineticFriction;
  if (c.b >= 0) {
    const BodyConstants& b = model.bodies[c.b];
    return {combineCoefficients(xi, b.restitution), combineCoefficients(mus, b.staticFriction),
            combineCoefficients(muk, b.kineticFriction)};
  }
  const Surface& s = model.surfaces[c.surface];
  return {combineCoefficients(xi, s.restitution), combineCoefficients(mus, s.staticFriction),
          combineCoefficients(muk, s.kineticFriction)};
}

// Normal relative velocity of b with respect to a at the contact: < 0 approaching.
double approach(const Side& a, const Side& b, const Vec3& n) {
  return n.dot(b.velocityAt() - a.velocityAt());
}

}  // namespace

namespace {

// A body over a surface's top face is the surface module's (support, friction,
// landing); FCL's contacts of that pair are left out.
bool onTopFace(const WorldModel& model, const std::vector<BodyState>& Y, const Contact& c) {
  return c.b < 0 && surfaceContact(model.surfaces[c.surface], model.bodies[c.a], Y[c.a]).overFace;
}

}  // namespace


bool anyContactImpact(const WorldModel& model, const std::vector<Contact>& contacts,
                      const std::vector<BodyState>& Y, double restingSpeed) {
  for (const Contact& c : contacts) {
    // As for surfaces (struckSurface): only a bouncing impact (xi > 0) is located in
    // time. With xi = 0 the pair ends with a common normal velocity, and the position
    // correction by inverse masses keeps their centre of mass where it would be.
    if (c.depth <= 0.0 || coefficientsOf(model, c).xi <= 0.0 || onTopFace(model, Y, c)) continue;
    const Side a = sideOf(model, Y, c.a, c.point);
    const Side b = sideOf(model, Y, c.b, c.point);
    if (approach(a, b, c.normal) < -restingSpeed) return true;
  }
  return false;
}

namespace {

// One contact per pair: the centroid of its points, their mean normal and the deepest
// depth (or the pair's overlap along the normal, when it is larger). A face contact (a
// box resting on a box) then takes one impulse through its patch's centre instead of
// corner impulses whose sequential order would leave a spurious spin and make stacks
// rock. A touching pair merges its touching points; a
// pair apart (a speculative contact) merges all of its points, so that the impulse
// that stops its approach acts through its patch's centre too.
void mergePairs(const WorldModel& model, const std::vector<BodyState>& Y,
                const std::vector<Contact>& contacts, std::vector<Contact>& merged) {
  merged.clear();
  for (size_t i = 0; i < contacts.size();) {
    if (onTopFace(model, Y, contacts[i])) {
      ++i;
      continue;
    }
    size_t end = i;
    bool touching = false;
    for (; end < contacts.size() && contacts[end].a == contacts[i].a && contacts[end].b == contacts[i].b &&
           contacts[end].surface == contacts[i].surface;
         ++end)
      touching = touching || contacts[end].depth >= -kTouching;
    Contact m = contacts[i];
    Vec3 point = Vec3::Zero(), normal = Vec3::Zero();
    int n = 0;
    m.depth = -std::numeric_limits<double>::infinity();
    for (size_t k = i; k < end; ++k) {
      if (touching && contacts[k].depth < -kTouching) continue;
      point += contacts[k].point;
      normal += contacts[k].normal;
      m.depth = std::max(m.depth, contacts[k].depth);
      if (contacts[k].pairOverlap > 0.0) m.depth = std::max(m.depth, contacts[k].pairOverlap);
      ++n;
    }
    i = end;
    m.point = point / n;
    m.normal = normal.normalized();
    merged.push_back(m);
  }
}

// Bodies resting on a surface's top face take part as contacts with a static partner,
// so that what bodies above press into them is answered in the same passes; bodies
// within `reach` of it take part in the position correction, which must not push them
// into it.
void appendSurfaceContacts(const WorldModel& model, const std::vector<BodyState>& Y, double reach,
                           std::vector<Contact>& out) {
  for (size_t i = 0; i < Y.size(); ++i) {
    if (clearOfSurfaces(model.surfaces, model.bodies[i].shape, Y[i].X, std::max(reach, kTouching))) continue;
    for (size_t s = 0; s < model.surfaces.size(); ++s) {
      const SurfaceContact sc = surfaceContact(model.surfaces[s], model.bodies[i], Y[i]);
      if (!sc.overFace || sc.gap > std::max(reach, kTouching)) continue;
      Contact c;
      c.a = static_cast<int>(i);
      c.surface = static_cast<int>(s);
      c.normal = -sc.n;  // from the body into the surface
      c.depth = -sc.gap;
      const Mat3 R = Y[i].q.normalized().toRotationMatrix();
      c.point = Y[i].X - supportDistance(model.bodies[i].shape, R, -sc.n) * sc.n;
      out.push_back(c);
    }
  }
}

// Level of each body in the stacks: 0 on a surface, k + 1 on a level-k body; bodies
// that rest on nothing static share the largest level. A pair supports when its gap
// is below `support`: touching for the impulses' shock propagation; the speculative
// reach for the position correction, where a base a few µm above the floor (a cube
// rocking on it) must still hold its tower rather than be pushed down by it.
std::vector<int> stackLevels(size_t bodies, const std::vector<Contact>& contacts, double support = kTouching) {
  constexpr int kFree = 1 << 20;
  std::vector<int> level(bodies, kFree);
  for (const Contact& c : contacts)
    if (c.b < 0 && c.depth >= -support) level[c.a] = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (const Contact& c : contacts) {
      if (c.b < 0 || c.depth < -support) continue;
      const int up = std::min(level[c.a], level[c.b]) + 1;
      for (int body : {c.a, c.b})
        if (level[body] > up && std::min(level[c.a], level[c.b]) < kFree) {
          level[body] = up;
          changed = true;
        }
    }
  }
  return level;
}

// Contacts ordered from the bottom of the stacks up (by the lower level of the pair;
// surfaces first).
std::vector<size_t> bottomUp(const std::vector<Contact>& contacts, const std::vector<int>& level) {
  std::vector<size_t> order(contacts.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto lower = [&](const Contact& c) { return c.b < 0 ? -1 : std::min(level[c.a], level[c.b]); };
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t x, size_t y) { return lower(contacts[x]) < lower(contacts[y]); });
  return order;
}

// Overlaps removed by moving bodies (translation only: positions change, velocities
// do not, so no energy is added). Each pair's overlap is taken out along its normal, a
// body on a surface moving out of it, an upper body moving off the lower one, both by
// inverse mass at equal levels. One move can push a body into a neighbour (a body
// lifted off its support into the one above it, a body pressed into the floor by one
// beside it), so the passes are repeated, each depth updated by the moves made so far
// (nonlinear Gauss-Seidel, as Box2D's position solver), until no overlap deeper than
// kResidual is left. Contacts with a gap (speculative ones) take part only when the
// moves close it. Returns how far a pair that was not among the contacts can have
// closed its gap (closedGap).
constexpr double kResidual = 1e-4;  // m: a tenth of the 1 mm a pile may overlap (issue 9)
constexpr int kMaxCorrectionPasses = 100;
// Passes after which every pair moves by inverse mass: projections in one metric,
// which converge whatever the stack levels say.
constexpr int kLevelPasses = 10;

// One pair as the position correction sees it: the share of the overlap each body
// takes, by stack level, and by inverse mass alone.
struct Separation {
  int a, b;  // b < 0: a static partner
  Vec3 n;    // from a to b
  double depth;
  double shareA, shareB;          // by level: 0 for a lower body that is below
  double massShareA, massShareB;  // by inverse mass
};

// The lower body of a pair at different levels stays put (a stack settles in one
// bottom-up sweep), but only when it is below the other along `up`: levels know
// contacts, not geometry, and a body resting against the underside of a body of a
// lower level would otherwise be pinned between two immovable partners.
std::vector<Separation> separations(const WorldModel& model, const std::vector<Contact>& contacts,
                                    const std::vector<int>& level, const std::vector<size_t>& order) {
  const Vec3 up = model.gravity.norm() > 0.0 ? Vec3(-model.gravity.normalized()) : Vec3::Zero();
  std::vector<Separation> out;
  out.reserve(order.size());
  for (size_t o : order) {
    const Contact& c = contacts[o];
    const double wa = 1.0 / model.bodies[c.a].mass;
    const double wb = c.b >= 0 ? 1.0 / model.bodies[c.b].mass : 0.0;
    Separation s{c.a, c.b, c.normal, c.depth, wa / (wa + wb), wb / (wa + wb), wa / (wa + wb), wb / (wa + wb)};
    if (c.b >= 0 && level[c.a] < level[c.b] && c.normal.dot(up) > 0.0) s.shareA = 0.0, s.shareB = 1.0;
    if (c.b >= 0 && level[c.b] < level[c.a] && c.normal.dot(up) < 0.0) s.shareA = 1.0, s.shareB = 0.0;
    out.push_back(s);
  }
  return out;
}

// Half extents (m) of a body's axis-aligned bounding box at orientation q: exact for a
// box, the bounding sphere's for other shapes.
Vec3 boundingHalfExtent(const Shape& shape, const Quat& q) {
  if (shape.type != ShapeType::Box) return Vec3::Constant(boundingRadius(shape));
  return rotationOf(q).cwiseAbs() * (0.5 * shape.size);
}

// After the moves d of the correction, from the poses Y before them: how far a pair
// that was not among the contacts (at least `reach` apart; a body and a surface too)
// can have closed its gap.
// Such a pair can overlap only if its moves differ by the reach, so only bodies moved
// by half the reach or more are looked at, each against every other body whose
// bounding box was closer than their moves differ. Returns the largest such
// difference (0 when none): a whole tower lifted as one closes no gap of its own, and
// a cube lifted beside a far one closes none either.
// Every body is met with every mover, so that meeting is one cheap test on centres
// (they must be within both bounding radii and both moves on every axis); only pairs
// that pass it take the bounding boxes, which need the orientations.
double closedGap(const WorldModel& model, const std::vector<BodyState>& Y, const std::vector<Vec3>& d,
                 double reach) {
  struct Mover {
    int body;
    Vec3 X;
    double radius, moved;
  };
  std::vector<Mover> movers;
  double closed = 0.0;
  for (size_t i = 0; i < Y.size(); ++i) {
    const double moved = d[i].norm();
    if (moved < 0.5 * reach) continue;
    const Shape& shape = model.bodies[i].shape;
    movers.push_back({static_cast<int>(i), Y[i].X, boundingRadius(shape), moved});
    // a surface farther than the reach (not among the contacts) that the move reaches
    if (moved >= reach && !clearOfSurfaces(model.surfaces, shape, Y[i].X, moved)) closed = std::max(closed, moved);
  }
  if (movers.empty()) return closed;
  for (size_t b = 0; b < Y.size(); ++b) {
    const double radius = boundingRadius(model.bodies[b].shape);
    const double movedB = d[b].norm();
    for (const Mover& a : movers) {
      if (static_cast<size_t>(a.body) == b) continue;
      if ((a.X - Y[b].X).cwiseAbs().maxCoeff() - a.radius - radius >= a.moved + movedB) continue;
      const double differ = (d[a.body] - d[b]).norm();
      if (differ < reach || differ <= closed) continue;
      const Vec3 halfA = boundingHalfExtent(model.bodies[a.body].shape, Y[a.body].q);
      const Vec3 halfB = boundingHalfExtent(model.bodies[b].shape, Y[b].q);
      const double gap = ((a.X - Y[b].X).cwiseAbs() - halfA - halfB).maxCoeff();
      if (gap < differ) closed = differ;
    }
  }
  return closed;
}

double correctPositions(const WorldModel& model, const std::vector<Contact>& contacts,
                        const std::vector<int>& level, const std::vector<size_t>& order, double reach,
                        std::vector<BodyState>& Y) {
  const std::vector<Separation> pairs = separations(model, contacts, level, order);
  std::vector<Vec3> moved(Y.size(), Vec3::Zero());
  for (int pass = 0; pass < kMaxCorrectionPasses; ++pass) {
    const bool byLevel = pass < kLevelPasses;
    double deepest = 0.0;
    for (const Separation& s : pairs) {
      const Vec3 relative = s.b >= 0 ? Vec3(moved[s.a] - moved[s.b]) : moved[s.a];
      const double depth = s.depth + relative.dot(s.n);
      if (depth <= 0.0) continue;
      deepest = std::max(deepest, depth);
      moved[s.a] -= depth * (byLevel ? s.shareA : s.massShareA) * s.n;
      if (s.b >= 0) moved[s.b] += depth * (byLevel ? s.shareB : s.massShareB) * s.n;
    }
    if (deepest <= kResidual) break;
  }
  const double closed = closedGap(model, Y, moved, reach);
  for (size_t i = 0; i < Y.size(); ++i) Y[i].X += moved[i];
  return closed;
}

}  // namespace

double resolveContacts(const WorldModel& model, const std::vector<Contact>& found, double h, double reach,
                       std::vector<BodyState>& Y, std::vector<int>& count) {
  const double restingSpeed = restingNormalSpeed(model.gravity, h);
  for (const Contact& c : found) {
    if (c.depth < -kTouching || c.b < 0) continue;
    ++count[c.a];
    ++count[c.b];
  }
  std::vector<Contact> contacts;
  mergePairs(model, Y, found, contacts);
  if (contacts.empty()) return 0.0;
  appendSurfaceContacts(model, Y, reach, contacts);
  // Poses do not change while impulses are exchanged: each body's inverse inertia,
  // each contact's sides and its inverse effective mass along the normal are computed
  // once, not in every Gauss-Seidel pass.
  std::vector<Mat3> Iinv(Y.size());
  std::vector<bool> known(Y.size(), false);
  auto inertiaOf = [&](int body) -> const Mat3& {
    if (!known[body]) Iinv[body] = inverseInertia(model, Y, body), known[body] = true;
    return Iinv[body];
  };
  // The passes keep each body's velocities (v = P / M, omega = I^-1 L) beside the
  // momenta that the impulses change: a contact point's velocity then costs a cross
  // product instead of a product by I^-1 in every pass.
  struct Motion {
    Vec3 v = Vec3::Zero(), omega = Vec3::Zero();
  };
  std::vector<Motion> motion(Y.size());
  // Each body's count of impulses so far: a row whose two bodies took none since it was
  // last found settled is still settled, and later passes skip it.
  std::vector<unsigned> version(Y.size(), 0u);
  auto versionOf = [&](int body) { return body < 0 ? 0u : version[body]; };
  auto pointVelocity = [&](int body, const Side& s) -> Vec3 {
    return body < 0 ? Vec3::Zero() : Vec3(motion[body].v + motion[body].omega.cross(s.r));
  };
  // The impulse J at a side's contact point: momenta and velocities, with I^-1 (r x J)
  // given (dOmega).
  auto push = [&](int body, const Side& s, const Vec3& J, const Vec3& rxJ, const Vec3& dOmega) {
    if (body < 0) return;
    ++version[body];
    Y[body].P += J;
    Y[body].L += rxJ;
    motion[body].v += s.invMass * J;
    motion[body].omega += dOmega;
  };
  struct Row {
    const Contact* c;
    Side a, b;
    double normalMass;  // 1 / (inverse effective masses along n)
    Coefficients k;
    double closing;     // m/s, approach speed that closes a speculative contact's gap in h (0: touching)
    Vec3 raXn, rbXn;    // r x n of each side
    Vec3 dOmegaA, dOmegaB;  // I^-1 (r x n) of each side: its spin per unit impulse along n
    bool settled = false;   // found settled with its bodies at these versions:
    unsigned versionA = 0, versionB = 0;
  };
  std::vector<Row> rows;
  rows.reserve(contacts.size());
  for (const Contact& c : contacts) {
    // Speculative contacts: a pair apart by a gap takes an impulse only when it would
    // otherwise close more than that gap in the next step, and then only what makes it
    // arrive touching (approach = gap / h): an inelastic body lands on the one below
    // instead of sinking into it by v h and being pushed out. Bouncing pairs (xi > 0)
    // are left alone: their impacts are located in time, and slowing them early would
    // take energy from the bounce.
    const Coefficients k = coefficientsOf(model, c);
    const bool touching = c.depth >= -kTouching;
    if (!touching && k.xi > 0.0) continue;
    Row row{&c, sideOf(model, Y, c.a, c.point, inertiaOf(c.a)),
            c.b < 0 ? Side{} : sideOf(model, Y, c.b, c.point, inertiaOf(c.b)), 0.0, k,
            touching ? 0.0 : -c.depth / h, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
    row.normalMass = 1.0 / (row.a.inverseEffectiveMass(c.normal) + row.b.inverseEffectiveMass(c.normal));
    row.raXn = row.a.r.cross(c.normal);
    row.rbXn = row.b.r.cross(c.normal);
    row.dOmegaA = row.a.Iinv * row.raXn;
    row.dOmegaB = row.b.Iinv * row.rbXn;
    for (int body : {c.a, c.b})
      if (body >= 0) motion[body] = {Y[body].P / model.bodies[body].mass, inertiaOf(body) * Y[body].L};
    rows.push_back(row);
  }
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    bool approaching = false;
    for (Row& row : rows) {
      const Contact& c = *row.c;
      if (row.settled && row.versionA == versionOf(c.a) && row.versionB == versionOf(c.b)) continue;
      const Side& a = row.a;
      const Side& b = row.b;
      const Vec3& n = c.normal;
      const double vrel = n.dot(pointVelocity(c.b, b) - pointVelocity(c.a, a));
      // Settled: an approach below 1 % of a resting body's speed (2 g h) sinks it by
      // less than 1 % of what gravity alone does in the step, which the position
      // correction takes out; without gravity, below 1e-9 m/s. A pile of 1000 cubes
      // then needs ~20 passes instead of ~140 for 1e-9 m/s.
      row.settled = vrel >= -row.closing - std::max(1e-9, 1e-2 * restingSpeed);
      row.versionA = versionOf(c.a);
      row.versionB = versionOf(c.b);
      if (row.settled) continue;
      approaching = true;
      // The seed's j = -(1 + xi) vrel / (1/Ma + 1/Mb + n.[(Ia^-1 (ra x n)) x ra + ...]);
      // an approach slower than a resting body's is not bounced (xi taken as 0). Apart
      // (a speculative contact), only the approach beyond the closing speed is taken
      // out, with no bounce and no friction.
      const double xi = row.closing == 0.0 && -vrel > restingSpeed ? row.k.xi : 0.0;
      const double j = -((1.0 + xi) * vrel + row.closing) * row.normalMass;
      push(c.a, a, -j * n, -j * row.raXn, -j * row.dOmegaA);
      push(c.b, b, j * n, j * row.rbXn, j * row.dOmegaB);
      if (row.closing > 0.0) continue;
      // Coulomb friction impulse against the tangential slip, |jt| <= mu j.
      const Vec3 u = pointVelocity(c.b, b) - pointVelocity(c.a, a);
      const Vec3 ut = u - u.dot(n) * n;
      const double slip = ut.norm();
      if (slip < 1e-15) continue;
      const Vec3 t = ut / slip;
      const Vec3 raXt = a.r.cross(t), rbXt = b.r.cross(t);
      const Vec3 spinA = a.Iinv * raXt, spinB = b.Iinv * rbXt;
      const double stick = slip / (a.invMass + raXt.dot(spinA) + b.invMass + rbXt.dot(spinB));
      const double jt = stick <= row.k.mus * j ? stick : row.k.muk * j;
      push(c.a, a, jt * t, jt * raXt, jt * spinA);
      push(c.b, b, -jt * t, -jt * rbXt, -jt * spinB);
    }
    if (!approaching) break;
  }
  // Shock propagation (Guendelman, Bridson & Fedkiw 2003): bodies resting on a surface
  // are level 0, bodies on those level 1, and so on. A last pass over the contacts,
  // from the bottom up, treats the lower body of each pair as immovable, so that what
  // is left of the approach goes to the body above: a heavy body on a light one can
  // no longer push it into the floor, which Gauss-Seidel passes alone settle far too
  // slowly at mass ratios of 1e3 and more.
  const std::vector<int> level = stackLevels(Y.size(), contacts);
  const std::vector<size_t> order = bottomUp(contacts, level);
  for (size_t o : order) {
    const Contact& c = contacts[o];
    if (c.depth < -kTouching || c.b < 0 || level[c.a] == level[c.b]) continue;
    Side a = sideOf(model, Y, c.a, c.point, inertiaOf(c.a));
    Side b = sideOf(model, Y, c.b, c.point, inertiaOf(c.b));
    (level[c.a] < level[c.b] ? a : b).freeze();
    const double vrel = approach(a, b, c.normal);
    if (vrel >= 0.0) continue;
    const double j = -vrel / (a.inverseEffectiveMass(c.normal) + b.inverseEffectiveMass(c.normal));
    if (a.invMass > 0.0) applyImpulse(Y, c.a, a, -j * c.normal);
    if (b.invMass > 0.0) applyImpulse(Y, c.b, b, j * c.normal);
  }
  const std::vector<int> withinReach = stackLevels(Y.size(), contacts, reach);
  return correctPositions(model, contacts, withinReach, bottomUp(contacts, withinReach), reach, Y);
}

double separateOverlaps(const WorldModel& model, const std::vector<Contact>& found, double reach,
                        std::vector<BodyState>& Y) {
  std::vector<Contact> contacts;
  mergePairs(model, Y, found, contacts);
  appendSurfaceContacts(model, Y, reach, contacts);
  if (contacts.empty()) return 0.0;
  const std::vector<int> level = stackLevels(Y.size(), contacts, reach);
  return correctPositions(model, contacts, level, bottomUp(contacts, level), reach, Y);
}

}  // namespace rigid
