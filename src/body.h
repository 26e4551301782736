// One rigid body, split as the seed paper splits it: constants, the state vector
// Y = (X, q, P, L), and auxiliary quantities derived from Y.
#pragma once

#include <string>
#include <vector>

#include "math_types.h"
#include "shape.h"

namespace rigid {

// Where a body starts: the scene's initial conditions (FMI start values).
struct BodyStart {
  Vec3 position = Vec3::Zero();         // m, centre of mass, world frame
  Quat orientation = Quat::Identity();  // body -> world; need not be unit until the run starts
  Vec3 velocity = Vec3::Zero();         // m/s, world frame
  Vec3 angularVelocity = Vec3::Zero();  // rad/s, world frame
};

// A named point of a body where an input force acts (the scene's "loads"): a thruster,
// a cable, a wheel load. The force and its moment r x F act in every force stage, r
// turning with the body.
struct PointLoad {
  std::string name;
  Vec3 point = Vec3::Zero();  // m, body frame, from the centre of mass
  bool bodyFrame = false;     // the force input is given in the body frame (else the world's)
};

// How a body moves: free, under the forces and contacts of the seed's dynamics, or
// driven, its motion given by another model (the FMU's inputs, drive.h): infinite mass
// to the contacts, which it pushes, carries and lifts free bodies with.
enum class Motion { Free, Driven };

// Body constants: fixed once a run starts.
struct BodyConstants {
  std::string name;
  Shape shape;
  // A driven body has mass 1 and Ibody = 1, so that its Y holds its velocities as P
  // and L (V = P, omega = L) and every reader of velocities needs no case for it; no
  // force acts on it and no contact moves it.
  Motion motion = Motion::Free;
  double mass = 1.0;                       // M, kg
  Mat3 Ibody = Mat3::Identity();           // kg m^2, about the centre of mass, body frame
  Mat3 IbodyInv = Mat3::Identity();        // 1/(kg m^2); inverted once here, never per step
  Vec3 principalMoments = Vec3::Ones();    // kg m^2, eigenvalues of Ibody
  Quat principalFrame = Quat::Identity();  // principal axes -> body frame
  bool inertiaFromShape = true;            // Ibody is the solid shape's and follows mass
  double restitution = 0.5;                // xi, 1
  double staticFriction = 0.6;             // mu_s, 1
  double kineticFriction = 0.4;            // mu_k, 1
  double rollingResistance = 0.0;          // m, the lever of the moment that resists rolling
  bool collides = true;                    // takes part in body-body collision detection
  std::vector<PointLoad> loads;            // points where input forces act
  BodyStart start;
};

inline bool driven(const BodyConstants& body) { return body.motion == Motion::Driven; }

// Makes a body driven: mass 1, Ibody = 1 (see BodyConstants::motion).
void makeDriven(BodyConstants& body);

// Sets M; when the inertia comes from the shape, Ibody scales with it.
void setMass(BodyConstants& body, double mass);

// Sets a given inertia tensor (already checked symmetric positive definite).
void setInertia(BodyConstants& body, const Mat3& Ibody);

// The state vector Y of one body.
struct BodyState {
  Vec3 X = Vec3::Zero();      // m, centre of mass, world frame
  Quat q = Quat::Identity();  // orientation, body -> world, unit after every step
  Vec3 P = Vec3::Zero();      // kg m/s, linear momentum
  Vec3 L = Vec3::Zero();      // kg m^2/s, angular momentum about the centre of mass
};

// dY/dt = (V, 1/2 omega q, F, T).
struct BodyDerivative {
  Vec3 dX;
  Eigen::Vector4d dq;  // in Quat's storage order (x, y, z, w)
  Vec3 dP;
  Vec3 dL;
};

// Auxiliary quantities of one body, derived from Y.
struct BodyAux {
  Vec3 V;      // m/s, P / M                      (computeAuxiliaries)
  Mat3 R;      // rotation of q, body -> world    (computeAuxiliaries)
  Mat3 Iinv;   // 1/(kg m^2), R Ibody^-1 R^T       (computeAuxiliaries only: the
               // surfaces' force stages and responses; refreshAuxiliaries leaves it)
  Vec3 omega;  // rad/s, I(t)^-1 L, world frame   (computeAuxiliaries)
  Vec3 F;      // N, total force at the centre of mass   (force stage)
  Vec3 T;      // N m, total torque about the centre of mass (force stage)
};

// External load applied by the FMU's inputs; held over a communication step.
struct BodyInput {
  Vec3 force = Vec3::Zero();   // N, at the centre of mass, world frame
  Vec3 torque = Vec3::Zero();  // N m, world frame
  std::vector<Vec3> loads;     // N, one per PointLoad of the body, in its frame
};

// The input of a body with `loads` load points, all zero.
inline BodyInput zeroInput(size_t loads) {
  BodyInput in;
  in.loads.assign(loads, Vec3::Zero());
  return in;
}

// Whether an input drives its body: some force, torque or load not zero.
inline bool drives(const BodyInput& in) {
  if (!in.force.isZero(0.0) || !in.torque.isZero(0.0)) return true;
  for (const Vec3& f : in.loads)
    if (!f.isZero(0.0)) return true;
  return false;
}

// R of the unit quaternion q / |q| for any q != 0 (Runge-Kutta stages are not unit):
// each product of two components is scaled by 2 / |q|^2, which costs a division
// instead of normalising q (a square root and four divisions).
inline Mat3 rotationOf(const Quat& q) {
  const double s = 2.0 / q.squaredNorm();
  const double xs = q.x() * s, ys = q.y() * s, zs = q.z() * s;
  const double wx = q.w() * xs, wy = q.w() * ys, wz = q.w() * zs;
  const double xx = q.x() * xs, xy = q.x() * ys, xz = q.x() * zs;
  const double yy = q.y() * ys, yz = q.y() * zs, zz = q.z() * zs;
  Mat3 R;
  // the matrix row by row
  // clang-format off
  R << 1.0 - (yy + zz), xy - wz, xz + wy,
       xy + wz, 1.0 - (xx + zz), yz - wx,
       xz - wy, yz + wx, 1.0 - (xx + yy);
  // clang-format on
  return R;
}

// omega = I(t)^-1 L = R (Ibody^-1 (R^T L)): three matrix-vector products instead of
// forming I(t)^-1, which only contacts use.
inline Vec3 angularVelocity(const BodyConstants& body, const Mat3& R, const Vec3& L) {
  return R * (body.IbodyInv * (R.transpose() * L));
}

// V, R, I(t)^-1 and omega from Y. q need not be unit (Runge-Kutta stages are not):
// R is taken from the normalised q.
void computeAuxiliaries(const BodyConstants& body, const BodyState& y, BodyAux& aux);

// V, R and omega only (aux.Iinv is left as it was): what a free body's derivative needs.
void computeVelocities(const BodyConstants& body, const BodyState& y, BodyAux& aux);

// Y of a body at rest in its start pose, with P = M V0 and L = I(0) omega0.
BodyState initialState(const BodyConstants& body);

bool isFinite(const BodyState& y);

}  // namespace rigid
