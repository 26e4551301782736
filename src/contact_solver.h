// The contact solver (solver.contacts = "manifold", the default): one pipeline for
// every touching pair, body-body and body-surface, a surface being a static box of
// infinite mass. Each pair brings the points of its contact patch (up to 4, the
// detector's manifold); the solver answers all of them together:
//   impacts      the seed's impulse j with restitution xi, pass after pass while some
//                pair approaches faster than a resting body can (Newton's cradle);
//   warm start   last step's accumulated impulses of the points that are still there;
//   velocities   sequential impulses (projected Gauss-Seidel): lambda_n >= 0, the
//                friction impulse in the disc |lambda_t| <= mu lambda_n (mu_s while the
//                point sticks, mu_k once it slides), speculative points allowed to
//                close their gap in the step and no more;
//   shock        a last sweep from the surfaces upwards, each row's lower body held:
//                what the passes left of a column's rocking is taken out level by level;
//   positions    split impulse: pseudo-velocities that move bodies out of overlap
//                and are then dropped, so that no energy is added;
//   store        the points and their impulses for the next step (ContactMemory).
#pragma once

#include <memory>
#include <vector>

#include "collision_detection.h"
#include "contact_memory.h"
#include "world.h"

namespace rigid {

// One solve's context: the step and where its figures go.
struct ContactStep {
  double h = 0.0;             // s, the internal step
  double restingSpeed = 0.0;  // m/s: a slower approach does not bounce (restingNormalSpeed)
  // Share of h times the solve's velocity change that moves the bodies: the share by
  // which the integrator moves a body under a constant force (constantForceDisplacement).
  double moveShare = 0.5;
};

// What a solve gave one surface through one body's points (impulses, impacts
// included): the impulse on the surface, N s, world frame.
struct SurfacePush {
  int body = -1;
  int surface = -1;
  Vec3 impulse = Vec3::Zero();
};

struct ContactSolveReport {
  int points = 0;         // contact points answered
  int iterations = 0;     // velocity iterations taken
  long rowSolves = 0;     // points solved over those iterations (a settled point skipped is not)
  double residual = 0.0;  // m/s, largest velocity change of the last iteration
  int impactPasses = 0;   // passes of the impact stage (0: no impact)
};

// The solver's constants, stated once (README, "Contacts").
namespace contact_solver {
constexpr int kMaxVelocityIterations = 60;   // cap of the Gauss-Seidel passes
constexpr double kVelocityTolerance = 1e-5;  // m/s: stop when no impulse changes a velocity more
// After this many passes without convergence, an island (bodies joined by rows) of at
// most kMaxBlockRows points whose masses differ by kBlockMassRatio or more also has its
// impulses solved at once, exactly (a heavy box on a light one: Gauss-Seidel passes the
// load down at a rate of the mass ratio per pass, and 1e6 does not converge in any
// number of passes). Islands of like masses are left to the passes: they converge, they
// hold a box on a ramp near its limit where the block's least-norm friction overshoots
// a corner's disc, and a block for every small island of a falling pile of 100 made its
// fall 3.5x dearer.
constexpr int kBlockAfter = 8;
constexpr int kMaxBlockRows = 32;
constexpr double kBlockMassRatio = 100.0;
// Shock propagation: after the passes, one sweep from the surfaces upwards in which a
// row's lower body is held as if infinitely heavy, each pair's points taken this many
// times at most (a tall column's residual rocking is the slowest mode of the passes).
constexpr int kShockPairPasses = 4;
// Coarse correction, before the passes: in each island of at most kMaxCoarsePairs
// touching pairs whose pairs all move slower than a resting body can (the impacts'
// threshold, 2|g|h), every pair that sticks with a load is welded and the wrenches that
// stop them all are solved at once (coarse_correction.h). Faster islands (a landing, a
// toppling column) are left to the passes: their pairs are about to part or slide.
constexpr int kMaxCoarsePairs = 64;
constexpr double kCoarseStill = 1e-7;        // m/s: an island whose pairs all move slower rests already
constexpr double kCoarseRegular = 1e-9;      // share of its diagonal added to the wrenches' matrix
constexpr double kCoarseSpread = 1e-12;      // m^2: points closer together carry no moment
constexpr double kCoarseSpreadRatio = 1e-3;  // a direction of the points' spread below this share carries none

constexpr int kPositionIterations = 8;   // split-impulse passes
constexpr double kSlop = 1e-4;           // m, overlap left alone (a resting body's seat)
constexpr double kBaumgarte = 0.2;       // share of the overlap beyond the slop removed per step
constexpr double kMaxPushOut = 1.0;      // m/s, cap of the position correction's speed
constexpr double kMatchDistance = 0.01;  // m: a point within this of last step's (body a's frame) is the same
}  // namespace contact_solver

// The solver's work buffers (contact_solver.cpp), kept from one solve to the next.
struct ContactScratch;
struct ContactScratchDeleter {
  void operator()(ContactScratch* s) const;
};
using ContactScratchPtr = std::unique_ptr<ContactScratch, ContactScratchDeleter>;

// Answers the contacts of Y (the end of the step, detected with the speculative
// margin; `contacts` sorted by pair as the detector returns them): changes P and L by
// the impulses and X, q by the position correction. `memory` holds last step's points
// on entry and this step's on return. Adds each body's touching points to count.
// `scratch` holds no state between solves, only buffers (made on first use). `pushes`
// is replaced by the impulses the bodies gave the surfaces, per body and surface.
ContactSolveReport solveContacts(const WorldModel& model, const std::vector<Contact>& contacts, const ContactStep& step,
                                 std::vector<ContactMemory>& memory, std::vector<BodyState>& Y, std::vector<int>& count,
                                 ContactScratchPtr& scratch, std::vector<SurfacePush>& pushes);

// Whether some contact of Y is a bouncing impact: overlapping, xi > 0, approaching
// faster than restingSpeed (m/s). The step then locates the instant of impact.
bool anyBouncingImpact(const WorldModel& model, const std::vector<Contact>& contacts, const std::vector<BodyState>& Y,
                       double restingSpeed);

}  // namespace rigid
