// rigid::parseScene: one test per rule of INTERFACE.md. Each asserts that a
// SceneError is thrown and that its message names the field and the limit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "scene.h"

namespace {

// A scene with one valid body; `bodyExtra` is appended inside the body object,
// `topExtra` inside the top-level object.
std::string sceneWith(const std::string& bodyExtra = "", const std::string& topExtra = "",
                      const std::string& shape = R"({"type": "sphere", "radius": 0.1})") {
  return R"({"name": "S", )" + topExtra + R"("bodies": [{"name": "b", "shape": )" + shape + R"(, "mass": 1.0)" +
         bodyExtra + "}]}";
}

// Message of the SceneError that parsing `text` throws; records a failure if none.
// Any other exception type escapes and fails the test.
std::string errorOf(const std::string& text) {
  try {
    rigid::parseScene(text);
  } catch (const rigid::SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no SceneError for scene:\n" << text;
  return "";
}

::testing::AssertionResult contains(const std::string& message, const std::string& part) {
  if (message.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "message \"" << message << "\" lacks \"" << part << "\"";
}

#define EXPECT_SCENE_ERROR(text, ...)                                           \
  do {                                                                          \
    const std::string msg_ = errorOf(text);                                     \
    for (const char* part_ : {__VA_ARGS__}) EXPECT_TRUE(contains(msg_, part_)); \
  } while (0)

const char* const kSurface = R"({"name": "floor", "min": [-5, -5, -1], "max": [5, 5, 0]})";
const char* const kMedium = R"({"name": "pool", "type": "water", "min": [-1, -1, -2], "max": [1, 1, -1]})";

}  // namespace

// The base scene of the negative tests is itself valid.
TEST(Scene, BaseSceneParses) { EXPECT_NO_THROW(rigid::parseScene(sceneWith())); }

TEST(Scene, MinimalSceneHasDocumentedDefaults) {
  const rigid::Scene s = rigid::parseScene(
      R"({"name": "Minimal", "bodies": [{"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "mass": 2}]})");
  EXPECT_EQ(s.model.name, "Minimal");
  EXPECT_EQ(s.model.gravity, rigid::Vec3(0.0, 0.0, -9.81));
  EXPECT_EQ(s.model.method, rigid::Method::RK4);
  EXPECT_EQ(s.model.maxStep, 1e-3);
  ASSERT_EQ(s.model.bodies.size(), 1u);
  const rigid::BodyConstants& b = s.model.bodies[0];
  EXPECT_EQ(b.name, "ball");
  EXPECT_EQ(b.mass, 2.0);
  EXPECT_EQ(b.restitution, 0.5);
  EXPECT_EQ(b.staticFriction, 0.6);
  EXPECT_EQ(b.kineticFriction, 0.4);
  EXPECT_EQ(b.start.orientation.w(), 1.0);
  EXPECT_EQ(b.start.orientation.x(), 0.0);
  EXPECT_EQ(b.start.orientation.y(), 0.0);
  EXPECT_EQ(b.start.orientation.z(), 0.0);
  EXPECT_EQ(b.start.position, rigid::Vec3::Zero());
  EXPECT_EQ(b.start.velocity, rigid::Vec3::Zero());
  EXPECT_EQ(b.start.angularVelocity, rigid::Vec3::Zero());
  EXPECT_TRUE(b.inertiaFromShape);
  const double I = 0.4 * 2.0 * 0.1 * 0.1;  // solid sphere
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(b.Ibody(i, i), I, 1e-15);
  EXPECT_TRUE(s.model.surfaces.empty());
  EXPECT_TRUE(s.model.media.empty());
}

