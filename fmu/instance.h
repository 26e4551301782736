// One FMU instance: the FMI 2.0 co-simulation state machine around a world.
// Owns everything it uses (no global mutable state), so instances run side by side
// in threads.
#pragma once

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "fmi2Functions.h"
#include "scene.h"
#include "snapshot.h"
#include "variables.h"

namespace rigidfmu {

// The states of the FMI 2.0 co-simulation state machine, as bits so that each
// function can name the states it is allowed in.
enum StateBits : unsigned {
  kInstantiated = 1u << 0,
  kInitializationMode = 1u << 1,
  kStepComplete = 1u << 2,  // slaveInitialized, ready for fmi2DoStep
  kStepFailed = 1u << 3,    // after fmi2Discard
  kTerminated = 1u << 4,
  kError = 1u << 5,
};

class Instance {
 public:
  // Reads the scene from the resources and checks the GUID; on failure logs why
  // through the callbacks' logger and returns nullptr.
  // `function` names the caller in those messages (fmi2Instantiate, or the FMI 3
  // adapter's fmi3InstantiateCoSimulation).
  static Instance* create(fmi2String instanceName, int type, fmi2String guid, fmi2String resourceLocation,
                          const fmi2CallbackFunctions* functions, fmi2Boolean loggingOn,
                          const char* function = "fmi2Instantiate");

  // The scene's variables, in value-reference order (the FMI 3 adapter checks types).
  const std::vector<Variable>& variables() const { return vars_; }

  // Refuses (fmi2Error, logged) a call made in a state outside `allowed`.
  bool allowedIn(unsigned allowed, const char* function);

  fmi2Status setDebugLogging(fmi2Boolean loggingOn, size_t n, const fmi2String categories[]);
  fmi2Status setupExperiment(fmi2Boolean toleranceDefined, fmi2Real tolerance, fmi2Real startTime,
                             fmi2Boolean stopTimeDefined, fmi2Real stopTime);
  fmi2Status enterInitializationMode();
  fmi2Status exitInitializationMode();
  fmi2Status terminate();
  fmi2Status reset();

  fmi2Status getReal(const fmi2ValueReference vr[], size_t n, fmi2Real value[]);
  fmi2Status getInteger(const fmi2ValueReference vr[], size_t n, fmi2Integer value[]);
  fmi2Status setReal(const fmi2ValueReference vr[], size_t n, const fmi2Real value[]);
  fmi2Status setInteger(const fmi2ValueReference vr[], size_t n, const fmi2Integer value[]);
  // Boolean and String: the FMU has no such variables; any reference is unknown.
  fmi2Status noVariablesOfType(const char* function, const fmi2ValueReference vr[], size_t n);

  // With returnEarlyAtImpact (FMI 3, earlyReturnAllowed), the step ends at the first
  // bouncing impact inside it, the impulse applied; returnedEarly() then says so and
  // the FMU's time is that instant.
  fmi2Status doStep(fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                    bool returnEarlyAtImpact = false);
  bool returnedEarly() const { return returnedEarly_; }

  // Directional derivatives of outputs after the next step with respect to inputs.
  fmi2Status getDirectionalDerivative(const fmi2ValueReference unknown[], size_t nUnknown,
                                      const fmi2ValueReference known[], size_t nKnown, const fmi2Real dvKnown[],
                                      fmi2Real dvUnknown[]);

  // First-order input derivatives (canInterpolateInputs) and output derivatives
  // (MaxOutputDerivativeOrder = 1).
  fmi2Status setInputDerivatives(const fmi2ValueReference vr[], size_t n, const fmi2Integer order[],
                                 const fmi2Real value[]);
  fmi2Status getOutputDerivatives(const fmi2ValueReference vr[], size_t n, const fmi2Integer order[], fmi2Real value[]);

  // FMU states: snapshots owned by this instance (freed with it).
  fmi2Status getState(fmi2FMUstate* state);
  fmi2Status setState(fmi2FMUstate state);
  fmi2Status freeState(fmi2FMUstate* state);
  fmi2Status serializedStateSize(fmi2FMUstate state, size_t* size);
  fmi2Status serializeState(fmi2FMUstate state, fmi2Byte bytes[], size_t size);
  fmi2Status deserializeState(const fmi2Byte bytes[], size_t size, fmi2FMUstate* state);

