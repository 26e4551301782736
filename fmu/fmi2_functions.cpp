// The FMI 2.0 entry points: the FMI 2 names, types and statuses mapped onto the
// version-neutral Instance, a peer of fmi3_functions.cpp. Each checks the instance and
// the state it is called in (fmi2_states.h), forwards to Instance, and catches every
// exception here, at the C boundary.
#include <cstdint>
#include <cstring>
#include <exception>
#include <string>
#include <type_traits>
#include <utility>

#include "entry_guard.h"
#include "fmi2Functions.h"
#include "fmi2_states.h"
#include "instance.h"
#include "status.h"

using rigidfmu::BaseType;
using rigidfmu::Instance;
using rigidfmu::Status;
namespace allowed = rigidfmu::fmi2_allowed;

static_assert(std::is_same_v<fmi2ValueReference, uint32_t>, "value references are 32-bit unsigned");
static_assert(std::is_same_v<fmi2Integer, int32_t>, "fmi2Integer is 32-bit");
static_assert(std::is_same_v<fmi2Real, double> && std::is_same_v<fmi2Byte, char>, "Real is double, Byte char");
static_assert(std::is_same_v<fmi2FMUstate, void*>, "FMU states are opaque pointers");

namespace {

fmi2Status toFmi2(Status status) {
  switch (status) {
    case Status::OK: return fmi2OK;
    case Status::Warning: return fmi2Warning;
    case Status::Discard: return fmi2Discard;
    case Status::Error: return fmi2Error;
    case Status::Fatal: return fmi2Fatal;
  }
  return fmi2Fatal;
}

// The bits of an enumeration argument (fmi2Type, fmi2StatusKind) as an int. A master
// may pass any value, and reading one outside the enumeration's range as the enum type
// is undefined behaviour (UBSan reports it), so it is copied out and compared as an int.
template <class Enum>
int enumBits(const Enum& e) {
  static_assert(sizeof(Enum) == sizeof(int), "FMI enumerations are int-sized here");
  int bits;
  std::memcpy(&bits, &e, sizeof bits);
  return bits;
}

// The logger's message is a printf format: a literal '%' must be doubled.
std::string escapePercent(const std::string& s) {
  std::string out;
  for (char c : s) {
    out += c;
    if (c == '%') out += '%';
  }
  return out;
}

// The instance's messages to the importer's fmi2CallbackLogger, under its instance name.
rigidfmu::Logger loggerOf(const fmi2CallbackFunctions& functions, const std::string& instanceName) {
  if (!functions.logger) return nullptr;
  return [logger = functions.logger, environment = functions.componentEnvironment, instanceName](
             Status status, const char* category, const std::string& message) {
    logger(environment, instanceName.c_str(), toFmi2(status), category, escapePercent(message).c_str());
  };
}

const char* typeAdvice(BaseType type) {
  return type == BaseType::Real ? "a Real, use fmi2Get/SetReal" : "an Integer or Enumeration, use fmi2Get/SetInteger";
}

template <class Body>
fmi2Status run(fmi2Component c, const char* function, unsigned states, Body body) {
  return toFmi2(rigidfmu::guarded(static_cast<Instance*>(c), function, states, body));
}

fmi2Status unsupported(fmi2Component c, const char* function, unsigned states, const char* why) {
  return toFmi2(rigidfmu::unsupported(static_cast<Instance*>(c), function, states, why));
}

// A status the FMU does not provide: Discard, logged.
fmi2Status noStatus(fmi2Component c, const char* function, unsigned states, const char* why) {
  return run(c, function, states, [&](Instance& i) { return i.report(Status::Discard, why); });
}

}  // namespace

extern "C" {

const char* fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char* fmi2GetVersion(void) { return fmi2Version; }

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn) {
  (void)visible;                   // no user interface to show
  if (!functions) return nullptr;  // nowhere to report to; the standard requires them
  try {
    rigidfmu::Adapter adapter{loggerOf(*functions, instanceName ? instanceName : ""), typeAdvice,
                              "fmi2SerializedFMUstateSize"};
    // Only Co-Simulation (an empty instanceName is refused first, by Instance::create).
    if (instanceName && *instanceName && enumBits(fmuType) != fmi2CoSimulation) {
      if (adapter.logger)
        adapter.logger(Status::Error, "logStatusError",
                       "fmi2Instantiate: this FMU implements Co-Simulation only (fmuType = fmi2CoSimulation)");
      return nullptr;
    }
    return Instance::create("fmi2Instantiate", instanceName, fmuGUID, fmuResourceLocation, loggingOn == fmi2True,
                            std::move(adapter));
  } catch (const std::exception& e) {
    if (functions->logger)
      functions->logger(functions->componentEnvironment, instanceName ? instanceName : "", fmi2Error, "logStatusError",
                        "fmi2Instantiate failed: %s", e.what());
  } catch (...) {
  }
  return nullptr;
}

void fmi2FreeInstance(fmi2Component c) { delete static_cast<Instance*>(c); }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[]) {
  return run(c, "fmi2SetDebugLogging", allowed::SetDebugLogging,
             [&](Instance& i) { return i.setDebugLogging(loggingOn == fmi2True, nCategories, categories); });
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean /*stopTimeDefined*/, fmi2Real /*stopTime*/) {
  // no stop time: the FMU runs as long as it is stepped
  return run(c, "fmi2SetupExperiment", allowed::SetupExperiment,
             [&](Instance& i) { return i.setupExperiment(toleranceDefined != fmi2False, tolerance, startTime); });
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  return run(c, "fmi2EnterInitializationMode", allowed::EnterInitializationMode,
             [](Instance& i) { return i.enterInitializationMode(); });
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  return run(c, "fmi2ExitInitializationMode", allowed::ExitInitializationMode,
             [](Instance& i) { return i.exitInitializationMode(); });
}

