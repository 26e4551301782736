// Driven bodies (BodyConstants::motion): their motion comes from another model through
// the FMU's inputs, the pose at each communication point and the velocities (with
// their rates, the input derivatives) over the step. The world moves them rigidly at
// constant velocities over each internal step; contacts see them as infinitely heavy.
#pragma once

#include <vector>

#include "body.h"

namespace rigid {

struct WorldModel;
struct WorldData;

// What the inputs of a driven body say at a communication point, world frame.
struct DriveInput {
  Vec3 position = Vec3::Zero();         // m, the body's origin (its frame's point)
  Quat orientation = Quat::Identity();  // body -> world; made unit at each step
  Vec3 velocity = Vec3::Zero();         // m/s
  Vec3 angularVelocity = Vec3::Zero();  // rad/s
  // Their rates over the step (the input derivatives of velocity and angularVelocity,
  // m/s^2 and rad/s^2), zero unless a master sets them; spent at each step's end.
  Vec3 acceleration = Vec3::Zero();
  Vec3 angularAcceleration = Vec3::Zero();
};

// The inputs of every body at its start values (used by the driven ones only).
std::vector<DriveInput> startDrive(const WorldModel& model);

// A driven body's path over a communication step of length h that starts where the
// body is (X0, q0) and ends where the inputs put it, position + h velocity + h^2/2
// acceleration: the body never jumps. The difference between where it is and where
// the inputs say it is at the step's start (zero when the master's pose and velocity
// agree) is closed at a constant rate over the step.
struct DrivePath {
  Vec3 closing = Vec3::Zero();      // m/s: (position - X0) / h
  Vec3 closingTurn = Vec3::Zero();  // rad/s: the rotation vector of orientation q0^-1, / h
  double jump = 0.0;                // m: |position - X0|, what the inputs moved the body by
};
DrivePath drivePath(const BodyState& y, const DriveInput& in, double h);

// Sets the driven bodies' velocities for the internal step [from, to] of a
// communication step, its inputs `in` and paths `paths` (per body): the mean of the
// path's velocities over it, so that the step moves each body exactly along its path.
void setDriveVelocities(const WorldModel& model, WorldData& data, const std::vector<DriveInput>& in,
                        const std::vector<DrivePath>& paths, double from, double to);

// Y(t + h) of a driven body moving at its velocities (P and L, BodyConstants::motion):
// X + h V, exp(h omega) q; its velocities unchanged.
BodyState driveStep(const BodyState& y, double h);

}  // namespace rigid