  fmi2Status getRealStatus(int kind, fmi2Real* value);  // kind: an fmi2StatusKind's bits
  fmi2Status getBooleanStatus(int kind, fmi2Boolean* value);

  // Logs with a status; errors, discards and warnings always reach the logger, other
  // categories only when debug logging has them on.
  void log(fmi2Status status, const char* category, const std::string& message) const;
  // Logs an error and returns fmi2Error.
  fmi2Status error(const std::string& message) const;
  // The same, the message after the name of the function that refused (called()).
  fmi2Status error(const char* function, const std::string& message) const;
  // The FMI 3 adapter names each call it makes on this instance (fmi3DoStep, ...):
  // the messages of the FMI 2 functions it maps onto then name the function the
  // importer called, not fmi2DoStep. An FMI 2 instance names none.
  void nameCall(const char* fmi3Function) { call_ = fmi3Function; }
  const char* called(const char* fmi2Function) const { return call_ ? call_ : fmi2Function; }
  void enterErrorState() { state_ = kError; }

 private:
  Instance(std::string name, const fmi2CallbackFunctions& functions, bool loggingOn, rigid::Scene scene);

  void restart();  // the just-instantiated state
  // The variable behind vr if it exists and has the given type; logs otherwise.
  // Real access takes Real variables; integer access Integer and Enumeration ones.
  const Variable* lookup(const char* function, fmi2ValueReference vr, bool integer) const;
  // Whether a variable may be written in the current state; logs otherwise.
  bool writable(const Variable& v) const;
  fmi2Status write(const Variable& v, double value);
  double read(const Variable& v) const;
  bool setupPhase() const { return state_ & (kInstantiated | kInitializationMode); }
  // Integrates the world over the next h seconds in internal steps of solver.step,
  // inputs ramped by their derivatives; reports sub-stepping in the log if asked.
  struct Interval {
    rigid::StepResult result;
    double from = 0.0, to = 0.0;  // s, the internal step that failed, from the start
    double impactAt = -1.0;       // s from the start: where an early return stopped
  };
  Interval advance(double h, bool report, bool stopAtImpact = false);
  // fmi2DoStep's arguments and the parameters set since the last step: fmi2OK, or
  // the error logged that names the argument or parameter and its limit.
  fmi2Status checkStep(fmi2Real tc, fmi2Real h) const;
  // A failed internal step of the communication step from tc: the FMU stays at the
  // last internal step it completed, in StepFailed; logs why and returns fmi2Discard.
  fmi2Status discardStep(fmi2Real tc, const Interval& run);
  // Why an internal step of that length failed, and what would have worked.
  std::string stepFailure(const rigid::StepResult& r, double internalStep) const;
  // Logs when the sub-stepping of the internal steps starts, changes or stops.
  void noteSubsteps(const rigid::StepResult& r, double h);

  std::string name_;
  fmi2CallbackFunctions functions_;
  bool loggingOn_;
  std::set<std::string> categories_;  // enabled debug categories
  const char* call_ = nullptr;        // the FMI 3 call in progress (nameCall), a literal

  rigid::Scene scene_;  // as read from the resources, for fmi2Reset
  std::vector<Variable> vars_;
  rigid::WorldModel model_;  // the scene's constants with parameters applied
  rigid::WorldData data_;

  unsigned state_ = kInstantiated;
  double startTime_ = 0.0;  // s
  double time_ = 0.0;       // s, time of the last communication point
  double lastSuccessfulTime_ = 0.0;
  bool wantsToTerminate_ = false;  // fmi2Terminated status
  bool returnedEarly_ = false;     // the last step ended at an impact (FMI 3 early return)
  std::string substepNote_;        // the sub-stepping last reported ("cause:count")
  std::string guid_;               // of the scene: checked when a state is deserialised
  double lastStepSize_ = 0.0;      // s, the last communication step (directional derivatives)
  // FMU states handed out, so that a pointer that is not one of them is refused.
  std::set<Snapshot*> states_;
  std::vector<std::unique_ptr<Snapshot>> owned_;
  Snapshot* ownState(fmi2FMUstate state, const char* function) const;
};

}  // namespace rigidfmu
