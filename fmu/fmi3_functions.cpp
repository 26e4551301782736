// The FMI 3.0 Co-Simulation entry points: the FMI 3 names, types and statuses mapped
// onto the version-neutral Instance, a peer of fmi2_functions.cpp. One state machine
// (fmi3_states.h names the states each function may be called in), one step, one
// snapshot format; what differs is the calling convention: the instance handle carries
// the master's log message callback (wrapped as the Instance's logger), the resource
// path is turned into the file URI the Instance reads, and Enumeration variables travel
// through fmi3Get/SetInt64. Every variable is a scalar (docs/scene-format.md, "FMI
// 3.0"): value references, names, units and descriptions are those of the FMI 2 FMU.
// With the master's permission (earlyReturnAllowed), fmi3DoStep returns early at the
// first bouncing impact inside the step: earlyReturn and lastSuccessfulTime = the
// impact's instant.
#include <cctype>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "entry_guard.h"
#include "fmi3Functions.h"
#include "fmi3_states.h"
#include "instance.h"
#include "status.h"

using rigidfmu::BaseType;
using rigidfmu::Instance;
using rigidfmu::Status;
namespace allowed = rigidfmu::fmi3_allowed;

static_assert(std::is_same_v<fmi3ValueReference, uint32_t> && std::is_same_v<fmi3Int32, int32_t> &&
                  std::is_same_v<fmi3Float64, double>,
              "the Instance's value types");
static_assert(std::is_same_v<fmi3FMUState, void*>, "FMU states are opaque pointers");

namespace {

// What fmi3InstantiateCoSimulation hands out: the Instance and the master's permission.
struct Fmi3Instance {
  bool earlyReturnAllowed = false;  // the master's permission (fmi3InstantiateCoSimulation)
  std::unique_ptr<Instance> core;
};

fmi3Status toFmi3(Status status) {
  switch (status) {
    case Status::OK: return fmi3OK;
    case Status::Warning: return fmi3Warning;
    case Status::Discard: return fmi3Discard;
    case Status::Error: return fmi3Error;
    case Status::Fatal: return fmi3Fatal;
  }
  return fmi3Fatal;
}

// The instance's messages to the master's fmi3LogMessageCallback.
rigidfmu::Logger loggerOf(fmi3InstanceEnvironment environment, fmi3LogMessageCallback logMessage) {
  if (!logMessage) return nullptr;
  return [environment, logMessage](Status status, const char* category, const std::string& message) {
    logMessage(environment, toFmi3(status), category, message.c_str());
  };
}

// What a variable of this type is and its accessors (an FMI 3 accessor is typed: Int32
// for Integer variables, Int64 for the Enumeration).
const char* typeAdvice(BaseType t) {
  return t == BaseType::Real      ? "a Float64, use fmi3Get/SetFloat64"
         : t == BaseType::Integer ? "an Int32, use fmi3Get/SetInt32"
                                  : "an Enumeration, use fmi3Get/SetInt64";
}

// FMI 3 gives the resources as a path (ending in a separator); the Instance reads a
// file URI: the path's bytes percent-encoded where a URI must (RFC 3986), '\' as '/'.
std::string fileUri(const char* path) {
  static const char* hex = "0123456789ABCDEF";
  std::string uri = "file://";
  if (path[0] != '/') uri += '/';  // C:/dir -> file:///C:/dir
  for (const char* p = path; *p; ++p) {
    const unsigned char c = static_cast<unsigned char>(*p == '\\' ? '/' : *p);
    const bool plain = std::isalnum(c) || c == '/' || c == '-' || c == '.' || c == '_' || c == '~' || c == ':';
    if (plain) {
      uri += static_cast<char>(c);
    } else {
      uri += '%';
      uri += hex[c >> 4];
      uri += hex[c & 15];
    }
  }
  return uri;
}

Fmi3Instance* fmuOf(fmi3Instance instance) { return static_cast<Fmi3Instance*>(instance); }

Instance* coreOf(fmi3Instance instance) {
  Fmi3Instance* fmu = fmuOf(instance);
  return fmu ? fmu->core.get() : nullptr;
}

template <class Body>
fmi3Status run(fmi3Instance instance, const char* function, unsigned states, Body body) {
  return toFmi3(rigidfmu::guarded(coreOf(instance), function, states, body));
}

fmi3Status unsupported(fmi3Instance instance, const char* function, const char* why) {
  return toFmi3(rigidfmu::unsupported(coreOf(instance), function, allowed::Unsupported, why));
}

// nValues must equal nValueReferences: every variable is a scalar.
bool scalars(Instance& i, size_t nvr, size_t nValues) {
  if (nvr == nValues) return true;
  i.error("nValues = " + std::to_string(nValues) + " but nValueReferences = " + std::to_string(nvr) +
          ": every variable of this FMU is a scalar");
  return false;
}

// Whether every reference is a variable of `type` (FMI 3 accessors are typed: Int32
// for Integer variables, Int64 for the Enumeration); refuses the first that is not.
bool allOfType(Instance& i, const fmi3ValueReference vr[], size_t n, BaseType type, const char* use) {
  if (n > 0 && !vr) {
    i.error("valueReferences is NULL but nValueReferences = " + std::to_string(n));
    return false;
  }
  const auto& vars = i.variables();
  for (size_t k = 0; k < n; ++k) {
    if (vr[k] >= vars.size()) {
      i.error("unknown value reference " + std::to_string(vr[k]) + " (this FMU has 0.." +
              std::to_string(vars.size() - 1) + ")");
      return false;
    }
    const auto& v = vars[vr[k]];
    if (v.type != type) {
      i.error("value reference " + std::to_string(vr[k]) + " (" + v.name + ") " + use + ": it is " +
              typeAdvice(v.type));
      return false;
    }
  }
  return true;
}

// Accessors of types this FMU has no variables of: every reference is unknown.
fmi3Status noVariables(fmi3Instance instance, const char* function, unsigned states, const fmi3ValueReference vr[],
                       size_t n) {
  return run(instance, function, states, [&](Instance& i) { return i.noVariablesOfType(vr, n); });
}

}  // namespace

