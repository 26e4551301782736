#include "dynamics.h"

#include "world.h"

#include "module_switches.h"
#if RIGID_WITH_SURFACES
#include "surface_contact.h"
#endif

namespace rigid {

namespace {

// Force stage: the applied forces, then the surfaces, whose support and friction
// answer the sum of all the others.
void accumulateForces(const WorldModel& model, const BodyConstants& body, const BodyInput& in,
                      const BodyState& y, BodyAux& aux) {
  accumulateAppliedForces(model, body, in, y, aux);
#if RIGID_WITH_SURFACES
  if (surfacesAsForces(model)) addSurfaceForces(model.surfaces, body, y, aux);
#endif
}

}  // namespace

bool forcesHeldOverStep(const WorldModel& model, const BodyConstants& body, const BodyInput& input,
                        const BodyState& y, double h) {
  if (!model.media.empty()) return false;
  if (!surfacesAsForces(model)) return true;
#if RIGID_WITH_SURFACES
  // A stage's position is within h times its velocity of X, and the stages' velocities
  // are within h times the applied acceleration of V.
  const double accel = model.gravity.norm() + input.force.norm() / body.mass;
  const double travel = h * (y.P.norm() / body.mass + h * accel);
  return clearOfSurfaces(model.surfaces, body.shape, y.X, travel);
#else
  (void)body, (void)input, (void)y, (void)h;
  return false;
#endif
}

void accumulateAppliedForces(const WorldModel& model, const BodyConstants& body,
                             const BodyInput& in, const BodyState& y, BodyAux& aux) {
  aux.F = body.mass * model.gravity + in.force;
  aux.T = in.torque;
#if RIGID_WITH_MEDIA
  for (const Medium& medium : model.media) addMediumForces(medium, body, y, model.gravity, aux);
#else
  (void)y;
#endif
}

void evaluateBodyDerivative(const WorldModel& model, const BodyConstants& body,
                            const BodyInput& input, const BodyState& y, BodyAux& aux,
                            BodyDerivative& dy, bool withSurfaces) {
  // Surfaces' support and friction need I(t)^-1 (the contact point's effective mass);
  // the other forces need only the velocities.
  if (withSurfaces && surfacesAsForces(model)) {
    computeAuxiliaries(body, y, aux);
    accumulateForces(model, body, input, y, aux);
  } else {
    computeVelocities(body, y, aux);
    accumulateAppliedForces(model, body, input, y, aux);
  }
  dy.dX = aux.V;
  dy.dq = orientationRate(aux.omega, y.q);
  dy.dP = aux.F;
  dy.dL = aux.T;
}

void evaluateDerivative(const WorldModel& model, const std::vector<BodyInput>& input,
                        const std::vector<BodyState>& Y, std::vector<BodyAux>& aux,
                        std::vector<BodyDerivative>& dY) {
  for (size_t i = 0; i < Y.size(); ++i)
    evaluateBodyDerivative(model, model.bodies[i], input[i], Y[i], aux[i], dY[i]);
}

}  // namespace rigid
