// Islands at rest are put to sleep, as Box2D, Bullet and Jolt put them: a pile that has
// settled costs neither integration nor detection nor a contact solve until something
// disturbs it. An island is a set of bodies joined by contacts (a surface joins none);
// it falls asleep when every body of it has been still (no point faster than
// SleepRules::speed, no input driving it, not on a moving belt) for SleepRules::time
// and the island rests on a surface. Bodies floating free never sleep: a slow tumble
// in space, a body bobbing in a fluid or a slow fall are motion, not rest. A sleeping
// body keeps its pose and its contact memory; its velocities are zero. It wakes, with
// its whole island, when an awake body touches it (or comes within the speculative
// margin), when an input drives it or the belt it rests on moves, or when a tunable
// parameter changes (wakeAll).
#pragma once

#include <vector>

#include "collision_cache.h"
#include "world.h"

namespace rigid {

// Wakes the island of every sleeping body that an input drives (a force, a torque or
// their rates not zero) or that rests on a moving belt (a surface's beltVelocity or its
// rate not zero). Returns whether any woke.
bool wakeDriven(WorldData& data);

// Sleeping bodies stay where they are: next[i] = Y[i].
void holdSleepers(const SleepState& s, const std::vector<BodyState>& Y, std::vector<BodyState>& next);

// Wakes the island of every sleeping body in `contacts` (the detector gives a sleeping
// body only pairs with awake ones). Returns whether any woke: the contacts are then
// detected again, with the woken islands' own.
bool wakeTouched(const std::vector<Contact>& contacts, WorldData& data);

// The loads of the sleeping bodies over a time tau added to WorldData::contactLoads:
// each keeps the contact force and torque and the pushes on surfaces it had when it
// fell asleep.
void addRestingLoads(WorldData& data, double tau);

// After a step of h: each awake body's stillness, then the cache's islands (of the
// step's contacts, islands.h; none are needed when it had none) that have been still
// long enough on a surface fall asleep (velocities zeroed). Returns whether any did.
bool updateSleep(const WorldModel& model, WorldData& data, double h, CollisionCache& cache);

}  // namespace rigid
