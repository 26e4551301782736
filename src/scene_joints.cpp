// The scene's joints (joint.h): read and checked, the anchors and axes given at the
// start poses turned into each body's frame.
#include <cmath>
#include <string>
#include <vector>

#include "scene_reader.h"

namespace rigid::scene_reader {

namespace {

struct TypeName {
  const char* name;
  JointType type;
};
constexpr TypeName kTypes[] = {{"revolute", JointType::Revolute},
                               {"prismatic", JointType::Prismatic},
                               {"spherical", JointType::Spherical},
                               {"fixed", JointType::Fixed},
                               {"distance", JointType::Distance}};

JointType readType(const Object& o) {
  const std::string type = o.string("type");
  for (const TypeName& t : kTypes)
    if (type == t.name) return t.type;
  fail(o.path("type"), "must be one of revolute, prismatic, spherical, fixed, distance, got \"" + type + "\"");
}

// A body's index by name; "world" (the first body only) is -1.
int bodyIndex(const std::vector<BodyConstants>& bodies, const json& name, const std::string& path, bool worldAllowed) {
  if (!name.is_string()) fail(path, "must be a body's name");
  const std::string n = name.get<std::string>();
  if (n == "world") {
    if (!worldAllowed) fail(path, "only the first body may be \"world\"");
    return -1;
  }
  for (size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].name == n) return static_cast<int>(i);
  fail(path, "no body is named \"" + n + "\"");
}

// A pose of the world or of a body at its start.
struct StartPose {
  Vec3 x = Vec3::Zero();
  Quat q = Quat::Identity();
};
StartPose startOf(const std::vector<BodyConstants>& bodies, int i) {
  if (i < 0) return {};
  return {bodies[i].start.position, bodies[i].start.orientation.normalized()};
}

// Two vectors, one in each body's frame ("anchors", "axes"), or one world vector at the
// start ("anchor", "axis"), which `local` turns into a body's frame.
template <class Local>
void pairOf(const Object& o, const char* one, const char* two, Vec3& a, Vec3& b, Local local) {
  if (o.has(one) && o.has(two)) fail(o.path(two), std::string("give either ") + one + " or " + two + ", not both");
  if (o.has(one)) {
    const Vec3 v = o.vec3(one, Vec3::Zero());
    a = local(v, 0);
    b = local(v, 1);
    return;
  }
  if (!o.has(two)) fail(o.path(one), std::string("is required (or ") + two + ", one per body in its frame)");
  const json& pair = o.at(two);
  if (!pair.is_array() || pair.size() != 2) fail(o.path(two), "must be two arrays of 3 numbers, one per body");
  a = Object::toVector(pair[0], o.path(two) + "[0]", 3);
  b = Object::toVector(pair[1], o.path(two) + "[1]", 3);
}

// The fields only some types take.
void refuseFieldsOf(const Object& o, JointType type) {
  auto refuse = [&](const char* key, const char* why) {
    if (o.has(key)) fail(o.path(key), why);
  };
  if (type != JointType::Revolute && type != JointType::Prismatic) {
    refuse("axis", "only revolute and prismatic joints have an axis");
    refuse("axes", "only revolute and prismatic joints have an axis");
  }
  if (!hasCoordinate(type)) {
    for (const char* key : {"limits", "motor", "spring"})
      refuse(key, "a spherical or fixed joint has no coordinate to limit, drive or spring");
  }
  if (type != JointType::Distance) {
    refuse("length", "only a distance joint has a length");
    refuse("rope", "only a distance joint can be a rope");
  }
}

void readLimits(const Object& o, JointConstants& j) {
  if (!o.has("limits")) return;
  const Eigen::VectorXd v = o.vector("limits", 2, Eigen::Vector2d::Zero());
  if (v[0] > v[1]) fail(o.path("limits"), "lower (" + num(v[0]) + ") must be <= upper (" + num(v[1]) + ")");
  if (j.type == JointType::Distance && v[0] < 0.0)
    fail(o.path("limits") + "[0]", "a length must be >= 0, got " + num(v[0]));
  j.limited = true;
  j.lower = v[0];
  j.upper = v[1];
}

// The stops' restitution: limits and a rigid rope's full length are stops.
void readRestitution(const Object& o, JointConstants& j) {
  if (!o.has("restitution")) return;
  if (!hasStops(j))
    fail(o.path("restitution"), "only a joint with limits (or a rope without a spring) has stops to bounce at");
  j.restitution = inRange(o, "restitution", 0.0, 0.0, 1.0);
}

// "motor": {"speed", "maxTorque" (revolute) or "maxForce"}; "spring": {"stiffness",
// "damping", "target" (not for a distance joint, whose target is its length)}.
void readDrives(const Object& o, JointConstants& j) {
  const bool turning = j.type == JointType::Revolute;
  if (o.has("motor")) {
    const char* most = turning ? "maxTorque" : "maxForce";
    const Object m(o.at("motor"), o.path("motor"), {"speed", most});
    j.motor = true;
    j.motorSpeed = m.number("speed", 0.0);
    j.maxMotorForce = positive(m, most);
  }
  if (o.has("spring")) {
    const bool distance = j.type == JointType::Distance;
    const Object s(o.at("spring"), o.path("spring"),
                   distance ? std::initializer_list<const char*>{"stiffness", "damping"}
                            : std::initializer_list<const char*>{"stiffness", "damping", "target"});
    j.spring = true;
    j.stiffness = s.number("stiffness", 0.0);
    j.damping = s.number("damping", 0.0);
    if (j.stiffness < 0.0) fail(s.path("stiffness"), "must be >= 0, got " + num(j.stiffness));
    if (j.damping < 0.0) fail(s.path("damping"), "must be >= 0, got " + num(j.damping));
    if (!(j.stiffness > 0.0 || j.damping > 0.0)) fail(s.path("stiffness"), "a spring needs stiffness or damping > 0");
    j.targetPosition = distance ? 0.0 : s.number("target", 0.0);
  }
}

JointConstants readJoint(const json& json, const std::string& path, const std::vector<BodyConstants>& bodies) {
  const Object o(json, path,
                 {"name", "type", "bodies", "anchor", "anchors", "axis", "axes", "length", "rope", "limits",
                  "restitution", "motor", "spring", "collide"});
  JointConstants j;
  j.name = identifier(o, "name");
  j.type = readType(o);
  refuseFieldsOf(o, j.type);
  if (!o.has("bodies") || !o.at("bodies").is_array() || o.at("bodies").size() != 2)
    fail(o.path("bodies"), "must name two bodies (the first may be \"world\")");
  j.a = bodyIndex(bodies, o.at("bodies")[0], o.path("bodies") + "[0]", true);
  j.b = bodyIndex(bodies, o.at("bodies")[1], o.path("bodies") + "[1]", false);
  if (j.a == j.b) fail(o.path("bodies"), "a joint joins two different bodies");
  if (driven(bodies[j.b]) && (j.a < 0 || driven(bodies[j.a])))
    fail(o.path("bodies"), "at least one of the two must be a free body (the others' motion is given)");
  const StartPose pose[2] = {startOf(bodies, j.a), startOf(bodies, j.b)};
  pairOf(o, "anchor", "anchors", j.anchorA, j.anchorB,
         [&](const Vec3& v, int k) { return Vec3(pose[k].q.conjugate() * (v - pose[k].x)); });
  if (j.type == JointType::Revolute || j.type == JointType::Prismatic) {
    pairOf(o, "axis", "axes", j.axisA, j.axisB, [&](const Vec3& v, int k) { return Vec3(pose[k].q.conjugate() * v); });
    for (Vec3* axis : {&j.axisA, &j.axisB}) {
      if (!(axis->norm() > 1e-9)) fail(o.path(o.has("axis") ? "axis" : "axes"), "must not be zero");
      axis->normalize();
    }
  }
  j.rest = pose[0].q.conjugate() * pose[1].q;
  if (j.type == JointType::Distance) {
    const double apart = ((pose[1].x + pose[1].q * j.anchorB) - (pose[0].x + pose[0].q * j.anchorA)).norm();
    j.length = o.number("length", apart);
    if (!(j.length > 0.0))
      fail(o.path("length"), "must be > 0 (m; by default the anchors' distance at the start), got " + num(j.length));
    j.rope = o.boolean("rope", false);
  }
  readLimits(o, j);
  readDrives(o, j);
  readRestitution(o, j);
  j.collide = o.boolean("collide", false);
  return j;
}

}  // namespace

void readJoints(const Object& scene, Scene& out) {
  if (!scene.has("joints")) return;
  const json& list = scene.at("joints");
  if (!list.is_array()) fail("joints", "must be an array");
  for (size_t i = 0; i < out.model.bodies.size(); ++i)
    if (out.model.bodies[i].name == "world" && !list.empty())
      fail("bodies[" + std::to_string(i) + "].name", "\"world\" names the world in joints: rename the body");
  std::set<std::string> names;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = "joints[" + std::to_string(i) + "]";
    out.model.joints.push_back(readJoint(list[i], path, out.model.bodies));
    if (!names.insert(out.model.joints.back().name).second)
      fail(path + ".name", "must be unique in joints, \"" + out.model.joints.back().name + "\" is used twice");
  }
}

}  // namespace rigid::scene_reader
