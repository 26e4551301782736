#include "surface_contact.h"

#include <algorithm>
#include <cmath>

namespace rigid {

namespace {

// A body is in contact with a face when its lowest point is within this distance.
constexpr double kContactDistance = 1e-9;  // m
// Slip speed below which a body on a surface counts as not slipping.
constexpr double kRestSpeed = 1e-9;  // m/s

Mat3 cross(const Vec3& r) {
  Mat3 m;
  m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return m;
}

// Friction at arm r on a body: the tangential block of the map from an impulse (or
// force) at the friction point to that point's velocity (or acceleration) change,
// K = I/M - [r]x I(t)^-1 [r]x, in an orthonormal tangent basis (t1, t2) of n.
struct TangentPlane {
  Vec3 t1, t2;
  Eigen::Matrix2d K;

  TangentPlane(const Vec3& n, const Vec3& r, double mass, const Mat3& Iinv) {
    t1 = n.unitOrthogonal();
    t2 = n.cross(t1);
    const Mat3 K3 = Mat3::Identity() / mass - cross(r) * Iinv * cross(r);
    K << t1.dot(K3 * t1), t1.dot(K3 * t2), t2.dot(K3 * t1), t2.dot(K3 * t2);
  }
  Eigen::Vector2d components(const Vec3& v) const { return {t1.dot(v), t2.dot(v)}; }
  Vec3 vector(const Eigen::Vector2d& c) const { return c.x() * t1 + c.y() * t2; }
  // The tangential force (impulse) at the friction point that cancels the tangential
  // acceleration (velocity) `a` of that point.
  Vec3 cancelling(const Vec3& a) const { return vector(-K.inverse() * components(a)); }
};

// Velocity of the friction point, tangential part.
Vec3 slipVelocity(const Vec3& V, const Vec3& omega, const Vec3& r, const Vec3& n) {
  const Vec3 u = V + omega.cross(r);
  return u - u.dot(n) * n;
}

}  // namespace

bool clearOfSurfaces(const std::vector<Surface>& surfaces, const Shape& shape, const Vec3& X, double travel) {
  const double reach = boundingRadius(shape) + travel + kContactDistance;
  for (const Surface& s : surfaces) {
    const Vec3 outside = ((s.R_WS.transpose() * (X - s.centre)).cwiseAbs() - s.halfExtent).cwiseMax(0.0);
    if (outside.squaredNorm() <= reach * reach) return false;
  }
  return true;
}

double restingNormalSpeed(const Vec3& gravity, double h) { return 2.0 * gravity.norm() * h + 1e-9; }

double combineCoefficients(double a, double b) { return std::sqrt(a * b); }

double supportDistance(const Shape& s, const Mat3& R, const Vec3& d) {
  switch (s.type) {
    case ShapeType::Sphere:
      return s.radius;
    case ShapeType::Box: {
      const Vec3 local = R.transpose() * d;
      return 0.5 * (local.cwiseAbs().dot(s.size));
    }
    case ShapeType::Cylinder:
    case ShapeType::Capsule: {
      const double c = std::abs(R.col(2).dot(d));  // cosine between axis and d
      const double along = 0.5 * s.length * c;
      if (s.type == ShapeType::Capsule) return along + s.radius;
      return along + s.radius * std::sqrt(std::max(0.0, 1.0 - c * c));
    }
  }
  return 0.0;
}

double spinFrictionArm(const Shape& s, const Mat3& R, const Vec3& n) {
  switch (s.type) {
    case ShapeType::Sphere:
      return 0.0;
    case ShapeType::Box: {
      int down = 0;  // the body axis along the normal: the face it rests on is across it
      for (int k = 1; k < 3; ++k)
        if (std::abs(R.col(k).dot(n)) > std::abs(R.col(down).dot(n))) down = k;
      const double p = 0.5 * s.size[(down + 1) % 3], q = 0.5 * s.size[(down + 2) % 3];
      const double d = std::hypot(p, q);
      return (2.0 * p * q * d + p * p * p * std::log((q + d) / p) + q * q * q * std::log((p + d) / q)) / (6.0 * p * q);
    }
    case ShapeType::Cylinder:
    case ShapeType::Capsule: {
      const bool standing = std::abs(R.col(2).dot(n)) > std::sqrt(0.5);
      if (standing) return s.type == ShapeType::Cylinder ? 2.0 * s.radius / 3.0 : 0.0;
      return 0.25 * s.length;
    }
  }
  return 0.0;
}

Vec3 frictionArm(const Shape& s, const Mat3& R, const Vec3& n) {
  switch (s.type) {
    case ShapeType::Sphere:
      return -s.radius * n;
    case ShapeType::Capsule: {
      // the centre of the lower cap, then down by the radius; lying flat, the middle
      const Vec3 axis = R.col(2);
      const double c = axis.dot(n);
      const double side = c > 0.0 ? -1.0 : (c < 0.0 ? 1.0 : 0.0);
      return side * 0.5 * s.length * axis - s.radius * n;
    }
    case ShapeType::Box:
    case ShapeType::Cylinder:
      return Vec3::Zero();
  }
  return Vec3::Zero();
}

SurfaceContact surfaceContact(const Surface& surface, const BodyConstants& body, const BodyState& y) {
  SurfaceContact c;
  const Vec3 p = surface.R_WS.transpose() * (y.X - surface.centre);  // surface frame
  const Vec3& e = surface.halfExtent;
  // Over the face: the centre of mass projects inside the face's bounds and lies
  // above the box's mid-plane (a body deeper than that is not resting on top).
  c.overFace = std::abs(p.x()) <= e.x() && std::abs(p.y()) <= e.y() && p.z() >= 0.0;
  if (!c.overFace) return c;
  c.n = surface.R_WS.col(2);
  const Mat3 R = y.q.normalized().toRotationMatrix();
  c.gap = p.z() - e.z() - supportDistance(body.shape, R, -c.n);
  c.mus = combineCoefficients(body.staticFriction, surface.staticFriction);
  c.muk = combineCoefficients(body.kineticFriction, surface.kineticFriction);
  c.xi = combineCoefficients(body.restitution, surface.restitution);
  return c;
}

void addSurfaceForces(const std::vector<Surface>& surfaces, const BodyConstants& body,
                      const BodyState& y, BodyAux& aux) {
  for (const Surface& surface : surfaces) {
    const SurfaceContact c = surfaceContact(surface, body, y);
    if (!c.overFace || c.gap > kContactDistance) continue;
    const double vn = aux.V.dot(c.n);
    if (vn > kRestSpeed) continue;  // leaving the face: no support
    const double N = -aux.F.dot(c.n);  // the support answers what presses the body on
    if (N <= 0.0) continue;            // pulled away: the face cannot hold it
    aux.F += N * c.n;
    // Coulomb friction at the friction point r: kinetic mu_k N against the slip; when
    // not slipping, static friction cancels the point's tangential acceleration if it
    // needs at most mu_s N, else the point starts to slip, mu_k N against that
    // acceleration. (With r = 0 this is friction on the centre of mass.)
    const Vec3 r = frictionArm(body.shape, aux.R, c.n);
    const Vec3 slip = slipVelocity(aux.V, aux.omega, r, c.n);
    const double slipSpeed = slip.norm();
    Vec3 f;
    if (slipSpeed > kRestSpeed) {
      f = -c.muk * N / slipSpeed * slip;
    } else {
      const TangentPlane plane(c.n, r, body.mass, aux.Iinv);
      const Vec3 a = aux.F / body.mass + (aux.Iinv * aux.T).cross(r);
      const Vec3 hold = plane.cancelling(a - a.dot(c.n) * c.n);
      const double need = hold.norm();
      f = need <= c.mus * N ? hold : Vec3(c.muk * N / need * hold);
    }
    aux.F += f;
    aux.T += r.cross(f);
    // Friction against spin about the normal, over the patch the body rests on:
    // kinetic mu_k N rho against the spin; when not spinning, static friction cancels
    // the applied torque about n up to mu_s N rho.
    const double rho = spinFrictionArm(body.shape, aux.R, c.n);
    if (rho > 0.0) {
      const double spin = aux.omega.dot(c.n);
      const double torque = std::abs(spin) * rho > kRestSpeed
                                ? -std::copysign(c.muk * N * rho, spin)
                                : -std::clamp(aux.T.dot(c.n), -c.mus * N * rho, c.mus * N * rho);
      aux.T += torque * c.n;
    }
  }
}

bool struckSurface(const std::vector<Surface>& surfaces, const BodyConstants& body,
                   const Vec3& gravity, double h, const BodyState& after) {
  for (const Surface& surface : surfaces) {
    const SurfaceContact c = surfaceContact(surface, body, after);
    // Only a landing that bounces (xi > 0) needs its instant: a bounce's height depends
    // on where it starts, while a landing with xi = 0 just stops along the normal,
    // which the end-of-step response does as well (and a pile of such landings would
    // otherwise re-integrate every step dozens of times).
    if (c.overFace && c.gap < 0.0 && c.xi > 0.0 &&
        (after.P / body.mass).dot(c.n) < -restingNormalSpeed(gravity, h))
      return true;
  }
  return false;
}

int respondToSurfaces(const std::vector<Surface>& surfaces, const BodyConstants& body,
                      const Vec3& gravity, const BodyAux& applied, double h,
                      const BodyState& before, BodyState& after) {
  int touching = 0;
  for (const Surface& surface : surfaces) {
    const SurfaceContact c = surfaceContact(surface, body, after);
    if (!c.overFace || c.gap > kContactDistance) continue;
    ++touching;
    Vec3 V = after.P / body.mass;
    const double vn = V.dot(c.n);
    if (c.gap < 0.0) after.X -= c.gap * c.n;  // out of the face, along its normal
    if (vn < 0.0) {
      // The seed's impulse along the normal, only while approaching: the normal
      // velocity is reversed and scaled by xi; slow approaches (resting) just stop.
      const double vnAfter = -vn > restingNormalSpeed(gravity, h) ? -c.xi * vn : 0.0;
      V += (vnAfter - vn) * c.n;
      after.P = body.mass * V;
    }
    const double N = -applied.F.dot(c.n);
    if (V.dot(c.n) > kRestSpeed || N <= 0.0) continue;
    // Stick: the impulse at the friction point that removes its slip.
    const Vec3 r = frictionArm(body.shape, applied.R, c.n);
    const Vec3 omega = applied.Iinv * after.L;
    const Vec3 slip = slipVelocity(V, omega, r, c.n);
    BodyAux was;
    computeAuxiliaries(body, before, was);
    const Vec3 slipBefore = slipVelocity(was.V, was.omega, r, c.n);
    const TangentPlane plane(c.n, r, body.mass, applied.Iinv);
    const Vec3 a = applied.F / body.mass + (applied.Iinv * applied.T).cross(r);
    const bool holds = plane.cancelling(a - a.dot(c.n) * c.n).norm() <= c.mus * N;
    const Vec3 stop = plane.cancelling(slip);
    const bool reversed = slip.dot(slipBefore) < 0.0;
    const bool stoppable = stop.norm() <= c.muk * N * h + body.mass * kRestSpeed;
    if (reversed || (holds && stoppable)) {
      after.P += stop;
      after.L += r.cross(stop);
    }
    // Stick against spin about the normal likewise: the angular impulse about n that
    // stops it, when the spin reversed in the step or kinetic friction can stop it
    // within one while static friction holds the applied torque.
    const double rho = spinFrictionArm(body.shape, applied.R, c.n);
    if (rho > 0.0) {
      const double spin = (applied.Iinv * after.L).dot(c.n);
      const double stopSpin = spin / c.n.dot(applied.Iinv * c.n);  // N m s about n
      const bool spinReversed = spin * was.omega.dot(c.n) < 0.0;
      const bool spinHolds = std::abs(applied.T.dot(c.n)) <= c.mus * N * rho;
      const bool spinStoppable = std::abs(stopSpin) <= (c.muk * N * h + body.mass * kRestSpeed) * rho;
      if (spinReversed || (spinHolds && spinStoppable)) after.L -= stopSpin * c.n;
    }
  }
  return touching;
}

}  // namespace rigid
