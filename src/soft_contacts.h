// Soft sub-steps: the velocity and position stages of the contact solve when a scene
// names solver.contacts = "soft" (after Box2D v3's soft step, Catto, "Solver2D", 2024).
// The step's contact solve is cut into kSoftSubsteps sub-steps of h_sub = h / n. Each
//   forces     adds its share of the velocity change that the integrator's applied
//              forces made over the step;
//   warm start applies the rows' impulses (each row's impulse is a sub-step's);
//   solve      passes over the rows with a soft position bias: an overlap beyond the
//              slop is a spring and damper (frequency kSoftFrequencyShare / h_sub,
//              damping ratio kSoftDampingRatio) that pushes the bodies apart;
//   move       moves the bodies by the sub-step's velocities (beyond the free motion);
//   relax      passes without the bias, so that the push-out leaves no velocity.
// A step costs the same passes whatever the pile: what they leave unconverged shows as
// a small overlap that the next sub-steps' bias takes out, where the Gauss-Seidel
// passes (the default) iterate to a tolerance and a tall column takes the cap.
// Speculative points may close their gap within the sub-step and no more. Experimental:
// it does not yet hold every contact test (mass ratios, a dropped column's rest, the
// energy bound; docs/guide/surfaces-and-contacts.md, "Soft sub-steps").
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
// move in s.substep.
void solveSubsteps(const ContactStep& step, ContactScratch& s, ContactSolveReport& report);

// The sub-steps' move into X and q.
void moveBySubsteps(const ContactScratch& s, std::vector<BodyState>& Y);

}  // namespace rigid