fmi2Status fmi2Terminate(fmi2Component c) {
  return run(c, "fmi2Terminate", allowed::Terminate, [](Instance& i) { return i.terminate(); });
}

fmi2Status fmi2Reset(fmi2Component c) {
  return run(c, "fmi2Reset", allowed::Reset, [](Instance& i) { return i.reset(); });
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
  return run(c, "fmi2GetReal", allowed::GetReal, [&](Instance& i) { return i.getReal(vr, nvr, value); });
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]) {
  return run(c, "fmi2GetInteger", allowed::GetInteger, [&](Instance& i) { return i.getInteger(vr, nvr, value); });
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean[]) {
  return run(c, "fmi2GetBoolean", allowed::GetBoolean, [&](Instance& i) { return i.noVariablesOfType(vr, nvr); });
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String[]) {
  return run(c, "fmi2GetString", allowed::GetString, [&](Instance& i) { return i.noVariablesOfType(vr, nvr); });
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
  return run(c, "fmi2SetReal", allowed::SetReal, [&](Instance& i) { return i.setReal(vr, nvr, value); });
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[]) {
  return run(c, "fmi2SetInteger", allowed::SetInteger, [&](Instance& i) { return i.setInteger(vr, nvr, value); });
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean[]) {
  return run(c, "fmi2SetBoolean", allowed::SetBoolean, [&](Instance& i) { return i.noVariablesOfType(vr, nvr); });
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String[]) {
  return run(c, "fmi2SetString", allowed::SetString, [&](Instance& i) { return i.noVariablesOfType(vr, nvr); });
}

// FMU states may be taken and restored in every state of the instance: a master rolls
// back from a failed step as well as from a completed one.
fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* state) {
  return run(c, "fmi2GetFMUstate", allowed::GetFMUstate, [&](Instance& i) { return i.getState(state); });
}
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state) {
  return run(c, "fmi2SetFMUstate", allowed::SetFMUstate, [&](Instance& i) { return i.setState(state); });
}
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* state) {
  return run(c, "fmi2FreeFMUstate", allowed::FreeFMUstate, [&](Instance& i) { return i.freeState(state); });
}
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t* size) {
  return run(c, "fmi2SerializedFMUstateSize", allowed::SerializedFMUstateSize,
             [&](Instance& i) { return i.serializedStateSize(state, size); });
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte bytes[], size_t size) {
  return run(c, "fmi2SerializeFMUstate", allowed::SerializeFMUstate,
             [&](Instance& i) { return i.serializeState(state, bytes, size); });
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte bytes[], size_t size, fmi2FMUstate* state) {
  return run(c, "fmi2DeSerializeFMUstate", allowed::DeSerializeFMUstate,
             [&](Instance& i) { return i.deserializeState(bytes, size, state); });
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference unknown[], size_t nUnknown,
                                        const fmi2ValueReference known[], size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[]) {
  return run(c, "fmi2GetDirectionalDerivative", allowed::GetDirectionalDerivative, [&](Instance& i) {
    return i.getDirectionalDerivative(unknown, nUnknown, known, nKnown, dvKnown, dvUnknown);
  });
}
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[]) {
  return run(c, "fmi2SetRealInputDerivatives", allowed::SetRealInputDerivatives,
             [&](Instance& i) { return i.setInputDerivatives(vr, nvr, order, value); });
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[]) {
  return run(c, "fmi2GetRealOutputDerivatives", allowed::GetRealOutputDerivatives,
             [&](Instance& i) { return i.getOutputDerivatives(vr, nvr, order, value); });
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean) {
  return run(c, "fmi2DoStep", allowed::DoStep,
             [&](Instance& i) { return i.doStep(currentCommunicationPoint, communicationStepSize); });
}

fmi2Status fmi2CancelStep(fmi2Component c) {
  return unsupported(c, "fmi2CancelStep", allowed::CancelStep, "steps are synchronous, canRunAsynchronuously is false");
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind, fmi2Status*) {
  return noStatus(c, "fmi2GetStatus", allowed::GetStatus, "steps are synchronous, no pending status");
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
  return run(c, "fmi2GetRealStatus", allowed::GetRealStatus, [&](Instance& i) {
    if (!value) return i.error("value is NULL");
    if (enumBits(s) != fmi2LastSuccessfulTime)
      return i.report(Status::Discard, "only fmi2LastSuccessfulTime is provided");
    *value = i.lastSuccessfulTime();
    return Status::OK;
  });
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind, fmi2Integer*) {
  return noStatus(c, "fmi2GetIntegerStatus", allowed::GetIntegerStatus, "no integer status is provided");
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
  return run(c, "fmi2GetBooleanStatus", allowed::GetBooleanStatus, [&](Instance& i) {
    if (!value) return i.error("value is NULL");
    if (enumBits(s) != fmi2Terminated) return i.report(Status::Discard, "only fmi2Terminated is provided");
    *value = i.wantsToTerminate() ? fmi2True : fmi2False;
    return Status::OK;
  });
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind, fmi2String*) {
  return noStatus(c, "fmi2GetStringStatus", allowed::GetStringStatus, "steps are synchronous, no pending status");
}

}  // extern "C"
