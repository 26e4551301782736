// Shock propagation (Guendelman, Bridson and Fedkiw, 2003): a sweep over the touching
// points from the surfaces upwards, each point's lower body held as if infinitely heavy.
// The contact solver's stage after its passes (contact_solver.cpp). Internal to the
// contact solver.
#pragma once

#include "contact_rows.h"

namespace rigid {
namespace contact_rows {

// One sweep over the touching rows between bodies of different support levels (1 on a
// surface, k + 1 on a body of level k through a loaded row), lowest first, each row's
// lower body held; a pair's rows are taken kShockPairPasses times at most. Rows on
// surfaces, between bodies of one level and in stacks that rest on no surface are left
// alone. The impulses accumulate into the rows'.
void shockPass(Solver& s);

}  // namespace contact_rows
}  // namespace rigid
