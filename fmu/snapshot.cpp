#include "snapshot.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace rigidfmu {

namespace {

constexpr char kMagic[8] = {'R', 'I', 'G', 'I', 'D', 'F', 'M', 'U'};

class Writer {
 public:
  template <class T>
  void put(const T& v) {
    const char* p = reinterpret_cast<const char*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  void put(const rigid::Vec3& v) {
    for (int i = 0; i < 3; ++i) put(v[i]);
  }
  void put(const rigid::Quat& q) { put(q.w()), put(q.x()), put(q.y()), put(q.z()); }
  std::vector<char> bytes;
};

class Reader {
 public:
  Reader(const char* p, size_t n) : p_(p), n_(n) {}
  template <class T>
  bool get(T& v) {
    if (n_ - at_ < sizeof(T)) return false;
    std::memcpy(&v, p_ + at_, sizeof(T));
    at_ += sizeof(T);
    return true;
  }
  bool get(rigid::Vec3& v) { return get(v[0]) && get(v[1]) && get(v[2]); }
  bool get(rigid::Quat& q) { return get(q.w()) && get(q.x()) && get(q.y()) && get(q.z()); }
  bool done() const { return at_ == n_; }

 private:
  const char* p_;
  size_t n_, at_ = 0;
};

// The contact solver's points: each names bodies and a surface of this scene.
std::string readContactMemory(Reader& r, Snapshot& out, bool& ok) {
  uint32_t points = 0;
  ok = ok && r.get(points);
  if (!ok) return "";
  const int bodies = static_cast<int>(out.model.bodies.size());
  const int surfaces = static_cast<int>(out.model.surfaces.size());
  if (points > 64u * static_cast<uint32_t>(bodies)) return "the serialized state is corrupt (contact points)";
  out.data.contactMemory.assign(points, rigid::ContactMemory{});
  for (rigid::ContactMemory& m : out.data.contactMemory) {
    int32_t a = 0, b = 0, surface = 0;
    uint8_t sliding = 0;
    ok = ok && r.get(a) && r.get(b) && r.get(surface) && r.get(m.localA) && r.get(m.normalImpulse) &&
         r.get(m.tangentImpulse) && r.get(m.twistImpulse) && r.get(sliding);
    m.sliding = sliding != 0;
    if (!ok) return "";
    const bool pair = b >= 0 && b < bodies && surface == -1;
    const bool onSurface = b == -1 && surface >= 0 && surface < surfaces;
    if (a < 0 || a >= bodies || !(pair || onSurface))
      return "the serialized state is corrupt (a contact point names no body or surface of this scene)";
    m.a = a, m.b = b, m.surface = surface;
  }
  // the sleeping bodies' points are kept apart while they sleep (sleep_state.h)
  out.data.sleep.memory.clear();
  rigid::movePoints(out.data.contactMemory, out.data.sleep.memory, [&](const rigid::ContactMemory& m) {
    return out.data.sleep.asleep[static_cast<size_t>(m.a)] != 0;
  });
  return "";
}

// The forces that sleeping bodies keep giving surfaces: each names a sleeping body and
// a surface of this scene.
std::string readRestingPushes(Reader& r, Snapshot& out, bool& ok) {
  uint32_t count = 0;
  ok = ok && r.get(count);
  if (!ok) return "";
  const size_t bodies = out.model.bodies.size(), surfaces = out.model.surfaces.size();
  if (count > 64u * bodies) return "the serialized state is corrupt (resting forces)";
  out.data.sleep.resting.assign(count, rigid::RestingPush{});
  for (rigid::RestingPush& p : out.data.sleep.resting) {
    int32_t body = 0, surface = 0;
    ok = ok && r.get(body) && r.get(surface) && r.get(p.force);
    if (!ok) return "";
    if (body < 0 || static_cast<size_t>(body) >= bodies || surface < 0 || static_cast<size_t>(surface) >= surfaces ||
        !out.data.sleep.asleep[static_cast<size_t>(body)])
      return "the serialized state is corrupt (a resting force names no sleeping body or surface of this scene)";
    p.body = body, p.surface = surface;
  }
  return "";
}

// A body's load forces and their rates (as many as the scene gives it).
bool readLoads(Reader& r, rigid::BodyInput& input, rigid::BodyInput& rate) {
  for (size_t k = 0; k < input.loads.size(); ++k)
    if (!r.get(input.loads[k]) || !r.get(rate.loads[k])) return false;
  return true;
}

// Friction, densities and viscosities finite and >= 0, restitutions in [0, 1].
bool materialsInRange(const rigid::WorldModel& m) {
  auto ok = [](double v) { return std::isfinite(v) && v >= 0.0; };
  for (const rigid::BodyConstants& b : m.bodies)
    if (!ok(b.staticFriction) || !ok(b.kineticFriction) || !ok(b.restitution) || b.restitution > 1.0) return false;
  for (const rigid::Surface& f : m.surfaces)
    if (!ok(f.staticFriction) || !ok(f.kineticFriction) || !ok(f.restitution) || f.restitution > 1.0) return false;
  for (const rigid::Medium& f : m.media)
    if (!ok(f.density) || !ok(f.viscosity)) return false;
  return true;
}

// The magic bytes, the format version, the scene's GUID and its number of bodies: a
// state of another format or scene is refused before anything else is read.
std::string readHeader(Reader& r, size_t size, const std::string& guid, size_t bodies, uint32_t& n) {
  char magic[8];
  for (char& c : magic)
    if (!r.get(c)) return "the serialized state is too short (" + std::to_string(size) + " bytes)";
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) return "the bytes are not a rigidfmu state";
  uint32_t version = 0, guidLength = 0;
  if (!r.get(version) || version != kSnapshotVersion)
    return "state format version " + std::to_string(version) + ", this FMU reads version " +
           std::to_string(kSnapshotVersion);
  if (!r.get(guidLength) || guidLength > 256) return "the serialized state is corrupt (GUID length)";
  std::string theirs(guidLength, '\0');
  for (char& c : theirs)
    if (!r.get(c)) return "the serialized state is too short";
  if (theirs != guid) return "the state is of another scene (GUID " + theirs + ", this FMU " + guid + ")";
  if (!r.get(n) || n != bodies) return "the state holds another number of bodies";
  return "";
}

// Values applied only once the whole state is read; the method is checked after the
// size, so that a state of the wrong size is refused for its size.
struct Deferred {
  uint32_t machine = 0;
  uint8_t terminate = 0;
  int32_t method = 0;
  int64_t steps = 0;
};

// The instance's times and the world's solver settings.
bool readRunState(Reader& r, Snapshot& out, Deferred& later) {
  return r.get(later.machine) && r.get(later.terminate) && r.get(out.startTime) && r.get(out.time) &&
         r.get(out.lastSuccessfulTime) && r.get(out.lastStepSize) && r.get(out.model.gravity) && r.get(later.method) &&
         r.get(out.model.maxStep) && r.get(out.model.tolerance) && r.get(out.model.energyGainLimit);
}

// The parameters and start values of bodies, surfaces and media, each within its range.
std::string readParameters(Reader& r, Snapshot& out, bool& ok) {
  for (rigid::BodyConstants& b : out.model.bodies) {
    double mass = 0.0;
    ok = ok && r.get(mass) && r.get(b.restitution) && r.get(b.staticFriction) && r.get(b.kineticFriction) &&
         r.get(b.start.position) && r.get(b.start.orientation) && r.get(b.start.velocity) &&
         r.get(b.start.angularVelocity);
    if (ok && !(mass > 0.0 && std::isfinite(mass))) return "the state holds a mass that is not > 0";
    if (ok) rigid::setMass(b, mass);  // Ibody follows, as when the parameter is set
  }
  for (rigid::Surface& f : out.model.surfaces)
    ok = ok && r.get(f.staticFriction) && r.get(f.kineticFriction) && r.get(f.restitution);
  for (rigid::Medium& m : out.model.media) ok = ok && r.get(m.density) && r.get(m.viscosity);
  if (ok && !materialsInRange(out.model))
    return "the state holds a friction, restitution or fluid property out of range";
  return "";
}

// Each body's state, inputs, contact count, energy audit, sleep and contact loads; a
// body asleep exactly when it is in an island of this scene.
std::string readBodyStates(Reader& r, Snapshot& out, uint32_t n, bool& ok) {
  for (uint32_t i = 0; i < n && ok; ++i) {
    rigid::BodyState& y = out.data.Y[i];
    int32_t contacts = 0, island = 0;
    uint8_t asleep = 0;
    ok = r.get(y.X) && r.get(y.q) && r.get(y.P) && r.get(y.L) && r.get(out.data.input[i].force) &&
         r.get(out.data.input[i].torque) && r.get(out.data.inputRate[i].force) && r.get(out.data.inputRate[i].torque) &&
         readLoads(r, out.data.input[i], out.data.inputRate[i]) && r.get(contacts) && r.get(out.data.audit.energy[i]) &&
         r.get(out.data.audit.reference[i]) && r.get(out.data.audit.carried[i]) && r.get(asleep) &&
         r.get(out.data.sleep.stillFor[i]) && r.get(island) && r.get(out.data.sleep.restForce[i]) &&
         r.get(out.data.sleep.restTorque[i]) && r.get(out.data.contactLoads.impulse[i]) &&
         r.get(out.data.contactLoads.angularImpulse[i]);
    out.data.contacts[i] = contacts;
    if (ok && (asleep > 1 || island < -1 || island >= static_cast<int32_t>(n) || (asleep == 1) != (island >= 0)))
      return "the serialized state is corrupt (sleep of body " + std::to_string(i) + ")";
    out.data.sleep.asleep[i] = static_cast<char>(asleep);
    out.data.sleep.island[i] = island;
  }
  out.data.sleep.sleeping = static_cast<int>(std::count(out.data.sleep.asleep.begin(), out.data.sleep.asleep.end(), 1));
  out.data.sleep.boxes.reset();  // derived from the flags and poses just read
  return "";
}

// The surfaces' contact impulses of the last communication step, and its length.
bool readSurfaceLoads(Reader& r, Snapshot& out) {
  for (rigid::Vec3& J : out.data.contactLoads.surfaceImpulse)
    if (!r.get(J)) return false;
  return r.get(out.data.contactLoads.duration);
}

}  // namespace

