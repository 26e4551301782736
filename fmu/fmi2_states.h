// The FMI 2.0 co-simulation state machine as one table: for each function, the states
// it may be called in (FMI 2.0.4, section 4.2.4, the table of calling sequences for
// co-simulation). A call in any other state is refused with fmi2Error and a message
// naming the function and the state (Instance::enter). fmi2Instantiate,
// fmi2FreeInstance and the platform/version queries take no instance and are always
// allowed.
#pragma once

#include "instance.h"

namespace rigidfmu::fmi2_allowed {

constexpr unsigned kAny = kInstantiated | kInitializationMode | kStepComplete | kStepFailed | kTerminated | kError;
constexpr unsigned kGet = kInitializationMode | kStepComplete | kStepFailed | kTerminated | kError;
constexpr unsigned kSet = kInstantiated | kInitializationMode | kStepComplete;
constexpr unsigned kStatus = kStepComplete | kStepFailed | kTerminated;

constexpr unsigned SetDebugLogging = kAny;
constexpr unsigned SetupExperiment = kInstantiated;
constexpr unsigned EnterInitializationMode = kInstantiated;
constexpr unsigned ExitInitializationMode = kInitializationMode;
constexpr unsigned Terminate = kStepComplete | kStepFailed;
constexpr unsigned Reset = kAny;
constexpr unsigned GetReal = kGet, GetInteger = kGet, GetBoolean = kGet, GetString = kGet;
constexpr unsigned SetReal = kSet, SetInteger = kSet, SetBoolean = kSet, SetString = kSet;
constexpr unsigned GetFMUstate = kAny, SetFMUstate = kAny, FreeFMUstate = kAny;
constexpr unsigned SerializedFMUstateSize = kAny, SerializeFMUstate = kAny, DeSerializeFMUstate = kAny;
constexpr unsigned GetDirectionalDerivative = kStepComplete;
constexpr unsigned SetRealInputDerivatives = kSet;
constexpr unsigned GetRealOutputDerivatives = kStepComplete | kStepFailed | kTerminated;
constexpr unsigned DoStep = kStepComplete;
constexpr unsigned CancelStep = kAny;  // answered "not supported" in any state
constexpr unsigned GetStatus = kStatus, GetRealStatus = kStatus, GetIntegerStatus = kStatus;
constexpr unsigned GetBooleanStatus = kStatus, GetStringStatus = kStatus;

}  // namespace rigidfmu::fmi2_allowed
