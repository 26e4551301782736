// Which bodies sleep, and the rules that put them to sleep (sleep.h): kept apart from
// the step's code so that the world's model and data can hold them.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "contact_memory.h"
#include "math_types.h"

namespace rigid {

class FixedBoxes;  // broadphase.h

// Scene constants (solver.sleep, solver.sleepSpeed, solver.sleepTime).
struct SleepRules {
  bool enabled = true;
  double speed = 0.01;  // m/s: a body none of whose points moves faster is still
  double time = 0.5;    // s: an island still this long, resting on a surface, sleeps
};

// The force a sleeping body keeps giving a surface: the last awake step's, N.
struct RestingPush {
  int body = -1;
  int surface = -1;
  Vec3 force = Vec3::Zero();
};

// Part of a run's state (the FMU state carries it).
struct SleepState {
  std::vector<char> asleep;      // per body
  std::vector<double> stillFor;  // s, per body: how long it has been still
  std::vector<int> island;       // per body: its sleeping island (a body index of it), -1 awake
  int sleeping = 0;              // bodies asleep
  // The contact force and torque (N, N m) of each sleeping body and the forces it gives
  // surfaces, as the last step before it slept measured them: a sleeping stack still
  // reports its support (WorldData::contactLoads).
  std::vector<Vec3> restForce, restTorque;
  std::vector<RestingPush> resting;
  // The sleeping bodies' contact memory (contact_memory.h), set aside from
  // WorldData::contactMemory while they sleep so that a woken island starts warm.
  std::vector<ContactMemory> memory;
  // Derived, not saved: the sleeping bodies' bounding boxes for collision detection
  // (CollisionDetector::fixedBoxes), null until built after islands fell asleep or woke.
  std::shared_ptr<const FixedBoxes> boxes;
};

// Every body awake, none still: the state a run starts from.
inline SleepState awakeState(size_t bodies) {
  SleepState s;
  s.asleep.assign(bodies, 0);
  s.stillFor.assign(bodies, 0.0);
  s.island.assign(bodies, -1);
  s.restForce.assign(bodies, Vec3::Zero());
  s.restTorque.assign(bodies, Vec3::Zero());
  return s;
}

// The contact memory of the sleeping bodies moved from `memory` (WorldData::
// contactMemory, which the solver replaces by the points it solved) into the sleep
// state's, until their island wakes (a woken island starts warm). Islands fall asleep
// and wake seldom: a step in between moves none. (Here, beside the state, so that the
// FMU state's reader parts a restored memory the same way in every module build.)
inline void setAsideSleeping(SleepState& s, std::vector<ContactMemory>& memory) {
  movePoints(memory, s.memory, [&](const ContactMemory& m) { return s.asleep[m.a] != 0; });
}

// Wakes every body (a tunable parameter such as gravity changed); each must then be
// still for the sleep time again before it sleeps. Their contact memory returns to
// `memory` (WorldData::contactMemory).
inline void wakeAll(SleepState& s, std::vector<ContactMemory>& memory) {
  s.asleep.assign(s.asleep.size(), 0);
  s.island.assign(s.island.size(), -1);
  s.stillFor.assign(s.stillFor.size(), 0.0);
  s.resting.clear();
  s.sleeping = 0;
  s.boxes.reset();
  movePoints(s.memory, memory, [](const ContactMemory&) { return true; });
}

}  // namespace rigid
