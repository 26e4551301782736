#include "snapshot.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>
#include <utility>

namespace rigidfmu {

namespace {

constexpr char kMagic[8] = {'R', 'I', 'G', 'I', 'D', 'F', 'M', 'U'};

// ---- two archives, one visit ----------------------------------------------------------
// visitState() names every field of a state once, in the order of the bytes; a Writer
// appends each field's bytes, a Reader reads them back into it. Doubles, Vec3 (x, y, z)
// and Quat (w, x, y, z) go as doubles; an integer with the width its call names (i32,
// u32, u8, i64), whatever its width in memory; a list of variable length as its count
// (u32), then its elements. Any other type is refused at compile time (a deleted
// overload), so that no field changes its width unseen.

class Writer {
 public:
  void operator()(const double& v) { put(v); }
  void operator()(const rigid::Vec3& v) { put(v[0]), put(v[1]), put(v[2]); }
  void operator()(const rigid::Quat& q) { put(q.w()), put(q.x()), put(q.y()), put(q.z()); }
  template <class T>
  void operator()(const T&) = delete;
  template <class T>
  void i32(const T& v) {
    put(wire<int32_t>(v));
  }
  template <class T>
  void u32(const T& v) {
    put(wire<uint32_t>(v));
  }
  template <class T>
  void u8(const T& v) {
    put(wire<uint8_t>(v));
  }
  template <class T>
  void i64(const T& v) {
    put(wire<int64_t>(v));
  }

  // The count, then each element; `most` and `corrupt` are the Reader's.
  template <class T, class Element>
  void list(const std::vector<T>& v, size_t /*most*/, const char* /*corrupt*/, Element element) {
    u32(v.size());
    for (const T& e : v) element(e);
  }
  // Two lists as one: the count of both, then the elements of `first` and `second`.
  template <class T, class Element>
  void joinedList(const std::vector<T>& first, const std::vector<T>& second, size_t /*most*/, const char* /*corrupt*/,
                  Element element) {
    u32(first.size() + second.size());
    for (const T& e : first) element(e);
    for (const T& e : second) element(e);
  }

  // A value's bytes as in memory (little-endian on every target the FMU is built for).
  template <class T>
  void put(const T& v) {
    static_assert(std::is_arithmetic_v<T>, "only numbers are written as they are in memory");
    const char* p = reinterpret_cast<const char*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }

  std::vector<char> bytes;

 private:
  template <class Wire, class T>
  static Wire wire(const T& v) {
    static_assert(std::is_integral_v<T> || std::is_enum_v<T>, "a number with a fraction goes as a double");
    return static_cast<Wire>(v);
  }
};

// Reads until the bytes run out or a list's count is refused; from then on it reads
// nothing and every field keeps the value it had.
class Reader {
 public:
  Reader(const char* p, size_t n) : p_(p), n_(n) {}

  void operator()(double& v) { get(v); }
  void operator()(rigid::Vec3& v) { get(v[0]), get(v[1]), get(v[2]); }
  void operator()(rigid::Quat& q) { get(q.w()), get(q.x()), get(q.y()), get(q.z()); }
  template <class T>
  void operator()(T&) = delete;
  template <class T>
  void i32(T& v) {
    take<int32_t>(v);
  }
  template <class T>
  void u32(T& v) {
    take<uint32_t>(v);
  }
  template <class T>
  void u8(T& v) {
    take<uint8_t>(v);
  }
  template <class T>
  void i64(T& v) {
    take<int64_t>(v);
  }

  // The count, refused (`corrupt`) above `most` before anything is allocated, then each
  // element.
  template <class T, class Element>
  void list(std::vector<T>& v, size_t most, const char* corrupt, Element element) {
    uint32_t count = 0;
    if (!get(count)) return;
    if (count > most) {
      refusal_ = corrupt;
      return;
    }
    v.assign(count, T{});
    for (T& e : v) element(e);
  }
  // Both lists' elements into `first`, `second` emptied: the caller parts them again.
  template <class T, class Element>
  void joinedList(std::vector<T>& first, std::vector<T>& second, size_t most, const char* corrupt, Element element) {
    second.clear();
    list(first, most, corrupt, element);
  }

