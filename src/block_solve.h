// The block solve of small islands of unlike masses: every impulse of an island (bodies
// joined by rows) of at most kMaxBlockRows points whose masses differ by kBlockMassRatio
// or more solved at once, exactly, to each row's target normal velocity (a heavy box on
// a light one: Gauss-Seidel passes carry the load down at a rate of the mass ratio per
// pass, and 1e6 does not converge in any number of passes). Used by the contact
// solver's passes (contact_solver.cpp). Internal to the contact solver.
#pragma once

#include "contact_rows.h"

namespace rigid {
namespace contact_rows {

// The islands that the block solve may take, into s.islandRows and s.blocks (none when
// the rows' bodies are of like masses). Rows do not change within a solve: found once.
void findBlockIslands(Solver& s);

// Every island of findBlockIslands with a row not settled has its impulses solved at
// once; its bodies' versions change, so that its rows are solved again.
void solveBlockIslands(Solver& s);

}  // namespace contact_rows
}  // namespace rigid
