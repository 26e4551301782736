// FMU states' bytes (fmu/snapshot.cpp): every field a state holds comes back from them
// into its own place, they are the bytes of format version kSnapshotVersion, and bytes
// that hold a value out of range, or are of another size or scene, are refused with the
// reason, the snapshot read into left as it was.
#include "snapshot.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scene.h"

namespace {

using rigid::ContactMemory;
using rigid::Quat;
using rigid::Vec3;
using rigidfmu::Snapshot;

const std::string kGuid = "{5eed5eed-0000-4000-8000-000000000039}";

// Two bodies (one with two load points), two surfaces and a medium: every list a state
// holds has an element, the load points' one has two.
const char* const kScene = R"({
  "name": "Snap", "solver": {"method": "rk4", "step": 0.001},
  "bodies": [
    {"name": "a", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "mass": 1.0, "position": [0, 0, 0.1],
     "loads": [{"name": "thruster", "point": [0, 0, -0.1], "frame": "body"},
               {"name": "tether", "point": [0, 0.1, 0.1], "frame": "world"}]},
    {"name": "b", "shape": {"type": "sphere", "radius": 0.1}, "mass": 2.0, "position": [1, 0, 0.1]}],
  "surfaces": [{"name": "floor", "min": [-5, -5, -1], "max": [5, 5, 0]},
               {"name": "wall", "min": [5, -5, 0], "max": [6, 5, 1]}],
  "media": [{"name": "pool", "type": "water", "min": [-1, -1, -2], "max": [1, 1, -1]}]})";

rigid::WorldModel sceneModel() { return rigid::parseScene(kScene).model; }

// What a fresh instance of the scene holds: the frame that bytes are read into.
Snapshot fresh(const rigid::WorldModel& model) {
  Snapshot s;
  s.model = model;
  s.data = rigid::initialData(model);
  return s;
}

// Distinct values, each exact in binary (1.5, 2.5, ...): a field read from another
// field's place shows, and the bytes do not depend on rounding.
struct Values {
  double k = 0.5;
  double next() { return k += 1.0; }
  double fraction() { return next() / 1024.0; }  // in [0, 1] for the first thousand values
  Vec3 vec() {
    const double x = next(), y = next();
    return Vec3(x, y, next());
  }
  Quat quat() {  // need not be unit: the bytes carry it as it is
    const double w = next(), x = next(), y = next();
    return Quat(w, x, y, next());
  }
};

ContactMemory point(int a, int b, int surface, bool sliding, Values& v) {
  ContactMemory m;
  m.a = a, m.b = b, m.surface = surface, m.sliding = sliding;
  m.localA = v.vec(), m.normalImpulse = v.next(), m.tangentImpulse = v.vec(), m.twistImpulse = v.next();
  return m;
}

void fillRunAndParameters(Snapshot& s, Values& v) {
  s.machineState = 8u;
  s.wantsToTerminate = true;
  s.startTime = v.next(), s.clock = {v.next(), v.next(), 1234567}, s.lastStepSize = v.next();
  s.model.gravity = v.vec();
  s.model.method = rigid::Method::Dopri5;
  s.model.maxStep = v.next(), s.model.tolerance = v.next(), s.model.energyGainLimit = v.next();
  for (rigid::BodyConstants& b : s.model.bodies) {
    rigid::setMass(b, v.next());
    b.restitution = v.fraction(), b.staticFriction = v.next(), b.kineticFriction = v.next();
    b.start = {v.vec(), v.quat(), v.vec(), v.vec()};
  }
  for (rigid::Surface& f : s.model.surfaces)
    f.staticFriction = v.next(), f.kineticFriction = v.next(), f.restitution = v.fraction();
  for (rigid::Medium& m : s.model.media) m.density = v.next(), m.viscosity = v.next();
}