  // A value's bytes into v; false (v as it was) once the bytes ran out or a count was
  // refused.
  template <class T>
  bool get(T& v) {
    if (tooShort_ || !refusal_.empty()) return false;
    if (n_ - at_ < sizeof(T)) {
      tooShort_ = true;
      return false;
    }
    std::memcpy(&v, p_ + at_, sizeof(T));
    at_ += sizeof(T);
    return true;
  }

  // Why a count was refused, "" when none was.
  const std::string& refusal() const { return refusal_; }
  // Every field read, and no byte left over.
  bool complete() const { return !tooShort_ && refusal_.empty() && at_ == n_; }

 private:
  template <class Wire, class T>
  void take(T& v) {
    static_assert(std::is_integral_v<T> || std::is_enum_v<T>, "a number with a fraction goes as a double");
    Wire w{};
    if (get(w)) v = static_cast<T>(w);
  }

  const char* p_;
  size_t n_, at_ = 0;
  bool tooShort_ = false;
  std::string refusal_;
};

// ---- the state, field by field --------------------------------------------------------
// One visit for both directions: State is `const Snapshot` when writing and `Snapshot`
// when reading (Model and Data likewise). Its order is the order of the bytes, format
// kSnapshotVersion: a change here is a change of the format (test_snapshot.cpp pins it).

// The instance's machine state, times and last step, and the world's solver settings.
template <class Archive, class State>
void visitRun(Archive& a, State& s) {
  a.u32(s.machineState), a.u8(s.wantsToTerminate);
  a(s.startTime), a(s.clock.origin), a(s.clock.step), a.i64(s.clock.count), a(s.lastStepSize);
  a(s.model.gravity), a.i32(s.model.method);
  a(s.model.maxStep), a(s.model.tolerance), a(s.model.energyGainLimit);
}

// The parameters and start values of bodies, surfaces (a conveyor's belt velocity
// too) and media; the rest of the model is the scene's, which the GUID names.
template <class Archive, class Model>
void visitParameters(Archive& a, Model& m) {
  for (auto& b : m.bodies) {
    a(b.mass), a(b.restitution), a(b.staticFriction), a(b.kineticFriction);
    a(b.start.position), a(b.start.orientation), a(b.start.velocity), a(b.start.angularVelocity);
  }
  for (auto& f : m.surfaces) a(f.staticFriction), a(f.kineticFriction), a(f.restitution);
  for (auto& f : m.media) a(f.density), a(f.viscosity);
  for (auto& f : m.surfaces)
    if (f.belt) a(f.beltVelocity);
}

// Body i's state Y, inputs and their rates (with those of its load points, as many as
// the scene gives it), contact count, energy audit, sleep and contact loads.
template <class Archive, class Data>
void visitBody(Archive& a, Data& d, size_t i) {
  auto& y = d.Y[i];
  auto &input = d.input[i], &rate = d.inputRate[i];
  a(y.X), a(y.q), a(y.P), a(y.L);
  a(input.force), a(input.torque), a(rate.force), a(rate.torque);
  for (size_t k = 0; k < input.loads.size(); ++k) a(input.loads[k]), a(rate.loads[k]);
  auto& drive = d.drive[i];  // (a free body's: its start values, unused)
  a(drive.position), a(drive.orientation), a(drive.velocity), a(drive.angularVelocity);
  a(drive.acceleration), a(drive.angularAcceleration);
  a.i32(d.contacts[i]);
  a(d.audit.energy[i]), a(d.audit.reference[i]), a(d.audit.carried[i]);
  a.u8(d.sleep.asleep[i]), a(d.sleep.stillFor[i]), a.i32(d.sleep.island[i]);
  a(d.sleep.restForce[i]), a(d.sleep.restTorque[i]);
  a(d.contactLoads.impulse[i]), a(d.contactLoads.angularImpulse[i]);
}

template <class Archive, class Push>
void visitRestingPush(Archive& a, Push& p) {
  a.i32(p.body), a.i32(p.surface), a(p.force);
}

template <class Archive, class Point>
void visitContactPoint(Archive& a, Point& m) {
  a.i32(m.a), a.i32(m.b), a.i32(m.surface);
  a(m.localA), a(m.normalImpulse), a(m.tangentImpulse), a(m.twistImpulse), a.u8(m.sliding);
}

// Each joint's tunable parameters and inputs' start values, then its run's memory,
// inputs, reactions and coordinates (how many joints, and of which type, is the scene's).
template <class Archive, class Model, class Data>
void visitJoints(Archive& a, Model& m, Data& d) {
  for (size_t k = 0; k < m.joints.size(); ++k) {
    auto& j = m.joints[k];
    a(j.maxMotorForce), a(j.stiffness), a(j.damping), a(j.restitution), a(j.lower), a(j.upper);
    a(j.motorSpeed), a(j.targetPosition);
    for (auto& impulse : d.joints.memory[k]) a(impulse);
    a(d.joints.angle[k]), a(d.joints.motorSpeed[k]), a(d.joints.targetPosition[k]);
    a(d.joints.motorSpeedRate[k]), a(d.joints.targetPositionRate[k]);
    a(d.joints.impulse[k]), a(d.joints.angularImpulse[k]), a(d.joints.position[k]), a(d.joints.speed[k]);
  }
}

// Every field of a state, in the order of its bytes (after the header).
template <class Archive, class State>
void visitState(Archive& a, State& s) {
  visitRun(a, s);
  visitParameters(a, s.model);
  auto& d = s.data;
  for (size_t i = 0; i < d.Y.size(); ++i) visitBody(a, d, i);
  for (auto& J : d.contactLoads.surfaceImpulse) a(J);
  a(d.contactLoads.duration);
  // the conveyors' belt inputs and their rates (other surfaces have none: zero)
  for (size_t k = 0; k < s.model.surfaces.size(); ++k)
    if (s.model.surfaces[k].belt) a(d.beltVelocity[k]), a(d.beltRate[k]);
  // lists that a corrupt count would make huge: at most 64 elements a body
  const size_t most = 64 * d.Y.size();
  a.list(d.sleep.resting, most, "the serialized state is corrupt (resting forces)",
         [&](auto& p) { visitRestingPush(a, p); });
  a.i64(d.steps);
  a(d.integrator.errorEstimate), a(d.integrator.adaptiveStep);
  // the awake bodies' contact memory, then the sleeping ones' (acceptContactMemory parts them)
  a.joinedList(d.contactMemory, d.sleep.memory, most, "the serialized state is corrupt (contact points)",
               [&](auto& m) { visitContactPoint(a, m); });
  visitJoints(a, s.model, d);
}

// ---- the tripwire ---------------------------------------------------------------------
// A field added to a struct that a state is made of must be visited above, or be derived
// or a constant of the scene: these counts stop the build until someone has decided which
// and updated the count. Fields, not sizeof: a small field may hide in padding, and sizes
// differ between targets (Eigen's alignment, a 4-byte long on Windows).

// Converts to any field's type; declared only, for unevaluated operands.
struct AnyField {
  template <class T>
  operator T() const;
};

template <class T, class Indices, class = void>
struct TakesInitialisers : std::false_type {};
template <class T, size_t... I>
struct TakesInitialisers<T, std::index_sequence<I...>, std::void_t<decltype(T{(void(I), AnyField{})...})>>
    : std::true_type {};

// The number of fields of the aggregate T: the most initialisers that T{...} takes.
template <class T, size_t N = 0>
constexpr size_t fieldCount() {
  if constexpr (TakesInitialisers<T, std::make_index_sequence<N + 1>>::value)
    return fieldCount<T, N + 1>();
  else
    return N;
}

// clang-format off
static_assert(fieldCount<Snapshot>() == 7,
              "a field was added to Snapshot: visit it in visitRun (fmu/snapshot.cpp), then update this count");
static_assert(fieldCount<rigid::WorldModel>() == 11,
              "a field was added to rigid::WorldModel: if a parameter sets it, visit it in visitRun "
              "(fmu/snapshot.cpp); then update this count");
static_assert(fieldCount<rigid::BodyConstants>() == 16,
              "a field was added to rigid::BodyConstants: if a parameter sets it, visit it in visitParameters "
              "(fmu/snapshot.cpp); then update this count");
static_assert(fieldCount<rigid::BodyStart>() == 4,
              "a field was added to rigid::BodyStart: visit it in visitParameters (fmu/snapshot.cpp), then update "
              "this count");
static_assert(fieldCount<rigid::Surface>() == 15,
              "a field was added to rigid::Surface: if a parameter sets it, visit it in visitParameters "
              "(fmu/snapshot.cpp); then update this count");
static_assert(fieldCount<rigid::Medium>() == 6,
              "a field was added to rigid::Medium: if a parameter sets it, visit it in visitParameters "
              "(fmu/snapshot.cpp); then update this count");
static_assert(fieldCount<rigid::WorldData>() == 19,
              "a field was added to rigid::WorldData: unless it is derived or scratch, visit it in visitState "
              "(fmu/snapshot.cpp); then update this count");
static_assert(fieldCount<rigid::BodyState>() == 4,
              "a field was added to rigid::BodyState: visit it in visitBody (fmu/snapshot.cpp), then update this "
              "count");
static_assert(fieldCount<rigid::BodyInput>() == 3,
              "a field was added to rigid::BodyInput: visit it in visitBody (fmu/snapshot.cpp), then update this "
              "count");
static_assert(fieldCount<rigid::DriveInput>() == 6,
              "a field was added to rigid::DriveInput: visit it in visitBody (fmu/snapshot.cpp), then update this "
              "count");
static_assert(fieldCount<rigid::WorldData::EnergyAudit>() == 3,
              "a field was added to rigid::WorldData::EnergyAudit: visit it in visitBody (fmu/snapshot.cpp), then "
              "update this count");
static_assert(fieldCount<rigid::SleepState>() == 9,
              "a field was added to rigid::SleepState: unless it is derived, visit it in visitBody or visitState "
              "(fmu/snapshot.cpp); then update this count");
static_assert(fieldCount<rigid::WorldData::ContactLoads>() == 4,
              "a field was added to rigid::WorldData::ContactLoads: visit it in visitBody or visitState "
              "(fmu/snapshot.cpp), then update this count");
static_assert(fieldCount<rigid::RestingPush>() == 3,
              "a field was added to rigid::RestingPush: visit it in visitRestingPush (fmu/snapshot.cpp), then "
              "update this count");
static_assert(fieldCount<rigid::IntegratorState>() == 2,
              "a field was added to rigid::IntegratorState: visit it in visitState (fmu/snapshot.cpp), then update "
              "this count");
static_assert(fieldCount<rigid::JointConstants>() == 23,
              "a field was added to rigid::JointConstants: if a parameter or input sets it, visit it in "
              "visitJoints (fmu/snapshot.cpp); then update this count");
static_assert(fieldCount<rigid::JointData>() == 10,
              "a field was added to rigid::JointData: unless it is derived, visit it in visitJoints "
              "(fmu/snapshot.cpp); then update this count");
static_assert(fieldCount<rigid::ContactMemory>() == 8,
              "a field was added to rigid::ContactMemory: visit it in visitContactPoint (fmu/snapshot.cpp), then "
              "update this count");
// clang-format on

// ---- the header -----------------------------------------------------------------------

// The magic bytes, the format version, the scene's GUID and its number of bodies.
void writeHeader(Writer& w, const std::string& guid, size_t bodies) {
  for (char c : kMagic) w.put(c);
  w.put(kSnapshotVersion);
  w.u32(guid.size());
  for (char c : guid) w.put(c);
  w.u32(bodies);
}

// A state of another format or scene is refused before anything else is read.
std::string readHeader(Reader& r, size_t size, const std::string& guid, size_t bodies) {
  char magic[8];
  for (char& c : magic)
    if (!r.get(c)) return "the serialized state is too short (" + std::to_string(size) + " bytes)";
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) return "the bytes are not a rigidfmu state";
  uint32_t version = 0, guidLength = 0, n = 0;
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

// ---- what the reader checks and derives, once every field is read ---------------------

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

// A motor's force > 0, springs' stiffness and damping >= 0, restitution in [0, 1],
// limits finite with lower <= upper: what setting the parameters allows.
bool jointsInRange(const rigid::WorldModel& m) {
  auto ok = [](double v) { return std::isfinite(v) && v >= 0.0; };
  for (const rigid::JointConstants& j : m.joints)
    if (!(j.maxMotorForce > 0.0 || !j.motor) || !ok(j.maxMotorForce) || !ok(j.stiffness) || !ok(j.damping) ||
        !ok(j.restitution) || j.restitution > 1.0 || !std::isfinite(j.lower) || !std::isfinite(j.upper) ||
        j.lower > j.upper)
      return false;
  return true;
}

// Masses > 0, each then set again so that Ibody follows, as when the parameter is set;
// materials in range.
std::string acceptParameters(rigid::WorldModel& m) {
  for (rigid::BodyConstants& b : m.bodies) {
    if (!(b.mass > 0.0 && std::isfinite(b.mass))) return "the state holds a mass that is not > 0";
    rigid::setMass(b, b.mass);
  }
  if (!materialsInRange(m)) return "the state holds a friction, restitution or fluid property out of range";
  if (!jointsInRange(m)) return "the state holds a joint's parameter out of range";
  return "";
}

// Each body asleep exactly when it is in an island of this scene; the count of sleepers
// and their bounding boxes follow from the flags.
std::string acceptSleep(rigid::SleepState& sleep) {
  const int n = static_cast<int>(sleep.asleep.size());
  for (int i = 0; i < n; ++i) {
    const char asleep = sleep.asleep[static_cast<size_t>(i)];
    const int island = sleep.island[static_cast<size_t>(i)];
    if ((asleep != 0 && asleep != 1) || island < -1 || island >= n || (asleep == 1) != (island >= 0))
      return "the serialized state is corrupt (sleep of body " + std::to_string(i) + ")";
  }
  sleep.sleeping = static_cast<int>(std::count(sleep.asleep.begin(), sleep.asleep.end(), 1));
  sleep.boxes.reset();  // derived from the flags and poses just read
  return "";
}

// The forces that sleeping bodies keep giving surfaces: each names a sleeping body and
// a surface of this scene.
std::string acceptRestingPushes(const rigid::WorldModel& m, const rigid::SleepState& sleep) {
  const size_t bodies = m.bodies.size(), surfaces = m.surfaces.size();
  for (const rigid::RestingPush& p : sleep.resting)
    if (p.body < 0 || static_cast<size_t>(p.body) >= bodies || p.surface < 0 ||
        static_cast<size_t>(p.surface) >= surfaces || !sleep.asleep[static_cast<size_t>(p.body)])
      return "the serialized state is corrupt (a resting force names no sleeping body or surface of this scene)";
  return "";
}

// The contact solver's points: each names bodies and a surface of this scene. The
// sleeping bodies' points are then set apart, as they are kept while they sleep
// (sleep_state.h).
std::string acceptContactMemory(const rigid::WorldModel& m, rigid::WorldData& d) {
  const int bodies = static_cast<int>(m.bodies.size()), surfaces = static_cast<int>(m.surfaces.size());
  for (const rigid::ContactMemory& p : d.contactMemory) {
    const bool pair = p.b >= 0 && p.b < bodies && p.surface == -1;
    const bool onSurface = p.b == -1 && p.surface >= 0 && p.surface < surfaces;
    if (p.a < 0 || p.a >= bodies || !(pair || onSurface))
      return "the serialized state is corrupt (a contact point names no body or surface of this scene)";
  }
  rigid::setAsideSleeping(d.sleep, d.contactMemory);  // the sleepers' points wait in the sleep state
  return "";
}

// Checks the values read and derives what follows from them, in the order of the bytes
// but for the method, last. Made only once every byte is read, so that a state of the
// wrong size is refused for its size, whatever values it holds.
std::string accept(Snapshot& out) {
  std::string why = acceptParameters(out.model);
  if (why.empty()) why = acceptSleep(out.data.sleep);
  if (why.empty()) why = acceptRestingPushes(out.model, out.data.sleep);
  if (why.empty()) why = acceptContactMemory(out.model, out.data);
  const int method = static_cast<int>(out.model.method);
  if (why.empty() && !rigid::methodFromValue(method))
    why = "the state holds an unknown solver.method " + std::to_string(method);
  return why;
}

}  // namespace

std::vector<char> serialize(const Snapshot& s, const std::string& guid) {
  Writer w;
  writeHeader(w, guid, s.model.bodies.size());
  visitState(w, s);
  return w.bytes;
}

std::string deserialize(const char* bytes, size_t size, const std::string& guid, Snapshot& s) {
  if (!bytes) return "the serialized state is NULL";
  Reader r(bytes, size);
  if (std::string why = readHeader(r, size, guid, s.model.bodies.size()); !why.empty()) return why;
  // read into a copy: `s` changes only when the whole state is accepted
  Snapshot out = s;
  visitState(r, out);
  if (!r.refusal().empty()) return r.refusal();
  if (!r.complete())
    return "the serialized state has " + std::to_string(size) + " bytes, not the size of a state of this scene";
  if (std::string why = accept(out); !why.empty()) return why;
  rigid::refreshAuxiliaries(out.model, out.data);
  s = std::move(out);
  return "";
}

}  // namespace rigidfmu