std::vector<char> serialize(const Snapshot& s, const std::string& guid) {
  Writer w;
  for (char c : kMagic) w.put(c);
  w.put(kSnapshotVersion);
  w.put(static_cast<uint32_t>(guid.size()));
  for (char c : guid) w.put(c);
  const uint32_t n = static_cast<uint32_t>(s.model.bodies.size());
  w.put(n);
  w.put(static_cast<uint32_t>(s.machineState));
  w.put(static_cast<uint8_t>(s.wantsToTerminate));
  w.put(s.startTime), w.put(s.time), w.put(s.lastSuccessfulTime), w.put(s.lastStepSize);
  w.put(s.model.gravity);
  w.put(static_cast<int32_t>(s.model.method));
  w.put(s.model.maxStep), w.put(s.model.tolerance), w.put(s.model.energyGainLimit);
  for (const rigid::BodyConstants& b : s.model.bodies) {
    w.put(b.mass), w.put(b.restitution), w.put(b.staticFriction), w.put(b.kineticFriction);
    w.put(b.start.position), w.put(b.start.orientation), w.put(b.start.velocity), w.put(b.start.angularVelocity);
  }
  for (const rigid::Surface& f : s.model.surfaces)
    w.put(f.staticFriction), w.put(f.kineticFriction), w.put(f.restitution);
  for (const rigid::Medium& m : s.model.media) w.put(m.density), w.put(m.viscosity);
  for (uint32_t i = 0; i < n; ++i) {
    const rigid::BodyState& y = s.data.Y[i];
    w.put(y.X), w.put(y.q), w.put(y.P), w.put(y.L);
    w.put(s.data.input[i].force), w.put(s.data.input[i].torque);
    w.put(s.data.inputRate[i].force), w.put(s.data.inputRate[i].torque);
    for (size_t k = 0; k < s.data.input[i].loads.size(); ++k)
      w.put(s.data.input[i].loads[k]), w.put(s.data.inputRate[i].loads[k]);
    w.put(static_cast<int32_t>(s.data.contacts[i]));
    w.put(s.data.audit.energy[i]), w.put(s.data.audit.reference[i]), w.put(s.data.audit.carried[i]);
    w.put(static_cast<uint8_t>(s.data.sleep.asleep[i])), w.put(s.data.sleep.stillFor[i]);
    w.put(static_cast<int32_t>(s.data.sleep.island[i]));
    w.put(s.data.sleep.restForce[i]), w.put(s.data.sleep.restTorque[i]);
    w.put(s.data.contactLoads.impulse[i]), w.put(s.data.contactLoads.angularImpulse[i]);
  }
  for (const rigid::Vec3& J : s.data.contactLoads.surfaceImpulse) w.put(J);
  w.put(s.data.contactLoads.duration);
  w.put(static_cast<uint32_t>(s.data.sleep.resting.size()));
  for (const rigid::RestingPush& p : s.data.sleep.resting)
    w.put(static_cast<int32_t>(p.body)), w.put(static_cast<int32_t>(p.surface)), w.put(p.force);
  w.put(static_cast<int64_t>(s.data.steps));
  w.put(s.data.integrator.errorEstimate);
  w.put(s.data.integrator.adaptiveStep);
  // the awake bodies' contact memory, then the sleeping ones' (readContactMemory parts them)
  w.put(static_cast<uint32_t>(s.data.contactMemory.size() + s.data.sleep.memory.size()));
  for (const auto* memory : {&s.data.contactMemory, &s.data.sleep.memory}) {
    for (const rigid::ContactMemory& m : *memory) {
      w.put(static_cast<int32_t>(m.a)), w.put(static_cast<int32_t>(m.b)), w.put(static_cast<int32_t>(m.surface));
      w.put(m.localA), w.put(m.normalImpulse), w.put(m.tangentImpulse), w.put(m.twistImpulse),
          w.put(static_cast<uint8_t>(m.sliding));
    }
  }
  return w.bytes;
}

