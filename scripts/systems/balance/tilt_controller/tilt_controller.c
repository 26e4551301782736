// A tilt controller as an FMI 2.0 Co-Simulation FMU: it tilts a paddle about the y
// axis to bring a ball rolling on it to `target` (world x) and hold it there. The
// tilt theta follows a PD law on the ball's position and velocity through a
// first-order filter of time constant tau,
//
//   command = Kp (target - ball.position) - Kd ball.velocity
//   rate    = (command - theta) / tau,    theta(t + h) = theta(t) + h rate(t)
//
// and the outputs are the paddle's motion as a driven body takes it: its origin held at
// `pivot` (velocity 0), its orientation the quaternion of theta about y (w, x, y, z) and
// its angular velocity the rate about y. theta is the filter's state: the orientation
// at each communication point is where the rate of the step before took the paddle,
// so pose and velocity agree and the paddle never has to close a gap. A positive theta
// lowers the paddle's +x end, and a ball rolling without slipping on it accelerates
// toward +x at 5/7 g sin theta. Sampled: the FMI functions are those of
// scripts/systems/sampled_fmu, this file is the model; modelDescription.xml beside it
// lists the same variables in the same order.
#include <math.h>

#include "sampled_fmu.h"

// Value references, as modelDescription.xml numbers them.
enum {
  Kp,
  Kd,
  TAU,
  TARGET,
  PIVOT,  // 3 of them
  BALL_POSITION = PIVOT + 3,
  BALL_VELOCITY,
  THETA,
  POSITION,                         // 3
  ORIENTATION = POSITION + 3,       // 4: w, x, y, z
  VELOCITY = ORIENTATION + 4,       // 3
  ANGULAR_VELOCITY = VELOCITY + 3,  // 3
  VARIABLE_COUNT = ANGULAR_VELOCITY + 3
};

static const SampledVariable kVariables[VARIABLE_COUNT] = {
    {"Kp", SAMPLED_PARAMETER, 0.342508, 0.0},         // rad/m
    {"Kd", SAMPLED_PARAMETER, 0.399592, 0.0},         // rad s/m
    {"timeConstant", SAMPLED_PARAMETER, 0.1, 1e-3},   // s
    {"target", SAMPLED_PARAMETER, 0.0, -INFINITY},    // m
    {"pivot[1]", SAMPLED_PARAMETER, 0.0, -INFINITY},  // m
    {"pivot[2]", SAMPLED_PARAMETER, 0.0, -INFINITY},
    {"pivot[3]", SAMPLED_PARAMETER, 0.0, -INFINITY},
    {"ball.position", SAMPLED_INPUT, 0.0, -INFINITY},        // m
    {"ball.velocity", SAMPLED_INPUT, 0.0, -INFINITY},        // m/s
    {"tilt", SAMPLED_OUTPUT, 0.0, -INFINITY},                // rad
    {"paddle.position[1]", SAMPLED_OUTPUT, 0.0, -INFINITY},  // m
    {"paddle.position[2]", SAMPLED_OUTPUT, 0.0, -INFINITY},
    {"paddle.position[3]", SAMPLED_OUTPUT, 0.0, -INFINITY},
    {"paddle.orientation[1]", SAMPLED_OUTPUT, 1.0, -INFINITY},
    {"paddle.orientation[2]", SAMPLED_OUTPUT, 0.0, -INFINITY},
    {"paddle.orientation[3]", SAMPLED_OUTPUT, 0.0, -INFINITY},
    {"paddle.orientation[4]", SAMPLED_OUTPUT, 0.0, -INFINITY},
    {"paddle.velocity[1]", SAMPLED_OUTPUT, 0.0, -INFINITY},  // m/s
    {"paddle.velocity[2]", SAMPLED_OUTPUT, 0.0, -INFINITY},
    {"paddle.velocity[3]", SAMPLED_OUTPUT, 0.0, -INFINITY},
    {"paddle.angularVelocity[1]", SAMPLED_OUTPUT, 0.0, -INFINITY},  // rad/s
    {"paddle.angularVelocity[2]", SAMPLED_OUTPUT, 0.0, -INFINITY},
    {"paddle.angularVelocity[3]", SAMPLED_OUTPUT, 0.0, -INFINITY},
};

static void outputs(double* v) {
  const double command = v[Kp] * (v[TARGET] - v[BALL_POSITION]) - v[Kd] * v[BALL_VELOCITY];
  const double theta = v[THETA];
  for (int i = 0; i < 3; ++i) {
    v[POSITION + i] = v[PIVOT + i];
    v[VELOCITY + i] = 0.0;
    v[ANGULAR_VELOCITY + i] = 0.0;
  }
  v[ORIENTATION + 0] = cos(theta / 2);
  v[ORIENTATION + 1] = 0.0;
  v[ORIENTATION + 2] = sin(theta / 2);
  v[ORIENTATION + 3] = 0.0;
  v[ANGULAR_VELOCITY + 1] = (command - theta) / v[TAU];
}

// theta over the step at the rate the paddle was given for it
static void advance(double* v, double h) { v[THETA] += h * v[ANGULAR_VELOCITY + 1]; }

const SampledModel kSampledModel = {"tilt_controller", VARIABLE_COUNT, kVariables, outputs, advance};
