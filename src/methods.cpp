// The integration methods by name and FMI enumeration value.
#include "integrator.h"

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

const char* methodName(Method method) {
  for (const MethodInfo& m : methods())
    if (m.method == method) return m.name;
  return "?";
}

}  // namespace rigid
