// A sampled controller as an FMI 2.0 Co-Simulation FMU: the FMI functions live in
// sampled_fmu.c, once for every controller of scripts/systems; a controller's own
// source defines only its model, `kSampledModel`: its Real variables (the value
// reference of each is its index, as its modelDescription.xml numbers them), what its
// outputs are of the rest, and how its state, if it has one, moves over a step.
//
// The outputs are sampled: fmi2DoStep advances the state over the step and computes the
// outputs from the inputs held over it, and they hold until the next step, so that the
// master's order of getting and setting within a communication point never changes a
// value. In initialisation mode the outputs follow the parameters and inputs as they
// are set. A parameter is fixed (set before initialisation ends); a value set must be
// finite and at least its variable's min.
// The builder (scripts/systems/fmus.py) compiles sampled_fmu.c with every controller.
#ifndef SAMPLED_FMU_H
#define SAMPLED_FMU_H

#include <stddef.h>

typedef enum { SAMPLED_PARAMETER, SAMPLED_INPUT, SAMPLED_OUTPUT } SampledCausality;

typedef struct {
  const char* name;  // as modelDescription.xml names it
  SampledCausality causality;
  double start;  // modelDescription.xml's start value; an output's value before it is computed
  double min;    // the least value it may be set to: its min in modelDescription.xml, or -INFINITY
} SampledVariable;

typedef struct {
  const char* identifier;  // the modelIdentifier: the name of an unnamed instance
  size_t count;
  const SampledVariable* variables;  // by value reference
  // Writes the outputs of values[] from its parameters, inputs and state. It must not
  // change the state (outputs that `advance` moves): computing twice changes nothing.
  void (*outputs)(double* values);
  // Moves the state (some of the outputs) over a step of h s, before `outputs`; NULL
  // when the outputs are a function of the inputs alone.
  void (*advance)(double* values, double h);
} SampledModel;

extern const SampledModel kSampledModel;  // defined by the controller's source

#endif  // SAMPLED_FMU_H