extern "C" {

const char* fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[]) {
  return run(instance, "fmi3SetDebugLogging", allowed::SetDebugLogging,
             [&](Instance& i) { return i.setDebugLogging(loggingOn, nCategories, categories); });
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName, fmi3String, fmi3String, fmi3Boolean, fmi3Boolean,
                                          fmi3InstanceEnvironment environment, fmi3LogMessageCallback logMessage) {
  if (logMessage)
    logMessage(environment, fmi3Error, "logStatusError",
               (std::string("fmi3InstantiateModelExchange (") + (instanceName ? instanceName : "") +
                "): this FMU implements Co-Simulation only")
                   .c_str());
  return nullptr;
}

fmi3Instance fmi3InstantiateCoSimulation(fmi3String instanceName, fmi3String instantiationToken,
                                         fmi3String resourcePath, fmi3Boolean visible, fmi3Boolean loggingOn,
                                         fmi3Boolean eventModeUsed, fmi3Boolean earlyReturnAllowed,
                                         const fmi3ValueReference[], size_t nRequiredIntermediateVariables,
                                         fmi3InstanceEnvironment environment, fmi3LogMessageCallback logMessage,
                                         fmi3IntermediateUpdateCallback) {
  (void)visible, (void)eventModeUsed;  // no user interface; no events to handle
  auto refuse = [&](const std::string& why) -> fmi3Instance {
    if (logMessage)
      logMessage(environment, fmi3Error, "logStatusError", ("fmi3InstantiateCoSimulation: " + why).c_str());
    return nullptr;
  };
  try {
    if (nRequiredIntermediateVariables > 0)
      return refuse("this FMU provides no intermediate update, so no required intermediate variables");
    if (!resourcePath || !*resourcePath) return refuse("no resourcePath was given");
    auto fmu = std::make_unique<Fmi3Instance>();
    fmu->earlyReturnAllowed = earlyReturnAllowed == fmi3True;
    const std::string uri = fileUri(resourcePath);
    fmu->core.reset(Instance::create("fmi3InstantiateCoSimulation", instanceName, instantiationToken, uri.c_str(),
                                     loggingOn,
                                     {loggerOf(environment, logMessage), typeAdvice, "fmi3SerializedFMUStateSize"}));
    return fmu->core ? fmu.release() : nullptr;
  } catch (const std::exception& e) {
    return refuse(std::string("failed: ") + e.what());
  } catch (...) {
    return refuse("failed");
  }
}