// Body 0 awake, body 1 asleep (an island of its own), resting on the floor.
void fillBodies(rigid::WorldData& d, Values& v) {
  for (size_t i = 0; i < d.Y.size(); ++i) {
    d.Y[i] = {v.vec(), v.quat(), v.vec(), v.vec()};
    d.input[i].force = v.vec(), d.input[i].torque = v.vec();
    d.inputRate[i].force = v.vec(), d.inputRate[i].torque = v.vec();
    for (size_t k = 0; k < d.input[i].loads.size(); ++k)
      d.input[i].loads[k] = v.vec(), d.inputRate[i].loads[k] = v.vec();
    d.drive[i] = {v.vec(), v.quat(), v.vec(), v.vec(), v.vec(), v.vec()};
    d.contacts[i] = static_cast<int>(i) + 3;
    d.audit.energy[i] = v.next(), d.audit.reference[i] = v.next(), d.audit.carried[i] = v.next();
    d.sleep.asleep[i] = i == 1;
    d.sleep.island[i] = i == 1 ? 1 : -1;
    d.sleep.stillFor[i] = v.next();
    d.sleep.restForce[i] = v.vec(), d.sleep.restTorque[i] = v.vec();
    d.contactLoads.impulse[i] = v.vec(), d.contactLoads.angularImpulse[i] = v.vec();
  }
  d.sleep.sleeping = 1;
  for (Vec3& J : d.contactLoads.surfaceImpulse) J = v.vec();
  d.contactLoads.duration = v.next();
}

void fillHistory(rigid::WorldData& d, Values& v) {
  d.sleep.resting = {{1, 0, v.vec()}};
  d.steps = 1234567;
  d.integrator.errorEstimate = v.next(), d.integrator.adaptiveStep = v.next();
  d.contactMemory = {point(0, 1, -1, true, v), point(0, -1, 0, false, v), point(0, -1, 1, true, v)};
  d.sleep.memory = {point(1, -1, 0, false, v), point(1, -1, 0, true, v)};
}

// A snapshot of the scene whose every saved field holds a value of its own.
Snapshot filled(const rigid::WorldModel& model) {
  Snapshot s = fresh(model);
  Values v;
  fillRunAndParameters(s, v);
  fillBodies(s.data, v);
  fillHistory(s.data, v);
  return s;
}

void expectSamePoints(const std::vector<ContactMemory>& x, const std::vector<ContactMemory>& y) {
  ASSERT_EQ(x.size(), y.size());
  for (size_t k = 0; k < x.size(); ++k) {
    EXPECT_EQ(x[k].a, y[k].a);
    EXPECT_EQ(x[k].b, y[k].b);
    EXPECT_EQ(x[k].surface, y[k].surface);
    EXPECT_EQ(x[k].localA, y[k].localA);
    EXPECT_EQ(x[k].normalImpulse, y[k].normalImpulse);
    EXPECT_EQ(x[k].tangentImpulse, y[k].tangentImpulse);
    EXPECT_EQ(x[k].twistImpulse, y[k].twistImpulse);
    EXPECT_EQ(x[k].sliding, y[k].sliding) << "point " << k;
  }
}

void expectSameRunAndParameters(const Snapshot& x, const Snapshot& y) {
  EXPECT_EQ(x.machineState, y.machineState);
  EXPECT_EQ(x.wantsToTerminate, y.wantsToTerminate);
  EXPECT_EQ(x.startTime, y.startTime);
  EXPECT_EQ(x.clock.origin, y.clock.origin);
  EXPECT_EQ(x.clock.step, y.clock.step);
  EXPECT_EQ(x.clock.count, y.clock.count);
  EXPECT_EQ(x.lastStepSize, y.lastStepSize);
  EXPECT_EQ(x.model.gravity, y.model.gravity);
  EXPECT_EQ(x.model.method, y.model.method);
  EXPECT_EQ(x.model.maxStep, y.model.maxStep);
  EXPECT_EQ(x.model.tolerance, y.model.tolerance);
  EXPECT_EQ(x.model.energyGainLimit, y.model.energyGainLimit);
  for (size_t i = 0; i < x.model.bodies.size(); ++i) {
    const rigid::BodyConstants &a = x.model.bodies[i], &b = y.model.bodies[i];
    EXPECT_EQ(a.mass, b.mass);
    EXPECT_EQ(a.Ibody, b.Ibody);
    EXPECT_EQ(a.restitution, b.restitution);
    EXPECT_EQ(a.staticFriction, b.staticFriction);
    EXPECT_EQ(a.kineticFriction, b.kineticFriction);
    EXPECT_EQ(a.start.position, b.start.position);
    EXPECT_EQ(a.start.orientation.coeffs(), b.start.orientation.coeffs());
    EXPECT_EQ(a.start.velocity, b.start.velocity);
    EXPECT_EQ(a.start.angularVelocity, b.start.angularVelocity);
  }
  for (size_t k = 0; k < x.model.surfaces.size(); ++k) {
    const rigid::Surface &a = x.model.surfaces[k], &b = y.model.surfaces[k];
    EXPECT_EQ(a.staticFriction, b.staticFriction);
    EXPECT_EQ(a.kineticFriction, b.kineticFriction);
    EXPECT_EQ(a.restitution, b.restitution);
  }
  for (size_t k = 0; k < x.model.media.size(); ++k) {
    EXPECT_EQ(x.model.media[k].density, y.model.media[k].density);
    EXPECT_EQ(x.model.media[k].viscosity, y.model.media[k].viscosity);
  }
}