TEST(Scene, FullBodyIsRead) {
  const rigid::Scene s = rigid::parseScene(sceneWith(
      R"(, "position": [1, 2, 3], "velocity": [4, 5, 6], "angularVelocity": [7, 8, 9],
         "restitution": 0.8, "staticFriction": 0.5, "kineticFriction": 0.3)",
      R"("gravity": [0, -1.62, 0], "solver": {"method": "euler", "step": 0.002}, )"));
  EXPECT_EQ(s.model.gravity, rigid::Vec3(0.0, -1.62, 0.0));
  EXPECT_EQ(s.model.method, rigid::Method::Euler);
  EXPECT_EQ(s.model.maxStep, 0.002);
  const rigid::BodyConstants& b = s.model.bodies[0];
  EXPECT_EQ(b.start.position, rigid::Vec3(1, 2, 3));
  EXPECT_EQ(b.start.velocity, rigid::Vec3(4, 5, 6));
  EXPECT_EQ(b.start.angularVelocity, rigid::Vec3(7, 8, 9));
  EXPECT_EQ(b.restitution, 0.8);
  EXPECT_EQ(b.staticFriction, 0.5);
  EXPECT_EQ(b.kineticFriction, 0.3);
}

TEST(Scene, NearUnitOrientationIsNormalised) {
  const double k = 1.0 + 8e-7;  // |q| off by 8e-7 < 1e-6
  char q[96];
  std::snprintf(q, sizeof q, "[%.17g, %.17g, 0, 0]", 0.6 * k, 0.8 * k);
  const rigid::Scene s = rigid::parseScene(sceneWith(std::string(", \"orientation\": ") + q));
  const rigid::Quat& o = s.model.bodies[0].start.orientation;
  EXPECT_NEAR(o.norm(), 1.0, 1e-15);
  EXPECT_NEAR(o.w(), 0.6, 1e-12);
  EXPECT_NEAR(o.x(), 0.8, 1e-12);
  EXPECT_EQ(o.y(), 0.0);
  EXPECT_EQ(o.z(), 0.0);
}

TEST(Scene, NotValidJson) { EXPECT_SCENE_ERROR(R"({"name": "S", "bodies": [)", "scene: not valid JSON"); }

TEST(Scene, TopLevelNotAnObject) {
  EXPECT_SCENE_ERROR("[1, 2, 3]", "scene: must be a JSON object");
  EXPECT_SCENE_ERROR("42", "scene: must be a JSON object");
}

TEST(Scene, UnknownTopLevelField) {
  EXPECT_SCENE_ERROR(sceneWith("", R"("gravitee": [0, 0, 0], )"),
                     "gravitee: unknown field (known: name, gravity, solver, bodies, surfaces, media, joints)");
}

TEST(Scene, UnknownBodyField) {
  EXPECT_SCENE_ERROR(sceneWith(R"(, "colour": "red")"), "bodies[0].colour: unknown field (known: ", "restitution");
}

TEST(Scene, UnknownSolverField) {
  EXPECT_SCENE_ERROR(sceneWith("", R"("solver": {"method": "rk4", "dt": 0.1}, )"),
                     "solver.dt: unknown field (known: method, step, tolerance, energyGainLimit, sleep, sleepSpeed, "
                     "sleepTime)");
}

// Contacts have one solver (issue 38): a scene that still chooses one, with any value,
// is refused, saying so.
TEST(Scene, ChoosingAContactSolverIsRefused) {
  for (const char* value : {"\"manifold\"", "\"substep\"", "\"soft\"", "\"newton\"", "\"centroid\"", "1"})
    EXPECT_SCENE_ERROR(sceneWith("", std::string(R"("solver": {"contacts": )") + value + "}, "),
                       "solver.contacts: was removed: every contact has one solver now, the constraint solver");
}

TEST(Scene, RollingResistanceIsALengthOfAtLeastZero) {
  EXPECT_EQ(rigid::parseScene(sceneWith()).model.bodies[0].rollingResistance, 0.0);
  EXPECT_EQ(rigid::parseScene(sceneWith(R"(, "rollingResistance": 0.002)")).model.bodies[0].rollingResistance, 0.002);
  EXPECT_SCENE_ERROR(sceneWith(R"(, "rollingResistance": -1)"),
                     "bodies[0].rollingResistance: must be >= 0 (m), got -1");
  const std::string surface = R"("surfaces": [{"name": "floor", "min": [-5, -5, -1], "max": [5, 5, 0], )"
                              R"("rollingResistance": 0.01}], )";
  EXPECT_EQ(rigid::parseScene(sceneWith("", surface)).model.surfaces[0].rollingResistance, 0.01);
}

