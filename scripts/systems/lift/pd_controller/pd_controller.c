// A one-axis PD position controller as an FMI 2.0 Co-Simulation FMU: the force that
// takes a body to `target` and holds it there,
//
//   force = Kp (target - position) - Kd velocity + mass gravity + load
//
// the PD law plus the weights it carries fed forward: the body's own (`mass` times
// `gravity`) and a measured one (`load`, N: the force a load on the body presses it
// down with, e.g. a contact force output). Sampled: the FMI functions are
// scripts/systems/sampled_fmu's, this file is the model; modelDescription.xml beside
// it lists the same variables in the same order.
#include "sampled_fmu.h"

#include <math.h>

// Value references, as modelDescription.xml numbers them.
enum { Kp, Kd, TARGET, MASS, GRAVITY, POSITION, VELOCITY, LOAD, FORCE, VARIABLE_COUNT };

static const SampledVariable kVariables[VARIABLE_COUNT] = {
    {"Kp", SAMPLED_PARAMETER, 1000.0, 0.0},           // N/m
    {"Kd", SAMPLED_PARAMETER, 200.0, 0.0},            // N s/m
    {"target", SAMPLED_PARAMETER, 0.0, -INFINITY},    // m
    {"mass", SAMPLED_PARAMETER, 0.0, 0.0},            // kg
    {"gravity", SAMPLED_PARAMETER, 9.81, -INFINITY},  // m/s^2
    {"position", SAMPLED_INPUT, 0.0, -INFINITY},      // m
    {"velocity", SAMPLED_INPUT, 0.0, -INFINITY},      // m/s
    {"load", SAMPLED_INPUT, 0.0, -INFINITY},          // N
    {"force", SAMPLED_OUTPUT, 0.0, -INFINITY},        // N
};

static void outputs(double* v) {
  v[FORCE] = v[Kp] * (v[TARGET] - v[POSITION]) - v[Kd] * v[VELOCITY] + v[MASS] * v[GRAVITY] + v[LOAD];
}

const SampledModel kSampledModel = {"pd_controller", VARIABLE_COUNT, kVariables, outputs, NULL};
