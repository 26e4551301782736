// Soft sub-steps: the velocity and position stages of the contact solve when a scene
// names solver.contacts = "soft" (after Box2D v3's soft step, Catto, "Solver2D", 2024).
// The step's contact solve is cut into kSoftSubsteps sub-steps of h_sub = h / n. Each
//   half        adds half the velocity change that the integrator's applied forces made
//               over the sub-step, with half of each row's last sub-step impulse;
//   impacts     a pair that touches and approaches faster than a resting body can takes
//               the seed's impulse at its merged point (contact_impacts.h);
//   solve       passes over the rows with a soft position bias: an overlap beyond the
//               slop is a spring and damper (frequency kSoftFrequencyShare / h_sub,
//               damping ratio kSoftDampingRatio) that pushes the bodies apart; islands
//               of unlike masses solved at once (block_solve.h);
//   move        moves the bodies by the velocities at mid-sub-step (beyond the free
//               motion);
//   half        the other half of the forces and impulses;
//   impacts     again, at the moved positions;
//   relax       passes without the bias, so that the push-out leaves no velocity; the
//               islands of unlike masses again; after the last sub-step, the shock
//               sweep (shock_propagation.h).
// A step costs a bounded number of passes whatever the pile: what they leave
// unconverged shows as a small overlap that the next sub-steps' bias takes out, where
// the Gauss-Seidel passes (the default) iterate to a tolerance and a tall column takes
// the cap. Speculative points may close their gap within the sub-step and no more.
// Experimental: it does not yet hold the default's energy bound
// (docs/guide/surfaces-and-contacts.md, "Soft sub-steps").
#pragma once

#include <vector>

#include "contact_rows.h"

namespace rigid {

// Before the warm start: each body's free motion over the step (from step.start to Y) and
// the impacts' change of its velocities (v - v0 after answerImpacts).
void beginSubsteps(const WorldModel& model, const ContactStep& step, const std::vector<BodyState>& Y,
                   ContactScratch& s);

// After the warm start (which matched each row's remembered step impulse, unapplied): the
// sub-steps. Leaves the bodies' velocities at the step's end, each row's impulses at
// their sum over the sub-steps (the step's, as the passes leave them), and each body's
// move in s.substep. The sub-steps' impacts on surfaces go to `pushes`.
void solveSubsteps(const ContactStep& step, ContactScratch& s, ContactSolveReport& report,
                   std::vector<SurfacePush>& pushes);

// The sub-steps' move into X and q.
void moveBySubsteps(const ContactScratch& s, std::vector<BodyState>& Y);

}  // namespace rigid
