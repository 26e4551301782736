#include "collision_response.h"

#include <algorithm>
#include <cmath>

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

Side sideOf(const WorldModel& model, const std::vector<BodyState>& Y, int body, const Vec3& point) {
  Side s;
  if (body < 0) return s;
  const BodyConstants& c = model.bodies[body];
  s.y = &Y[body];
  s.invMass = 1.0 / c.mass;
  const Mat3 R = Y[body].q.normalized().toRotationMatrix();
  s.Iinv = R * c.IbodyInv * R.transpose();
  s.r = point - Y[body].X;
  return s;
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

double halfThickness(const Shape& s) {
  switch (s.type) {
    case ShapeType::Sphere:
    case ShapeType::Capsule: return s.radius;
    case ShapeType::Box: return 0.5 * s.size.minCoeff();
    case ShapeType::Cylinder: return std::min(s.radius, 0.5 * s.length);
  }
  return 0.0;
}

double boundingRadius(const Shape& s) {
  switch (s.type) {
    case ShapeType::Sphere: return s.radius;
    case ShapeType::Capsule: return s.radius + 0.5 * s.length;
    case ShapeType::Box: return 0.5 * s.size.norm();
    case ShapeType::Cylinder: return std::hypot(s.radius, 0.5 * s.length);
  }
  return 0.0;
}

bool anyContactImpact(const WorldModel& model, const std::vector<Contact>& contacts,
                      const std::vector<BodyState>& Y, double restingSpeed) {
  for (const Contact& c : contacts) {
    if (c.depth <= 0.0 || onTopFace(model, Y, c)) continue;
    const Side a = sideOf(model, Y, c.a, c.point);
    const Side b = sideOf(model, Y, c.b, c.point);
    if (approach(a, b, c.normal) < -restingSpeed) return true;
  }
  return false;
}

namespace {

// One contact per touching pair: the centroid of its points, their mean normal and
// the deepest depth. A face contact (a box resting on a box) then takes one impulse
// through its patch's centre instead of corner impulses whose sequential order would
// leave a spurious spin and make stacks rock.
void mergePairs(const WorldModel& model, const std::vector<BodyState>& Y,
                const std::vector<Contact>& contacts, std::vector<Contact>& merged) {
  merged.clear();
  for (size_t i = 0; i < contacts.size();) {
    Contact m = contacts[i];
    if (onTopFace(model, Y, m)) {
      ++i;
      continue;
    }
    Vec3 point = Vec3::Zero(), normal = Vec3::Zero();
    int n = 0;
    size_t k = i;
    for (; k < contacts.size() && contacts[k].a == m.a && contacts[k].b == m.b &&
           contacts[k].surface == m.surface;
         ++k) {
      if (contacts[k].depth < -kTouching) continue;
      point += contacts[k].point;
      normal += contacts[k].normal;
      m.depth = std::max(m.depth, contacts[k].depth);
      ++n;
    }
    i = k;
    if (n == 0) continue;
    m.point = point / n;
    m.normal = normal.normalized();
    merged.push_back(m);
  }
}

// Bodies resting on a surface's top face take part as contacts with a static partner,
// so that what bodies above press into them is answered in the same passes.
void appendSurfaceContacts(const WorldModel& model, const std::vector<BodyState>& Y,
                           std::vector<Contact>& out) {
  for (size_t i = 0; i < Y.size(); ++i) {
    for (size_t s = 0; s < model.surfaces.size(); ++s) {
      const SurfaceContact sc = surfaceContact(model.surfaces[s], model.bodies[i], Y[i]);
      if (!sc.overFace || sc.gap > kTouching) continue;
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

}  // namespace

void resolveContacts(const WorldModel& model, const std::vector<Contact>& found,
                     double restingSpeed, std::vector<BodyState>& Y, std::vector<int>& count) {
  for (const Contact& c : found) {
    if (c.depth < -kTouching || c.b < 0) continue;
    ++count[c.a];
    ++count[c.b];
  }
  std::vector<Contact> contacts;
  mergePairs(model, Y, found, contacts);
  if (contacts.empty()) return;
  appendSurfaceContacts(model, Y, contacts);
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    bool approaching = false;
    for (const Contact& c : contacts) {
      if (c.depth < -kTouching) continue;
      const Side a = sideOf(model, Y, c.a, c.point);
      const Side b = sideOf(model, Y, c.b, c.point);
      const Vec3& n = c.normal;
      const double vrel = approach(a, b, n);
      if (vrel >= -1e-12) continue;
      approaching = true;
      const Coefficients k = coefficientsOf(model, c);
      // The seed's j = -(1 + xi) vrel / (1/Ma + 1/Mb + n.[(Ia^-1 (ra x n)) x ra + ...]);
      // an approach slower than a resting body's is not bounced (xi taken as 0).
      const double xi = -vrel > restingSpeed ? k.xi : 0.0;
      const double j = -(1.0 + xi) * vrel / (a.inverseEffectiveMass(n) + b.inverseEffectiveMass(n));
      applyImpulse(Y, c.a, a, -j * n);
      applyImpulse(Y, c.b, b, j * n);
      // Coulomb friction impulse against the tangential slip, |jt| <= mu j.
      const Vec3 u = b.velocityAt() - a.velocityAt();
      const Vec3 ut = u - u.dot(n) * n;
      const double slip = ut.norm();
      if (slip < 1e-15) continue;
      const Vec3 t = ut / slip;
      const double stick = slip / (a.inverseEffectiveMass(t) + b.inverseEffectiveMass(t));
      const double jt = stick <= k.mus * j ? stick : k.muk * j;
      applyImpulse(Y, c.a, a, jt * t);
      applyImpulse(Y, c.b, b, -jt * t);
    }
    if (!approaching) break;
  }
  // Overlaps removed pair by pair, translation only, in inverse proportion to mass.
  for (const Contact& c : contacts) {
    if (c.depth <= 0.0) continue;
    const double wa = 1.0 / model.bodies[c.a].mass;
    const double wb = c.b >= 0 ? 1.0 / model.bodies[c.b].mass : 0.0;
    Y[c.a].X -= c.depth * wa / (wa + wb) * c.normal;
    if (c.b >= 0) Y[c.b].X += c.depth * wb / (wa + wb) * c.normal;
  }
}

}  // namespace rigid
