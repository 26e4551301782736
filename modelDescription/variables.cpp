#include "variables.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rigidfmu {

using rigid::BodyConstants;
using rigid::Scene;
using rigid::WorldData;
using rigid::WorldModel;

namespace {

const char* const kAxis[3] = {"x", "y", "z"};
const char* const kQuatPart[4] = {"w", "x", "y", "z"};

struct VectorQuantity {
  Quantity quantity;
  const char* field;  // name after "<body>."
  int size;
  Causality causality;
  Initial initial;
  const char* unit;
  const char* meaning;
};

// Per-body vectors, in the order they appear in the table.
const VectorQuantity kBodyVectors[] = {
    {Quantity::Position, "position", 3, Causality::Output, Initial::Exact, "m", "centre of mass X, world frame"},
    {Quantity::Orientation, "orientation", 4, Causality::Output, Initial::Exact, "1",
     "orientation q, unit quaternion body to world"},
    {Quantity::Velocity, "velocity", 3, Causality::Output, Initial::Exact, "m/s", "velocity V = P/M, world frame"},
    {Quantity::AngularVelocity, "angularVelocity", 3, Causality::Output, Initial::Exact, "rad/s",
     "angular velocity omega = I(t)^-1 L, world frame"},
    {Quantity::LinearMomentum, "linearMomentum", 3, Causality::Output, Initial::Calculated, "kg.m/s",
     "linear momentum P, world frame"},
    {Quantity::AngularMomentum, "angularMomentum", 3, Causality::Output, Initial::Calculated, "kg.m2/s",
     "angular momentum L about the centre of mass, world frame"},
    {Quantity::Force, "force", 3, Causality::Input, Initial::None, "N",
     "external force at the centre of mass, world frame"},
    {Quantity::Torque, "torque", 3, Causality::Input, Initial::None, "N.m", "external torque, world frame"},
};

// A driven body's pose and velocities: inputs (drive.h), with the scene's as start.
const VectorQuantity kDrivenVectors[] = {
    {Quantity::Position, "position", 3, Causality::Input, Initial::None, "m",
     "driven: position of its origin at the communication point, world frame"},
    {Quantity::Orientation, "orientation", 4, Causality::Input, Initial::None, "1",
     "driven: orientation at the communication point, quaternion body to world (made unit)"},
    {Quantity::Velocity, "velocity", 3, Causality::Input, Initial::None, "m/s",
     "driven: velocity over the communication step (its input derivative: the acceleration), world frame"},
    {Quantity::AngularVelocity, "angularVelocity", 3, Causality::Input, Initial::None, "rad/s",
     "driven: angular velocity over the communication step (its input derivative: the angular acceleration), "
     "world frame"},
};

// The per-body vectors of a free or a driven body.
std::vector<VectorQuantity> vectorsOf(const BodyConstants& body) {
  if (rigid::driven(body)) return {std::begin(kDrivenVectors), std::end(kDrivenVectors)};
  return {std::begin(kBodyVectors), std::end(kBodyVectors)};
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

double vectorPart(const rigid::Vec3& v, int c) { return v[c]; }

double quatPart(const rigid::Quat& q, int c) {
  switch (c) {
    case 0: return q.w();
    case 1: return q.x();
    case 2: return q.y();
    default: return q.z();
  }
}

void setQuatPart(rigid::Quat& q, int c, double value) {
  switch (c) {
    case 0: q.w() = value; break;
    case 1: q.x() = value; break;
    case 2: q.y() = value; break;
    default: q.z() = value; break;
  }
}

// The component of a pose or velocity variable in a start value.
double startValue(const Variable& v, const rigid::BodyStart& start) {
  switch (v.quantity) {
    case Quantity::Position: return start.position[v.component];
    case Quantity::Orientation: return quatPart(start.orientation, v.component);
    case Quantity::Velocity: return start.velocity[v.component];
    default: return start.angularVelocity[v.component];
  }
}

// The same in a run: a free body's from its state, a driven body's its inputs' values.
double poseValue(const Variable& v, const WorldModel& model, const WorldData& data) {
  const int b = v.body, c = v.component;
  if (rigid::driven(model.bodies[b])) {
    const rigid::DriveInput& in = data.drive[b];
    return startValue(v, {in.position, in.orientation, in.velocity, in.angularVelocity});
  }
  switch (v.quantity) {
    case Quantity::Position: return data.Y[b].X[c];
    case Quantity::Orientation: return quatPart(data.Y[b].q, c);
    case Quantity::Velocity: return data.aux[b].V[c];
    default: return data.aux[b].omega[c];
  }
}

// Sets the component of a pose or velocity variable among these.
void setMotionPart(const Variable& v, rigid::Vec3& position, rigid::Quat& orientation, rigid::Vec3& velocity,
                   rigid::Vec3& angularVelocity, double value) {
  switch (v.quantity) {
    case Quantity::Position: position[v.component] = value; break;
    case Quantity::Orientation: setQuatPart(orientation, v.component, value); break;
    case Quantity::Velocity: velocity[v.component] = value; break;
    default: angularVelocity[v.component] = value; break;
  }
}

// The friction coefficient a friction variable names.
double& frictionOf(const Variable& v, WorldModel& model) {
  switch (v.quantity) {
    case Quantity::StaticFriction: return model.bodies[v.body].staticFriction;
    case Quantity::KineticFriction: return model.bodies[v.body].kineticFriction;
    case Quantity::SurfaceStaticFriction: return model.surfaces[v.body].staticFriction;
    default: return model.surfaces[v.body].kineticFriction;
  }
}

// The unit of a joint's coordinate, its rate and the force along it.
struct JointUnits {
  const char* position;
  const char* speed;
  const char* force;
  const char* stiffness;
  const char* damping;
};
JointUnits unitsOf(const rigid::JointConstants& j) {
  if (j.type == rigid::JointType::Revolute) return {"rad", "rad/s", "N.m", "N.m/rad", "N.m.s/rad"};
  return {"m", "m/s", "N", "N/m", "N.s/m"};
}

// The joints' variables, after every other (their value references come last): the
// coordinate and its speed, the reaction, and what the scene gave the joint (motor,
// spring, limits) as inputs and tunable parameters.
template <class Add>
void addJointVariables(const WorldModel& model, Add add) {
  const char* mean = "mean over the last communication step (0 before the first)";
  for (size_t k = 0; k < model.joints.size(); ++k) {
    const rigid::JointConstants& j = model.joints[k];
    const int ji = static_cast<int>(k);
    const JointUnits u = unitsOf(j);
    const std::string what = j.type == rigid::JointType::Revolute    ? "angle of b about the axis from its start"
                             : j.type == rigid::JointType::Prismatic ? "offset of b's anchor from a's along the axis"
                                                                     : "distance between the anchors";
    auto scalar = [&](const char* field, Quantity q, Causality causality, Variability variability, const char* unit,
                      const std::string& meaning) {
      const Initial initial = causality == Causality::Output  ? Initial::Calculated
                              : causality == Causality::Input ? Initial::None
                                                              : Initial::Exact;
      add({0, j.name + "." + field, q, ji, 0, causality, variability, initial, BaseType::Real, unit,
           j.name + ": " + meaning});
    };
    if (rigid::hasCoordinate(j.type)) {
      scalar("position", Quantity::JointPosition, Causality::Output, Variability::Continuous, u.position,
             what + (j.type == rigid::JointType::Revolute ? " (counted through every turn)" : ""));
      scalar("speed", Quantity::JointSpeed, Causality::Output, Variability::Continuous, u.speed,
             "rate of change of its position");
    }
    for (int c = 0; c < 3; ++c) {
      add({0, j.name + ".reactionForce[" + std::to_string(c + 1) + "]", Quantity::JointReactionForce, ji, c,
           Causality::Output, Variability::Continuous, Initial::Calculated, BaseType::Real, "N",
           j.name + ": force the joint exerts on its second body, world frame, " + mean + ", " + kAxis[c]});
    }
    for (int c = 0; c < 3; ++c) {
      add({0, j.name + ".reactionTorque[" + std::to_string(c + 1) + "]", Quantity::JointReactionTorque, ji, c,
           Causality::Output, Variability::Continuous, Initial::Calculated, BaseType::Real, "N.m",
           j.name + ": torque the joint exerts on its second body about its anchor there, world frame, " + mean + ", " +
               kAxis[c]});
    }
    if (j.motor) {
      scalar("motorSpeed", Quantity::JointMotorSpeed, Causality::Input, Variability::Continuous, u.speed,
             "the motor's target speed");
      scalar(j.type == rigid::JointType::Revolute ? "maxMotorTorque" : "maxMotorForce", Quantity::JointMaxMotorForce,
             Causality::Parameter, Variability::Tunable, u.force, "the most the motor exerts, > 0");
    }
    if (j.spring) {
      if (j.type != rigid::JointType::Distance)
        scalar("targetPosition", Quantity::JointTargetPosition, Causality::Input, Variability::Continuous, u.position,
               "the position the spring pulls toward");
      scalar("stiffness", Quantity::JointStiffness, Causality::Parameter, Variability::Tunable, u.stiffness,
             "the spring's stiffness, >= 0");
      scalar("damping", Quantity::JointDamping, Causality::Parameter, Variability::Tunable, u.damping,
             "the spring's damping, >= 0");
    }
    if (rigid::hasStops(j))
      scalar("restitution", Quantity::JointRestitution, Causality::Parameter, Variability::Tunable, "1",
             "coefficient of restitution of its stops (limits, a rope's length), in [0, 1]");
    if (j.limited) {
      scalar("lower", Quantity::JointLower, Causality::Parameter, Variability::Tunable, u.position,
             "lower limit of its position, <= upper");
      scalar("upper", Quantity::JointUpper, Causality::Parameter, Variability::Tunable, u.position,
             "upper limit of its position, >= lower");
    }
  }
}

// A joint's value (Setup: the start values; Running: the run's).
double jointValue(const Variable& v, const WorldModel& model, const WorldData& data, Phase phase) {
  const rigid::JointConstants& j = model.joints[static_cast<size_t>(v.body)];
  const size_t k = static_cast<size_t>(v.body);
  const bool setup = phase == Phase::Setup;
  const double duration = data.contactLoads.duration;
  switch (v.quantity) {
    case Quantity::JointPosition: return data.joints.position[k];
    case Quantity::JointSpeed: return data.joints.speed[k];
    case Quantity::JointReactionForce:
      return setup || !(duration > 0.0) ? 0.0 : data.joints.impulse[k][v.component] / duration;
    case Quantity::JointReactionTorque:
      return setup || !(duration > 0.0) ? 0.0 : data.joints.angularImpulse[k][v.component] / duration;
    case Quantity::JointMotorSpeed: return setup ? j.motorSpeed : data.joints.motorSpeed[k];
    case Quantity::JointTargetPosition: return setup ? j.targetPosition : data.joints.targetPosition[k];
    case Quantity::JointMaxMotorForce: return j.maxMotorForce;
    case Quantity::JointStiffness: return j.stiffness;
    case Quantity::JointDamping: return j.damping;
    case Quantity::JointRestitution: return j.restitution;
    case Quantity::JointLower: return j.lower;
    default: return j.upper;
  }
}

// Writes a joint's input or parameter; "" or why not.
std::string writeJoint(const Variable& v, double value, WorldModel& model, WorldData& data, Phase phase) {
  rigid::JointConstants& j = model.joints[static_cast<size_t>(v.body)];
  const size_t k = static_cast<size_t>(v.body);
  switch (v.quantity) {
    case Quantity::JointMotorSpeed:
      (phase == Phase::Setup ? j.motorSpeed : data.joints.motorSpeed[k]) = value;
      return "";
    case Quantity::JointTargetPosition:
      (phase == Phase::Setup ? j.targetPosition : data.joints.targetPosition[k]) = value;
      return "";
    case Quantity::JointMaxMotorForce:
      if (!(value > 0.0)) return v.name + ": must be > 0 " + v.unit + ", got " + fmt(value);
      j.maxMotorForce = value;
      return "";
    case Quantity::JointStiffness:
    case Quantity::JointDamping:
      if (value < 0.0) return v.name + ": must be >= 0 " + v.unit + ", got " + fmt(value);
      (v.quantity == Quantity::JointStiffness ? j.stiffness : j.damping) = value;
      return "";
    case Quantity::JointRestitution:
      if (value < 0.0 || value > 1.0) return v.name + ": must be in [0, 1], got " + fmt(value);
      j.restitution = value;
      return "";
    case Quantity::JointLower: j.lower = value; return "";
    case Quantity::JointUpper: j.upper = value; return "";
    default: return v.name + ": a calculated output; it cannot be set";
  }
}

}  // namespace

std::vector<Variable> modelVariables(const Scene& scene) {
  std::vector<Variable> vars;
  auto add = [&](Variable v) {
    v.vr = static_cast<unsigned>(vars.size());
    vars.push_back(std::move(v));
  };

  add({0, "time", Quantity::Time, -1, 0, Causality::Independent, Variability::Continuous, Initial::None, BaseType::Real,
       "s", "simulation time"});
  for (int c = 0; c < 3; ++c)
    add({0, std::string("gravity[") + std::to_string(c + 1) + "]", Quantity::Gravity, -1, c, Causality::Parameter,
         Variability::Tunable, Initial::Exact, BaseType::Real, "m/s2",
         std::string("gravitational acceleration g, ") + kAxis[c] + " (world frame)"});
  add({0, "solver.method", Quantity::SolverMethod, -1, 0, Causality::Parameter, Variability::Fixed, Initial::Exact,
       BaseType::Enumeration, "", "integration method (unit: none, an enumeration)"});
  add({0, "solver.step", Quantity::SolverStep, -1, 0, Causality::Parameter, Variability::Fixed, Initial::Exact,
       BaseType::Real, "s", "largest internal step; a communication step is split into steps of at most this"});
  add({0, "solver.tolerance", Quantity::SolverTolerance, -1, 0, Causality::Parameter, Variability::Fixed,
       Initial::Exact, BaseType::Real, "1",
       "local error tolerance of the adaptive method dopri5 (absolute and relative); 0: fixed steps"});
  add({0, "solver.energyGainLimit", Quantity::SolverEnergyGainLimit, -1, 0, Causality::Parameter, Variability::Tunable,
       Initial::Exact, BaseType::Real, "1",
       "largest relative gain of a torque-free body's rotational energy over the run; a step "
       "beyond it is refused (the step is discarded); 0: unchecked"});
  add({0, "solver.steps", Quantity::SolverSteps, -1, 0, Causality::Output, Variability::Discrete, Initial::Calculated,
       BaseType::Integer, "", "internal steps taken in the last communication step (sub-steps included)"});
  add({0, "solver.errorEstimate", Quantity::SolverErrorEstimate, -1, 0, Causality::Output, Variability::Discrete,
       Initial::Calculated, BaseType::Real, "1",
       "the adaptive method's last local error estimate; 0 for fixed-step methods"});

  for (size_t b = 0; b < scene.model.bodies.size(); ++b) {
    const BodyConstants& body = scene.model.bodies[b];
    const int bi = static_cast<int>(b);
    if (!rigid::driven(body))
      add({0, body.name + ".mass", Quantity::Mass, bi, 0, Causality::Parameter, Variability::Fixed, Initial::Exact,
           BaseType::Real, "kg", body.name + ": mass M"});
    add({0, body.name + ".restitution", Quantity::Restitution, bi, 0, Causality::Parameter, Variability::Fixed,
         Initial::Exact, BaseType::Real, "1", body.name + ": coefficient of restitution xi, in [0, 1]"});
    const rigid::BodyVariables& exposed = scene.variables[b];
    for (const VectorQuantity& q : vectorsOf(body)) {
      const auto& chosen = q.causality == Causality::Input ? exposed.inputs : exposed.outputs;
      if (!chosen.count(q.field)) continue;
      for (int c = 0; c < q.size; ++c) {
        const char* part = q.size == 4 ? kQuatPart[c] : kAxis[c];
        add({0, body.name + "." + q.field + "[" + std::to_string(c + 1) + "]", q.quantity, bi, c, q.causality,
             Variability::Continuous, q.initial, BaseType::Real, q.unit, body.name + ": " + q.meaning + ", " + part});
      }
    }
    if (exposed.outputs.count("contacts"))
      add({0, body.name + ".contacts", Quantity::Contacts, bi, 0, Causality::Output, Variability::Discrete,
           Initial::Calculated, BaseType::Integer, "",
           body.name + ": number of contact points at the end of the last step (surfaces and bodies)"});
  }
  // The scene's material and fluid constants, after every earlier variable so that
  // their value references stay as they were. Tunable: the contact solve and the media
  // read them afresh at every step, and nothing derived from them is kept (geometry,
  // which the detector and the bounding boxes are built from, stays fixed).
  auto parameter = [&](const std::string& owner, const char* field, Quantity q, int index, const char* unit,
                       const std::string& meaning) {
    add({0, owner + "." + field, q, index, 0, Causality::Parameter, Variability::Tunable, Initial::Exact,
         BaseType::Real, unit, owner + ": " + meaning});
  };
  const char* combined = " (a pair's coefficient is the geometric mean of its two sides')";
  // a body's friction, only where it can touch something (a surface, or another body
  // when two or more collide): elsewhere it would be a parameter that changes nothing
  const auto& bodies = scene.model.bodies;
  const long colliding = std::count_if(bodies.begin(), bodies.end(), [](const BodyConstants& b) { return b.collides; });
  auto touches = [&](size_t b) { return !scene.model.surfaces.empty() || (bodies[b].collides && colliding >= 2); };
  for (size_t b = 0; b < bodies.size(); ++b) {
    if (!touches(b)) continue;
    const std::string& name = bodies[b].name;
    parameter(name, "staticFriction", Quantity::StaticFriction, static_cast<int>(b), "1",
              std::string("static friction coefficient mu_s, >= kineticFriction") + combined);
    parameter(name, "kineticFriction", Quantity::KineticFriction, static_cast<int>(b), "1",
              std::string("kinetic friction coefficient mu_k, >= 0") + combined);
  }
  for (size_t s = 0; s < scene.model.surfaces.size(); ++s) {
    const std::string& name = scene.model.surfaces[s].name;
    const int si = static_cast<int>(s);
    parameter(name, "staticFriction", Quantity::SurfaceStaticFriction, si, "1",
              std::string("surface's static friction coefficient mu_s, >= kineticFriction") + combined);
    parameter(name, "kineticFriction", Quantity::SurfaceKineticFriction, si, "1",
              std::string("surface's kinetic friction coefficient mu_k, >= 0") + combined);
    parameter(name, "restitution", Quantity::SurfaceRestitution, si, "1",
              std::string("surface's coefficient of restitution xi, in [0, 1]") + combined);
  }
  for (size_t m = 0; m < scene.model.media.size(); ++m) {
    const std::string& name = scene.model.media[m].name;
    const int mi = static_cast<int>(m);
    parameter(name, "density", Quantity::MediumDensity, mi, "kg/m3",
              "fluid density rho, >= 0 (buoyancy rho V g, drag)");
    parameter(name, "viscosity", Quantity::MediumViscosity, mi, "Pa.s",
              "fluid dynamic viscosity, >= 0 (the drag's linear term)");
  }
  // The contact loads of the last communication step (its impulses over its length),
  // where something can touch: per body (its outputs list permitting) and per surface.
  auto vector = [&](const std::string& name, Quantity q, int index, const char* unit, const std::string& meaning) {
    for (int c = 0; c < 3; ++c)
      add({0, name + "[" + std::to_string(c + 1) + "]", q, index, c, Causality::Output, Variability::Continuous,
           Initial::Calculated, BaseType::Real, unit, meaning + ", " + kAxis[c]});
  };
  const char* mean =
      "mean over the last communication step (its contact impulses, impacts included, divided by its "
      "length; 0 before the first)";
  for (size_t b = 0; b < bodies.size(); ++b) {
    if (!touches(b)) continue;
    const std::set<std::string>& outputs = scene.variables[b].outputs;
    const std::string& name = bodies[b].name;
    if (outputs.count("contactForce"))
      vector(name + ".contactForce", Quantity::ContactForce, static_cast<int>(b), "N",
             name + ": force of its contacts (surfaces and bodies), world frame, " + mean);
    if (outputs.count("contactTorque"))
      vector(name + ".contactTorque", Quantity::ContactTorque, static_cast<int>(b), "N.m",
             name + ": torque of its contacts about " +
                 (rigid::driven(bodies[b]) ? "its origin (the point its position input gives)" : "the centre of mass") +
                 ", world frame, " + mean);
  }
  for (size_t s = 0; s < scene.model.surfaces.size(); ++s)
    if (scene.model.surfaces[s].forceOutput)
      vector(scene.model.surfaces[s].name + ".force", Quantity::SurfaceForce, static_cast<int>(s), "N",
             scene.model.surfaces[s].name + ": force the bodies exert on the surface, world frame, " + mean);
  // Forces at the bodies' load points, last too.
  for (size_t b = 0; b < bodies.size(); ++b) {
    for (size_t k = 0; k < bodies[b].loads.size(); ++k) {
      const rigid::PointLoad& load = bodies[b].loads[k];
      const std::string at = "(" + fmt(load.point.x()) + ", " + fmt(load.point.y()) + ", " + fmt(load.point.z()) +
                             ") m from the centre of mass, body frame";
      for (int c = 0; c < 3; ++c) {
        Variable v{0,
                   bodies[b].name + "." + load.name + ".force[" + std::to_string(c + 1) + "]",
                   Quantity::LoadForce,
                   static_cast<int>(b),
                   c,
                   Causality::Input,
                   Variability::Continuous,
                   Initial::None,
                   BaseType::Real,
                   "N",
                   bodies[b].name + ": force at its load point " + load.name + " " + at + ", in the " +
                       (load.bodyFrame ? "body" : "world") + " frame, " + kAxis[c]};
        v.load = static_cast<int>(k);
        add(v);
      }
    }
  }
  // The conveyors' belt velocities, last of all.
  for (size_t s = 0; s < scene.model.surfaces.size(); ++s) {
    const rigid::Surface& surface = scene.model.surfaces[s];
    if (!surface.belt) continue;
    for (int c = 0; c < 3; ++c)
      add({0, surface.name + ".beltVelocity[" + std::to_string(c + 1) + "]", Quantity::BeltVelocity,
           static_cast<int>(s), c, Causality::Input, Variability::Continuous, Initial::None, BaseType::Real, "m/s",
           surface.name +
               ": velocity of the surface's material (a conveyor's belt), world frame; only its part "
               "along each contact's plane acts, " +
               kAxis[c]});
  }
  addJointVariables(scene.model, add);
  return vars;
}

std::vector<unsigned> initialDependencies(const std::vector<Variable>& vars, const Variable& v,
                                          const WorldModel& model) {
  // P = M V depends on the mass and the same velocity component; L = R Ibody R^T omega
  // on the orientation, every angular velocity component and, when Ibody comes from
  // the shape, on the mass.
  std::vector<unsigned> deps;
  for (const Variable& k : vars) {
    if (k.body != v.body) continue;
    bool dep = false;
    if (v.quantity == Quantity::LinearMomentum)
      dep = k.quantity == Quantity::Mass || (k.quantity == Quantity::Velocity && k.component == v.component);
    else if (v.quantity == Quantity::AngularMomentum)
      dep = k.quantity == Quantity::Orientation || k.quantity == Quantity::AngularVelocity ||
            (k.quantity == Quantity::Mass && model.bodies[v.body].inertiaFromShape);
    if (dep) deps.push_back(k.vr + 1);
  }
  std::sort(deps.begin(), deps.end());
  return deps;
}

double readValue(const Variable& v, const WorldModel& model, const WorldData& data, Phase phase) {
  const int b = v.body, c = v.component;
  const bool setup = phase == Phase::Setup;
  switch (v.quantity) {
    case Quantity::Time: return 0.0;
    case Quantity::Gravity: return model.gravity[c];
    case Quantity::SolverMethod: return static_cast<double>(static_cast<int>(model.method));
    case Quantity::SolverStep: return model.maxStep;
    case Quantity::SolverTolerance: return model.tolerance;
    case Quantity::SolverEnergyGainLimit: return model.energyGainLimit;
    case Quantity::SolverSteps: return setup ? 0.0 : static_cast<double>(data.steps);
    case Quantity::SolverErrorEstimate: return setup ? 0.0 : data.integrator.errorEstimate;
    case Quantity::Mass: return model.bodies[b].mass;
    case Quantity::Restitution: return model.bodies[b].restitution;
    case Quantity::StaticFriction: return model.bodies[b].staticFriction;
    case Quantity::KineticFriction: return model.bodies[b].kineticFriction;
    case Quantity::SurfaceStaticFriction: return model.surfaces[b].staticFriction;
    case Quantity::SurfaceKineticFriction: return model.surfaces[b].kineticFriction;
    case Quantity::SurfaceRestitution: return model.surfaces[b].restitution;
    case Quantity::MediumDensity: return model.media[b].density;
    case Quantity::MediumViscosity: return model.media[b].viscosity;
    case Quantity::Position:
    case Quantity::Orientation:
    case Quantity::Velocity:
    case Quantity::AngularVelocity: return setup ? startValue(v, model.bodies[b].start) : poseValue(v, model, data);
    case Quantity::LinearMomentum:
      return setup ? vectorPart(rigid::initialState(model.bodies[b]).P, c) : data.Y[b].P[c];
    case Quantity::AngularMomentum:
      return setup ? vectorPart(rigid::initialState(model.bodies[b]).L, c) : data.Y[b].L[c];
    case Quantity::Force: return data.input[b].force[c];
    case Quantity::Torque: return data.input[b].torque[c];
    case Quantity::LoadForce: return data.input[b].loads[static_cast<size_t>(v.load)][c];
    case Quantity::BeltVelocity: return setup ? model.surfaces[b].beltVelocity[c] : data.beltVelocity[b][c];
    case Quantity::Contacts: return setup ? 0.0 : static_cast<double>(data.contacts[b]);
    case Quantity::ContactForce:
    case Quantity::ContactTorque:
    case Quantity::SurfaceForce: {
      const WorldData::ContactLoads& loads = data.contactLoads;
      if (setup || !(loads.duration > 0.0)) return 0.0;
      const std::vector<rigid::Vec3>& of = v.quantity == Quantity::ContactForce    ? loads.impulse
                                           : v.quantity == Quantity::ContactTorque ? loads.angularImpulse
                                                                                   : loads.surfaceImpulse;
      return of[static_cast<size_t>(b)][c] / loads.duration;
    }
    case Quantity::JointPosition:
    case Quantity::JointSpeed:
    case Quantity::JointReactionForce:
    case Quantity::JointReactionTorque:
    case Quantity::JointMotorSpeed:
    case Quantity::JointTargetPosition:
    case Quantity::JointMaxMotorForce:
    case Quantity::JointStiffness:
    case Quantity::JointDamping:
    case Quantity::JointRestitution:
    case Quantity::JointLower:
    case Quantity::JointUpper: return jointValue(v, model, data, phase);
  }
  return 0.0;
}

std::string writeValue(const Variable& v, double value, WorldModel& model, WorldData& data, Phase phase) {
  if (!std::isfinite(value)) return v.name + ": must be finite, got " + fmt(value);
  const int b = v.body, c = v.component;
  switch (v.quantity) {
    case Quantity::Time: return v.name + ": the independent variable cannot be set";
    case Quantity::Gravity: model.gravity[c] = value; return "";
    case Quantity::SolverMethod: {
      // Range and wholeness first: casting 1e10 to int would be undefined.
      const bool whole = value == std::floor(value) && std::abs(value) < 1e6;
      const auto method = whole ? rigid::methodFromValue(static_cast<int>(value)) : std::nullopt;
      if (!method) {
        std::string list;
        for (const rigid::MethodInfo& m : rigid::methods())
          list +=
              std::string(list.empty() ? "" : ", ") + std::to_string(static_cast<int>(m.method)) + " (" + m.name + ")";
        return v.name + ": must be one of " + list + ", got " + fmt(value);
      }
      model.method = *method;
      return "";
    }
    case Quantity::SolverStep:
      if (!(value > 0.0)) return v.name + ": must be > 0 s, got " + fmt(value);
      model.maxStep = value;
      return "";
    case Quantity::SolverTolerance:
      if (value < 0.0) return v.name + ": must be >= 0, got " + fmt(value);
      model.tolerance = value;
      return "";
    case Quantity::SolverEnergyGainLimit:
      if (value < 0.0) return v.name + ": must be >= 0 (0: unchecked), got " + fmt(value);
      model.energyGainLimit = value;
      return "";
    case Quantity::SolverSteps:
    case Quantity::SolverErrorEstimate: return v.name + ": a calculated output; it cannot be set";
    case Quantity::Mass:
      if (!(value > 0.0)) return v.name + ": must be > 0 kg, got " + fmt(value);
      rigid::setMass(model.bodies[b], value);
      return "";
    case Quantity::Restitution:
      if (value < 0.0 || value > 1.0) return v.name + ": must be in [0, 1], got " + fmt(value);
      model.bodies[b].restitution = value;
      return "";
    case Quantity::SurfaceRestitution:
      if (value < 0.0 || value > 1.0) return v.name + ": must be in [0, 1], got " + fmt(value);
      model.surfaces[b].restitution = value;
      return "";
    case Quantity::StaticFriction:
    case Quantity::KineticFriction:
    case Quantity::SurfaceStaticFriction:
    case Quantity::SurfaceKineticFriction:
      if (value < 0.0) return v.name + ": must be >= 0, got " + fmt(value);
      frictionOf(v, model) = value;
      return "";
    case Quantity::MediumDensity:
      if (value < 0.0) return v.name + ": must be >= 0 kg/m3, got " + fmt(value);
      model.media[b].density = value;
      return "";
    case Quantity::MediumViscosity:
      if (value < 0.0) return v.name + ": must be >= 0 Pa.s, got " + fmt(value);
      model.media[b].viscosity = value;
      return "";
    case Quantity::Position:
    case Quantity::Orientation:
    case Quantity::Velocity:
    case Quantity::AngularVelocity:
      if (phase == Phase::Setup) {
        setMotionPart(v, model.bodies[b].start.position, model.bodies[b].start.orientation,
                      model.bodies[b].start.velocity, model.bodies[b].start.angularVelocity, value);
        return "";
      }
      if (!rigid::driven(model.bodies[b])) return v.name + ": an output; it can be set only before the run starts";
      setMotionPart(v, data.drive[b].position, data.drive[b].orientation, data.drive[b].velocity,
                    data.drive[b].angularVelocity, value);
      return "";
    case Quantity::LinearMomentum:
    case Quantity::AngularMomentum: return v.name + ": a calculated output; set velocity or angularVelocity instead";
    case Quantity::Force: data.input[b].force[c] = value; return "";
    case Quantity::Torque: data.input[b].torque[c] = value; return "";
    case Quantity::LoadForce: data.input[b].loads[static_cast<size_t>(v.load)][c] = value; return "";
    case Quantity::BeltVelocity:  // before the run, the start value (the run starts from the model's)
      (phase == Phase::Setup ? model.surfaces[b].beltVelocity : data.beltVelocity[b])[c] = value;
      return "";
    case Quantity::Contacts:
    case Quantity::ContactForce:
    case Quantity::ContactTorque:
    case Quantity::SurfaceForce: return v.name + ": a calculated output; it cannot be set";
    case Quantity::JointPosition:
    case Quantity::JointSpeed:
    case Quantity::JointReactionForce:
    case Quantity::JointReactionTorque:
    case Quantity::JointMotorSpeed:
    case Quantity::JointTargetPosition:
    case Quantity::JointMaxMotorForce:
    case Quantity::JointStiffness:
    case Quantity::JointDamping:
    case Quantity::JointRestitution:
    case Quantity::JointLower:
    case Quantity::JointUpper: return writeJoint(v, value, model, data, phase);
  }
  return v.name + ": cannot be set";
}

std::string parameterConflict(const WorldModel& model) {
  auto check = [](const std::string& name, double mus, double muk) -> std::string {
    if (muk <= mus) return "";
    return name + ".kineticFriction: must be <= " + name + ".staticFriction (" + fmt(mus) + "), got " + fmt(muk);
  };
  for (const BodyConstants& b : model.bodies)
    if (std::string why = check(b.name, b.staticFriction, b.kineticFriction); !why.empty()) return why;
  for (const rigid::Surface& s : model.surfaces)
    if (std::string why = check(s.name, s.staticFriction, s.kineticFriction); !why.empty()) return why;
  for (const rigid::JointConstants& j : model.joints) {
    if (j.limited && j.lower > j.upper)
      return j.name + ".lower: must be <= " + j.name + ".upper (" + fmt(j.upper) + "), got " + fmt(j.lower);
    if (j.limited && j.type == rigid::JointType::Distance && j.lower < 0.0)
      return j.name + ".lower: a length must be >= 0 m, got " + fmt(j.lower);
  }
  return "";
}

}  // namespace rigidfmu
