#include "dynamics.h"

#include "world.h"

#include "module_switches.h"

namespace rigid {

bool forcesHeldOverStep(const WorldModel& model) { return model.media.empty(); }

bool forcesHeldOverStep(const WorldModel& model, const BodyConstants& body) {
  return forcesHeldOverStep(model) && body.loads.empty();
}

void accumulateAppliedForces(const WorldModel& model, const BodyConstants& body, const BodyInput& in,
                             const BodyState& y, BodyAux& aux) {
  aux.F = body.mass * model.gravity + in.force;
  aux.T = in.torque;
  // loads at points: the force (turned into the world frame when given in the body's)
  // and its moment r x F about the centre of mass, r = R p turning with the body
  for (size_t k = 0; k < body.loads.size(); ++k) {
    const PointLoad& load = body.loads[k];
    const Vec3 F = load.bodyFrame ? Vec3(aux.R * in.loads[k]) : in.loads[k];
    aux.F += F;
    aux.T += (aux.R * load.point).cross(F);
  }
  if constexpr (modules::kMedia) {
    for (const Medium& medium : model.media) addMediumForces(medium, body, y, model.gravity, aux);
  } else {
    (void)y;
  }
}

void evaluateBodyDerivative(const WorldModel& model, const BodyConstants& body, const BodyInput& input,
                            const BodyState& y, BodyAux& aux, BodyDerivative& dy) {
  computeVelocities(body, y, aux);
  accumulateAppliedForces(model, body, input, y, aux);
  dy.dX = aux.V;
  dy.dq = orientationRate(aux.omega, y.q);
  dy.dP = aux.F;
  dy.dL = aux.T;
}

void evaluateDerivative(const WorldModel& model, const std::vector<int>& bodies, const std::vector<BodyInput>& input,
                        const std::vector<BodyState>& Y, std::vector<BodyAux>& aux, std::vector<BodyDerivative>& dY) {
  for (int i : bodies) evaluateBodyDerivative(model, model.bodies[i], input[i], Y[i], aux[i], dY[i]);
}

}  // namespace rigid