std::string deserialize(const char* bytes, size_t size, const std::string& guid, Snapshot& s) {
  if (!bytes) return "the serialized state is NULL";
  Reader r(bytes, size);
  uint32_t n = 0;
  if (std::string why = readHeader(r, size, guid, s.model.bodies.size(), n); !why.empty()) return why;
  // read into a copy: `s` changes only when the whole state is accepted
  Snapshot out = s;
  Deferred later;
  bool ok = readRunState(r, out, later);
  if (std::string why = readParameters(r, out, ok); !why.empty()) return why;
  if (std::string why = readBodyStates(r, out, n, ok); !why.empty()) return why;
  ok = ok && readSurfaceLoads(r, out);
  if (std::string why = readRestingPushes(r, out, ok); !why.empty()) return why;
  ok = ok && r.get(later.steps) && r.get(out.data.integrator.errorEstimate) && r.get(out.data.integrator.adaptiveStep);
  if (std::string why = readContactMemory(r, out, ok); !why.empty()) return why;
  if (!ok || !r.done())
    return "the serialized state has " + std::to_string(size) + " bytes, not the size of a state of this scene";
  const auto m = rigid::methodFromValue(later.method);
  if (!m) return "the state holds an unknown solver.method " + std::to_string(later.method);
  out.model.method = *m;
  out.data.steps = later.steps;
  out.machineState = later.machine;
  out.wantsToTerminate = later.terminate != 0;
  rigid::refreshAuxiliaries(out.model, out.data);
  s = std::move(out);
  return "";
}

}  // namespace rigidfmu
