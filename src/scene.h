// Scene files (JSON, see INTERFACE.md): read, check every rule, and turn into the
// world's constants. A broken rule throws SceneError whose message names the field
// and the limit, e.g. "bodies[2].mass: must be > 0, got -1".
#pragma once

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "world.h"

namespace rigid {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The FMU variables a body exposes: the scene's optional body fields "outputs" and
// "inputs", lists of the names below; by default all of them.
inline const std::vector<std::string> kBodyOutputs = {"position",        "orientation",    "velocity",
                                                      "angularVelocity", "linearMomentum", "angularMomentum",
                                                      "contacts",        "contactForce",   "contactTorque"};
inline const std::vector<std::string> kBodyInputs = {"force", "torque"};
// A driven body's (BodyConstants::motion): its pose and velocities are always inputs;
// it may choose among these outputs.
inline const std::vector<std::string> kDrivenOutputs = {"contacts", "contactForce", "contactTorque"};
inline const std::vector<std::string> kDrivenInputs = {"position", "orientation", "velocity", "angularVelocity"};
struct BodyVariables {
  std::set<std::string> outputs;
  std::set<std::string> inputs;
};

struct Scene {
  WorldModel model;                      // name, gravity, solver, bodies, surfaces, media
  std::vector<BodyVariables> variables;  // one per body
  std::string canonicalJson;             // the parsed file, keys sorted: identifies the scene
  std::vector<std::string> warnings;     // notes for the user that break no rule (a mesh's hull)
};

// A scene given as text names no files: a mesh in it is refused.
Scene parseScene(const std::string& jsonText);
// A scene file; the mesh files it names are read relative to its folder.
Scene loadSceneFile(const std::string& path);  // path in UTF-8, on every platform

// Defaults of the scene format, documented in the README.
namespace defaults {
constexpr double kSolverStep = 1e-3;       // s
constexpr double kTolerance = 1e-6;        // 1, adaptive methods' local error tolerance
constexpr double kEnergyGainLimit = 1e-3;  // 1, the energy audit's limit (world.h)
constexpr double kRestitution = 0.5;
constexpr double kStaticFriction = 0.6;
constexpr double kKineticFriction = 0.4;
constexpr double kAirDensity = 1.204;         // kg/m^3, 20 C, 1 atm
constexpr double kAirViscosity = 1.813e-5;    // Pa s
constexpr double kWaterDensity = 998.2;       // kg/m^3, 20 C
constexpr double kWaterViscosity = 1.002e-3;  // Pa s
// m: how deep behind its front a mesh surface's triangle collides: a body must not
// cross it within one internal step.
constexpr double kSurfaceMeshThickness = 0.1;
}  // namespace defaults

}  // namespace rigid