TEST(Scene, SleepRules) {
  const rigid::WorldModel fallback = rigid::parseScene(sceneWith("", "")).model;
  EXPECT_TRUE(fallback.sleep.enabled);
  EXPECT_EQ(fallback.sleep.speed, 0.01);
  EXPECT_EQ(fallback.sleep.time, 0.5);
  const rigid::WorldModel set =
      rigid::parseScene(sceneWith("", R"("solver": {"sleep": false, "sleepSpeed": 0.002, "sleepTime": 2}, )")).model;
  EXPECT_FALSE(set.sleep.enabled);
  EXPECT_EQ(set.sleep.speed, 0.002);
  EXPECT_EQ(set.sleep.time, 2.0);
  EXPECT_SCENE_ERROR(sceneWith("", R"("solver": {"sleep": "yes"}, )"), "solver.sleep: must be true or false");
  EXPECT_SCENE_ERROR(sceneWith("", R"("solver": {"sleepSpeed": -0.01}, )"),
                     "solver.sleepSpeed: must be >= 0 (m/s), got -0.01");
  EXPECT_SCENE_ERROR(sceneWith("", R"("solver": {"sleepTime": 0}, )"), "solver.sleepTime: must be > 0, got 0");
}

// Their FMU variables are NAME.field: a body and a surface named alike would share
// NAME.staticFriction.
TEST(Scene, BodiesSurfacesMediaAndJointsShareOneNameSpace) {
  const std::string floorNamedB = R"("surfaces": [{"name": "b", "min": [-1, -1, -1], "max": [1, 1, 0]}], )";
  EXPECT_SCENE_ERROR(sceneWith("", floorNamedB),
                     "surfaces[0].name: \"b\" is also the name of bodies[0]; bodies, surfaces, media and "
                     "joints share one name space (their FMU variables are NAME.field)");
  const std::string poolNamedFloor = R"("surfaces": [{"name": "floor", "min": [-1, -1, -1], "max": [1, 1, 0]}],
      "media": [{"name": "floor", "min": [-1, -1, 0], "max": [1, 1, 1]}], )";
  EXPECT_SCENE_ERROR(sceneWith("", poolNamedFloor),
                     "media[0].name: \"floor\" is also the name of surfaces[0]; bodies, surfaces, media and "
                     "joints share one name space (their FMU variables are NAME.field)");
}

TEST(Scene, LoadPoints) {
  const rigid::WorldModel m =
      rigid::parseScene(
          sceneWith(
              R"(, "loads": [{"name": "thruster", "point": [0, 0, -0.1], "frame": "body"}, {"name": "cable", "point": [0.1, 0, 0]}])"))
          .model;
  ASSERT_EQ(m.bodies[0].loads.size(), 2u);
  EXPECT_EQ(m.bodies[0].loads[0].name, "thruster");
  EXPECT_EQ(m.bodies[0].loads[0].point, rigid::Vec3(0, 0, -0.1));
  EXPECT_TRUE(m.bodies[0].loads[0].bodyFrame);
  EXPECT_FALSE(m.bodies[0].loads[1].bodyFrame);  // the world frame by default, as b.force
  EXPECT_SCENE_ERROR(sceneWith(R"(, "loads": {"name": "x"})"), "bodies[0].loads: must be an array of load points");
  EXPECT_SCENE_ERROR(sceneWith(R"(, "loads": [{"name": "x"}])"),
                     "bodies[0].loads[0].point: is required (m, body frame, from the centre of mass)");
  EXPECT_SCENE_ERROR(sceneWith(R"(, "loads": [{"name": "x", "point": [0, 0, 0], "frame": "local"}])"),
                     "bodies[0].loads[0].frame: must be \"world\" or \"body\", got \"local\"");
  EXPECT_SCENE_ERROR(sceneWith(R"(, "loads": [{"name": "x", "point": [0, 0, 0]}, {"name": "x", "point": [1, 0, 0]}])"),
                     "bodies[0].loads[1].name: \"x\" is used twice in this body");
}

