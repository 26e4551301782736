// The integration methods by name and FMI enumeration value.
#include "integrator.h"

#include <limits>

namespace rigid {

const std::vector<MethodInfo>& methods() {
  static const std::vector<MethodInfo> kMethods = {
      {Method::Euler, "euler", "explicit Euler, first order (the seed's Euler method)"},
      {Method::RK4, "rk4", "classic Runge-Kutta, fourth order (the seed's default)"},
      {Method::SymplecticEuler, "symplecticEuler",
       "semi-implicit (symplectic) Euler, first order: momenta, then positions and a rotation by the new angular velocity"},
      {Method::Splitting, "splitting",
       "kick-drift-kick with the Dullweber-Leimkuhler-McLachlan free-rotation splitting, second order: |L| exact, energy bounded"},
      {Method::LieRK4, "lieRk4",
       "Runge-Kutta-Munthe-Kaas 4 on the rotation group, fourth order: q unit by construction"},
      {Method::Dopri5, "dopri5",
       "adaptive embedded Dormand-Prince 5(4) with step-size control to solver.tolerance"},
      {Method::Rosenbrock, "rosenbrock",
       "linearly implicit Rosenbrock ROS2, second order, L-stable: for stiff drag and buoyancy"},
  };
  return kMethods;
}

std::optional<Method> methodFromName(const std::string& name) {
  for (const MethodInfo& m : methods())
    if (name == m.name) return m.method;
  return std::nullopt;
}

std::optional<Method> methodFromValue(int value) {
  for (const MethodInfo& m : methods())
    if (value == static_cast<int>(m.method)) return m.method;
  return std::nullopt;
}

StabilityLimits stabilityLimits(Method method) {
  constexpr double kNone = std::numeric_limits<double>::infinity();
  // Spin: at most a radian of turn per step for methods that integrate q' = 1/2 omega q
  // by polynomials. Damping and oscillation: the real and imaginary extents of each
  // method's stability region (RK4: 2.785 and 2.828; Euler: 2 and none, as it grows on
  // the imaginary axis, so it sub-steps oscillations to h omega <= 0.05), with 10 %
  // margin.
  switch (method) {
    case Method::Euler: return {1.0, 0.9 * 2.0, 0.05};
    case Method::RK4: return {1.0, 0.9 * 2.785, 0.9 * 2.828};
    case Method::SymplecticEuler: return {1.0, 0.9 * 2.0, 0.9 * 2.0};
    case Method::Splitting: return {kNone, 0.9 * 2.0, 0.9 * 2.0};
    case Method::LieRK4: return {kNone, 0.9 * 2.785, 0.9 * 2.828};
    case Method::Dopri5:
    case Method::Rosenbrock: return {kNone, kNone, kNone};
  }
  return {kNone, kNone, kNone};
}

const char* methodName(Method method) {
  for (const MethodInfo& m : methods())
    if (m.method == method) return m.name;
  return "?";
}

}  // namespace rigid
