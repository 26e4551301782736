// The constraint solver: Box2D v3's soft step in three dimensions, one solver for every
// touching pair, body-body and body-surface (a surface is a static box of infinite
// mass). It moves the bodies of the contact islands over a step, in this order:
//   impacts      the seed's impulse j with restitution xi at every touching pair that
//                approaches faster than a resting body can (the step starts at the
//                located instant of the impact), pass after pass (Newton's cradle);
//   sub-steps    kSubsteps times: the applied forces' velocity change, the warm start
//                (each row's accumulated impulse), the solve with a soft bias that
//                pushes overlaps apart, the positions from the new velocities, and a
//                relax pass without the bias, so that the push adds no velocity;
//   store        the impulses, for the next step's warm start (ContactMemory).
// One row type per constraint: a point's normal (lambda_n >= 0), a pair's friction at
// the centre of its patch (two tangents and a twist about the normal, bounded together
// by mu lambda_N on an ellipsoid whose twist axis is scaled by the patch radius). On a
// conveyor, the belt's velocity (WorldData::beltVelocity, its part along the contact
// plane) is that of the surface's material: friction acts against the slip relative to it.
// Joints join as rows beside the contacts (ExtraRows, joint_rows.h), solved first in
// each pass so that contacts have the last word. Bodies that neither a contact nor a
// joint holds are left to the integrator.
#pragma once

#include <memory>
#include <vector>

#include "collision_detection.h"
#include "contact_memory.h"
#include "solver_rows.h"
#include "world.h"

namespace rigid {

namespace constraint_solver {
constexpr int kSubsteps = 4;
constexpr int kRelaxPasses = 1;  // docs/decisions/0001-constraint-solver.md: two, measured and not kept
// Contact softness (Box2D's b2MakeSoft): a natural frequency, as a share of the
// sub-step rate, and a damping ratio; a point on a surface (infinite mass) is twice as
// stiff. A quarter of the sub-step rate is Box2D's upper bound, where the soft step
// stays stable; the stiffest contact sinks least under a column's load (the sinking
// of a soft contact grows with the load it carries over its effective mass).
constexpr double kContactHertzShare = 0.1;
constexpr double kDampingRatio = 10.0;
constexpr double kMaxPushOut = 3.0;  // m/s, the fastest an overlap is pushed apart
}  // namespace constraint_solver

// The solver's buffers, kept between steps (CollisionCache): no state, only space.
struct ConstraintScratch;
struct ConstraintScratchDeleter {
  void operator()(ConstraintScratch* s) const;
};
using ConstraintScratchPtr = std::unique_ptr<ConstraintScratch, ConstraintScratchDeleter>;

// What one step of the solver did.
struct ConstraintReport {
  int points = 0;        // contact points answered
  int impactPasses = 0;  // passes of the impacts (0: none)
};

// What a solve gave one surface through one body's points (impulses, impacts
// included): the impulse on the surface, N s, world frame.
struct SurfacePush {
  int body = -1;
  int surface = -1;
  Vec3 impulse = Vec3::Zero();
};

// What the solver gave the bodies over a step: each body's contact impulse and its
// moment about the centre of mass (N s, N m s, world frame), and the surfaces' pushes.
// A step's contact impulses: per body (N s, N m s about the centre of mass; both empty
// when the step had no contacts) and on the surfaces.
struct ContactImpulses {
  std::vector<Vec3> linear, angular;
  std::vector<SurfacePush> pushes;
  void clear() {
    linear.clear();
    angular.clear();
    pushes.clear();
  }
};

// Moves the bodies that `contacts` (detected at data.Y, the step's start, with a
// speculative margin; sorted by pair) join over a step h: next[i] of each such body
// is replaced, every other next[i] is left as the integrator made it. The solve starts
// from `remembered` (last step's points) and writes this step's to `stored`, so that
// a step may be tried again from the same start (an impact located by bisection);
// `impulses` takes the step's contact impulses; `count` gains each body's touching
// points. The contacts' stiffness and resting speed are solver.step's (model.maxStep),
// whatever h is: a step split at a located impact (h down to 1e-15 of it), or cut into
// sub-steps, keeps the same springs, not ones stiffer by (maxStep/h)^2. `extra` (or
// null): rows beyond the contacts', the joints'.
ConstraintReport solveConstraints(const WorldModel& model, const WorldData& data, const std::vector<Contact>& contacts,
                                  double h, const std::vector<ContactMemory>& remembered,
                                  std::vector<ContactMemory>& stored, std::vector<BodyState>& next,
                                  std::vector<int>& count, ConstraintScratchPtr& scratch, ContactImpulses& impulses,
                                  ExtraRows* extra = nullptr);

// The impacts stage alone, at the instant of data.Y: a step that ends at a located
// bouncing impact and returns there (FMI 3's early return) answers it before it
// returns, as the next step's start would. next[i] of each struck body takes its new
// momenta (positions unchanged); `impulses` takes the impulses.
ConstraintReport answerImpactsNow(const WorldModel& model, const WorldData& data, const std::vector<Contact>& contacts,
                                  double h, std::vector<BodyState>& next, ConstraintScratchPtr& scratch,
                                  ContactImpulses& impulses);

// Whether some contact of Y is a bouncing impact: overlapping, xi > 0, approaching
// faster than restingSpeed (m/s). The step then locates the instant of impact.
bool anyBouncingImpact(const WorldModel& model, const std::vector<Contact>& contacts, const std::vector<BodyState>& Y,
                       double restingSpeed);

}  // namespace rigid