TEST(Scene, NameNotIdentifier) {
  EXPECT_SCENE_ERROR(
      R"({"name": "2fast", "bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1}]})",
      "name: must be a C identifier ([A-Za-z_][A-Za-z0-9_]*), got \"2fast\"");
}

TEST(Scene, BodyNameNotIdentifier) {
  EXPECT_SCENE_ERROR(
      R"({"name": "S", "bodies": [{"name": "my ball", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1}]})",
      "bodies[0].name: must be a C identifier", "got \"my ball\"");
}

TEST(Scene, GravityNotThreeNumbers) {
  EXPECT_SCENE_ERROR(sceneWith("", R"("gravity": [0, -9.81], )"), "gravity: must be an array of 3 numbers");
  EXPECT_SCENE_ERROR(sceneWith("", R"("gravity": [0, "down", 0], )"), "gravity[1]: must be a number");
}

TEST(Scene, SolverMethodUnknown) {
  EXPECT_SCENE_ERROR(
      sceneWith("", R"("solver": {"method": "rk5"}, )"),
      "solver.method: must be one of euler, rk4, symplecticEuler, splitting, lieRk4, dopri5, rosenbrock, got \"rk5\"");
}

TEST(Scene, SolverStepNotPositive) {
  EXPECT_SCENE_ERROR(sceneWith("", R"("solver": {"step": 0}, )"), "solver.step: must be > 0, got 0");
  EXPECT_SCENE_ERROR(sceneWith("", R"("solver": {"step": -0.001}, )"), "solver.step: must be > 0, got -0.001");
}

TEST(Scene, BodiesMissing) { EXPECT_SCENE_ERROR(R"({"name": "S"})", "bodies: is required"); }

TEST(Scene, BodiesEmpty) {
  EXPECT_SCENE_ERROR(R"({"name": "S", "bodies": []})", "bodies: must hold at least one body");
}

TEST(Scene, BodyNameMissing) {
  EXPECT_SCENE_ERROR(R"({"name": "S", "bodies": [{"shape": {"type": "sphere", "radius": 0.1}, "mass": 1}]})",
                     "bodies[0].name: is required");
}

TEST(Scene, DuplicateBodyName) {
  EXPECT_SCENE_ERROR(
      R"({"name": "S", "bodies": [
           {"name": "b", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1},
           {"name": "c", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1},
           {"name": "b", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1}]})",
      "bodies[2].name: must be unique in bodies, \"b\" is used twice");
}

TEST(Scene, ShapeTypeUnknown) {
  EXPECT_SCENE_ERROR(
      sceneWith("", "", R"({"type": "cone", "radius": 0.1})"),
      "bodies[0].shape.type: must be one of sphere, box, cylinder, capsule, mesh, compound, got \"cone\"");
}

TEST(Scene, SphereRadiusNotPositive) {
  EXPECT_SCENE_ERROR(sceneWith("", "", R"({"type": "sphere", "radius": 0})"),
                     "bodies[0].shape.radius: must be > 0, got 0");
  EXPECT_SCENE_ERROR(sceneWith("", "", R"({"type": "sphere", "radius": -0.5})"),
                     "bodies[0].shape.radius: must be > 0, got -0.5");
}

TEST(Scene, BoxSizeComponentNotPositive) {
  EXPECT_SCENE_ERROR(sceneWith("", "", R"({"type": "box", "size": [0.1, -0.2, 0.3]})"),
                     "bodies[0].shape.size[1]: must be > 0, got -0.2");
  EXPECT_SCENE_ERROR(sceneWith("", "", R"({"type": "box", "size": [0.1, 0.2, 0]})"),
                     "bodies[0].shape.size[2]: must be > 0, got 0");
}

