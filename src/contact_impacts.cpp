#include "contact_impacts.h"

namespace rigid {
namespace contact_rows {

void impactRows(const Solver& s, std::vector<Row>& out, std::vector<std::pair<size_t, size_t>>& pairs) {
  out.clear();
  pairs.clear();
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
      pairs.emplace_back(i, end);
    }
    i = end;
  }
}

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

}  // namespace contact_rows
}  // namespace rigid
