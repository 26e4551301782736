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

enum class FmiVersion { Fmi2, Fmi3 };

// The FMI 2.0 or 3.0 model description of the scene's FMU, from one variable table.
std::string modelDescriptionXml(const rigid::Scene& scene, FmiVersion version = FmiVersion::Fmi2);

}  // namespace rigidfmu
