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

bool anyContactImpact(const WorldModel& model, const std::vector<Contact>& contacts,
                      const std::vector<BodyState>& Y, double restingSpeed) {
  for (const Contact& c : contacts) {
    if (c.depth <= 0.0) continue;
    const Side a = sideOf(model, Y, c.a, c.point);
    const Side b = sideOf(model, Y, c.b, c.point);
    if (approach(a, b, c.normal) < -restingSpeed) return true;
  }
  return false;
}

void resolveContacts(const WorldModel& model, const std::vector<Contact>& contacts,
                     double restingSpeed, std::vector<BodyState>& Y, std::vector<int>& count) {
  for (const Contact& c : contacts) {
    if (c.depth < -kTouching || c.b < 0) continue;
    ++count[c.a];
    ++count[c.b];
  }
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
  // Overlaps removed pair by pair (the deepest point of each pair), translation only.
  for (size_t i = 0; i < contacts.size();) {
    const Contact& first = contacts[i];
    double depth = 0.0;
    Vec3 n = first.normal;
    size_t k = i;
    for (; k < contacts.size() && contacts[k].a == first.a && contacts[k].b == first.b &&
           contacts[k].surface == first.surface;
         ++k) {
      if (contacts[k].depth > depth) {
        depth = contacts[k].depth;
        n = contacts[k].normal;
      }
    }
    i = k;
    if (depth <= 0.0) continue;
    const double wa = 1.0 / model.bodies[first.a].mass;
    const double wb = first.b >= 0 ? 1.0 / model.bodies[first.b].mass : 0.0;
    Y[first.a].X -= depth * wa / (wa + wb) * n;
    if (first.b >= 0) Y[first.b].X += depth * wb / (wa + wb) * n;
  }
}

}  // namespace rigid
