// What a row of the constraint solver is made of, shared by the contacts' rows
// (constraint_solver.cpp) and the joints' (joint_rows.cpp): the bodies as the solver
// sees them, a row's direction (Jacobian), the soft step, and the impulse that moves
// both bodies. Also the door through which rows other than the contacts' join a solve
// (ExtraRows), so that the solver itself carries no joint code.
#pragma once

#include <vector>

#include "math_types.h"

namespace rigid {

struct WorldModel;
struct WorldData;

namespace solver {

// Box2D's b2MakeSoft: a spring of natural frequency `hertz` and damping ratio zeta
// over a step h, as the bias rate of the position error and the shares of the
// effective mass and of the accumulated impulse in each impulse (massScale +
// impulseScale = 1). Rigid: no bias, the whole mass.
struct Softness {
  double biasRate = 0.0, massScale = 1.0, impulseScale = 0.0;
};

inline Softness makeSoft(double hertz, double zeta, double h) {
  constexpr double kPi = 3.14159265358979323846;
  const double omega = 2.0 * kPi * hertz;
  const double a1 = 2.0 * zeta + h * omega, a2 = h * omega * a1, a3 = 1.0 / (1.0 + a2);
  return {omega / a1, a2 * a3, a3};
}

// The same soft step for a physical spring of stiffness k and damping c acting on a
// row of effective mass m (k = m omega^2, c = 2 zeta m omega): an implicit spring over h.
inline Softness makeSpring(double k, double c, double m, double h) {
  const double a2 = h * (c + h * k) / m, a3 = 1.0 / (1.0 + a2);
  return {c + h * k > 0.0 ? k / (c + h * k) : 0.0, a2 * a3, a3};
}

// A body as the solver sees it; the last slot stands for every surface and the world
// (no inverse mass or inertia, never moves, at the origin). A driven body has none
// either, and moves at its velocities whatever the rows do.
struct Body {
  double invMass = 0.0;
  Mat3 invInertia = Mat3::Zero();             // 1/(kg m^2), world frame, at the step's start
  Vec3 v = Vec3::Zero(), w = Vec3::Zero();    // velocities now
  Vec3 v0 = Vec3::Zero(), w0 = Vec3::Zero();  // at the step's start
  Vec3 dv = Vec3::Zero(), dw = Vec3::Zero();  // the applied forces' velocity change in a sub-step
  Vec3 x0 = Vec3::Zero();                     // m, centre of mass at the step's start
  Vec3 moved = Vec3::Zero();                  // m, since the step's start
  Vec3 turned = Vec3::Zero();                 // rad, the sub-steps' rotations h omega, summed
  Quat q0 = Quat::Identity(), q = Quat::Identity();
  // some row gave it an impulse, or a joint holds it: else the integrator's free motion
  // stands (its order, not the sub-steps' first order, for a body that only comes
  // within the margin)
  bool pushed = false;
  // A driven body: the impulse the rows gave it and its moment about its centre (N s,
  // N m s), which nothing else records (its velocities do not change).
  bool driven = false;
  Vec3 felt = Vec3::Zero(), feltMoment = Vec3::Zero();
};

// One direction of a row: an impulse lambda acts +lambda along it on b, -lambda on a.
struct Jacobian {
  Vec3 linear = Vec3::Zero();
  Vec3 angularA = Vec3::Zero(), angularB = Vec3::Zero();
  Vec3 spinA = Vec3::Zero(), spinB = Vec3::Zero();  // I^-1 angular: the spin per unit impulse
  // m/s, the velocity along it of B's material beyond B's own motion: a belt's, on a
  // friction tangent; zero on every other row
  double drift = 0.0;
};

inline Jacobian jacobian(const Body& A, const Body& B, const Vec3& linear, const Vec3& angularA, const Vec3& angularB) {
  return {linear, angularA, angularB, A.invInertia * angularA, B.invInertia * angularB, 0.0};
}

// The coupling of two directions through the bodies' masses: J_x M^-1 J_y^T.
inline double coupling(const Body& A, const Body& B, const Jacobian& x, const Jacobian& y) {
  return (A.invMass + B.invMass) * x.linear.dot(y.linear) + x.angularA.dot(y.spinA) + x.angularB.dot(y.spinB);
}

// The relative velocity of a row's two sides along it: B's material moves at B's motion
// plus the row's drift.
inline double velocityAlong(const Body& A, const Body& B, const Jacobian& j) {
  return j.linear.dot(B.v - A.v) + j.angularB.dot(B.w) - j.angularA.dot(A.w) + j.drift;
}

inline void applyImpulse(Body& A, Body& B, const Jacobian& j, double lambda) {
  if (lambda == 0.0) return;
  A.pushed = B.pushed = true;
  A.v -= lambda * A.invMass * j.linear;
  A.w -= lambda * j.spinA;
  B.v += lambda * B.invMass * j.linear;
  B.w += lambda * j.spinB;
  if (A.driven) A.felt -= lambda * j.linear, A.feltMoment -= lambda * j.angularA;
  if (B.driven) B.felt += lambda * j.linear, B.feltMoment += lambda * j.angularB;
}

}  // namespace solver

// Rows that join a solve beside the contacts' (the joints', joint_rows.h), called at
// the same places as the contacts' rows: the solver prepares the bodies they name,
// answers their impacts with the contacts', then in each sub-step warm-starts them and
// solves them (with and without the bias). They sum what they apply themselves.
class ExtraRows {
 public:
  virtual ~ExtraRows() = default;
  // The step's rows, from the state and memory of data; appends the bodies they hold.
  virtual void prepare(const WorldModel& model, const WorldData& data, double h, std::vector<int>& bodies) = 0;
  // Whether a solve has rows: a step with neither these nor contacts solves nothing.
  virtual bool any() const = 0;
  // Impacts at the step's start, with the bodies' velocities then (the seed's impulse,
  // as the contacts'): whether a row struck.
  virtual bool impact(std::vector<solver::Body>& bodies, double restingSpeed, double h) = 0;
  virtual void warmStart(std::vector<solver::Body>& bodies) = 0;
  virtual void solve(std::vector<solver::Body>& bodies, double hSub, bool useBias) = 0;
};

}  // namespace rigid
