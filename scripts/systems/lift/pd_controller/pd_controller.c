// A one-axis PD position controller as an FMI 2.0 Co-Simulation FMU: the force that
// takes a body to `target` and holds it there,
//
//   force = Kp (target - position) - Kd velocity + mass gravity + load
//
// the PD law plus the weights it carries fed forward: the body's own (`mass` times
// `gravity`) and a measured one (`load`, N: the force a load on the body presses it
// down with, e.g. a contact force output). The output is sampled: doStep computes it
// from the inputs held over the step and it holds until the next step, so that the
// master's order of getting and setting within a communication point never changes
// a value. modelDescription.xml beside this file lists the same value references;
// the builder (scripts/systems/fmus.py) compiles this file against the FMI headers of
// the installed fmpy package and passes the XML's GUID as MODEL_GUID.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fmi2Functions.h"

#ifndef MODEL_GUID
#error "MODEL_GUID: the GUID of modelDescription.xml (the builder defines it)"
#endif

// Value references, as modelDescription.xml numbers them.
enum { Kp, Kd, TARGET, MASS, GRAVITY, POSITION, VELOCITY, LOAD, FORCE, VARIABLE_COUNT };

static const char* const kNames[VARIABLE_COUNT] = {"Kp",       "Kd",       "target", "mass", "gravity",
                                                   "position", "velocity", "load",   "force"};

typedef enum { INSTANTIATED, INITIALISING, STEPPING, TERMINATED } Phase;

typedef struct {
  double values[VARIABLE_COUNT];  // by value reference, SI units
  Phase phase;
  fmi2CallbackFunctions callbacks;
  char name[64];  // the instance name, for messages
} Controller;

static void say(const Controller* c, fmi2Status status, const char* category, const char* message) {
  if (c->callbacks.logger) c->callbacks.logger(c->callbacks.componentEnvironment, c->name, status, category, message);
}

static fmi2Status refuse(const Controller* c, const char* message) {
  say(c, fmi2Error, "logStatusError", message);
  return fmi2Error;
}

static double law(const double* v) {
  return v[Kp] * (v[TARGET] - v[POSITION]) - v[Kd] * v[VELOCITY] + v[MASS] * v[GRAVITY] + v[LOAD];
}

static int isParameter(fmi2ValueReference vr) { return vr <= GRAVITY; }

// The start values of modelDescription.xml.
static void start(Controller* c) {
  static const double kStart[VARIABLE_COUNT] = {1000.0, 200.0, 0.0, 0.0, 9.81, 0.0, 0.0, 0.0, 0.0};
  memcpy(c->values, kStart, sizeof kStart);
  c->phase = INSTANTIATED;
}

// ---- instance -----------------------------------------------------------------------

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn) {
  (void)fmuResourceLocation, (void)visible, (void)loggingOn;
  if (!functions || !functions->allocateMemory || !functions->freeMemory) return NULL;
  Controller* c = (Controller*)functions->allocateMemory(1, sizeof(Controller));
  if (!c) return NULL;
  c->callbacks = *functions;
  snprintf(c->name, sizeof c->name, "%s", instanceName ? instanceName : "pd_controller");
  if (fmuType != fmi2CoSimulation || !fmuGUID || strcmp(fmuGUID, MODEL_GUID) != 0) {
    refuse(c, fmuType != fmi2CoSimulation ? "fmi2Instantiate: only Co-Simulation"
                                          : "fmi2Instantiate: the GUID is not this FMU's (" MODEL_GUID ")");
    functions->freeMemory(c);
    return NULL;
  }
  start(c);
  return c;
}

void fmi2FreeInstance(fmi2Component component) {
  Controller* c = (Controller*)component;
  if (c) c->callbacks.freeMemory(c);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
  (void)toleranceDefined, (void)tolerance, (void)startTime, (void)stopTimeDefined, (void)stopTime;
  return ((Controller*)c)->phase == INSTANTIATED ? fmi2OK : refuse(c, "fmi2SetupExperiment: only once instantiated");
}

fmi2Status fmi2EnterInitializationMode(fmi2Component component) {
  Controller* c = (Controller*)component;
  if (c->phase != INSTANTIATED) return refuse(c, "fmi2EnterInitializationMode: only once instantiated");
  c->phase = INITIALISING;
  return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component component) {
  Controller* c = (Controller*)component;
  if (c->phase != INITIALISING) return refuse(c, "fmi2ExitInitializationMode: only in initialisation mode");
  c->values[FORCE] = law(c->values);
  c->phase = STEPPING;
  return fmi2OK;
}

fmi2Status fmi2DoStep(fmi2Component component, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
  (void)currentCommunicationPoint, (void)noSetFMUStatePriorToCurrentPoint;
  Controller* c = (Controller*)component;
  if (c->phase != STEPPING) return refuse(c, "fmi2DoStep: only after fmi2ExitInitializationMode");
  if (!(communicationStepSize > 0.0)) return refuse(c, "fmi2DoStep: communicationStepSize must be > 0");
  c->values[FORCE] = law(c->values);
  return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component component) {
  ((Controller*)component)->phase = TERMINATED;
  return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component component) {
  start((Controller*)component);
  return fmi2OK;
}

