// The FMU's GUID, derived from the scene's content: the same scene always gives the
// same GUID, and any change to it (or to the variable layout) gives another.
#pragma once

#include <string>

#include "scene.h"

namespace rigidfmu {

// Bumped whenever the variable table or the meaning of a variable changes, so that
// an FMU built by an older version is told apart from a new one of the same scene.
inline constexpr const char* kLayoutVersion = "rigidfmu-layout-1";

std::string sceneGuid(const rigid::Scene& scene);

}  // namespace rigidfmu