TEST(Scene, CylinderLengthNotPositive) {
  EXPECT_SCENE_ERROR(sceneWith("", "", R"({"type": "cylinder", "radius": 0.1, "length": 0})"),
                     "bodies[0].shape.length: must be > 0, got 0");
}

TEST(Scene, CapsuleLengthNegative) {
  EXPECT_SCENE_ERROR(sceneWith("", "", R"({"type": "capsule", "radius": 0.1, "length": -0.1})"),
                     "bodies[0].shape.length: must be >= 0, got -0.1");
  // Length 0 is the limit: a sphere-shaped capsule is accepted.
  EXPECT_NO_THROW(rigid::parseScene(sceneWith("", "", R"({"type": "capsule", "radius": 0.1, "length": 0})")));
}

TEST(Scene, MassMissing) {
  EXPECT_SCENE_ERROR(R"({"name": "S", "bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 0.1}}]})",
                     "bodies[0].mass: is required");
}

TEST(Scene, MassNotPositive) {
  EXPECT_SCENE_ERROR(
      R"({"name": "S", "bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 0.1}, "mass": -1}]})",
      "bodies[0].mass: must be > 0, got -1");
  EXPECT_SCENE_ERROR(
      R"({"name": "S", "bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 0.1}, "mass": 0}]})",
      "bodies[0].mass: must be > 0, got 0");
}

TEST(Scene, InertiaNotSymmetric) {
  EXPECT_SCENE_ERROR(sceneWith(R"(, "inertia": [[1, 0.1, 0], [0, 1, 0], [0, 0, 1]])"),
                     "bodies[0].inertia: must be symmetric within 1e-9 relative");
}

TEST(Scene, InertiaNotPositiveDefinite) {
  EXPECT_SCENE_ERROR(sceneWith(R"(, "inertia": [[-1, 0, 0], [0, 2, 0], [0, 0, 2]])"),
                     "bodies[0].inertia: must be positive definite, smallest principal moment is -1");
  EXPECT_SCENE_ERROR(sceneWith(R"(, "inertia": [[0, 0, 0], [0, 1, 0], [0, 0, 1]])"),
                     "bodies[0].inertia: must be positive definite, smallest principal moment is 0");
}

TEST(Scene, InertiaViolatesTriangleInequality) {
  EXPECT_SCENE_ERROR(sceneWith(R"(, "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 2.5]])"),
                     "bodies[0].inertia: principal moments must satisfy the triangle inequality: "
                     "largest 2.5 > sum of the others 2");
}

TEST(Scene, InertiaAtTriangleLimitIsAccepted) {
  const rigid::Scene s = rigid::parseScene(sceneWith(R"(, "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 2]])"));
  const rigid::BodyConstants& b = s.model.bodies[0];
  EXPECT_FALSE(b.inertiaFromShape);
  rigid::Mat3 expected = rigid::Vec3(1, 1, 2).asDiagonal();
  EXPECT_EQ(b.Ibody, expected);
  rigid::Mat3 expectedInv = rigid::Vec3(1, 1, 0.5).asDiagonal();
  EXPECT_LT((b.IbodyInv - expectedInv).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Scene, OrientationNotUnit) {
  EXPECT_SCENE_ERROR(
      sceneWith(R"(, "orientation": [1, 0, 0, 0.01])"),
      "bodies[0].orientation: must be a unit quaternion (w, x, y, z) within 1e-6, got |q| = 1.0000499987");
  EXPECT_SCENE_ERROR(sceneWith(R"(, "orientation": [0, 0, 0, 0])"), "bodies[0].orientation: must be a unit quaternion",
                     "got |q| = 0");
}

