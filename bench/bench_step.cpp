// rigid-bench-step [STEPS]: ns per body-step of the bare integrator (rk4, one free
// body under gravity), linked with the world built without any optional module. The
// baseline that scripts/bench_pruning.py sets the FMUs against.
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "world.h"

int main(int argc, char** argv) {
  const long steps = argc > 1 ? std::atol(argv[1]) : 2000000;
  rigid::WorldModel model;
  model.name = "bench";
  rigid::BodyConstants body;
  body.name = "ball";
  body.shape.radius = 0.1;
  rigid::setMass(body, 1.0);
  body.start.position = rigid::Vec3(0, 0, 1e3);
  body.start.velocity = rigid::Vec3(1, 2, 3);
  body.start.angularVelocity = rigid::Vec3(0.1, 2, 0.3);
  model.bodies.push_back(body);
  rigid::WorldData data = rigid::initialData(model);
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) rigid::step(model, data, 1e-3);
  const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
  // print the state so that the loop is not optimised away
  std::printf("%.3f ns per body-step (z = %.6g)\n", ns / static_cast<double>(steps), data.Y[0].X.z());
  return 0;
}
