// The FMI 2.0 Co-Simulation functions of a sampled controller (sampled_fmu.h), around
// the model its own source defines: one copy for every controller of scripts/systems.
// The XML's GUID comes in as MODEL_GUID (scripts/systems/fmus.py passes it).
#include "sampled_fmu.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fmi2Functions.h"

#ifndef MODEL_GUID
#error "MODEL_GUID: the GUID of modelDescription.xml (the builder defines it)"
#endif

typedef enum { INSTANTIATED, INITIALISING, STEPPING, TERMINATED } Phase;

typedef struct {
  Phase phase;
  fmi2CallbackFunctions callbacks;
  char name[64];    // the instance name, for messages
  double values[];  // by value reference, SI units: kSampledModel.count of them
} Controller;

static void say(const Controller* c, fmi2Status status, const char* category, const char* message) {
  if (c->callbacks.logger) c->callbacks.logger(c->callbacks.componentEnvironment, c->name, status, category, message);
}

static fmi2Status refuse(const Controller* c, const char* message) {
  say(c, fmi2Error, "logStatusError", message);
  return fmi2Error;
}

// Names the function and the variable: "fmi2SetReal: Kp is ...".
static fmi2Status refuseNaming(const Controller* c, const char* function, const char* name, const char* what) {
  char message[192];
  snprintf(message, sizeof message, "%s: %s %s", function, name, what);
  return refuse(c, message);
}

static fmi2Status refuseReference(const Controller* c, const char* function) {
  char message[128];
  snprintf(message, sizeof message, "%s: no such value reference (0 to %zu)", function, kSampledModel.count - 1);
  return refuse(c, message);
}

// The start values of modelDescription.xml.
static void start(Controller* c) {
  for (size_t i = 0; i < kSampledModel.count; ++i) c->values[i] = kSampledModel.variables[i].start;
  c->phase = INSTANTIATED;
}

// ---- instance -----------------------------------------------------------------------

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn) {
  (void)fmuResourceLocation, (void)visible, (void)loggingOn;
  if (!functions || !functions->allocateMemory || !functions->freeMemory) return NULL;
  Controller* c = (Controller*)functions->allocateMemory(1, sizeof(Controller) + kSampledModel.count * sizeof(double));
  if (!c) return NULL;
  c->callbacks = *functions;
  snprintf(c->name, sizeof c->name, "%s", instanceName ? instanceName : kSampledModel.identifier);
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
  kSampledModel.outputs(c->values);
  c->phase = STEPPING;
  return fmi2OK;
}

fmi2Status fmi2DoStep(fmi2Component component, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
  (void)currentCommunicationPoint, (void)noSetFMUStatePriorToCurrentPoint;
  Controller* c = (Controller*)component;
  if (c->phase != STEPPING) return refuse(c, "fmi2DoStep: only after fmi2ExitInitializationMode");
  if (!(communicationStepSize > 0.0)) return refuse(c, "fmi2DoStep: communicationStepSize must be > 0");
  if (kSampledModel.advance) kSampledModel.advance(c->values, communicationStepSize);
  kSampledModel.outputs(c->values);
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
  // in initialisation mode the outputs follow the values as they are set
  if (c->phase == INITIALISING) kSampledModel.outputs(c->values);
  for (size_t i = 0; i < nvr; ++i) {
    if (vr[i] >= kSampledModel.count) return refuseReference(c, "fmi2GetReal");
    value[i] = c->values[vr[i]];
  }
  return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component component, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
  Controller* c = (Controller*)component;
  for (size_t i = 0; i < nvr; ++i) {
    if (vr[i] >= kSampledModel.count) return refuseReference(c, "fmi2SetReal");
    const SampledVariable* v = &kSampledModel.variables[vr[i]];
    if (v->causality == SAMPLED_OUTPUT) return refuseNaming(c, "fmi2SetReal", v->name, "is an output");
    if (v->causality == SAMPLED_PARAMETER && c->phase != INSTANTIATED && c->phase != INITIALISING)
      return refuseNaming(c, "fmi2SetReal", v->name, "is a fixed parameter: set it before initialisation ends");
    if (!isfinite(value[i])) return refuseNaming(c, "fmi2SetReal", v->name, "must be finite");
    if (value[i] < v->min) {
      char limit[48];
      snprintf(limit, sizeof limit, "must be >= %g", v->min);
      return refuseNaming(c, "fmi2SetReal", v->name, limit);
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
