// The FMI 3.0 Co-Simulation entry points, over the same Instance as the FMI 2 ones:
// one state machine (fmi3_states.h names the states each function may be called in),
// one step, one snapshot format. What differs is only the calling convention: the
// instance handle carries the FMI 3 logger (the Instance logs through an FMI 2
// callback that forwards to it), the resource path is turned into the file URI the
// Instance reads, and Enumeration variables travel through fmi3Get/SetInt64.
// Every variable is a scalar (docs/scene-format.md, "FMI 3.0"): value references,
// names, units and descriptions are those of the FMI 2 FMU. With the master's
// permission (earlyReturnAllowed), fmi3DoStep returns early at the first bouncing
// impact inside the step: earlyReturn and lastSuccessfulTime = the impact's instant.
#include <cctype>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "entry_guard.h"
#include "fmi3Functions.h"
#include "fmi3_states.h"
#include "instance.h"

using rigidfmu::BaseType;
using rigidfmu::Instance;
namespace allowed = rigidfmu::fmi3_allowed;

static_assert(int(fmi3OK) == int(fmi2OK) && int(fmi3Warning) == int(fmi2Warning) &&
                  int(fmi3Discard) == int(fmi2Discard) && int(fmi3Error) == int(fmi2Error) &&
                  int(fmi3Fatal) == int(fmi2Fatal),
              "FMI 3 statuses are FMI 2's, value for value");
static_assert(sizeof(fmi3ValueReference) == sizeof(fmi2ValueReference), "value references of one size");
static_assert(sizeof(fmi3Int32) == sizeof(fmi2Integer), "Int32 is FMI 2's Integer");

namespace {

// What fmi3InstantiateCoSimulation hands out: the Instance and the master's logger.
struct Fmi3Instance {
  fmi3InstanceEnvironment environment = nullptr;
  fmi3LogMessageCallback logMessage = nullptr;
  std::string name;
  bool earlyReturnAllowed = false;  // the master's permission (fmi3InstantiateCoSimulation)
  std::unique_ptr<Instance> core;
};

// The Instance's FMI 2 logger: the formatted message to the FMI 3 one.
void forwardLog(fmi2ComponentEnvironment env, fmi2String, fmi2Status status, fmi2String category, fmi2String message,
                ...) {
  const auto* fmu = static_cast<const Fmi3Instance*>(env);
  if (!fmu || !fmu->logMessage) return;
  va_list args;
  va_start(args, message);
  va_list again;
  va_copy(again, args);
  const int n = std::vsnprintf(nullptr, 0, message, args);
  va_end(args);
  std::string text(n > 0 ? static_cast<size_t>(n) : 0, '\0');
  if (n > 0) std::vsnprintf(text.data(), text.size() + 1, message, again);
  va_end(again);
  fmu->logMessage(fmu->environment, static_cast<fmi3Status>(status), category, text.c_str());
}

void* allocate(size_t n, size_t size) { return std::calloc(n, size); }

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

// guarded() of the FMI 2 entry points, for an FMI 3 instance handle.
template <class Body>
fmi3Status run(fmi3Instance instance, const char* function, unsigned states, Body body) {
  Fmi3Instance* fmu = fmuOf(instance);
  if (!fmu || !fmu->core) return fmi3Error;
  fmu->core->nameCall(function);
  return static_cast<fmi3Status>(rigidfmu::guarded(fmu->core.get(), function, states, body));
}

fmi3Status unsupported(fmi3Instance instance, const char* function, const char* why) {
  Fmi3Instance* fmu = fmuOf(instance);
  if (!fmu || !fmu->core) return fmi3Error;
  return static_cast<fmi3Status>(rigidfmu::unsupported(fmu->core.get(), function, allowed::Unsupported, why));
}

// nValues must equal nValueReferences: every variable is a scalar.
bool scalars(Instance& i, const char* function, size_t nvr, size_t nValues) {
  if (nvr == nValues) return true;
  i.error(std::string(function) + ": nValues = " + std::to_string(nValues) +
          " but nValueReferences = " + std::to_string(nvr) + ": every variable of this FMU is a scalar");
  return false;
}

const char* useFor(BaseType t) {
  return t == BaseType::Real      ? "is a Float64, use fmi3Get/SetFloat64"
         : t == BaseType::Integer ? "is an Int32, use fmi3Get/SetInt32"
                                  : "is an Enumeration, use fmi3Get/SetInt64";
}

// Whether every reference is a variable of `type` (FMI 3 accessors are typed: Int32
// for Integer variables, Int64 for the Enumeration); refuses the first that is not.
bool allOfType(Instance& i, const char* function, const fmi3ValueReference vr[], size_t n, BaseType type,
               const char* use) {
  const auto& vars = i.variables();
  for (size_t k = 0; k < n; ++k) {
    if (vr[k] >= vars.size()) {
      i.error(std::string(function) + ": unknown value reference " + std::to_string(vr[k]) + " (this FMU has 0.." +
              std::to_string(vars.size() - 1) + ")");
      return false;
    }
    const auto& v = vars[vr[k]];
    if (v.type != type) {
      i.error(std::string(function) + ": value reference " + std::to_string(vr[k]) + " (" + v.name + ") " + use +
              ": it " + useFor(v.type));
      return false;
    }
  }
  return true;
}

// Accessors of types this FMU has no variables of: every reference is unknown.
fmi3Status noVariables(fmi3Instance instance, const char* function, unsigned states, const fmi3ValueReference vr[],
                       size_t n) {
  return run(instance, function, states, [&](Instance& i) { return i.noVariablesOfType(function, vr, n); });
}

}  // namespace

