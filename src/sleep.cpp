#include "sleep.h"

#include <algorithm>
#include <numeric>

#include "islands.h"

namespace rigid {

namespace {

// A woken body must be still for the sleep time again before it sleeps: what woke it
// (a touch, an input, a new parameter) may take a few steps to move it.
void wakeIsland(SleepState& s, int island) {
  for (size_t i = 0; i < s.asleep.size(); ++i) {
    if (!s.asleep[i] || s.island[i] != island) continue;
    s.asleep[i] = 0;
    s.island[i] = -1;
    s.stillFor[i] = 0.0;
    --s.sleeping;
  }
  s.resting.erase(
      std::remove_if(s.resting.begin(), s.resting.end(), [&](const RestingPush& p) { return !s.asleep[p.body]; }),
      s.resting.end());
}

}  // namespace

bool wakeDriven(WorldData& data) {
  SleepState& s = data.sleep;
  bool woke = false;
  for (size_t i = 0; i < s.asleep.size() && s.sleeping > 0; ++i) {
    if (!s.asleep[i] || !(drives(data.input[i]) || drives(data.inputRate[i]))) continue;
    wakeIsland(s, s.island[i]);
    woke = true;
  }
  return woke;
}

void holdSleepers(const SleepState& s, const std::vector<BodyState>& Y, std::vector<BodyState>& next) {
  if (s.sleeping == 0) return;
  for (size_t i = 0; i < Y.size(); ++i)
    if (s.asleep[i]) next[i] = Y[i];
}

bool wakeTouched(const std::vector<Contact>& contacts, SleepState& s) {
  if (s.sleeping == 0) return false;
  bool woke = false;
  for (const Contact& c : contacts) {
    for (int body : {c.a, c.b}) {
      if (body < 0 || !s.asleep[body]) continue;
      wakeIsland(s, s.island[body]);
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

void updateSleep(const WorldModel& model, WorldData& data, double h, CollisionCache& cache) {
  if (!model.sleep.enabled) return;
  SleepState& s = data.sleep;
  const int n = static_cast<int>(data.Y.size());
  for (int i = 0; i < n; ++i) {
    if (s.asleep[i]) continue;
    const double speed = data.aux[i].V.norm() + data.aux[i].omega.norm() * cache.boundingRadius[i];
    const bool still = speed < model.sleep.speed && !drives(data.input[i]) && !drives(data.inputRate[i]);
    s.stillFor[i] = still ? s.stillFor[i] + h : 0.0;
  }
  // Islands of the awake bodies (a sleeping body has no contacts: the detector skips
  // its pairs with sleeping bodies and surfaces, and any other one woke it).
  const std::vector<Contact>& contacts = cache.contacts;
  std::vector<int>& parent = cache.island;
  parent.resize(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const Contact& c : contacts)
    if (c.b >= 0) parent[islandRoot(parent, c.a)] = islandRoot(parent, c.b);
  std::vector<char>& grounded = cache.grounded;
  std::vector<char>& ready = cache.ready;
  grounded.assign(n, 0);
  ready.assign(n, 1);
  for (const Contact& c : contacts)
    if (c.b < 0) grounded[islandRoot(parent, c.a)] = 1;
  for (int i = 0; i < n; ++i)
    if (!s.asleep[i] && s.stillFor[i] < model.sleep.time) ready[islandRoot(parent, i)] = 0;
  for (int i = 0; i < n; ++i) {
    const int root = islandRoot(parent, i);
    if (s.asleep[i] || !ready[root] || !grounded[root]) continue;
    s.asleep[i] = 1;
    s.island[i] = root;
    ++s.sleeping;
    s.restForce[i] = cache.impulses.linear[i] / h;
    s.restTorque[i] = cache.impulses.angular[i] / h;
    for (const SurfacePush& p : cache.impulses.pushes)
      if (p.body == i) s.resting.push_back({i, p.surface, p.impulse / h});
    data.Y[i].P.setZero();
    data.Y[i].L.setZero();
    data.aux[i].V.setZero();
    data.aux[i].omega.setZero();
  }
}

void setAsideSleeping(const SleepState& s, std::vector<ContactMemory>& memory, CollisionCache& cache) {
  std::vector<ContactMemory>& kept = cache.sleepingMemory;
  kept.clear();
  if (s.sleeping == 0) return;
  for (const ContactMemory& m : memory)
    if (s.asleep[m.a]) kept.push_back(m);
  memory.erase(std::remove_if(memory.begin(), memory.end(), [&](const ContactMemory& m) { return s.asleep[m.a]; }),
               memory.end());
}

void mergeBackSleeping(std::vector<ContactMemory>& memory, CollisionCache& cache) {
  const std::vector<ContactMemory>& kept = cache.sleepingMemory;
  std::vector<ContactMemory>& merged = cache.mergedMemory;
  if (kept.empty()) return;
  merged.clear();
  std::merge(memory.begin(), memory.end(), kept.begin(), kept.end(), std::back_inserter(merged),
             [](const ContactMemory& x, const ContactMemory& y) {
               return pairKey(x.a, x.b, x.surface) < pairKey(y.a, y.b, y.surface);
             });
  memory.swap(merged);
}

}  // namespace rigid
