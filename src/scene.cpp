#include "scene.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "mesh_file.h"
#include "scene_reader.h"

namespace rigid {

using json = nlohmann::json;
using namespace scene_reader;

namespace {

// Coulomb coefficients: staticFriction >= kineticFriction >= 0.
void friction(const Object& o, double& mus, double& muk) {
  mus = o.number("staticFriction", defaults::kStaticFriction);
  muk = o.number("kineticFriction", std::min(defaults::kKineticFriction, mus));
  if (muk < 0.0) fail(o.path("kineticFriction"), "must be >= 0, got " + num(muk));
  if (mus < muk) fail(o.path("staticFriction"), "must be >= kineticFriction (" + num(muk) + "), got " + num(mus));
}

// Where the scene's files are: the folder that a mesh's path is relative to (none for a
// scene given as text), and the notes for the user that reading them leaves.
struct SceneFiles {
  std::optional<std::string> folder;
  std::vector<std::string>* warnings = nullptr;
};

// A mesh's scale: one factor, or one per axis of the file; each > 0 (a mirror would
// turn the mesh inside out).
Vec3 meshScale(const Object& o) {
  if (!o.has("scale")) return Vec3::Ones();
  const Vec3 s = o.at("scale").is_number() ? Vec3::Constant(Object::toNumber(o.at("scale"), o.path("scale")))
                                           : Vec3(Object::toVector(o.at("scale"), o.path("scale"), 3));
  if (!(s.minCoeff() > 0.0)) fail(o.path("scale"), "must be > 0 (one factor or one per axis)");
  return s;
}

// The folder that the mesh file `o.file` is read from.
const std::string& meshFolder(const Object& o, const SceneFiles& files) {
  if (!files.folder) fail(o.path("file"), "a mesh needs the scene's folder: read the scene from its file");
  return *files.folder;
}

Shape readMesh(const Object& o, const SceneFiles& files) {
  Shape s;
  s.type = ShapeType::Mesh;
  std::string warning;
  s.mesh = readMeshShape(meshFolder(o, files), o.string("file"), meshScale(o), o.path("file"), warning);
  if (!warning.empty() && files.warnings) files.warnings->push_back(warning);
  return s;
}

Shape readShape(const json& j, const std::string& path, const SceneFiles& files);

// A compound's parts: each a primitive (placed by its centre) or a mesh (by its
// file's origin), no compound, at a pose in the compound's frame.
Shape readCompound(const Object& o, const SceneFiles& files) {
  if (!o.has("parts") || !o.at("parts").is_array() || o.at("parts").empty())
    fail(o.path("parts"), "must be an array of at least one part");
  std::vector<PlacedShape> placed;
  for (size_t k = 0; k < o.at("parts").size(); ++k) {
    const Object part(o.at("parts")[k], o.path("parts") + "[" + std::to_string(k) + "]",
                      {"shape", "position", "orientation"});
    if (!part.has("shape")) fail(part.path("shape"), "is required");
    PlacedShape p;
    p.shape = readShape(part.at("shape"), part.path("shape"), files);
    if (p.shape.type == ShapeType::Compound) fail(part.path("shape") + ".type", "a part cannot be a compound");
    p.position = part.vec3("position", Vec3::Zero());
    p.orientation = unitQuaternion(part, "orientation");
    placed.push_back(p);
  }
  Shape s;
  s.type = ShapeType::Compound;
  s.compound = makeCompound(placed, o.path("parts"));
  return s;
}

Shape readShape(const json& j, const std::string& path, const SceneFiles& files) {
  if (!j.is_object() || !j.contains("type")) fail(path + ".type", "is required");
  if (!j["type"].is_string()) fail(path + ".type", "must be a string");
  const std::string type = j["type"].get<std::string>();
  Shape s;
  if (type == "sphere") {
    Object o(j, path, {"type", "radius"});
    s.type = ShapeType::Sphere;
    s.radius = positive(o, "radius");
  } else if (type == "box") {
    Object o(j, path, {"type", "size"});
    s.type = ShapeType::Box;
    if (!o.has("size")) fail(o.path("size"), "is required");
    s.size = o.vec3("size", Vec3::Zero());
    for (int i = 0; i < 3; ++i)
      if (!(s.size[i] > 0.0))
        fail(o.path("size") + "[" + std::to_string(i) + "]", "must be > 0, got " + num(s.size[i]));
  } else if (type == "cylinder" || type == "capsule") {
    Object o(j, path, {"type", "radius", "length"});
    s.type = type == "cylinder" ? ShapeType::Cylinder : ShapeType::Capsule;
    s.radius = positive(o, "radius");
    s.length = o.number("length");
    if (s.type == ShapeType::Cylinder && !(s.length > 0.0)) fail(o.path("length"), "must be > 0, got " + num(s.length));
    if (s.type == ShapeType::Capsule && s.length < 0.0) fail(o.path("length"), "must be >= 0, got " + num(s.length));
  } else if (type == "mesh") {
    s = readMesh(Object(j, path, {"type", "file", "scale"}), files);
  } else if (type == "compound") {
    s = readCompound(Object(j, path, {"type", "parts"}), files);
  } else {
    fail(path + ".type", "must be one of sphere, box, cylinder, capsule, mesh, compound, got \"" + type + "\"");
  }
  return s;
}

// A given inertia: symmetric, positive definite, principal moments obeying the
// triangle inequality (no principal moment exceeds the sum of the other two, which
// every real mass distribution satisfies). Equality, the flat-lamina limit, is allowed.
Mat3 readInertia(const json& j, const std::string& path) {
  if (!j.is_array() || j.size() != 3) fail(path, "must be a 3x3 array of numbers");
  Mat3 I;
  for (int r = 0; r < 3; ++r) {
    const Eigen::VectorXd row = Object::toVector(j[r], path + "[" + std::to_string(r) + "]", 3);
    I.row(r) = row.transpose();
  }
  const double scale = I.cwiseAbs().maxCoeff();
  if ((I - I.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) fail(path, "must be symmetric within 1e-9 relative");
  const Vec3 m = Eigen::SelfAdjointEigenSolver<Mat3>(I).eigenvalues();  // ascending
  if (!(m[0] > 0.0)) fail(path, "must be positive definite, smallest principal moment is " + num(m[0]));
  if (m[2] > (m[0] + m[1]) * (1.0 + 1e-9))
    fail(path, "principal moments must satisfy the triangle inequality: largest " + num(m[2]) +
                   " > sum of the others " + num(m[0] + m[1]));
  return 0.5 * (I + I.transpose());
}

// "loads": [{"name", "point" (m, body frame, from the centre of mass), "frame":
// "world" (default) or "body", the frame of the force input}], names unique in the body.
std::vector<PointLoad> readLoads(const Object& body) {
  std::vector<PointLoad> loads;
  if (!body.has("loads")) return loads;
  const json& list = body.at("loads");
  if (!list.is_array()) fail(body.path("loads"), "must be an array of load points");
  std::set<std::string> names;
  for (size_t i = 0; i < list.size(); ++i) {
    const Object o(list[i], body.path("loads") + "[" + std::to_string(i) + "]", {"name", "point", "frame"});
    PointLoad load;
    load.name = identifier(o, "name");
    if (!names.insert(load.name).second) fail(o.path("name"), "\"" + load.name + "\" is used twice in this body");
    if (!o.has("point")) fail(o.path("point"), "is required (m, body frame, from the centre of mass)");
    load.point = o.vec3("point", Vec3::Zero());
    const std::string frame = o.string("frame", "world");
    if (frame != "world" && frame != "body")
      fail(o.path("frame"), "must be \"world\" or \"body\", got \"" + frame + "\"");
    load.bodyFrame = frame == "body";
    loads.push_back(load);
  }
  return loads;
}

// The lever (m) of the moment that resists rolling: finite, >= 0, default 0 (none).
double rollingResistance(const Object& o) {
  const double e = o.number("rollingResistance", 0.0);
  if (!(e >= 0.0) || !std::isfinite(e)) fail(o.path("rollingResistance"), "must be >= 0 (m), got " + num(e));
  return e;
}

// "motion": "free" (the default) or "driven" (drive.h). A driven body's motion comes
// from its inputs: it has no mass, no force inputs and no load points, and it acts
// only through its contacts.
Motion readMotion(const Object& o) {
  const std::string motion = o.string("motion", "free");
  if (motion == "free") return Motion::Free;
  if (motion != "driven") fail(o.path("motion"), "must be one of free, driven, got \"" + motion + "\"");
  for (const char* key : {"mass", "inertia", "loads", "inputs"})
    if (o.has(key))
      fail(o.path(key),
           "not for a driven body: its motion comes from its inputs (position, orientation, velocity, "
           "angularVelocity) and no force moves it");
  if (!o.boolean("collision", true))
    fail(o.path("collision"), "a driven body must collide: it acts on the world only through its contacts");
  return Motion::Driven;
}

// A body's start orientation and velocities, and its contact materials.
void readStartAndMaterial(const Object& o, BodyConstants& b) {
  b.start.orientation = unitQuaternion(o, "orientation");
  b.start.velocity = o.vec3("velocity", Vec3::Zero());
  b.start.angularVelocity = o.vec3("angularVelocity", Vec3::Zero());
  b.restitution = inRange(o, "restitution", defaults::kRestitution, 0.0, 1.0);
  friction(o, b.staticFriction, b.kineticFriction);
  b.rollingResistance = rollingResistance(o);
}

// A free body's mass: given, or its density times its shape's volume (one of the two).
double readMass(const Object& o, const Shape& shape) {
  if (o.has("mass") && o.has("density")) fail(o.path("density"), "give mass or density, not both");
  if (!o.has("density")) return positive(o, "mass");
  return positive(o, "density") * shapeVolume(shape);
}

BodyConstants readBody(const json& j, const std::string& path, const SceneFiles& files) {
  Object o(j, path,
           {"name", "shape", "motion", "mass", "density", "inertia", "position", "orientation", "velocity",
            "angularVelocity", "restitution", "staticFriction", "kineticFriction", "rollingResistance", "collision",
            "outputs", "inputs", "loads"});
  BodyConstants b;
  b.name = identifier(o, "name");
  if (!o.has("shape")) fail(o.path("shape"), "is required");
  b.shape = readShape(o.at("shape"), o.path("shape"), files);
  if (readMotion(o) == Motion::Driven) {
    makeDriven(b);
  } else {
    setMass(b, readMass(o, b.shape));
    if (o.has("inertia")) setInertia(b, readInertia(o.at("inertia"), o.path("inertia")));
  }
  b.start.position = o.vec3("position", Vec3::Zero());
  readStartAndMaterial(o, b);
  b.collides = o.boolean("collision", true);
  b.loads = readLoads(o);
  return b;
}

void readBox(const Object& o, Vec3& min, Vec3& max) {
  if (!o.has("min")) fail(o.path("min"), "is required");
  if (!o.has("max")) fail(o.path("max"), "is required");
  min = o.vec3("min", Vec3::Zero());
  max = o.vec3("max", Vec3::Zero());
  for (int i = 0; i < 3; ++i)
    if (!(max[i] > min[i]))
      fail(o.path("max") + "[" + std::to_string(i) + "]",
           "must be > min[" + std::to_string(i) + "] (" + num(min[i]) + "), got " + num(max[i]));
}

// A list of names, each one of `allowed`, no repeats; absent: all of `allowed`.
std::set<std::string> nameList(const Object& o, const char* key, const std::vector<std::string>& allowed) {
  if (!o.has(key)) return {allowed.begin(), allowed.end()};
  const json& list = o.at(key);
  if (!list.is_array()) fail(o.path(key), "must be an array of names");
  std::string known;
  for (const std::string& a : allowed) known += (known.empty() ? "" : ", ") + a;
  std::set<std::string> names;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = o.path(key) + "[" + std::to_string(i) + "]";
    if (!list[i].is_string()) fail(path, "must be a string, one of " + known);
    const std::string name = list[i].get<std::string>();
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
      fail(path, "must be one of " + known + ", got \"" + name + "\"");
    if (!names.insert(name).second) fail(path, "\"" + name + "\" is listed twice");
  }
  return names;
}

// A moving surface ("motion": "driven": a platform, an elevator, a paddle) is a driven
// body with the surface's box as its shape, centred between min and max, turned by
// its orientation; its pose and velocities are inputs like any driven body's.
BodyConstants readMovingSurface(const json& j, const std::string& path) {
  Object o(j, path,
           {"name", "motion", "min", "max", "orientation", "velocity", "angularVelocity", "staticFriction",
            "kineticFriction", "restitution", "rollingResistance", "outputs"});
  BodyConstants b;
  b.name = identifier(o, "name");
  Vec3 min, max;
  readBox(o, min, max);
  b.shape.type = ShapeType::Box;
  b.shape.size = max - min;
  readMotion(o);
  makeDriven(b);
  b.start.position = 0.5 * (min + max);
  readStartAndMaterial(o, b);
  return b;
}

bool moving(const json& surface) {
  return surface.is_object() && surface.contains("motion") && surface.at("motion") == "driven";
}

// A surface of a mesh file's triangles: "mesh": {"file", "scale", "thickness"}, the
// file's frame placed by "position" and "orientation"; min and max become the box that
// bounds the triangles.
void readMeshSurface(const Object& o, const SceneFiles& files, Surface& s) {
  for (const char* key : {"min", "max", "beltVelocity"})
    if (o.has(key)) fail(o.path(key), "a mesh surface is placed by position and orientation, and has no belt");
  const Object m(o.at("mesh"), o.path("mesh"), {"file", "scale", "thickness"});
  const double thickness = positive(m, "thickness", &defaults::kSurfaceMeshThickness);
  s.mesh = readSurfaceMesh(meshFolder(m, files), m.string("file"), meshScale(m), o.vec3("position", Vec3::Zero()),
                           unitQuaternion(o, "orientation"), thickness, m.path("file"));
  s.min = s.max = s.mesh->vertices.front();
  for (const Vec3& v : s.mesh->vertices) s.min = s.min.cwiseMin(v), s.max = s.max.cwiseMax(v);
}

Surface readSurface(const json& j, const std::string& path, const SceneFiles& files) {
  Object o(j, path,
           {"name", "motion", "min", "max", "orientation", "staticFriction", "kineticFriction", "restitution",
            "rollingResistance", "outputs", "beltVelocity", "mesh", "position"});
  if (o.string("motion", "static") != "static")
    fail(o.path("motion"), "must be one of static, driven, got \"" + o.string("motion", "") + "\"");
  Surface s;
  s.name = identifier(o, "name");
  if (o.has("mesh")) {
    readMeshSurface(o, files, s);
  } else {
    if (o.has("position")) fail(o.path("position"), "a box surface is placed by min and max");
    readBox(o, s.min, s.max);
    s.orientation = unitQuaternion(o, "orientation");
  }
  friction(o, s.staticFriction, s.kineticFriction);
  s.restitution = inRange(o, "restitution", defaults::kRestitution, 0.0, 1.0);
  s.rollingResistance = rollingResistance(o);
  s.forceOutput = nameList(o, "outputs", {"force"}).count("force") > 0;
  s.belt = o.has("beltVelocity");  // a conveyor: its belt's velocity becomes an input
  s.beltVelocity = o.vec3("beltVelocity", Vec3::Zero());
  finishSurface(s);
  return s;
}

Medium readMedium(const json& j, const std::string& path) {
  Object o(j, path, {"name", "type", "min", "max", "density", "viscosity"});
  Medium m;
  m.name = identifier(o, "name");
  const std::string type = o.string("type", "water");
  double rho = 0.0, mu = 0.0;
  if (type == "air") {
    m.type = FluidType::Air;
    rho = defaults::kAirDensity;
    mu = defaults::kAirViscosity;
  } else if (type == "water") {
    m.type = FluidType::Water;
    rho = defaults::kWaterDensity;
    mu = defaults::kWaterViscosity;
  } else if (type == "custom") {
    m.type = FluidType::Custom;
    if (!o.has("density")) fail(o.path("density"), "is required for a custom medium");
    if (!o.has("viscosity")) fail(o.path("viscosity"), "is required for a custom medium");
  } else {
    fail(o.path("type"), "must be one of air, water, custom, got \"" + type + "\"");
  }
  readBox(o, m.min, m.max);
  // Density 0 is allowed: a medium with viscous drag only (no buoyancy, no pressure drag).
  m.density = o.number("density", rho);
  if (m.density < 0.0) fail(o.path("density"), "must be >= 0, got " + num(m.density));
  m.viscosity = o.number("viscosity", mu);
  if (m.viscosity < 0.0) fail(o.path("viscosity"), "must be >= 0, got " + num(m.viscosity));
  return m;
}

template <class T, class Read>
std::vector<T> readList(const Object& o, const char* key, bool required, Read read) {
  std::vector<T> out;
  if (!o.has(key)) {
    if (required) fail(o.path(key), "is required");
    return out;
  }
  const json& list = o.at(key);
  if (!list.is_array()) fail(o.path(key), "must be an array");
  std::set<std::string> names;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = o.path(key) + "[" + std::to_string(i) + "]";
    out.push_back(read(list[i], path));
    if (!names.insert(out.back().name).second)
      fail(path + ".name", "must be unique in " + std::string(key) + ", \"" + out.back().name + "\" is used twice");
  }
  return out;
}

// Bodies, surfaces, media and joints name their FMU variables alike (NAME.field: a body's
// staticFriction and a surface's would be one variable), so no name is used twice
// across the four lists.
void checkOneNameSpace(const WorldModel& m) {
  std::map<std::string, std::string> owner;  // name -> where it was first given
  auto claim = [&](const std::string& name, const std::string& where) {
    const auto [it, fresh] = owner.emplace(name, where);
    if (!fresh)
      fail(where + ".name", "\"" + name + "\" is also the name of " + it->second +
                                "; bodies, surfaces, media and joints share one name space (their FMU variables are "
                                "NAME.field)");
  };
  for (size_t i = 0; i < m.bodies.size(); ++i) claim(m.bodies[i].name, "bodies[" + std::to_string(i) + "]");
  for (size_t i = 0; i < m.surfaces.size(); ++i) claim(m.surfaces[i].name, "surfaces[" + std::to_string(i) + "]");
  for (size_t i = 0; i < m.media.size(); ++i) claim(m.media[i].name, "media[" + std::to_string(i) + "]");
  for (size_t i = 0; i < m.joints.size(); ++i) claim(m.joints[i].name, "joints[" + std::to_string(i) + "]");
}

// The FMU variables a body chooses (its "outputs" and "inputs"); a driven body's
// inputs are always its pose and velocities.
BodyVariables variablesOf(const json& j, const std::string& path, const BodyConstants& b) {
  const Object body(j, path, {});
  if (driven(b)) return {nameList(body, "outputs", kDrivenOutputs), {kDrivenInputs.begin(), kDrivenInputs.end()}};
  return {nameList(body, "outputs", kBodyOutputs), nameList(body, "inputs", kBodyInputs)};
}

// The static surfaces into the model's surfaces; moving ones become driven bodies,
// after the scene's bodies.
void readSurfaces(const Object& o, Scene& scene, const SceneFiles& files) {
  if (!o.has("surfaces")) return;
  const json& list = o.at("surfaces");
  if (!list.is_array()) fail("surfaces", "must be an array");
  std::set<std::string> names;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = "surfaces[" + std::to_string(i) + "]";
    const Object named(list[i], path, {});
    const std::string name = identifier(named, "name");
    if (!names.insert(name).second) fail(path + ".name", "must be unique in surfaces, \"" + name + "\" is used twice");
    if (!moving(list[i])) {
      scene.model.surfaces.push_back(readSurface(list[i], path, files));
      continue;
    }
    scene.model.bodies.push_back(readMovingSurface(list[i], path));
    scene.variables.push_back(variablesOf(list[i], path, scene.model.bodies.back()));
  }
}

}  // namespace

