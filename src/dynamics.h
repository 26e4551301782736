// The right-hand side dY/dt = f(Y): auxiliaries, then forces, then the derivative.
#pragma once

#include <vector>

#include "body.h"

namespace rigid {

struct WorldModel;

// For every body: auxiliaries of Y, the accumulated force and torque, and
// dY/dt = (V, 1/2 omega q, F, T). aux is filled as a by-product.
void evaluateDerivative(const WorldModel& model, const std::vector<BodyInput>& input,
                        const std::vector<BodyState>& Y, std::vector<BodyAux>& aux,
                        std::vector<BodyDerivative>& dY);

}  // namespace rigid
