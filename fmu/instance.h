// One FMU instance: the co-simulation state machine around a world, in no FMI
// version's types (Reference-FMUs' model instance): fmi2_functions.cpp and
// fmi3_functions.cpp are peers that map their version's names, types and statuses onto
// it. Owns everything it uses (no global mutable state), so instances run side by side
// in threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "communication_clock.h"
#include "scene.h"
#include "snapshot.h"
#include "status.h"
#include "variables.h"

namespace rigidfmu {

// The states of the co-simulation state machine, as bits so that each function can
// name the states it is allowed in (fmi2_states.h, fmi3_states.h).
enum StateBits : unsigned {
  kInstantiated = 1u << 0,
  kInitializationMode = 1u << 1,
  kStepComplete = 1u << 2,  // initialised, ready for a step (FMI 3: Step Mode)
  kStepFailed = 1u << 3,    // after a discarded step
  kTerminated = 1u << 4,
  kError = 1u << 5,
};

// What the adapter of an FMI version gives its instances: the importer's logger, and
// the names by which messages point the importer to other functions of that version.
// (The function the importer called is named by the entry guard: Instance::enter.)
struct Adapter {
  Logger logger;
  // What a variable of this type is and how it is reached: "a Real, use fmi2Get/SetReal".
  const char* (*typeAdvice)(BaseType type) = nullptr;
  const char* stateSizeFunction = "";  // the function that gives a serialised state's size
};

class Instance {
 public:
  // Reads the scene from the resources (a file URI) and checks the GUID (FMI 3: the
  // instantiation token); on failure logs why through the adapter's logger and returns
  // nullptr. `function` is the instantiating function the importer called: it names
  // those messages.
  static Instance* create(const char* function, const char* instanceName, const char* guid,
                          const char* resourceLocation, bool loggingOn, Adapter adapter);

  // The scene's variables, in value-reference order (the FMI 3 adapter checks types).
  const std::vector<Variable>& variables() const { return vars_; }

  // The entry guard's check (entry_guard.h): `function`, the function the importer
  // called, becomes the call in progress, which every message of the call names; a
  // call in a state outside `allowed` is refused (Error, logged).
  bool enter(const char* function, unsigned allowed);

  Status setDebugLogging(bool loggingOn, size_t n, const char* const categories[]);
  Status setupExperiment(bool toleranceDefined, double tolerance, double startTime);  // s
  Status enterInitializationMode();
  Status exitInitializationMode();
  Status terminate();
  Status reset();

  // Real access takes Real variables; Integer access Integer and Enumeration ones.
  Status getReal(const uint32_t vr[], size_t n, double value[]);
  Status getInteger(const uint32_t vr[], size_t n, int32_t value[]);
  Status setReal(const uint32_t vr[], size_t n, const double value[]);
  Status setInteger(const uint32_t vr[], size_t n, const int32_t value[]);
  // Types the FMU has no variables of (Boolean, String, ...): any reference is unknown.
  Status noVariablesOfType(const uint32_t vr[], size_t n);

  // With returnEarlyAtImpact (FMI 3, earlyReturnAllowed), the step ends at the first
  // bouncing impact inside it, the impulse applied; returnedEarly() then says so and
  // the FMU's time is that instant.
  Status doStep(double currentCommunicationPoint, double communicationStepSize, bool returnEarlyAtImpact = false);
  bool returnedEarly() const { return returnedEarly_; }
  double lastSuccessfulTime() const { return clock_.now(); }   // s
  bool wantsToTerminate() const { return wantsToTerminate_; }  // after a discarded step

  // Directional derivatives of outputs after the next step with respect to inputs.
  Status getDirectionalDerivative(const uint32_t unknown[], size_t nUnknown, const uint32_t known[], size_t nKnown,
                                  const double dvKnown[], double dvUnknown[]);

  // First-order input derivatives (canInterpolateInputs) and output derivatives
  // (MaxOutputDerivativeOrder = 1).
  Status setInputDerivatives(const uint32_t vr[], size_t n, const int32_t order[], const double value[]);
  Status getOutputDerivatives(const uint32_t vr[], size_t n, const int32_t order[], double value[]);

