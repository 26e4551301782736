// FMU states: everything that shapes an instance's future, copied, and its versioned,
// pointer-free serialisation (one format for the FMI 2 and FMI 3 FMUs).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "communication_clock.h"
#include "world.h"

namespace rigidfmu {

struct Snapshot {
  rigid::WorldModel model;  // parameters and start values as set
  rigid::WorldData data;    // state Y, inputs, counters, integrator history
  unsigned machineState = 0;
  double startTime = 0.0;    // s
  CommunicationClock clock;  // the FMU's time (communication_clock.h)
  bool wantsToTerminate = false;
  double lastStepSize = 0.0;  // s, the last communication step (directional derivatives)
};

// Bumped whenever the layout of the bytes changes (visitState in snapshot.cpp, which
// both writes and reads them): an old serialisation is then refused.
// 2: input derivatives; 3: energy audit, last step; 4: the contact solver's memory;
// 5: which bodies sleep; 6: friction, surfaces' restitution, media's density and
// viscosity, forces at load points; 7: the contact loads, and those of sleeping bodies;
// 8: the contact points' twist impulse; 9: the communication clock, driven bodies' inputs;
// 10: joints
inline constexpr uint32_t kSnapshotVersion = 12;

// The bytes of a snapshot of a scene with this GUID.
std::vector<char> serialize(const Snapshot& s, const std::string& guid);

// Reads bytes back into `s` (whose model and data must be those of the same scene, as
// freshly instantiated); returns "" or why the bytes are refused (size, version, GUID,
// body count, a value out of range).
std::string deserialize(const char* bytes, size_t size, const std::string& guid, Snapshot& s);

}  // namespace rigidfmu
