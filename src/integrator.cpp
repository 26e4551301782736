#include "integrator.h"

#include "dynamics.h"
#include "world.h"

namespace rigid {

namespace {

// out = y + h * k, body by body.
void addScaled(const std::vector<BodyState>& y, double h, const std::vector<BodyDerivative>& k,
               std::vector<BodyState>& out) {
  for (size_t i = 0; i < y.size(); ++i) {
    out[i].X = y[i].X + h * k[i].dX;
    out[i].q.coeffs() = y[i].q.coeffs() + h * k[i].dq;
    out[i].P = y[i].P + h * k[i].dP;
    out[i].L = y[i].L + h * k[i].dL;
  }
}

void eulerStep(const WorldModel& m, WorldData& d, double h, std::vector<BodyState>& next) {
  std::vector<BodyDerivative>& k1 = d.scratch.k[0];
  evaluateDerivative(m, d.input, d.Y, d.aux, k1);
  addScaled(d.Y, h, k1, next);
}

void rk4Step(const WorldModel& m, WorldData& d, double h, std::vector<BodyState>& next) {
  auto& [k1, k2, k3, k4] = d.scratch.k;
  std::vector<BodyState>& stage = d.scratch.stage;
  evaluateDerivative(m, d.input, d.Y, d.aux, k1);
  addScaled(d.Y, 0.5 * h, k1, stage);
  evaluateDerivative(m, d.input, stage, d.aux, k2);
  addScaled(d.Y, 0.5 * h, k2, stage);
  evaluateDerivative(m, d.input, stage, d.aux, k3);
  addScaled(d.Y, h, k3, stage);
  evaluateDerivative(m, d.input, stage, d.aux, k4);
  // Each k is scaled before the sum, so that derivatives near the largest double do
  // not overflow in k1 + 2 k2 + 2 k3 + k4 when the step itself is finite.
  const double w1 = h / 6.0, w2 = h / 3.0;
  for (size_t i = 0; i < d.Y.size(); ++i) {
    const BodyState& y = d.Y[i];
    BodyState& out = next[i];
    out.X = y.X + (w1 * k1[i].dX + w2 * k2[i].dX + w2 * k3[i].dX + w1 * k4[i].dX);
    out.q.coeffs() = y.q.coeffs() + (w1 * k1[i].dq + w2 * k2[i].dq + w2 * k3[i].dq + w1 * k4[i].dq);
    out.P = y.P + (w1 * k1[i].dP + w2 * k2[i].dP + w2 * k3[i].dP + w1 * k4[i].dP);
    out.L = y.L + (w1 * k1[i].dL + w2 * k2[i].dL + w2 * k3[i].dL + w1 * k4[i].dL);
  }
}

}  // namespace

void integrate(const WorldModel& model, WorldData& data, double h, std::vector<BodyState>& next) {
  switch (model.method) {
    case Method::Euler: eulerStep(model, data, h, next); return;
    case Method::RK4: rk4Step(model, data, h, next); return;
  }
}

}  // namespace rigid