  // FMU states: snapshots owned by this instance (freed with it), handed out as opaque
  // pointers.
  Status getState(void** state);
  Status setState(void* state);
  Status freeState(void** state);
  Status serializedStateSize(void* state, size_t* size);
  Status serializeState(void* state, char bytes[], size_t size);
  Status deserializeState(const char bytes[], size_t size, void** state);

  // Logs with a status; errors, discards and warnings always reach the logger, other
  // categories only when debug logging has them on.
  void log(Status status, const char* category, const std::string& message) const;
  // Logs "<the function called>: message" in the status's category and returns the
  // status: every warning, discard and error names the function the importer called.
  Status report(Status status, const std::string& message) const;
  Status error(const std::string& message) const { return report(Status::Error, message); }
  void enterErrorState() { state_ = kError; }

 private:
  Instance(std::string name, Adapter adapter, bool loggingOn, rigid::Scene scene, const char* function);

  void restart();  // the just-instantiated state
  // "<the function called>: message".
  std::string inCall(const std::string& message) const;
  // The variable behind vr if it exists and has the given type; logs otherwise.
  // Real access takes Real variables; integer access Integer and Enumeration ones.
  const Variable* lookup(uint32_t vr, bool integer) const;
  // Whether a variable may be written in the current state; logs otherwise.
  bool writable(const Variable& v) const;
  Status write(const Variable& v, double value);
  double read(const Variable& v) const;
  bool setupPhase() const { return state_ & (kInstantiated | kInitializationMode); }
  // Integrates the world over the next h seconds in internal steps of solver.step,
  // inputs ramped by their derivatives; reports sub-stepping in the log if asked.
  struct Interval {
    rigid::StepResult result;
    double from = 0.0, to = 0.0;  // s, the internal step that failed, from the start
    double impactAt = -1.0;       // s from the start: where an early return stopped
  };
  Interval advance(double h, bool reportSubsteps, bool stopAtImpact = false);
  // The driven bodies' paths over a step of h (empty without driven bodies); with
  // `reportJumps`, a warning for each whose inputs moved it by more than its half
  // thickness: it gets there within the step, pushing what it meets.
  std::vector<rigid::DrivePath> drivePaths(double h, bool reportJumps) const;
  // The step's arguments and the parameters set since the last step: OK, or the
  // error logged that names the argument or parameter and its limit.
  Status checkStep(double tc, double h) const;
  // A failed internal step of the communication step from tc: the FMU stays at the
  // last internal step it completed, in StepFailed; logs why and returns Discard.
  Status discardStep(double tc, const Interval& run);
  // Why an internal step of that length failed, and what would have worked.
  std::string stepFailure(const rigid::StepResult& r, double internalStep) const;
  // Logs when the sub-stepping of the internal steps starts, changes or stops.
  void noteSubsteps(const rigid::StepResult& r, double h);

  std::string name_;
  Adapter adapter_;
  bool loggingOn_;
  std::set<std::string> categories_;  // enabled debug categories
  const char* function_;              // the call in progress (enter), a literal

  rigid::Scene scene_;  // as read from the resources, for reset
  std::vector<Variable> vars_;
  rigid::WorldModel model_;  // the scene's constants with parameters applied
  rigid::WorldData data_;

  unsigned state_ = kInstantiated;
  double startTime_ = 0.0;         // s
  CommunicationClock clock_;       // the time of the last communication point
  bool wantsToTerminate_ = false;  // after a discarded step (fmi2Terminated, terminateSimulation)
  bool returnedEarly_ = false;     // the last step ended at an impact (FMI 3 early return)
  std::string substepNote_;        // the sub-stepping last reported ("cause:count")
  std::string guid_;               // of the scene: checked when a state is deserialised
  double lastStepSize_ = 0.0;      // s, the last communication step (directional derivatives)
  // FMU states handed out, so that a pointer that is not one of them is refused.
  std::set<Snapshot*> states_;
  std::vector<std::unique_ptr<Snapshot>> owned_;
  Snapshot* ownState(void* state) const;
};

}  // namespace rigidfmu