void expectSameBodies(const rigid::WorldData& x, const rigid::WorldData& y) {
  for (size_t i = 0; i < x.Y.size(); ++i) {
    EXPECT_EQ(x.Y[i].X, y.Y[i].X);
    EXPECT_EQ(x.Y[i].q.coeffs(), y.Y[i].q.coeffs());
    EXPECT_EQ(x.Y[i].P, y.Y[i].P);
    EXPECT_EQ(x.Y[i].L, y.Y[i].L);
    EXPECT_EQ(x.input[i].force, y.input[i].force);
    EXPECT_EQ(x.input[i].torque, y.input[i].torque);
    EXPECT_EQ(x.input[i].loads, y.input[i].loads);
    EXPECT_EQ(x.inputRate[i].loads, y.inputRate[i].loads);
    EXPECT_EQ(x.inputRate[i].force, y.inputRate[i].force);
    EXPECT_EQ(x.inputRate[i].torque, y.inputRate[i].torque);
    EXPECT_EQ(x.drive[i].position, y.drive[i].position);
    EXPECT_EQ(x.drive[i].orientation.coeffs(), y.drive[i].orientation.coeffs());
    EXPECT_EQ(x.drive[i].velocity, y.drive[i].velocity);
    EXPECT_EQ(x.drive[i].angularVelocity, y.drive[i].angularVelocity);
    EXPECT_EQ(x.drive[i].acceleration, y.drive[i].acceleration);
    EXPECT_EQ(x.drive[i].angularAcceleration, y.drive[i].angularAcceleration);
    EXPECT_EQ(x.contacts[i], y.contacts[i]);
    EXPECT_EQ(x.audit.energy[i], y.audit.energy[i]);
    EXPECT_EQ(x.audit.reference[i], y.audit.reference[i]);
    EXPECT_EQ(x.audit.carried[i], y.audit.carried[i]);
    EXPECT_EQ(x.sleep.asleep[i], y.sleep.asleep[i]);
    EXPECT_EQ(x.sleep.island[i], y.sleep.island[i]);
    EXPECT_EQ(x.sleep.stillFor[i], y.sleep.stillFor[i]);
    EXPECT_EQ(x.sleep.restForce[i], y.sleep.restForce[i]);
    EXPECT_EQ(x.sleep.restTorque[i], y.sleep.restTorque[i]);
    EXPECT_EQ(x.contactLoads.impulse[i], y.contactLoads.impulse[i]);
    EXPECT_EQ(x.contactLoads.angularImpulse[i], y.contactLoads.angularImpulse[i]) << "body " << i;
  }
  EXPECT_EQ(x.sleep.sleeping, y.sleep.sleeping);
  EXPECT_EQ(x.contactLoads.surfaceImpulse, y.contactLoads.surfaceImpulse);
  EXPECT_EQ(x.contactLoads.duration, y.contactLoads.duration);
}

