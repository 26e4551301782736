// Joints: two bodies, or a body and the world, held together at anchor points. Each
// type removes some of the relative motion and leaves the rest free:
//   revolute   (hinge)  the anchors meet, the axes stay aligned: turns about the axis
//   prismatic  (slider) the axes stay aligned and the orientations fixed: slides along the axis
//   spherical  (ball)   the anchors meet: turns freely
//   fixed      (weld)   the anchors meet and the orientations stay fixed: no motion
//   distance   (rod, rope, spring) the anchors stay `length` apart (a rope only pulls)
// The free coordinate of a revolute (angle, rad), prismatic (offset, m) or distance
// (length, m) joint can have limits, a speed motor and a spring toward a target. The
// constraint solver answers joints as rows beside the contacts (joint_rows.h).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "math_types.h"

namespace rigid {

enum class JointType { Revolute, Prismatic, Spherical, Fixed, Distance };

// Whether the type has a free coordinate (angle or offset or length).
inline bool hasCoordinate(JointType t) {
  return t == JointType::Revolute || t == JointType::Prismatic || t == JointType::Distance;
}

// Constants of one joint (tunable ones change between communication steps).
struct JointConstants {
  std::string name;
  JointType type = JointType::Spherical;
  int a = -1, b = -1;            // bodies; a = -1: the world (its frame is the world frame)
  Vec3 anchorA = Vec3::Zero();   // m, in body a's frame from its centre of mass
  Vec3 anchorB = Vec3::Zero();   // m, in body b's frame from its centre of mass
  Vec3 axisA = Vec3::UnitZ();    // unit, body a's frame (revolute, prismatic)
  Vec3 axisB = Vec3::UnitZ();    // unit, body b's frame
  Quat rest = Quat::Identity();  // qA^-1 qB at the start: the angle's zero, a weld's hold
  double length = 0.0;           // m, a distance joint's length (a spring's rest length)
  bool rope = false;             // a distance joint that only pulls (with a spring: an elastic one)
  // Limits of the coordinate (rad or m), and the restitution of a stop at them (or at
  // a rope's full length): the share of the approach speed the stop gives back.
  bool limited = false;
  double lower = 0.0, upper = 0.0;
  double restitution = 0.0;
  // A speed motor: the coordinate's speed driven toward the input motorSpeed with at
  // most maxMotorForce (N, or N m for a revolute joint).
  bool motor = false;
  double maxMotorForce = 0.0;
  // A spring on the coordinate toward the input targetPosition (a distance joint's:
  // toward `length`): stiffness N/m or N m/rad, damping N s/m or N m s/rad. Without
  // one, a distance joint is rigid.
  bool spring = false;
  double stiffness = 0.0, damping = 0.0;
  bool collide = false;  // the two bodies' contacts are detected too
  // Start values of the inputs.
  double motorSpeed = 0.0;      // rad/s or m/s
  double targetPosition = 0.0;  // rad or m
};

// Whether the coordinate has stops to strike: limits, or a rigid rope's full length.
inline bool hasStops(const JointConstants& j) { return j.limited || (j.rope && !j.spring); }

// The rows of a joint, each with its slot in JointMemory: the anchors meeting (3, or
// the 2 across a slider's axis), the orientations (3, or the 2 that keep a hinge's
// axes aligned), the coordinate held (a rigid distance), its spring, its lower and
// upper limits, its motor.
enum JointRow { kPoint0, kPoint1, kPoint2, kTurn0, kTurn1, kTurn2, kHold, kSpring, kLower, kUpper, kMotor };
constexpr int kJointRows = 11;

// What a run keeps of its joints (WorldData::joints), per joint.
struct JointData {
  // Part of the FMU state: each row's impulse in the last sub-step (N s or N m s), the
  // next step's warm start; a revolute joint's angle counted through every turn (rad, at
  // the end of the last step); the inputs; the reactions summed since the contact loads
  // were last cleared (the force on b and its moment about b's anchor, N s and N m s,
  // world frame; WorldData::contactLoads.duration is their time).
  std::vector<std::array<double, kJointRows>> memory;
  std::vector<double> angle;
  std::vector<double> motorSpeed, targetPosition;
  // The inputs' derivatives for the next communication step (1/s times their units),
  // spent by it, as the bodies' input rates.
  std::vector<double> motorSpeedRate, targetPositionRate;
  std::vector<Vec3> impulse, angularImpulse;
  // Derived from the state after each step: the coordinate and its rate.
  std::vector<double> position, speed;
};

}  // namespace rigid
