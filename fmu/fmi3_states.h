// The FMI 3.0 co-simulation state machine as one table, in the Instance's states (as
// the FMI 2 one, fmi2_states.h): Instantiated, Initialization Mode, Step Mode (the
// Instance's kStepComplete, and kStepFailed after a discarded step), Terminated and
// the Error state (FMI 3.0, section 4.1, the co-simulation state machine without Event
// Mode and Configuration Mode, which this FMU does not have). A call in any other state
// is refused with fmi3Error and a message naming the function and the state.
#pragma once

#include "instance.h"

namespace rigidfmu::fmi3_allowed {

constexpr unsigned kAny = kInstantiated | kInitializationMode | kStepComplete | kStepFailed | kTerminated | kError;
constexpr unsigned kStepMode = kStepComplete | kStepFailed;
constexpr unsigned kGet = kInitializationMode | kStepMode | kTerminated | kError;
constexpr unsigned kSet = kInstantiated | kInitializationMode | kStepComplete;

constexpr unsigned SetDebugLogging = kAny;
constexpr unsigned EnterInitializationMode = kInstantiated;
constexpr unsigned ExitInitializationMode = kInitializationMode;
constexpr unsigned Terminate = kStepMode;
constexpr unsigned Reset = kAny;
constexpr unsigned Get = kGet;
constexpr unsigned Set = kSet;
constexpr unsigned FMUState = kAny;  // get, set, free, (de)serialise: a master rolls back from any state
constexpr unsigned GetDirectionalDerivative = kStepComplete;
constexpr unsigned GetOutputDerivatives = kStepMode | kTerminated;
constexpr unsigned DoStep = kStepComplete;
constexpr unsigned Unsupported = kAny;  // answered "not supported" in any state

}  // namespace rigidfmu::fmi3_allowed
