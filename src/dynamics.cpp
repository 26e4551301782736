#include "dynamics.h"

#include "world.h"

namespace rigid {

namespace {

// Force stage: gravity at the centre of mass plus the external load.
void accumulateForces(const WorldModel& model, const BodyConstants& body, const BodyInput& in,
                      BodyAux& aux) {
  aux.F = body.mass * model.gravity + in.force;
  aux.T = in.torque;
}

// 1/2 omega q with omega as the pure quaternion (0, omega); omega is in the world
// frame and q maps body to world, so omega multiplies from the left.
Eigen::Vector4d spin(const Vec3& omega, const Quat& q) {
  const Quat w(0.0, omega.x(), omega.y(), omega.z());
  return 0.5 * (w * q).coeffs();
}

}  // namespace

void evaluateDerivative(const WorldModel& model, const std::vector<BodyInput>& input,
                        const std::vector<BodyState>& Y, std::vector<BodyAux>& aux,
                        std::vector<BodyDerivative>& dY) {
  for (size_t i = 0; i < Y.size(); ++i) {
    const BodyConstants& body = model.bodies[i];
    computeAuxiliaries(body, Y[i], aux[i]);
    accumulateForces(model, body, input[i], aux[i]);
    dY[i].dX = aux[i].V;
    dY[i].dq = spin(aux[i].omega, Y[i].q);
    dY[i].dP = aux[i].F;
    dY[i].dL = aux[i].T;
  }
}

}  // namespace rigid
