// The integration methods by name and FMI enumeration value.
#include "integrator.h"

#include <limits>

namespace rigid {

const std::vector<MethodInfo>& methods() {
  static const std::vector<MethodInfo> kMethods = {
      {Method::Euler, "euler", "explicit Euler, first order (the seed's Euler method)"},
      {Method::RK4, "rk4", "classic Runge-Kutta, fourth order (the seed's default)"},
      {Method::SymplecticEuler, "symplecticEuler",
       "semi-implicit (symplectic) Euler, first order: momenta, then positions and the free rotation under the new L "
       "(as in splitting)"},
      {Method::Splitting, "splitting",
       "kick-drift-kick with the Dullweber-Leimkuhler-McLachlan free-rotation splitting, second order: |L| exact, "
       "energy bounded"},
      {Method::LieRK4, "lieRk4",
       "Runge-Kutta-Munthe-Kaas 4 on the rotation group, fourth order: q unit by construction"},
      {Method::Dopri5, "dopri5", "adaptive embedded Dormand-Prince 5(4) with step-size control to solver.tolerance"},
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
  // Spin: the h |omega| at which a free rotation's energy stays within 1e-3 over 1e4
  // steps and more for the fourth- and second-order methods (measured by
  // scripts/stress.sh: rk4 loses 6 % at h |omega| = 1); symplecticEuler turns q as
  // splitting does. Explicit Euler to 0.05, which bounds its error per step, not its
  // energy gain: the energy audit (WorldModel::energyGainLimit) refuses that. Damping
  // and oscillation: the real and imaginary extents of each method's stability region
  // (RK4: 2.785 and 2.828; symplectic methods: 2 and 2), with 10 % margin. Explicit
  // Euler grows on every oscillation (no step is stable): 0 refuses it there.
  // Symplectic Euler is stable on an oscillation to h omega = 2 but, first order, its
  // energy swings by ~h omega / 2 of the oscillation's energy (bounded, no drift): it
  // is held to h omega <= 2e-3, an energy swing within 1e-3 (a 1 mm draft swung by
  // 4 % at h omega = 0.1 in scripts/stress.sh).
  switch (method) {
    case Method::Euler: return {0.05, 0.9 * 2.0, 0.0};
    case Method::RK4: return {0.1, 0.9 * 2.785, 0.9 * 2.828};
    case Method::SymplecticEuler: return {0.15, 0.9 * 2.0, 2e-3};
    case Method::Splitting: return {0.15, 0.9 * 2.0, 0.9 * 2.0};
    case Method::LieRK4: return {0.1, 0.9 * 2.785, 0.9 * 2.828};
    case Method::Rosenbrock: return {0.15, kNone, kNone};  // q turns as in splitting
    case Method::Dopri5: return {kNone, kNone, kNone};
  }
  return {kNone, kNone, kNone};
}

const char* methodName(Method method) {
  for (const MethodInfo& m : methods())
    if (m.method == method) return m.name;
  return "?";
}

}  // namespace rigid
