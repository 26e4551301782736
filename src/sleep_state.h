// Which bodies sleep, and the rules that put them to sleep (sleep.h): kept apart from
// the step's code so that the world's model and data can hold them.
#pragma once

#include <cstddef>
#include <vector>

namespace rigid {

// Scene constants (solver.sleep, solver.sleepSpeed, solver.sleepTime).
struct SleepRules {
  bool enabled = true;
  double speed = 0.01;  // m/s: a body none of whose points moves faster is still
  double time = 0.5;    // s: an island still this long, resting on a surface, sleeps
};

// Part of a run's state (the FMU state carries it).
struct SleepState {
  std::vector<char> asleep;      // per body
  std::vector<double> stillFor;  // s, per body: how long it has been still
  std::vector<int> island;       // per body: its sleeping island (a body index of it), -1 awake
  int sleeping = 0;              // bodies asleep
};

// Every body awake, none still: the state a run starts from.
inline SleepState awakeState(size_t bodies) {
  SleepState s;
  s.asleep.assign(bodies, 0);
  s.stillFor.assign(bodies, 0.0);
  s.island.assign(bodies, -1);
  return s;
}

// Wakes every body (a tunable parameter such as gravity changed); each must then be
// still for the sleep time again before it sleeps.
inline void wakeAll(SleepState& s) {
  s.asleep.assign(s.asleep.size(), 0);
  s.island.assign(s.island.size(), -1);
  s.stillFor.assign(s.stillFor.size(), 0.0);
  s.sleeping = 0;
}

}  // namespace rigid