extern "C" {

const char* fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[]) {
  return run(instance, "fmi3SetDebugLogging", allowed::SetDebugLogging,
             [&](Instance& i) { return i.setDebugLogging(loggingOn ? fmi2True : fmi2False, nCategories, categories); });
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
    fmu->environment = environment;
    fmu->logMessage = logMessage;
    fmu->earlyReturnAllowed = earlyReturnAllowed == fmi3True;
    fmi2CallbackFunctions callbacks = {forwardLog, allocate, std::free, nullptr, fmu.get()};
    const std::string uri = fileUri(resourcePath);
    fmu->core.reset(Instance::create(instanceName, fmi2CoSimulation, instantiationToken, uri.c_str(), &callbacks,
                                     loggingOn ? fmi2True : fmi2False, "fmi3InstantiateCoSimulation"));
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
                                       fmi3Float64 startTime, fmi3Boolean stopTimeDefined, fmi3Float64 stopTime) {
  return run(instance, "fmi3EnterInitializationMode", allowed::EnterInitializationMode, [&](Instance& i) {
    const fmi2Status s = i.setupExperiment(toleranceDefined ? fmi2True : fmi2False, tolerance, startTime,
                                           stopTimeDefined ? fmi2True : fmi2False, stopTime);
    return s == fmi2OK ? i.enterInitializationMode() : s;
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
    if (!scalars(i, "fmi3GetFloat64", nvr, nValues)) return fmi2Error;
    if (!allOfType(i, "fmi3GetFloat64", vr, nvr, BaseType::Real, "is not a Float64")) return fmi2Error;
    return i.getReal(vr, nvr, values);
  });
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, const fmi3Float64 values[],
                          size_t nValues) {
  return run(instance, "fmi3SetFloat64", allowed::Set, [&](Instance& i) {
    if (!scalars(i, "fmi3SetFloat64", nvr, nValues)) return fmi2Error;
    if (!allOfType(i, "fmi3SetFloat64", vr, nvr, BaseType::Real, "is not a Float64")) return fmi2Error;
    return i.setReal(vr, nvr, values);
  });
}

fmi3Status fmi3GetInt32(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, fmi3Int32 values[],
                        size_t nValues) {
  return run(instance, "fmi3GetInt32", allowed::Get, [&](Instance& i) {
    if (!scalars(i, "fmi3GetInt32", nvr, nValues)) return fmi2Error;
    if (!allOfType(i, "fmi3GetInt32", vr, nvr, BaseType::Integer, "is not an Int32")) return fmi2Error;
    return i.getInteger(vr, nvr, values);
  });
}

