// modelDescription.xml of a scene's FMU, written from the variable table.
#pragma once

#include <string>

#include "scene.h"

namespace rigidfmu {

// Log categories the FMU declares and understands in fmi2SetDebugLogging.
struct LogCategory {
  const char* name;
  const char* description;
};
extern const LogCategory kLogCategories[];
extern const int kLogCategoryCount;

std::string modelDescriptionXml(const rigid::Scene& scene);

}  // namespace rigidfmu
