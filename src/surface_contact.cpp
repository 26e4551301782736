#include "surface_contact.h"

#include <cmath>

namespace rigid {

namespace {

// A body is in contact with a face when its lowest point is within this distance.
constexpr double kContactDistance = 1e-9;  // m
// Tangential speed below which a body on a surface counts as at rest.
constexpr double kRestSpeed = 1e-9;  // m/s

// Normal speed below which an impact does not bounce and a body may rest: what
// gravity adds in two steps, so that a resting body's per-step sinking never bounces.
double restingNormalSpeed(const Vec3& gravity, double h) { return 2.0 * gravity.norm() * h + 1e-9; }

}  // namespace

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
    // Coulomb friction: static holds the body while the tangential load is at most
    // mu_s N; a sliding body feels mu_k N against its sliding velocity; a body at rest
    // whose load exceeds mu_s N starts to slide along the load.
    const Vec3 Ft = aux.F - aux.F.dot(c.n) * c.n;
    const Vec3 vt = aux.V - vn * c.n;
    const double speed = vt.norm();
    if (speed > kRestSpeed) {
      aux.F -= c.muk * N / speed * vt;
    } else if (Ft.norm() <= c.mus * N) {
      aux.F -= Ft;
    } else {
      aux.F -= c.muk * N / Ft.norm() * Ft;
    }
  }
}

void respondToSurfaces(const std::vector<Surface>& surfaces, const BodyConstants& body,
                       const Vec3& gravity, const Vec3& F, double h, const BodyState& before,
                       BodyState& after) {
  for (const Surface& surface : surfaces) {
    const SurfaceContact c = surfaceContact(surface, body, after);
    if (!c.overFace || c.gap > kContactDistance) continue;
    Vec3 V = after.P / body.mass;
    const double vn = V.dot(c.n);
    if (c.gap < 0.0) after.X -= c.gap * c.n;  // out of the face, along its normal
    if (vn < 0.0) {
      // The seed's impulse along the normal, only while approaching: the normal
      // velocity is reversed and scaled by xi; slow approaches (resting) just stop.
      const double vnAfter = -vn > restingNormalSpeed(gravity, h) ? -c.xi * vn : 0.0;
      V += (vnAfter - vn) * c.n;
    }
    const double N = -F.dot(c.n);
    if (V.dot(c.n) <= kRestSpeed && N > 0.0) {
      const Vec3 vtBefore = before.P / body.mass - (before.P / body.mass).dot(c.n) * c.n;
      const Vec3 vt = V - V.dot(c.n) * c.n;
      const Vec3 Ft = F + N * c.n;
      const bool reversed = vt.dot(vtBefore) < 0.0;
      const bool holds = Ft.norm() <= c.mus * N;
      const bool stoppable = vt.norm() <= c.muk * N / body.mass * h + kRestSpeed;
      if (reversed || (holds && stoppable)) V -= vt;
    }
    after.P = body.mass * V;
  }
}

}  // namespace rigid
