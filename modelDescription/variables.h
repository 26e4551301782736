// The FMU's variables of one scene: the table that modelDescription.xml is written
// from and that the FMU maps value references with (one source of truth), and the
// single place where a variable's value is read from or written to the world.
#pragma once

#include <string>
#include <vector>

#include "scene.h"

namespace rigidfmu {

enum class Causality { Parameter, Input, Output, Independent };
enum class Variability { Fixed, Tunable, Discrete, Continuous };
enum class Initial { None, Exact, Calculated };
// FMI base type. Integer and Enumeration values travel through fmi2Get/SetInteger.
enum class BaseType { Real, Integer, Enumeration };

// A line per kind: world and solver; body, surface and medium parameters; body state;
// inputs; contact outputs; surface inputs; joints' outputs, inputs and parameters.
// clang-format off
enum class Quantity {
  Time, Gravity, SolverMethod, SolverStep, SolverTolerance, SolverEnergyGainLimit, SolverSteps, SolverErrorEstimate,
  Mass, Restitution, StaticFriction, KineticFriction,
  SurfaceStaticFriction, SurfaceKineticFriction, SurfaceRestitution, MediumDensity, MediumViscosity,
  Position, Orientation, Velocity, AngularVelocity, LinearMomentum, AngularMomentum,
  Force, Torque, LoadForce,
  Contacts, ContactForce, ContactTorque, SurfaceForce,
  BeltVelocity,
  JointPosition, JointSpeed, JointReactionForce, JointReactionTorque, JointMotorSpeed, JointTargetPosition,
  JointMaxMotorForce, JointStiffness, JointDamping, JointRestitution, JointLower, JointUpper,
};
// clang-format on

struct Variable {
  unsigned vr = 0;   // value reference = index in the table
  std::string name;  // structured name, e.g. ball.position[1]
  Quantity quantity = Quantity::Time;
  int body = -1;      // index of the body (of the surface, medium or joint for theirs), -1 for world variables
  int component = 0;  // 0-based: x, y, z; quaternions w, x, y, z
  Causality causality = Causality::Output;
  Variability variability = Variability::Continuous;
  Initial initial = Initial::None;
  BaseType type = BaseType::Real;
  std::string unit;  // Real only
  std::string description;
  int load = -1;  // LoadForce: which of the body's load points
};

// Every variable of the scene's FMU, in value-reference order.
std::vector<Variable> modelVariables(const rigid::Scene& scene);

// Indices (1-based, as in ModelStructure) of the variables an initial unknown depends on.
std::vector<unsigned> initialDependencies(const std::vector<Variable>& vars, const Variable& v,
                                          const rigid::WorldModel& model);

// Phase of a run: before the run starts, exact start values are read from and written
// to the bodies' start values; afterwards outputs come from the state.
enum class Phase { Setup, Running };

// The value of a Real or Enumeration variable (time is kept by the FMU, not here).
double readValue(const Variable& v, const rigid::WorldModel& model, const rigid::WorldData& data, Phase phase);

// Writes a value; returns "" on success or the reason it is refused, naming the
// variable and the limit. Writes only what the variable owns; the caller decides when
// a variable may be written at all. A friction coefficient is checked alone here
// (finite, >= 0); that mu_k <= mu_s is checked when the pair takes effect
// (parameterConflict), so that the two can be set in either order; so are a joint's
// limits.
std::string writeValue(const Variable& v, double value, rigid::WorldModel& model, rigid::WorldData& data, Phase phase);

// "" when every body's and surface's kinetic friction is at most its static friction
// and every joint's lower limit at most its upper, else the first that is not, naming
// both variables and their values.
std::string parameterConflict(const rigid::WorldModel& model);

}  // namespace rigidfmu