void expectSameHistory(const rigid::WorldData& x, const rigid::WorldData& y) {
  ASSERT_EQ(x.sleep.resting.size(), y.sleep.resting.size());
  for (size_t k = 0; k < x.sleep.resting.size(); ++k) {
    EXPECT_EQ(x.sleep.resting[k].body, y.sleep.resting[k].body);
    EXPECT_EQ(x.sleep.resting[k].surface, y.sleep.resting[k].surface);
    EXPECT_EQ(x.sleep.resting[k].force, y.sleep.resting[k].force);
  }
  EXPECT_EQ(x.steps, y.steps);
  EXPECT_EQ(x.integrator.errorEstimate, y.integrator.errorEstimate);
  EXPECT_EQ(x.integrator.adaptiveStep, y.integrator.adaptiveStep);
  expectSamePoints(x.contactMemory, y.contactMemory);
  expectSamePoints(x.sleep.memory, y.sleep.memory);
}

// The state read from bytes, into a fresh snapshot of the scene.
std::string readInto(Snapshot& target, const std::vector<char>& bytes, const std::string& guid = kGuid) {
  return rigidfmu::deserialize(bytes.data(), bytes.size(), guid, target);
}

// 64-bit FNV-1a of the bytes.
uint64_t hashOf(const std::vector<char>& bytes) {
  uint64_t h = 14695981039346656037ull;
  for (char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  return h;
}

TEST(Snapshot, EveryFieldComesBackFromTheBytesIntoItsOwnPlace) {
  const rigid::WorldModel model = sceneModel();
  const Snapshot s = filled(model);
  const std::vector<char> bytes = rigidfmu::serialize(s, kGuid);
  Snapshot back = fresh(model);
  ASSERT_EQ(readInto(back, bytes), "");
  expectSameRunAndParameters(s, back);
  expectSameBodies(s.data, back.data);
  expectSameHistory(s.data, back.data);
  EXPECT_EQ(rigidfmu::serialize(back, kGuid), bytes);
  // and what is derived from them: the velocities of the state read
  EXPECT_EQ(back.data.aux[1].V, s.data.Y[1].P / s.model.bodies[1].mass);
}

// The bytes of the filled snapshot, pinned: a field added, removed, moved or widened
// changes them. Then bump kSnapshotVersion in fmu/snapshot.h (a state of the old layout
// must be refused, not misread) and pin the new size and hash here.
TEST(Snapshot, TheBytesAreThoseOfTheFormatVersion) {
  const std::vector<char> bytes = rigidfmu::serialize(filled(sceneModel()), kGuid);
  EXPECT_EQ(rigidfmu::kSnapshotVersion, 12u);
  EXPECT_EQ(bytes.size(), 2070u);
  EXPECT_EQ(hashOf(bytes), 0x2aabeff40b21def2ull);
}

// A conveyor's belt velocity (its start value, its value in the run and its rate) comes
// back from the bytes; only a surface with a belt adds them (72 bytes), so that the
// states of scenes without belts keep the layout pinned above.
TEST(Snapshot, AConveyorsBeltComesBackAndOnlyAConveyorAddsBytes) {
  rigid::WorldModel model = sceneModel();
  const size_t plain = rigidfmu::serialize(filled(model), kGuid).size();
  model.surfaces[1].belt = true;  // the wall, as if its scene gave "beltVelocity"
  Snapshot s = filled(model);
  s.model.surfaces[1].beltVelocity = Vec3(1.5, 2.5, 3.5);
  s.data.beltVelocity[1] = Vec3(4.5, 5.5, 6.5), s.data.beltRate[1] = Vec3(7.5, 8.5, 9.5);
  const std::vector<char> bytes = rigidfmu::serialize(s, kGuid);
  EXPECT_EQ(bytes.size(), plain + 72u);
  Snapshot back = fresh(model);
  ASSERT_EQ(readInto(back, bytes), "");
  EXPECT_EQ(back.model.surfaces[1].beltVelocity, s.model.surfaces[1].beltVelocity);
  EXPECT_EQ(back.data.beltVelocity, s.data.beltVelocity);
  EXPECT_EQ(back.data.beltRate, s.data.beltRate);
  expectSameRunAndParameters(s, back);
  expectSameBodies(s.data, back.data);
  expectSameHistory(s.data, back.data);
}

// A hinge between the two bodies with limits, a motor and a spring: its tunable
// parameters, its inputs' start values and its run (warm-start impulses, angle, inputs,
// reactions, coordinate) come back from the bytes; only joints add them (256 bytes).
rigid::WorldModel withHinge(rigid::WorldModel model) {
  rigid::JointConstants j;
  j.name = "hinge", j.type = rigid::JointType::Revolute, j.a = 0, j.b = 1;
  j.limited = j.motor = j.spring = true;
  model.joints.push_back(j);
  return model;
}

TEST(Snapshot, AJointComesBackAndOnlyAJointAddsBytes) {
  const size_t plain = rigidfmu::serialize(filled(sceneModel()), kGuid).size();
  const rigid::WorldModel model = withHinge(sceneModel());
  Snapshot s = filled(model);
  Values v;
  rigid::JointConstants& j = s.model.joints[0];
  j.maxMotorForce = v.next(), j.stiffness = v.next(), j.damping = v.next(), j.restitution = v.fraction();
  j.lower = v.next(), j.upper = v.next(), j.motorSpeed = v.next(), j.targetPosition = v.next();
  rigid::JointData& d = s.data.joints;
  for (double& impulse : d.memory[0]) impulse = v.next();
  d.angle[0] = v.next(), d.motorSpeed[0] = v.next(), d.targetPosition[0] = v.next();
  d.motorSpeedRate[0] = v.next(), d.targetPositionRate[0] = v.next();
  d.impulse[0] = v.vec(), d.angularImpulse[0] = v.vec(), d.position[0] = v.next(), d.speed[0] = v.next();
  const std::vector<char> bytes = rigidfmu::serialize(s, kGuid);
  EXPECT_EQ(bytes.size(), plain + 256u);
  Snapshot back = fresh(model);
  ASSERT_EQ(readInto(back, bytes), "");
  const rigid::JointConstants& b = back.model.joints[0];
  EXPECT_EQ(b.maxMotorForce, j.maxMotorForce);
  EXPECT_EQ(b.stiffness, j.stiffness);
  EXPECT_EQ(b.damping, j.damping);
  EXPECT_EQ(b.restitution, j.restitution);
  EXPECT_EQ(b.lower, j.lower);
  EXPECT_EQ(b.upper, j.upper);
  EXPECT_EQ(b.motorSpeed, j.motorSpeed);
  EXPECT_EQ(b.targetPosition, j.targetPosition);
  const rigid::JointData& e = back.data.joints;
  EXPECT_EQ(e.memory, d.memory);
  EXPECT_EQ(e.angle, d.angle);
  EXPECT_EQ(e.motorSpeed, d.motorSpeed);
  EXPECT_EQ(e.targetPosition, d.targetPosition);
  EXPECT_EQ(e.motorSpeedRate, d.motorSpeedRate);
  EXPECT_EQ(e.targetPositionRate, d.targetPositionRate);
  EXPECT_EQ(e.impulse, d.impulse);
  EXPECT_EQ(e.angularImpulse, d.angularImpulse);
  EXPECT_EQ(e.position, d.position);
  EXPECT_EQ(e.speed, d.speed);
  expectSameRunAndParameters(s, back);
  expectSameBodies(s.data, back.data);
  expectSameHistory(s.data, back.data);
  // and a joint's parameter out of range is refused, as setting it is
  for (auto spoil :
       {+[](rigid::JointConstants& x) { x.restitution = 1.5; },
        +[](rigid::JointConstants& x) { x.maxMotorForce = 0.0; }, +[](rigid::JointConstants& x) { x.stiffness = -1.0; },
        +[](rigid::JointConstants& x) { x.lower = x.upper + 1.0; }}) {
    Snapshot bad = s;
    spoil(bad.model.joints[0]);
    Snapshot target = fresh(model);
    EXPECT_EQ(readInto(target, rigidfmu::serialize(bad, kGuid)), "the state holds a joint's parameter out of range");
  }
}

struct Spoilt {
  const char* why;                       // the reason deserialize() gives
  std::function<void(Snapshot&)> spoil;  // a value out of range
};

TEST(Snapshot, AValueOutOfRangeIsRefusedWithItsReasonAndNothingRead) {
  const std::string corrupt = "the serialized state is corrupt ";
  const std::string material = "the state holds a friction, restitution or fluid property out of range";
  const std::string pushes = corrupt + "(a resting force names no sleeping body or surface of this scene)";
  const std::string points = corrupt + "(a contact point names no body or surface of this scene)";
  const std::vector<Spoilt> cases = {
      {"the state holds a mass that is not > 0", [](Snapshot& s) { s.model.bodies[1].mass = 0.0; }},
      {material.c_str(), [](Snapshot& s) { s.model.bodies[0].restitution = 1.5; }},
      {material.c_str(), [](Snapshot& s) { s.model.surfaces[1].kineticFriction = -1.0; }},
      {material.c_str(), [](Snapshot& s) { s.model.media[0].viscosity = -1.0; }},
      {"the serialized state is corrupt (sleep of body 0)", [](Snapshot& s) { s.data.sleep.asleep[0] = 2; }},
      {"the serialized state is corrupt (sleep of body 0)", [](Snapshot& s) { s.data.sleep.island[0] = 0; }},
      {"the serialized state is corrupt (sleep of body 1)", [](Snapshot& s) { s.data.sleep.island[1] = 2; }},
      {"the serialized state is corrupt (sleep of body 1)", [](Snapshot& s) { s.data.sleep.asleep[1] = 0; }},
      {"the serialized state is corrupt (resting forces)",
       [](Snapshot& s) { s.data.sleep.resting.resize(129, s.data.sleep.resting[0]); }},
      {pushes.c_str(), [](Snapshot& s) { s.data.sleep.resting[0].body = 0; }},
      {pushes.c_str(), [](Snapshot& s) { s.data.sleep.resting[0].surface = 2; }},
      {"the serialized state is corrupt (contact points)",
       [](Snapshot& s) { s.data.contactMemory.resize(127, s.data.contactMemory[0]); }},
      {points.c_str(), [](Snapshot& s) { s.data.contactMemory[0].a = 2; }},
      {points.c_str(), [](Snapshot& s) { s.data.contactMemory[0].surface = 0; }},
      {points.c_str(), [](Snapshot& s) { s.data.sleep.memory[1].surface = -1; }},
      {"the state holds an unknown solver.method 99", [](Snapshot& s) { s.model.method = rigid::Method(99); }},
  };
  const rigid::WorldModel model = sceneModel();
  const std::vector<char> untouched = rigidfmu::serialize(fresh(model), kGuid);
  for (const Spoilt& c : cases) {
    Snapshot s = filled(model);
    c.spoil(s);
    Snapshot target = fresh(model);
    EXPECT_EQ(readInto(target, rigidfmu::serialize(s, kGuid)), c.why);
    EXPECT_EQ(rigidfmu::serialize(target, kGuid), untouched) << c.why;
  }
}

TEST(Snapshot, BytesOfAnotherSizeFormatOrSceneAreRefused) {
  const rigid::WorldModel model = sceneModel();
  const std::vector<char> bytes = rigidfmu::serialize(filled(model), kGuid);
  Snapshot target = fresh(model);
  std::vector<char> shorter(bytes.begin(), bytes.end() - 1), longer = bytes, newer = bytes;
  longer.push_back(0);
  newer[8] = 13;  // the version's low byte
  EXPECT_EQ(readInto(target, shorter), "the serialized state has " + std::to_string(bytes.size() - 1) +
                                           " bytes, not the size of a state of this scene");
  EXPECT_EQ(readInto(target, longer), "the serialized state has " + std::to_string(bytes.size() + 1) +
                                          " bytes, not the size of a state of this scene");
  EXPECT_EQ(readInto(target, newer), "state format version 13, this FMU reads version 12");
  EXPECT_EQ(readInto(target, bytes, "{other}"), "the state is of another scene (GUID " + kGuid + ", this FMU {other})");
  EXPECT_EQ(readInto(target, std::vector<char>(bytes.begin(), bytes.begin() + 5)),
            "the serialized state is too short (5 bytes)");
  EXPECT_EQ(rigidfmu::deserialize(nullptr, 0, kGuid, target), "the serialized state is NULL");
  rigid::WorldModel one = model;
  one.bodies.pop_back();
  Snapshot single = fresh(one);
  EXPECT_EQ(readInto(single, bytes), "the state holds another number of bodies");
  // and the state is still readable into the target, which nothing has changed
  EXPECT_EQ(rigidfmu::serialize(target, kGuid), rigidfmu::serialize(fresh(model), kGuid));
  EXPECT_EQ(readInto(target, bytes), "");
}

}  // namespace