TEST(Scene, RestitutionOutsideUnitInterval) {
  EXPECT_SCENE_ERROR(sceneWith(R"(, "restitution": 1.5)"), "bodies[0].restitution: must be in [0, 1], got 1.5");
  EXPECT_SCENE_ERROR(sceneWith(R"(, "restitution": -0.1)"), "bodies[0].restitution: must be in [0, 1], got -0.1");
  EXPECT_NO_THROW(rigid::parseScene(sceneWith(R"(, "restitution": 1)")));
  EXPECT_NO_THROW(rigid::parseScene(sceneWith(R"(, "restitution": 0)")));
}

TEST(Scene, KineticFrictionNegative) {
  EXPECT_SCENE_ERROR(sceneWith(R"(, "kineticFriction": -0.1)"), "bodies[0].kineticFriction: must be >= 0, got -0.1");
}

TEST(Scene, StaticFrictionBelowKinetic) {
  EXPECT_SCENE_ERROR(sceneWith(R"(, "staticFriction": 0.3, "kineticFriction": 0.5)"),
                     "bodies[0].staticFriction: must be >= kineticFriction (0.5), got 0.3");
  // Equality is the limit and is accepted.
  EXPECT_NO_THROW(rigid::parseScene(sceneWith(R"(, "staticFriction": 0.5, "kineticFriction": 0.5)")));
}

TEST(Scene, SurfaceMinNotBelowMax) {
  EXPECT_SCENE_ERROR(sceneWith("", R"("surfaces": [{"name": "floor", "min": [-5, -5, 0], "max": [5, 5, 0]}], )"),
                     "surfaces[0].max[2]: must be > min[2] (0), got 0");
  EXPECT_SCENE_ERROR(sceneWith("", R"("surfaces": [{"name": "floor", "min": [1, -5, -1], "max": [-1, 5, 0]}], )"),
                     "surfaces[0].max[0]: must be > min[0] (1), got -1");
}

TEST(Scene, DuplicateSurfaceName) {
  EXPECT_SCENE_ERROR(sceneWith("", std::string(R"("surfaces": [)") + kSurface + ", " + kSurface + "], "),
                     "surfaces[1].name: must be unique in surfaces, \"floor\" is used twice");
}

TEST(Scene, MediumTypeUnknown) {
  EXPECT_SCENE_ERROR(
      sceneWith("", R"("media": [{"name": "tank", "type": "oil", "min": [-1, -1, -1], "max": [1, 1, 1]}], )"),
      "media[0].type: must be one of air, water, custom, got \"oil\"");
}

TEST(Scene, MediumDensityNegative) {
  // 0 is allowed (a medium with viscous drag only); below 0 is not.
  EXPECT_SCENE_ERROR(
      sceneWith(
          "",
          R"("media": [{"name": "tank", "type": "water", "min": [-1, -1, -1], "max": [1, 1, 1], "density": -1}], )"),
      "media[0].density: must be >= 0, got -1");
  EXPECT_SCENE_ERROR(
      sceneWith(
          "",
          R"("media": [{"name": "tank", "type": "custom", "min": [-1, -1, -1], "max": [1, 1, 1], "density": -5, "viscosity": 1}], )"),
      "media[0].density: must be >= 0, got -5");
  const rigid::Scene s = rigid::parseScene(sceneWith(
      "",
      R"("media": [{"name": "tank", "type": "custom", "min": [-1, -1, -1], "max": [1, 1, 1], "density": 0, "viscosity": 2}], )"));
  ASSERT_EQ(s.model.media.size(), 1u);
  EXPECT_EQ(s.model.media[0].density, 0.0);
  EXPECT_EQ(s.model.media[0].viscosity, 2.0);
}

TEST(Scene, MediumViscosityNegative) {
  EXPECT_SCENE_ERROR(
      sceneWith(
          "",
          R"("media": [{"name": "tank", "type": "air", "min": [-1, -1, -1], "max": [1, 1, 1], "viscosity": -0.001}], )"),
      "media[0].viscosity: must be >= 0, got -0.001");
}

TEST(Scene, CustomMediumWithoutDensity) {
  EXPECT_SCENE_ERROR(
      sceneWith(
          "",
          R"("media": [{"name": "tank", "type": "custom", "min": [-1, -1, -1], "max": [1, 1, 1], "viscosity": 0.1}], )"),
      "media[0].density: is required for a custom medium");
}