fmi3Instance fmi3InstantiateScheduledExecution(fmi3String instanceName, fmi3String, fmi3String, fmi3Boolean,
                                               fmi3Boolean, fmi3InstanceEnvironment environment,
                                               fmi3LogMessageCallback logMessage, fmi3ClockUpdateCallback,
                                               fmi3LockPreemptionCallback, fmi3UnlockPreemptionCallback) {
  if (logMessage)
    logMessage(environment, fmi3Error, "logStatusError",
               (std::string("fmi3InstantiateScheduledExecution (") + (instanceName ? instanceName : "") +
                "): this FMU implements Co-Simulation only")
                   .c_str());
  return nullptr;
}

void fmi3FreeInstance(fmi3Instance instance) { delete fmuOf(instance); }

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined, fmi3Float64 tolerance,
                                       fmi3Float64 startTime, fmi3Boolean /*stopTimeDefined*/,
                                       fmi3Float64 /*stopTime*/) {
  // no stop time: the FMU runs as long as it is stepped
  return run(instance, "fmi3EnterInitializationMode", allowed::EnterInitializationMode, [&](Instance& i) {
    const Status s = i.setupExperiment(toleranceDefined, tolerance, startTime);
    return s == Status::OK ? i.enterInitializationMode() : s;
  });
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance) {
  return run(instance, "fmi3ExitInitializationMode", allowed::ExitInitializationMode,
             [](Instance& i) { return i.exitInitializationMode(); });
}

fmi3Status fmi3EnterEventMode(fmi3Instance instance) {
  return unsupported(instance, "fmi3EnterEventMode", "hasEventMode is false");
}

fmi3Status fmi3Terminate(fmi3Instance instance) {
  return run(instance, "fmi3Terminate", allowed::Terminate, [](Instance& i) { return i.terminate(); });
}

fmi3Status fmi3Reset(fmi3Instance instance) {
  return run(instance, "fmi3Reset", allowed::Reset, [](Instance& i) { return i.reset(); });
}

// ---- values ----------------------------------------------------------------------------

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, fmi3Float64 values[],
                          size_t nValues) {
  return run(instance, "fmi3GetFloat64", allowed::Get, [&](Instance& i) {
    if (!scalars(i, nvr, nValues)) return Status::Error;
    if (!allOfType(i, vr, nvr, BaseType::Real, "is not a Float64")) return Status::Error;
    return i.getReal(vr, nvr, values);
  });
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, const fmi3Float64 values[],
                          size_t nValues) {
  return run(instance, "fmi3SetFloat64", allowed::Set, [&](Instance& i) {
    if (!scalars(i, nvr, nValues)) return Status::Error;
    if (!allOfType(i, vr, nvr, BaseType::Real, "is not a Float64")) return Status::Error;
    return i.setReal(vr, nvr, values);
  });
}

fmi3Status fmi3GetInt32(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, fmi3Int32 values[],
                        size_t nValues) {
  return run(instance, "fmi3GetInt32", allowed::Get, [&](Instance& i) {
    if (!scalars(i, nvr, nValues)) return Status::Error;
    if (!allOfType(i, vr, nvr, BaseType::Integer, "is not an Int32")) return Status::Error;
    return i.getInteger(vr, nvr, values);
  });
}

fmi3Status fmi3SetInt32(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, const fmi3Int32 values[],
                        size_t nValues) {
  return run(instance, "fmi3SetInt32", allowed::Set, [&](Instance& i) {
    if (!scalars(i, nvr, nValues)) return Status::Error;
    if (!allOfType(i, vr, nvr, BaseType::Integer, "is not an Int32")) return Status::Error;
    return i.setInteger(vr, nvr, values);
  });
}

// The Enumeration (solver.method) travels as Int64 (FMI 3.0, section 2.4.7.5).
fmi3Status fmi3GetInt64(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, fmi3Int64 values[],
                        size_t nValues) {
  return run(instance, "fmi3GetInt64", allowed::Get, [&](Instance& i) {
    if (!scalars(i, nvr, nValues)) return Status::Error;
    if (!allOfType(i, vr, nvr, BaseType::Enumeration,
                   "is not an Enumeration (the Int64 accessor "
                   "reads Enumerations only)"))
      return Status::Error;
    std::vector<int32_t> read(nvr);
    const Status s = i.getInteger(vr, nvr, read.data());
    if (s == Status::OK)
      for (size_t k = 0; k < nvr; ++k) values[k] = read[k];
    return s;
  });
}

