// Media of the seed paper: box-shaped volumes of fluid that resist the bodies moving
// through them (drag) and hold them up (Archimedes' buoyancy).
#pragma once

#include <string>

#include "body.h"

namespace rigid {

enum class FluidType { Air, Water, Custom };

struct Medium {
  std::string name;
  FluidType type = FluidType::Water;
  Vec3 min = Vec3::Zero();  // m, axis-aligned box, world frame
  Vec3 max = Vec3::Zero();
  double density = 0.0;    // kg/m^3
  double viscosity = 0.0;  // Pa s
};

// Adds to aux.F and aux.T the buoyancy and drag that the medium exerts on the body.
// aux.V, aux.R and aux.omega must be those of y (computeAuxiliaries).
void addMediumForces(const Medium& medium, const BodyConstants& body, const BodyState& y, const Vec3& gravity,
                     BodyAux& aux);

// Rates (1/s) of the medium's forces on a body that bound an explicit method's step:
// damping, the largest rate of the drag (linear and angular, per unit of velocity);
// oscillation, the angular frequency of the body's heave on buoyancy when it floats.
struct MediumRates {
  double damping = 0.0;
  double oscillation = 0.0;
};
MediumRates mediumRates(const Medium& medium, const BodyConstants& body, const BodyState& y, const BodyAux& aux,
                        const Vec3& gravity);

}  // namespace rigid