TEST(Scene, SurfaceIsRead) {
  const rigid::Scene s = rigid::parseScene(sceneWith("", std::string(R"("surfaces": [)") + kSurface + "], "));
  ASSERT_EQ(s.model.surfaces.size(), 1u);
  const rigid::Surface& f = s.model.surfaces[0];
  EXPECT_EQ(f.name, "floor");
  // derived: centre and half extents of the box
  EXPECT_TRUE(f.centre.isApprox(0.5 * (f.min + f.max)));
  EXPECT_TRUE(f.halfExtent.isApprox(0.5 * (f.max - f.min)));
}

// "beltVelocity" makes a surface a conveyor (its velocity an FMU input); without it a
// surface has none and stays still.
TEST(Scene, ABeltVelocityMakesTheSurfaceAConveyor) {
  auto with = [](const std::string& belt) {
    return sceneWith("", R"("surfaces": [{"name": "floor", "min": [-5, -5, -1], "max": [5, 5, 0])" + belt + "}], ");
  };
  const rigid::Surface still = rigid::parseScene(with("")).model.surfaces[0];
  EXPECT_FALSE(still.belt);
  EXPECT_EQ(still.beltVelocity, rigid::Vec3::Zero());
  const rigid::Surface belt = rigid::parseScene(with(R"(, "beltVelocity": [1.5, -0.5, 0])")).model.surfaces[0];
  EXPECT_TRUE(belt.belt);
  EXPECT_EQ(belt.beltVelocity, rigid::Vec3(1.5, -0.5, 0));
  EXPECT_TRUE(rigid::parseScene(with(R"(, "beltVelocity": [0, 0, 0])")).model.surfaces[0].belt);
  EXPECT_SCENE_ERROR(with(R"(, "beltVelocity": [1, 0])"), "surfaces[0].beltVelocity: must be an array of 3 numbers");
  EXPECT_SCENE_ERROR(with(R"(, "beltVelocity": [1, 0, "x"])"), "surfaces[0].beltVelocity[2]: must be a number");
}

TEST(Scene, WaterMediumTakesWatersValues) {
  const rigid::Scene s = rigid::parseScene(sceneWith("", std::string(R"("media": [)") + kMedium + "], "));
  ASSERT_EQ(s.model.media.size(), 1u);
  EXPECT_EQ(s.model.media[0].density, 998.2);       // kg/m^3, water at 20 C
  EXPECT_EQ(s.model.media[0].viscosity, 1.002e-3);  // Pa s
}

TEST(Scene, ExposedVariablesDefaultToAll) {
  const rigid::Scene s = rigid::parseScene(sceneWith());
  ASSERT_EQ(s.variables.size(), 1u);
  EXPECT_EQ(s.variables[0].outputs.size(), rigid::kBodyOutputs.size());
  EXPECT_EQ(s.variables[0].inputs.size(), rigid::kBodyInputs.size());
}

TEST(Scene, ExposedVariablesAreRead) {
  const rigid::Scene s = rigid::parseScene(sceneWith(R"(, "outputs": ["position", "orientation"], "inputs": [])"));
  EXPECT_EQ(s.variables[0].outputs, (std::set<std::string>{"position", "orientation"}));
  EXPECT_TRUE(s.variables[0].inputs.empty());
}

TEST(Scene, ExposedOutputUnknown) {
  EXPECT_SCENE_ERROR(
      sceneWith(R"(, "outputs": ["position", "speed"])"),
      "bodies[0].outputs[1]: must be one of position, orientation, velocity, "
      "angularVelocity, linearMomentum, angularMomentum, contacts, contactForce, contactTorque, got \"speed\"");
}

TEST(Scene, ExposedInputTwice) {
  EXPECT_SCENE_ERROR(sceneWith(R"(, "inputs": ["force", "force"])"), "bodies[0].inputs[1]: \"force\" is listed twice");
}

