// The integration methods by name and FMI enumeration value.
#include "integrator.h"

namespace rigid {

const std::vector<MethodInfo>& methods() {
  static const std::vector<MethodInfo> kMethods = {
      {Method::Euler, "euler", "explicit Euler, first order (the seed's Euler method)"},
      {Method::RK4, "rk4", "classic Runge-Kutta, fourth order (the seed's default)"},
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
