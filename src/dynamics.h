// The right-hand side dY/dt = f(Y): auxiliaries, then forces, then the derivative.
#pragma once

#include <vector>

#include "body.h"

namespace rigid {

struct WorldModel;

// dq/dt = 1/2 omega q with omega as the pure quaternion (0, omega), in Quat's storage
// order: omega is in the world frame and q maps body to world, so omega multiplies
// from the left.
inline Eigen::Vector4d orientationRate(const Vec3& omega, const Quat& q) {
  const Quat w(0.0, omega.x(), omega.y(), omega.z());
  return 0.5 * (w * q).coeffs();
}

// Whether every force on a body stays constant over a step: gravity and the inputs
// (held over each step) only, with no media (buoyancy and drag follow the state).
// Contacts act in the constraint solver after the integrator (constraint_solver.h), not
// as forces.
bool forcesHeldOverStep(const WorldModel& model);
// The same for one body: also no load at a point, whose moment (and, in the body frame,
// force) turns with the body.
bool forcesHeldOverStep(const WorldModel& model, const BodyConstants& body);

// Every force on one body: gravity, the inputs, the media. Adds to nothing: sets
// aux.F and aux.T. aux's V, R and omega must be those of y.
void accumulateAppliedForces(const WorldModel& model, const BodyConstants& body, const BodyInput& input,
                             const BodyState& y, BodyAux& aux);

// dY/dt of one body (bodies exert no forces on each other outside contacts).
void evaluateBodyDerivative(const WorldModel& model, const BodyConstants& body, const BodyInput& input,
                            const BodyState& y, BodyAux& aux, BodyDerivative& dy);

// For every listed body: auxiliaries of Y, the accumulated force and torque, and
// dY/dt = (V, 1/2 omega q, F, T). aux is filled as a by-product.
void evaluateDerivative(const WorldModel& model, const std::vector<int>& bodies, const std::vector<BodyInput>& input,
                        const std::vector<BodyState>& Y, std::vector<BodyAux>& aux, std::vector<BodyDerivative>& dY);

}  // namespace rigid