fmi3Status fmi3SetInt64(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, const fmi3Int64 values[],
                        size_t nValues) {
  return run(instance, "fmi3SetInt64", allowed::Set, [&](Instance& i) {
    if (!scalars(i, nvr, nValues)) return Status::Error;
    if (!allOfType(i, vr, nvr, BaseType::Enumeration,
                   "is not an Enumeration (the Int64 accessor "
                   "writes Enumerations only)"))
      return Status::Error;
    std::vector<int32_t> narrow(nvr);
    for (size_t k = 0; k < nvr; ++k) {
      if (values[k] < std::numeric_limits<int32_t>::min() || values[k] > std::numeric_limits<int32_t>::max())
        return i.error(i.variables()[vr[k]].name + " = " + std::to_string(values[k]) + " is not one of its items");
      narrow[k] = static_cast<int32_t>(values[k]);
    }
    return i.setInteger(vr, nvr, narrow.data());
  });
}

// Types this FMU has no variables of.
#define RIGIDFMU_NO_VARIABLES(Type, CType)                                                                            \
  fmi3Status fmi3Get##Type(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, CType[], size_t) {       \
    return noVariables(instance, "fmi3Get" #Type, allowed::Get, vr, nvr);                                             \
  }                                                                                                                   \
  fmi3Status fmi3Set##Type(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, const CType[], size_t) { \
    return noVariables(instance, "fmi3Set" #Type, allowed::Set, vr, nvr);                                             \
  }
RIGIDFMU_NO_VARIABLES(Float32, fmi3Float32)
RIGIDFMU_NO_VARIABLES(Int8, fmi3Int8)
RIGIDFMU_NO_VARIABLES(UInt8, fmi3UInt8)
RIGIDFMU_NO_VARIABLES(Int16, fmi3Int16)
RIGIDFMU_NO_VARIABLES(UInt16, fmi3UInt16)
RIGIDFMU_NO_VARIABLES(UInt32, fmi3UInt32)
RIGIDFMU_NO_VARIABLES(UInt64, fmi3UInt64)
RIGIDFMU_NO_VARIABLES(Boolean, fmi3Boolean)
RIGIDFMU_NO_VARIABLES(String, fmi3String)
#undef RIGIDFMU_NO_VARIABLES

fmi3Status fmi3GetBinary(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, size_t[], fmi3Binary[],
                         size_t) {
  return noVariables(instance, "fmi3GetBinary", allowed::Get, vr, nvr);
}
fmi3Status fmi3SetBinary(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, const size_t[],
                         const fmi3Binary[], size_t) {
  return noVariables(instance, "fmi3SetBinary", allowed::Set, vr, nvr);
}
fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, fmi3Clock[]) {
  return noVariables(instance, "fmi3GetClock", allowed::Get, vr, nvr);
}
fmi3Status fmi3SetClock(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, const fmi3Clock[]) {
  return noVariables(instance, "fmi3SetClock", allowed::Set, vr, nvr);
}

// ---- dependencies, states, derivatives ------------------------------------------------------

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance instance, fmi3ValueReference, size_t*) {
  return unsupported(instance, "fmi3GetNumberOfVariableDependencies", "providesPerElementDependencies is false");
}
fmi3Status fmi3GetVariableDependencies(fmi3Instance instance, fmi3ValueReference, size_t[], fmi3ValueReference[],
                                       size_t[], fmi3DependencyKind[], size_t) {
  return unsupported(instance, "fmi3GetVariableDependencies", "providesPerElementDependencies is false");
}

fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState* state) {
  return run(instance, "fmi3GetFMUState", allowed::FMUState, [&](Instance& i) { return i.getState(state); });
}
fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState state) {
  return run(instance, "fmi3SetFMUState", allowed::FMUState, [&](Instance& i) { return i.setState(state); });
}
fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState* state) {
  return run(instance, "fmi3FreeFMUState", allowed::FMUState, [&](Instance& i) { return i.freeState(state); });
}
fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState state, size_t* size) {
  return run(instance, "fmi3SerializedFMUStateSize", allowed::FMUState,
             [&](Instance& i) { return i.serializedStateSize(state, size); });
}
fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState state, fmi3Byte bytes[], size_t size) {
  return run(instance, "fmi3SerializeFMUState", allowed::FMUState,
             [&](Instance& i) { return i.serializeState(state, reinterpret_cast<char*>(bytes), size); });
}
fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte bytes[], size_t size, fmi3FMUState* state) {
  return run(instance, "fmi3DeserializeFMUState", allowed::FMUState,
             [&](Instance& i) { return i.deserializeState(reinterpret_cast<const char*>(bytes), size, state); });
}

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[], size_t nUnknowns,
                                        const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[],
                                        size_t nSeed, fmi3Float64 sensitivity[], size_t nSensitivity) {
  return run(instance, "fmi3GetDirectionalDerivative", allowed::GetDirectionalDerivative, [&](Instance& i) {
    if (nSeed != nKnowns || nSensitivity != nUnknowns)
      return i.error(
          "nSeed must equal nKnowns and nSensitivity nUnknowns "
          "(every variable is a scalar), got " +
          std::to_string(nSeed) + "/" + std::to_string(nKnowns) + " and " + std::to_string(nSensitivity) + "/" +
          std::to_string(nUnknowns));
    return i.getDirectionalDerivative(unknowns, nUnknowns, knowns, nKnowns, seed, sensitivity);
  });
}
fmi3Status fmi3GetAdjointDerivative(fmi3Instance instance, const fmi3ValueReference[], size_t,
                                    const fmi3ValueReference[], size_t, const fmi3Float64[], size_t, fmi3Float64[],
                                    size_t) {
  return unsupported(instance, "fmi3GetAdjointDerivative", "providesAdjointDerivatives is false");
}

fmi3Status fmi3GetOutputDerivatives(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                    const fmi3Int32 orders[], fmi3Float64 values[], size_t nValues) {
  return run(instance, "fmi3GetOutputDerivatives", allowed::GetOutputDerivatives, [&](Instance& i) {
    if (!scalars(i, nvr, nValues)) return Status::Error;
    return i.getOutputDerivatives(vr, nvr, orders, values);
  });
}

// ---- the step ----------------------------------------------------------------------------

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint, fmi3Float64 communicationStepSize,
                      fmi3Boolean, fmi3Boolean* eventHandlingNeeded, fmi3Boolean* terminateSimulation,
                      fmi3Boolean* earlyReturn, fmi3Float64* lastSuccessfulTime) {
  return run(instance, "fmi3DoStep", allowed::DoStep, [&](Instance& i) {
    if (!eventHandlingNeeded || !terminateSimulation || !earlyReturn || !lastSuccessfulTime)
      return i.error(
          "eventHandlingNeeded, terminateSimulation, earlyReturn and lastSuccessfulTime "
          "must not be NULL");
    const Status s = i.doStep(currentCommunicationPoint, communicationStepSize, fmuOf(instance)->earlyReturnAllowed);
    *eventHandlingNeeded = fmi3False;
    *earlyReturn = i.returnedEarly() ? fmi3True : fmi3False;
    *terminateSimulation = i.wantsToTerminate() ? fmi3True : fmi3False;
    *lastSuccessfulTime = i.lastSuccessfulTime();
    return s;
  });
}

fmi3Status fmi3EnterStepMode(fmi3Instance instance) {
  return unsupported(instance, "fmi3EnterStepMode", "without Event Mode the FMU is in Step Mode after initialisation");
}
fmi3Status fmi3ActivateModelPartition(fmi3Instance instance, fmi3ValueReference, fmi3Float64) {
  return unsupported(instance, "fmi3ActivateModelPartition", "Scheduled Execution is not implemented");
}

// ---- interfaces this FMU does not implement ---------------------------------------------------