// ---- values -------------------------------------------------------------------------

fmi2Status fmi2GetReal(fmi2Component component, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
  Controller* c = (Controller*)component;
  for (size_t i = 0; i < nvr; ++i) {
    if (vr[i] >= VARIABLE_COUNT) return refuse(c, "fmi2GetReal: no such value reference (0 to 8)");
    // in initialisation mode the output follows the values as they are set
    value[i] = vr[i] == FORCE && c->phase == INITIALISING ? law(c->values) : c->values[vr[i]];
  }
  return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component component, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
  Controller* c = (Controller*)component;
  char message[160];
  for (size_t i = 0; i < nvr; ++i) {
    if (vr[i] >= VARIABLE_COUNT) return refuse(c, "fmi2SetReal: no such value reference (0 to 8)");
    const char* name = kNames[vr[i]];
    if (vr[i] == FORCE) return refuse(c, "fmi2SetReal: force is an output");
    if (isParameter(vr[i]) && c->phase != INSTANTIATED && c->phase != INITIALISING) {
      snprintf(message, sizeof message, "fmi2SetReal: %s is a fixed parameter: set it before initialisation ends",
               name);
      return refuse(c, message);
    }
    if (!isfinite(value[i])) {
      snprintf(message, sizeof message, "fmi2SetReal: %s must be finite", name);
      return refuse(c, message);
    }
    c->values[vr[i]] = value[i];
  }
  return fmi2OK;
}

// ---- what this FMU does not have ------------------------------------------------------

const char* fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char* fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[]) {
  (void)c, (void)loggingOn, (void)nCategories, (void)categories;
  return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]) {
  (void)vr, (void)value;
  return nvr == 0 ? fmi2OK : refuse(c, "fmi2GetInteger: this FMU has no Integer variables");
}
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[]) {
  (void)vr, (void)value;
  return nvr == 0 ? fmi2OK : refuse(c, "fmi2GetBoolean: this FMU has no Boolean variables");
}
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[]) {
  (void)vr, (void)value;
  return nvr == 0 ? fmi2OK : refuse(c, "fmi2GetString: this FMU has no String variables");
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[]) {
  (void)vr, (void)value;
  return nvr == 0 ? fmi2OK : refuse(c, "fmi2SetInteger: this FMU has no Integer variables");
}
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[]) {
  (void)vr, (void)value;
  return nvr == 0 ? fmi2OK : refuse(c, "fmi2SetBoolean: this FMU has no Boolean variables");
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[]) {
  (void)vr, (void)value;
  return nvr == 0 ? fmi2OK : refuse(c, "fmi2SetString: this FMU has no String variables");
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* state) {
  (void)state;
  return refuse(c, "fmi2GetFMUstate: not supported (canGetAndSetFMUstate is false)");
}
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state) {
  (void)state;
  return refuse(c, "fmi2SetFMUstate: not supported (canGetAndSetFMUstate is false)");
}
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* state) {
  (void)state;
  return refuse(c, "fmi2FreeFMUstate: not supported (canGetAndSetFMUstate is false)");
}
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t* size) {
  (void)state, (void)size;
  return refuse(c, "fmi2SerializedFMUstateSize: not supported (canSerializeFMUstate is false)");
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte bytes[], size_t size) {
  (void)state, (void)bytes, (void)size;
  return refuse(c, "fmi2SerializeFMUstate: not supported (canSerializeFMUstate is false)");
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte bytes[], size_t size, fmi2FMUstate* state) {
  (void)bytes, (void)size, (void)state;
  return refuse(c, "fmi2DeSerializeFMUstate: not supported (canSerializeFMUstate is false)");
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference unknown[], size_t nUnknown,
                                        const fmi2ValueReference known[], size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[]) {
  (void)unknown, (void)nUnknown, (void)known, (void)nKnown, (void)dvKnown, (void)dvUnknown;
  return refuse(c, "fmi2GetDirectionalDerivative: not supported");
}
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[]) {
  (void)vr, (void)nvr, (void)order, (void)value;
  return refuse(c, "fmi2SetRealInputDerivatives: not supported (canInterpolateInputs is false)");
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[]) {
  (void)vr, (void)nvr, (void)order, (void)value;
  return refuse(c, "fmi2GetRealOutputDerivatives: not supported (maxOutputDerivativeOrder is 0)");
}
fmi2Status fmi2CancelStep(fmi2Component c) { return refuse(c, "fmi2CancelStep: every step completes at once"); }

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status* value) {
  (void)s, (void)value;
  return refuse(c, "fmi2GetStatus: every step completes at once");
}
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
  (void)s, (void)value;
  return refuse(c, "fmi2GetRealStatus: every step completes at once");
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer* value) {
  (void)s, (void)value;
  return refuse(c, "fmi2GetIntegerStatus: every step completes at once");
}
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
  (void)s, (void)value;
  return refuse(c, "fmi2GetBooleanStatus: every step completes at once");
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String* value) {
  (void)s, (void)value;
  return refuse(c, "fmi2GetStringStatus: every step completes at once");
}