namespace {

Scene parseScene(const std::string& text, const SceneFiles& files) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw SceneError(std::string("scene: not valid JSON: ") + e.what());
  }
  Object o(j, "", {"name", "gravity", "solver", "bodies", "surfaces", "media", "joints"});
  Scene scene;
  WorldModel& m = scene.model;
  m.name = identifier(o, "name", "scene");
  m.gravity = o.vec3("gravity", Vec3(0.0, 0.0, -9.81));
  if (o.has("solver")) {
    // The choice of contact solver went with issue 38: one solver answers every contact.
    if (o.at("solver").is_object() && o.at("solver").contains("contacts"))
      fail("solver.contacts",
           "was removed: every contact has one solver now, the constraint solver (docs/decisions/"
           "0001-constraint-solver.md); delete the field");
    Object s(o.at("solver"), "solver",
             {"method", "step", "tolerance", "energyGainLimit", "sleep", "sleepSpeed", "sleepTime"});
    const std::string method = s.string("method", "rk4");
    const auto chosen = methodFromName(method);
    if (!chosen) {
      std::string list;
      for (const MethodInfo& mi : methods()) list += std::string(list.empty() ? "" : ", ") + mi.name;
      fail("solver.method", "must be one of " + list + ", got \"" + method + "\"");
    }
    m.method = *chosen;
    const double step = defaults::kSolverStep;
    m.maxStep = positive(s, "step", &step);
    m.tolerance = s.number("tolerance", defaults::kTolerance);
    if (m.tolerance < 0.0) fail("solver.tolerance", "must be >= 0, got " + num(m.tolerance));
    m.energyGainLimit = s.number("energyGainLimit", defaults::kEnergyGainLimit);
    if (m.energyGainLimit < 0.0)
      fail("solver.energyGainLimit", "must be >= 0 (0: unchecked), got " + num(m.energyGainLimit));
    m.sleep.enabled = s.boolean("sleep", m.sleep.enabled);
    m.sleep.speed = s.number("sleepSpeed", m.sleep.speed);
    if (!(m.sleep.speed >= 0.0)) fail("solver.sleepSpeed", "must be >= 0 (m/s), got " + num(m.sleep.speed));
    const double time = m.sleep.time;
    m.sleep.time = positive(s, "sleepTime", &time);
  }
  m.bodies = readList<BodyConstants>(o, "bodies", true,
                                     [&](const json& b, const std::string& path) { return readBody(b, path, files); });
  if (m.bodies.empty()) fail("bodies", "must hold at least one body");
  for (size_t i = 0; i < m.bodies.size(); ++i)
    scene.variables.push_back(variablesOf(o.at("bodies")[i], "bodies[" + std::to_string(i) + "]", m.bodies[i]));
  readSurfaces(o, scene, files);
  m.media = readList<Medium>(o, "media", false, readMedium);
  for (size_t i = 0; i < m.bodies.size() && !m.media.empty(); ++i)
    if (m.bodies[i].shape.type == ShapeType::Mesh || m.bodies[i].shape.type == ShapeType::Compound)
      fail("bodies[" + std::to_string(i) + "].shape",
           std::string("a ") + shapeTypeName(m.bodies[i].shape.type) +
               " body in a scene with media: not yet (media take spheres, boxes, cylinders and capsules)");
  readJoints(o, scene);
  checkOneNameSpace(m);
  scene.canonicalJson = j.dump();
  return scene;
}

}  // namespace

Scene parseScene(const std::string& text) { return parseScene(text, SceneFiles{}); }

Scene loadSceneFile(const std::string& path) {
  // The path is UTF-8 (a decoded file URI): on Windows a narrow path would be read in
  // the ANSI code page and a folder such as C:\Users\José would not open.
  std::ifstream in(std::filesystem::u8path(path), std::ios::binary);
  if (!in) throw SceneError("scene: cannot open \"" + path + "\"");
  std::ostringstream text;
  text << in.rdbuf();
  std::vector<std::string> warnings;
  const std::filesystem::path folder = std::filesystem::u8path(path).parent_path();
  Scene scene = parseScene(text.str(), SceneFiles{folder.u8string(), &warnings});
  scene.warnings = std::move(warnings);
  return scene;
}

}  // namespace rigid