fmi3Status fmi3EnterConfigurationMode(fmi3Instance instance) {
  return unsupported(instance, "fmi3EnterConfigurationMode", "this FMU has no structural parameters");
}
fmi3Status fmi3ExitConfigurationMode(fmi3Instance instance) {
  return unsupported(instance, "fmi3ExitConfigurationMode", "this FMU has no structural parameters");
}
fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance instance) {
  return unsupported(instance, "fmi3EvaluateDiscreteStates", "this FMU has no clocks");
}
fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance) {
  return unsupported(instance, "fmi3EnterContinuousTimeMode", "this FMU implements Co-Simulation only");
}

#define RIGIDFMU_UNSUPPORTED(Name, Why, ...) \
  fmi3Status fmi3##Name(fmi3Instance instance, __VA_ARGS__) { return unsupported(instance, "fmi3" #Name, Why); }
#define RIGIDFMU_NO_CLOCKS "this FMU has no clocks"
#define RIGIDFMU_NO_ME "this FMU implements Co-Simulation only"
RIGIDFMU_UNSUPPORTED(GetIntervalDecimal, RIGIDFMU_NO_CLOCKS, const fmi3ValueReference[], size_t, fmi3Float64[],
                     fmi3IntervalQualifier[])
RIGIDFMU_UNSUPPORTED(GetIntervalFraction, RIGIDFMU_NO_CLOCKS, const fmi3ValueReference[], size_t, fmi3UInt64[],
                     fmi3UInt64[], fmi3IntervalQualifier[])
RIGIDFMU_UNSUPPORTED(GetShiftDecimal, RIGIDFMU_NO_CLOCKS, const fmi3ValueReference[], size_t, fmi3Float64[])
RIGIDFMU_UNSUPPORTED(GetShiftFraction, RIGIDFMU_NO_CLOCKS, const fmi3ValueReference[], size_t, fmi3UInt64[],
                     fmi3UInt64[])
RIGIDFMU_UNSUPPORTED(SetIntervalDecimal, RIGIDFMU_NO_CLOCKS, const fmi3ValueReference[], size_t, const fmi3Float64[])
RIGIDFMU_UNSUPPORTED(SetIntervalFraction, RIGIDFMU_NO_CLOCKS, const fmi3ValueReference[], size_t, const fmi3UInt64[],
                     const fmi3UInt64[])
RIGIDFMU_UNSUPPORTED(SetShiftDecimal, RIGIDFMU_NO_CLOCKS, const fmi3ValueReference[], size_t, const fmi3Float64[])
RIGIDFMU_UNSUPPORTED(SetShiftFraction, RIGIDFMU_NO_CLOCKS, const fmi3ValueReference[], size_t, const fmi3UInt64[],
                     const fmi3UInt64[])
RIGIDFMU_UNSUPPORTED(UpdateDiscreteStates, "hasEventMode is false", fmi3Boolean*, fmi3Boolean*, fmi3Boolean*,
                     fmi3Boolean*, fmi3Boolean*, fmi3Float64*)
RIGIDFMU_UNSUPPORTED(CompletedIntegratorStep, RIGIDFMU_NO_ME, fmi3Boolean, fmi3Boolean*, fmi3Boolean*)
RIGIDFMU_UNSUPPORTED(SetTime, RIGIDFMU_NO_ME, fmi3Float64)
RIGIDFMU_UNSUPPORTED(SetContinuousStates, RIGIDFMU_NO_ME, const fmi3Float64[], size_t)
RIGIDFMU_UNSUPPORTED(GetContinuousStateDerivatives, RIGIDFMU_NO_ME, fmi3Float64[], size_t)
RIGIDFMU_UNSUPPORTED(GetEventIndicators, RIGIDFMU_NO_ME, fmi3Float64[], size_t)
RIGIDFMU_UNSUPPORTED(GetContinuousStates, RIGIDFMU_NO_ME, fmi3Float64[], size_t)
RIGIDFMU_UNSUPPORTED(GetNominalsOfContinuousStates, RIGIDFMU_NO_ME, fmi3Float64[], size_t)
RIGIDFMU_UNSUPPORTED(GetNumberOfEventIndicators, RIGIDFMU_NO_ME, size_t*)
RIGIDFMU_UNSUPPORTED(GetNumberOfContinuousStates, RIGIDFMU_NO_ME, size_t*)
#undef RIGIDFMU_UNSUPPORTED
#undef RIGIDFMU_NO_CLOCKS
#undef RIGIDFMU_NO_ME

}  // extern "C"