TEST(Scene, ExposedListNotAnArray) {
  EXPECT_SCENE_ERROR(sceneWith(R"(, "inputs": "force")"), "bodies[0].inputs: must be an array of names");
}

// ---- driven bodies and moving surfaces (drive.h) ---------------------------------------

std::string drivenScene(const std::string& extra) {
  return R"({"name": "D", "bodies": [{"name": "pusher", "motion": "driven", )"
         R"("shape": {"type": "box", "size": [1, 1, 0.1]})" +
         extra + "}]}";
}

TEST(Scene, ADrivenBodyHasUnitMassAndItsStartValuesAsInputs) {
  const rigid::Scene s = rigid::parseScene(drivenScene(R"(, "position": [1, 2, 3], "velocity": [0.5, 0, 0])"));
  const rigid::BodyConstants& b = s.model.bodies[0];
  EXPECT_TRUE(rigid::driven(b));
  EXPECT_EQ(b.mass, 1.0);
  EXPECT_EQ(b.IbodyInv, rigid::Mat3::Identity());
  EXPECT_EQ(b.start.position, rigid::Vec3(1, 2, 3));
  EXPECT_EQ(s.variables[0].inputs, (std::set<std::string>{"position", "orientation", "velocity", "angularVelocity"}));
  EXPECT_EQ(s.variables[0].outputs, (std::set<std::string>{"contacts", "contactForce", "contactTorque"}));
}

TEST(Scene, ADrivenBodyRefusesWhatOnlyAFreeBodyHas) {
  for (const char* key : {"mass", "inertia", "loads", "inputs"}) {
    const std::string expected = std::string("bodies[0].") + key + ": not for a driven body: its motion comes from";
    EXPECT_SCENE_ERROR(drivenScene(std::string(", \"") + key + "\": 1"), expected.c_str());
  }
  EXPECT_SCENE_ERROR(drivenScene(R"(, "collision": false)"),
                     "bodies[0].collision: a driven body must collide: it acts on the world only through its contacts");
  EXPECT_SCENE_ERROR(R"({"name": "D", "bodies": [{"name": "b", "motion": "kinematic", "shape": {"type": "sphere",
                     "radius": 1}}]})",
                     "bodies[0].motion: must be one of free, driven, got \"kinematic\"");
  EXPECT_SCENE_ERROR(drivenScene(R"(, "outputs": ["position"])"),
                     "bodies[0].outputs[0]: must be one of contacts, contactForce, contactTorque, got \"position\"");
}

TEST(Scene, AMovingSurfaceIsADrivenBoxAfterTheBodies) {
  const rigid::Scene s = rigid::parseScene(
      sceneWith("", R"("surfaces": [{"name": "lift", "motion": "driven", "min": [-1, -2, -0.2], "max": [1, 2, 0],
                           "orientation": [1, 0, 0, 0], "staticFriction": 0.9, "kineticFriction": 0.7}, )" +
                        std::string(kSurface) + "], "));
  ASSERT_EQ(s.model.bodies.size(), 2u);
  ASSERT_EQ(s.model.surfaces.size(), 1u);
  const rigid::BodyConstants& lift = s.model.bodies[1];
  EXPECT_EQ(lift.name, "lift");
  EXPECT_TRUE(rigid::driven(lift));
  EXPECT_EQ(lift.shape.type, rigid::ShapeType::Box);
  EXPECT_EQ(lift.shape.size, rigid::Vec3(2, 4, 0.2));
  EXPECT_EQ(lift.start.position, rigid::Vec3(0, 0, -0.1));
  EXPECT_EQ(lift.staticFriction, 0.9);
  EXPECT_EQ(s.variables.size(), 2u);
  EXPECT_SCENE_ERROR(sceneWith("", R"("surfaces": [{"name": "lift", "motion": "moving", "min": [0, 0, 0],
                                   "max": [1, 1, 1]}], )"),
                     "surfaces[0].motion: must be one of static, driven, got \"moving\"");
}
