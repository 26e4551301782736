// The joints' rows in the constraint solver (joint.h for the types). Each joint is a
// few rows of the kind the contacts' are, solved in the same sub-steps and passes:
// the anchors meeting and the orientations held are equalities, softened as Box2D v3
// softens its joints (a stiff spring of kJointHertzShare of the sub-step rate, so that
// drift is pulled back without adding energy; the relax pass then takes the push's
// velocity out); a limit is one-sided like a contact's normal; a motor is bounded by
// its largest force; a spring is an implicit spring of the joint's stiffness and
// damping. Row impulses are remembered from step to step (warm start).
#pragma once

#include <memory>
#include <vector>

#include "solver_rows.h"

namespace rigid {

struct WorldModel;
struct WorldData;
struct ContactImpulses;

namespace joint_solver {
// Twice the contacts' stiffness (constraint_solver.h), as Box2D v3 has it: at the
// sub-step rate's fifth the soft step is still far from its stability bound.
constexpr double kJointHertzShare = 0.2;
constexpr double kJointDampingRatio = 2.0;
}  // namespace joint_solver

// The rows of the model's joints, for solveConstraints. Holds no state between
// steps: what a solve leaves (memory, reactions) goes into WorldData by commitJoints.
std::unique_ptr<ExtraRows> makeJointRows(const WorldModel& model);

// After a step whose last solve had `rows` is committed: the rows' impulses into
// data.joints.memory (the next step's warm start), their reactions into the sums, and
// out of `contacts`, the solve's impulses on the bodies (a body's contact loads are
// its contacts' alone; its joints report their own).
void commitJoints(const ExtraRows& rows, WorldData& data, ContactImpulses& contacts);

// The joints' coordinates and speeds of data.Y into data.joints (a revolute angle
// counted on through every turn from the last one's).
void measureJoints(const WorldModel& model, WorldData& data);

// data.joints at the start of a run: no memory, the inputs' start values, the
// coordinates of the start state.
void startJoints(const WorldModel& model, WorldData& data);

}  // namespace rigid
