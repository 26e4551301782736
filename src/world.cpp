#include "world.h"

#include <utility>

#include "dynamics.h"
#include "surface_contact.h"

namespace rigid {

WorldData initialData(const WorldModel& model) {
  const size_t n = model.bodies.size();
  WorldData d;
  d.Y.reserve(n);
  for (const BodyConstants& body : model.bodies) d.Y.push_back(initialState(body));
  d.input.assign(n, BodyInput{});
  d.aux.resize(n);
  d.scratch.stage.resize(n);
  d.scratch.next.resize(n);
  for (auto& k : d.scratch.k) k.resize(n);
  refreshAuxiliaries(model, d);
  return d;
}

void refreshAuxiliaries(const WorldModel& model, WorldData& data) {
  for (size_t i = 0; i < data.Y.size(); ++i)
    computeAuxiliaries(model.bodies[i], data.Y[i], data.aux[i]);
}

namespace {

void normaliseOrientations(std::vector<BodyState>& Y) {
  for (BodyState& y : Y) y.q.normalize();
}

// Contact response: what happens at an instant rather than over the step. The
// surfaces need the applied force at the new state to tell whether static friction
// holds a body that has come to rest.
void respondToContacts(const WorldModel& model, WorldData& data, double h,
                       std::vector<BodyState>& after) {
  if (model.surfaces.empty()) return;
  for (size_t i = 0; i < after.size(); ++i) {
    BodyAux& aux = data.aux[i];
    computeAuxiliaries(model.bodies[i], after[i], aux);
    accumulateAppliedForces(model, model.bodies[i], data.input[i], after[i], aux);
    respondToSurfaces(model.surfaces, model.bodies[i], model.gravity, aux.F, h, data.Y[i], after[i]);
  }
}

int firstNonFinite(const std::vector<BodyState>& Y) {
  for (size_t i = 0; i < Y.size(); ++i)
    if (!isFinite(Y[i])) return static_cast<int>(i);
  return -1;
}

}  // namespace

StepResult step(const WorldModel& model, WorldData& data, double h) {
  std::vector<BodyState>& next = data.scratch.next;
  integrate(model, data, h, next);  // auxiliaries -> forces -> derivative, per stage
  normaliseOrientations(next);
  respondToContacts(model, data, h, next);
  if (const int bad = firstNonFinite(next); bad >= 0) return {false, bad};
  std::swap(data.Y, next);
  refreshAuxiliaries(model, data);
  return {};
}

double totalEnergy(const WorldModel& model, const WorldData& data) {
  double e = 0.0;
  for (size_t i = 0; i < data.Y.size(); ++i)
    e += kineticEnergy(data.Y[i], data.aux[i]) -
         model.bodies[i].mass * model.gravity.dot(data.Y[i].X);
  return e;
}

}  // namespace rigid
