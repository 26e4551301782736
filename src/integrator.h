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
enum class Method : int { Euler = 1, RK4 = 2 };

struct MethodInfo {
  Method method;
  const char* name;         // as in scene files and the FMI enumeration
  const char* description;
};
const std::vector<MethodInfo>& methods();
std::optional<Method> methodFromName(const std::string& name);
std::optional<Method> methodFromValue(int value);
const char* methodName(Method method);

// Y(t + h) of every body into `next` (q not yet normalised). Reads data.Y and
// data.input; uses data.scratch and data.aux as work space.
void integrate(const WorldModel& model, WorldData& data, double h, std::vector<BodyState>& next);

}  // namespace rigid
