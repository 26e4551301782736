// Impacts as the seed answers them: the touching points of a pair merged into one, and
// the seed's impulse j with restitution xi (and a Coulomb friction impulse) at it. Used
// before the solve (contact_solver.cpp, answerImpacts). Internal to the contact solver.
#pragma once

#include <utility>
#include <vector>

#include "contact_rows.h"

namespace rigid {
namespace contact_rows {

// The touching points of each pair merged into one (centroid, mean normal) into `out`,
// and the range of s.rows that each came from into `pairs`: an impact on a face then
// takes one impulse through the patch's centre instead of corner impulses whose
// sequential order would leave a spurious spin.
void impactRows(const Solver& s, std::vector<Row>& out, std::vector<std::pair<size_t, size_t>>& pairs);

// The seed's impulse at one merged point, j = -(1 + xi) vrel m_eff, then a Coulomb
// friction impulse against the slip, |jt| <= mu j (static when it stops the slip). A
// point on a surface adds what it gave the surface to `pushes`.
void impact(Solver& s, const Row& r, double vrel, std::vector<SurfacePush>& pushes);

}  // namespace contact_rows
}  // namespace rigid
