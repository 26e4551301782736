// Time integrators of the state vectors: the seed's explicit Euler and classic RK4.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "body.h"

namespace rigid {

struct WorldModel;
struct WorldData;

// Values are the FMI enumeration values of solver.method: never renumber.
enum class Method : int {
  Euler = 1,            // explicit Euler (seed)
  RK4 = 2,              // classic Runge-Kutta (seed, default)
  SymplecticEuler = 3,  // semi-implicit Euler: momenta first, then positions
  Splitting = 4,        // kick-drift-kick with the Dullweber-Leimkuhler-McLachlan free rotation
  LieRK4 = 5,           // Runge-Kutta-Munthe-Kaas 4: q moves by exponentials, unit by construction
  Dopri5 = 6,           // adaptive embedded Dormand-Prince 5(4)
  Rosenbrock = 7,       // linearly implicit ROS2, L-stable: stiff drag and buoyancy
};

// How far a fixed-step explicit method's step may go (h times the rate) before it
// leaves its stability region: fast spin (|omega|), damping (drag rate) and
// oscillation (heave frequency). Infinity: no limit (exact rotations, adaptive or
// implicit methods).
struct StabilityLimits {
  double spin, damping, oscillation;
};
StabilityLimits stabilityLimits(Method method);

struct MethodInfo {
  Method method;
  const char* name;  // as in scene files and the FMI enumeration
  const char* description;
};
const std::vector<MethodInfo>& methods();
std::optional<Method> methodFromName(const std::string& name);
std::optional<Method> methodFromValue(int value);
const char* methodName(Method method);

// What the integrator carries from one internal step to the next: part of a run's
// state (WorldData::integrator), so the FMU state saves it and a restored run takes the
// same steps, bitwise.
struct IntegratorState {
  double adaptiveStep = 0.0;   // s, the adaptive method's next trial step (0: none yet)
  double errorEstimate = 0.0;  // 1, its last accepted step's local error estimate (0 for fixed steps)
};

// Y(t + h) of the listed bodies (ascending indices) into `next` (q not yet normalised);
// the other bodies' entries are left as they are (sleeping bodies are not integrated).
// Reads data.Y and data.input; uses data.scratch and data.aux as work space. Returns
// the number of steps it took: 1, or the accepted steps of the adaptive method, which
// also sets data.integrator; 0 when the adaptive method cannot meet its tolerance.
int integrate(const WorldModel& model, WorldData& data, const std::vector<int>& bodies, double h,
              std::vector<BodyState>& next);

// Unit quaternion of the rotation by the rotation vector theta (rad).
Quat rotationQuaternion(const Vec3& theta);

}  // namespace rigid