fmi3Status fmi3SetInt32(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, const fmi3Int32 values[],
                        size_t nValues) {
  return run(instance, "fmi3SetInt32", allowed::Set, [&](Instance& i) {
    if (!scalars(i, "fmi3SetInt32", nvr, nValues)) return fmi2Error;
    if (!allOfType(i, "fmi3SetInt32", vr, nvr, BaseType::Integer, "is not an Int32")) return fmi2Error;
    return i.setInteger(vr, nvr, values);
  });
}

// The Enumeration (solver.method) travels as Int64 (FMI 3.0, section 2.4.7.5).
fmi3Status fmi3GetInt64(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, fmi3Int64 values[],
                        size_t nValues) {
  return run(instance, "fmi3GetInt64", allowed::Get, [&](Instance& i) {
    if (!scalars(i, "fmi3GetInt64", nvr, nValues)) return fmi2Error;
    if (!allOfType(i, "fmi3GetInt64", vr, nvr, BaseType::Enumeration,
                   "is not an Enumeration (the Int64 accessor "
                   "reads Enumerations only)"))
      return fmi2Error;
    std::vector<fmi2Integer> read(nvr);
    const fmi2Status s = i.getInteger(vr, nvr, read.data());
    if (s == fmi2OK)
      for (size_t k = 0; k < nvr; ++k) values[k] = read[k];
    return s;
  });
}

fmi3Status fmi3SetInt64(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, const fmi3Int64 values[],
                        size_t nValues) {
  return run(instance, "fmi3SetInt64", allowed::Set, [&](Instance& i) {
    if (!scalars(i, "fmi3SetInt64", nvr, nValues)) return fmi2Error;
    if (!allOfType(i, "fmi3SetInt64", vr, nvr, BaseType::Enumeration,
                   "is not an Enumeration (the Int64 accessor "
                   "writes Enumerations only)"))
      return fmi2Error;
    std::vector<fmi2Integer> narrow(nvr);
    for (size_t k = 0; k < nvr; ++k) {
      if (values[k] < std::numeric_limits<fmi2Integer>::min() || values[k] > std::numeric_limits<fmi2Integer>::max())
        return i.error("fmi3SetInt64: " + i.variables()[vr[k]].name + " = " + std::to_string(values[k]) +
                       " is not one of its items");
      narrow[k] = static_cast<fmi2Integer>(values[k]);
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
             [&](Instance& i) { return i.serializeState(state, reinterpret_cast<fmi2Byte*>(bytes), size); });
}
fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte bytes[], size_t size, fmi3FMUState* state) {
  return run(instance, "fmi3DeserializeFMUState", allowed::FMUState,
             [&](Instance& i) { return i.deserializeState(reinterpret_cast<const fmi2Byte*>(bytes), size, state); });
}

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[], size_t nUnknowns,
                                        const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[],
                                        size_t nSeed, fmi3Float64 sensitivity[], size_t nSensitivity) {
  return run(instance, "fmi3GetDirectionalDerivative", allowed::GetDirectionalDerivative, [&](Instance& i) {
    if (nSeed != nKnowns || nSensitivity != nUnknowns)
      return i.error(
          "fmi3GetDirectionalDerivative: nSeed must equal nKnowns and nSensitivity nUnknowns "
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
    if (!scalars(i, "fmi3GetOutputDerivatives", nvr, nValues)) return fmi2Error;
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
          "fmi3DoStep: eventHandlingNeeded, terminateSimulation, earlyReturn and lastSuccessfulTime "
          "must not be NULL");
    const fmi2Status s =
        i.doStep(currentCommunicationPoint, communicationStepSize, fmuOf(instance)->earlyReturnAllowed);
    fmi2Real reached = 0.0;
    fmi2Boolean terminated = fmi2False;
    i.getRealStatus(fmi2LastSuccessfulTime, &reached);
    i.getBooleanStatus(fmi2Terminated, &terminated);
    *eventHandlingNeeded = fmi3False;
    *earlyReturn = i.returnedEarly() ? fmi3True : fmi3False;
    *terminateSimulation = terminated == fmi2True ? fmi3True : fmi3False;
    *lastSuccessfulTime = reached;
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
