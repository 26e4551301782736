#include "sleep.h"

#include <algorithm>

#include "islands.h"

namespace rigid {

namespace {

// A woken body must be still for the sleep time again before it sleeps: what woke it
// (a touch, an input, a new parameter) may take a few steps to move it. Its contact
// memory returns to `memory` (WorldData::contactMemory).
void wakeIsland(SleepState& s, std::vector<ContactMemory>& memory, int island) {
  for (size_t i = 0; i < s.asleep.size(); ++i) {
    if (!s.asleep[i] || s.island[i] != island) continue;
    s.asleep[i] = 0;
    s.island[i] = -1;
    s.stillFor[i] = 0.0;
    --s.sleeping;
  }
  s.boxes.reset();
  s.resting.erase(
      std::remove_if(s.resting.begin(), s.resting.end(), [&](const RestingPush& p) { return !s.asleep[p.body]; }),
      s.resting.end());
  movePoints(s.memory, memory, [&](const ContactMemory& m) { return !s.asleep[m.a]; });
}

// Whether a surface's belt moves, or its velocity changes over the step: what rests on
// it is carried, not at rest.
bool beltMoves(const WorldData& data, size_t surface) {
  return data.beltVelocity[surface] != Vec3::Zero() || data.beltRate[surface] != Vec3::Zero();
}

// Wakes the sleeping islands that rest on a moving belt (their contact memory, set
// aside while they sleep, names the surface).
bool wakeCarried(WorldData& data) {
  SleepState& s = data.sleep;
  bool anyMoves = false;
  for (size_t k = 0; k < data.beltVelocity.size(); ++k) anyMoves = anyMoves || beltMoves(data, k);
  if (!anyMoves || s.sleeping == 0) return false;
  std::vector<int> islands;
  for (const ContactMemory& m : s.memory)
    if (m.b < 0 && beltMoves(data, static_cast<size_t>(m.surface))) islands.push_back(s.island[m.a]);
  for (int island : islands) wakeIsland(s, data.contactMemory, island);
  return !islands.empty();
}

}  // namespace

bool wakeDriven(WorldData& data) {
  SleepState& s = data.sleep;
  bool woke = false;
  for (size_t i = 0; i < s.asleep.size() && s.sleeping > 0; ++i) {
    if (!s.asleep[i] || !(drives(data.input[i]) || drives(data.inputRate[i]))) continue;
    wakeIsland(s, data.contactMemory, s.island[i]);
    woke = true;
  }
  return wakeCarried(data) || woke;
}

void holdSleepers(const SleepState& s, const std::vector<BodyState>& Y, std::vector<BodyState>& next) {
  if (s.sleeping == 0) return;
  for (size_t i = 0; i < Y.size(); ++i)
    if (s.asleep[i]) next[i] = Y[i];
}

bool wakeTouched(const std::vector<Contact>& contacts, WorldData& data) {
  SleepState& s = data.sleep;
  if (s.sleeping == 0) return false;
  bool woke = false;
  for (const Contact& c : contacts) {
    for (int body : {c.a, c.b}) {
      if (body < 0 || !s.asleep[body]) continue;
      wakeIsland(s, data.contactMemory, s.island[body]);
      woke = true;
    }
  }
  return woke;
}

void addRestingLoads(WorldData& data, double tau) {
  const SleepState& s = data.sleep;
  if (s.sleeping == 0) return;
  WorldData::ContactLoads& loads = data.contactLoads;
  for (size_t i = 0; i < s.asleep.size(); ++i) {
    if (!s.asleep[i]) continue;
    loads.impulse[i] += tau * s.restForce[i];
    loads.angularImpulse[i] += tau * s.restTorque[i];
  }
  for (const RestingPush& p : s.resting) loads.surfaceImpulse[p.surface] += tau * p.force;
}

bool updateSleep(const WorldModel& model, WorldData& data, double h, CollisionCache& cache) {
  SleepState& s = data.sleep;
  if (cache.contacts.empty()) {  // a body that touches nothing does not rest: its stillness restarts
    for (int i : data.scratch.awake) s.stillFor[i] = 0.0;
    return false;
  }
  for (int i : data.scratch.awake) {
    const double speed = data.aux[i].V.norm() + data.aux[i].omega.norm() * cache.boundingRadius[i];
    const bool still = speed < model.sleep.speed && !drives(data.input[i]) && !drives(data.inputRate[i]);
    s.stillFor[i] = still ? s.stillFor[i] + h : 0.0;
  }
  for (const Contact& c : cache.contacts)  // carried by a moving belt: not at rest, however slow
    if (c.b < 0 && beltMoves(data, static_cast<size_t>(c.surface))) s.stillFor[c.a] = 0.0;
  // An island sleeps whole, when it rests on a surface and all of it has been still
  // long enough. (A sleeping body has no contacts: the detector skips its pairs with
  // sleeping bodies and surfaces, and any other one woke it.)
  const Islands& islands = cache.islands;
  std::vector<char>& ready = cache.ready;
  ready = islands.grounded;
  for (int i : data.scratch.awake)
    if (s.stillFor[i] < model.sleep.time) ready[islands.root[i]] = 0;
  bool fell = false;
  for (int i : data.scratch.awake) {
    const int root = islands.root[i];
    if (!ready[root]) continue;
    fell = true;
    s.asleep[i] = 1;
    s.island[i] = root;
    ++s.sleeping;
    const bool touched = !cache.impulses.linear.empty();
    s.restForce[i] = touched ? Vec3(cache.impulses.linear[i] / h) : Vec3::Zero();
    s.restTorque[i] = touched ? Vec3(cache.impulses.angular[i] / h) : Vec3::Zero();
    for (const SurfacePush& p : cache.impulses.pushes)
      if (p.body == i) s.resting.push_back({i, p.surface, p.impulse / h});
    data.Y[i].P.setZero();
    data.Y[i].L.setZero();
    data.aux[i].V.setZero();
    data.aux[i].omega.setZero();
  }
  if (fell) {
    setAsideSleeping(s, data.contactMemory);
    s.boxes.reset();
  }
  return fell;
}

}  // namespace rigid
