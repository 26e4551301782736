// The FMI 2.0 entry points. Each checks the instance and the state it is called in,
// forwards to Instance, and catches every exception here, at the C boundary.
#include <exception>
#include <string>

#include "entry_guard.h"
#include "fmi2Functions.h"
#include "fmi2_states.h"
#include "instance.h"

using rigidfmu::enumBits;
using rigidfmu::guarded;
using rigidfmu::Instance;
using rigidfmu::unsupported;
namespace allowed = rigidfmu::fmi2_allowed;

extern "C" {

const char* fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char* fmi2GetVersion(void) { return fmi2Version; }

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn) {
  (void)visible;  // no user interface to show
  try {
    return Instance::create(instanceName, enumBits(fmuType), fmuGUID, fmuResourceLocation, functions, loggingOn);
  } catch (const std::exception& e) {
    if (functions && functions->logger)
      functions->logger(functions->componentEnvironment, instanceName ? instanceName : "", fmi2Error, "logStatusError",
                        "fmi2Instantiate failed: %s", e.what());
  } catch (...) {
  }
  return nullptr;
}

void fmi2FreeInstance(fmi2Component c) { delete static_cast<Instance*>(c); }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[]) {
  return guarded(c, "fmi2SetDebugLogging", allowed::SetDebugLogging,
                 [&](Instance& i) { return i.setDebugLogging(loggingOn, nCategories, categories); });
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
  return guarded(c, "fmi2SetupExperiment", allowed::SetupExperiment, [&](Instance& i) {
    return i.setupExperiment(toleranceDefined, tolerance, startTime, stopTimeDefined, stopTime);
  });
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  return guarded(c, "fmi2EnterInitializationMode", allowed::EnterInitializationMode,
                 [](Instance& i) { return i.enterInitializationMode(); });
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  return guarded(c, "fmi2ExitInitializationMode", allowed::ExitInitializationMode,
                 [](Instance& i) { return i.exitInitializationMode(); });
}

fmi2Status fmi2Terminate(fmi2Component c) {
  return guarded(c, "fmi2Terminate", allowed::Terminate, [](Instance& i) { return i.terminate(); });
}

fmi2Status fmi2Reset(fmi2Component c) {
  return guarded(c, "fmi2Reset", allowed::Reset, [](Instance& i) { return i.reset(); });
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
  return guarded(c, "fmi2GetReal", allowed::GetReal, [&](Instance& i) { return i.getReal(vr, nvr, value); });
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]) {
  return guarded(c, "fmi2GetInteger", allowed::GetInteger, [&](Instance& i) { return i.getInteger(vr, nvr, value); });
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean[]) {
  return guarded(c, "fmi2GetBoolean", allowed::GetBoolean,
                 [&](Instance& i) { return i.noVariablesOfType("fmi2GetBoolean", vr, nvr); });
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String[]) {
  return guarded(c, "fmi2GetString", allowed::GetString,
                 [&](Instance& i) { return i.noVariablesOfType("fmi2GetString", vr, nvr); });
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
  return guarded(c, "fmi2SetReal", allowed::SetReal, [&](Instance& i) { return i.setReal(vr, nvr, value); });
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[]) {
  return guarded(c, "fmi2SetInteger", allowed::SetInteger, [&](Instance& i) { return i.setInteger(vr, nvr, value); });
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean[]) {
  return guarded(c, "fmi2SetBoolean", allowed::SetBoolean,
                 [&](Instance& i) { return i.noVariablesOfType("fmi2SetBoolean", vr, nvr); });
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String[]) {
  return guarded(c, "fmi2SetString", allowed::SetString,
                 [&](Instance& i) { return i.noVariablesOfType("fmi2SetString", vr, nvr); });
}

// FMU states may be taken and restored in every state of the instance: a master rolls
// back from a failed step as well as from a completed one.
fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* state) {
  return guarded(c, "fmi2GetFMUstate", allowed::GetFMUstate, [&](Instance& i) { return i.getState(state); });
}
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state) {
  return guarded(c, "fmi2SetFMUstate", allowed::SetFMUstate, [&](Instance& i) { return i.setState(state); });
}
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* state) {
  return guarded(c, "fmi2FreeFMUstate", allowed::FreeFMUstate, [&](Instance& i) { return i.freeState(state); });
}
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t* size) {
  return guarded(c, "fmi2SerializedFMUstateSize", allowed::SerializedFMUstateSize,
                 [&](Instance& i) { return i.serializedStateSize(state, size); });
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte bytes[], size_t size) {
  return guarded(c, "fmi2SerializeFMUstate", allowed::SerializeFMUstate,
                 [&](Instance& i) { return i.serializeState(state, bytes, size); });
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte bytes[], size_t size, fmi2FMUstate* state) {
  return guarded(c, "fmi2DeSerializeFMUstate", allowed::DeSerializeFMUstate,
                 [&](Instance& i) { return i.deserializeState(bytes, size, state); });
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference unknown[], size_t nUnknown,
                                        const fmi2ValueReference known[], size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[]) {
  return guarded(c, "fmi2GetDirectionalDerivative", allowed::GetDirectionalDerivative, [&](Instance& i) {
    return i.getDirectionalDerivative(unknown, nUnknown, known, nKnown, dvKnown, dvUnknown);
  });
}
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[]) {
  return guarded(c, "fmi2SetRealInputDerivatives", allowed::SetRealInputDerivatives,
                 [&](Instance& i) { return i.setInputDerivatives(vr, nvr, order, value); });
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[]) {
  return guarded(c, "fmi2GetRealOutputDerivatives", allowed::GetRealOutputDerivatives,
                 [&](Instance& i) { return i.getOutputDerivatives(vr, nvr, order, value); });
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean) {
  return guarded(c, "fmi2DoStep", allowed::DoStep,
                 [&](Instance& i) { return i.doStep(currentCommunicationPoint, communicationStepSize); });
}

fmi2Status fmi2CancelStep(fmi2Component c) {
  return unsupported(c, "fmi2CancelStep", allowed::CancelStep, "steps are synchronous, canRunAsynchronuously is false");
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind, fmi2Status*) {
  return guarded(c, "fmi2GetStatus", allowed::GetStatus, [](Instance& i) {
    i.log(fmi2Discard, "logStatusDiscard", "fmi2GetStatus: steps are synchronous, no pending status");
    return fmi2Discard;
  });
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
  return guarded(c, "fmi2GetRealStatus", allowed::GetRealStatus,
                 [&](Instance& i) { return i.getRealStatus(enumBits(s), value); });
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind, fmi2Integer*) {
  return guarded(c, "fmi2GetIntegerStatus", allowed::GetIntegerStatus, [](Instance& i) {
    i.log(fmi2Discard, "logStatusDiscard", "fmi2GetIntegerStatus: no integer status is provided");
    return fmi2Discard;
  });
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
  return guarded(c, "fmi2GetBooleanStatus", allowed::GetBooleanStatus,
                 [&](Instance& i) { return i.getBooleanStatus(enumBits(s), value); });
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind, fmi2String*) {
  return guarded(c, "fmi2GetStringStatus", allowed::GetStringStatus, [](Instance& i) {
    i.log(fmi2Discard, "logStatusDiscard", "fmi2GetStringStatus: steps are synchronous, no pending status");
    return fmi2Discard;
  });
}

}  // extern "C"
