// The FMU's variable table, modelDescription.xml and GUID of a scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "guid.h"
#include "model_description_xml.h"
#include "variables.h"

namespace {

using rigidfmu::Causality;
using rigidfmu::Phase;
using rigidfmu::Variable;

const char* const kScene = R"({
  "name": "Demo",
  "gravity": [0.5, -0.25, -9.81],
  "solver": {"method": "euler", "step": 0.002},
  "bodies": [
    {"name": "b", "shape": {"type": "box", "size": [0.2, 0.4, 0.6]}, "mass": 2.0,
     "position": [1, 2, 3], "orientation": [0.6, 0.8, 0, 0], "velocity": [0.5, -1.5, 2.5],
     "angularVelocity": [0.3, -0.2, 0.7], "restitution": 0.8},
    {"name": "c", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1.0}
  ]
})";

const Variable& find(const std::vector<Variable>& vars, const std::string& name) {
  for (const Variable& v : vars)
    if (v.name == name) return v;
  throw std::runtime_error("no variable " + name);
}

std::set<std::string> expectedBodyNames(const std::string& b) {
  std::set<std::string> names;
  for (const char* f :
       {"position", "velocity", "angularVelocity", "linearMomentum", "angularMomentum", "force", "torque"})
    for (int i = 1; i <= 3; ++i) names.insert(b + "." + f + "[" + std::to_string(i) + "]");
  for (int i = 1; i <= 4; ++i) names.insert(b + ".orientation[" + std::to_string(i) + "]");
  names.insert(b + ".mass");
  names.insert(b + ".restitution");
  names.insert(b + ".contacts");        // extension: contact points in the last step (issue 4)
  names.insert(b + ".staticFriction");  // issue 18: friction as tunable parameters
  names.insert(b + ".kineticFriction");
  for (const char* f : {"contactForce", "contactTorque"})  // issue 18: the contact loads
    for (int i = 1; i <= 3; ++i) names.insert(b + "." + f + "[" + std::to_string(i) + "]");
  return names;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

class Description : public ::testing::Test {
 protected:
  rigid::Scene scene = rigid::parseScene(kScene);
  std::vector<Variable> vars = rigidfmu::modelVariables(scene);
  rigid::WorldModel model = scene.model;
  rigid::WorldData data = rigid::initialData(scene.model);
};

}  // namespace

TEST_F(Description, ValueReferencesAreIndicesInOrderAndNamesUnique) {
  ASSERT_FALSE(vars.empty());
  std::set<std::string> names;
  for (size_t i = 0; i < vars.size(); ++i) {
    EXPECT_EQ(vars[i].vr, static_cast<unsigned>(i)) << vars[i].name;
    EXPECT_TRUE(names.insert(vars[i].name).second) << "duplicate name " << vars[i].name;
  }
}

TEST_F(Description, VariableNamesAreThoseOfTheInterface) {
  std::map<std::string, std::set<std::string>> byOwner;
  for (const Variable& v : vars) {
    const std::string owner = v.body >= 0 ? scene.model.bodies[static_cast<size_t>(v.body)].name : std::string("world");
    byOwner[owner].insert(v.name);
  }
  EXPECT_EQ(byOwner["b"], expectedBodyNames("b"));
  EXPECT_EQ(byOwner["c"], expectedBodyNames("c"));
  // World variables: those of INTERFACE.md plus FMI's independent variable, time.
  const std::set<std::string> world = {"time", "gravity[1]", "gravity[2]", "gravity[3]", "solver.method", "solver.step",
                                       // extensions (issue 6): adaptive tolerance, step counts
                                       "solver.tolerance", "solver.steps", "solver.errorEstimate",
                                       // issue 7: the energy audit's limit
                                       "solver.energyGainLimit"};
  EXPECT_EQ(byOwner["world"], world);
  EXPECT_EQ(byOwner.size(), 3u);
  EXPECT_EQ(vars.size(), 2u * 36u + 10u);  // 36 per body, 10 for the world
}

TEST_F(Description, CausalityAndUnitsFollowTheInterfaceTable) {
  struct Row {
    const char* field;
    int n;
    Causality causality;
    const char* unit;
  };
  const Row rows[] = {
      {"position", 3, Causality::Output, "m"},
      {"orientation", 4, Causality::Output, "1"},
      {"velocity", 3, Causality::Output, "m/s"},
      {"angularVelocity", 3, Causality::Output, "rad/s"},
      {"linearMomentum", 3, Causality::Output, "kg.m/s"},
      {"angularMomentum", 3, Causality::Output, "kg.m2/s"},
      {"force", 3, Causality::Input, "N"},
      {"torque", 3, Causality::Input, "N.m"},
  };
  for (const Row& r : rows)
    for (int i = 1; i <= r.n; ++i) {
      const Variable& v = find(vars, std::string("b.") + r.field + "[" + std::to_string(i) + "]");
      EXPECT_EQ(v.causality, r.causality) << v.name;
      EXPECT_EQ(v.unit, r.unit) << v.name;
      EXPECT_EQ(v.type, rigidfmu::BaseType::Real) << v.name;
    }
  EXPECT_EQ(find(vars, "b.mass").causality, Causality::Parameter);
  EXPECT_EQ(find(vars, "b.mass").unit, "kg");
  EXPECT_EQ(find(vars, "b.restitution").causality, Causality::Parameter);
  EXPECT_EQ(find(vars, "b.restitution").unit, "1");
  for (int i = 1; i <= 3; ++i) {
    const Variable& g = find(vars, "gravity[" + std::to_string(i) + "]");
    EXPECT_EQ(g.causality, Causality::Parameter);
    EXPECT_EQ(g.variability, rigidfmu::Variability::Tunable);
    EXPECT_EQ(g.unit, "m/s2");
  }
  EXPECT_EQ(find(vars, "solver.method").causality, Causality::Parameter);
  EXPECT_EQ(find(vars, "solver.method").type, rigidfmu::BaseType::Enumeration);
  EXPECT_EQ(find(vars, "solver.step").causality, Causality::Parameter);
  EXPECT_EQ(find(vars, "solver.step").unit, "s");
}

TEST_F(Description, EveryRealHasAUnitAndEveryVariableADescription) {
  for (const Variable& v : vars) {
    if (v.type == rigidfmu::BaseType::Real) {
      EXPECT_FALSE(v.unit.empty()) << v.name;
    }
    EXPECT_FALSE(v.description.empty()) << v.name;
  }
}

TEST_F(Description, XmlListsEveryVariableWithItsReferenceAndTheGuid) {
  const std::string xml = rigidfmu::modelDescriptionXml(scene);
  EXPECT_TRUE(contains(xml, "fmiVersion=\"2.0\""));
  EXPECT_TRUE(contains(xml, "guid=\"" + rigidfmu::sceneGuid(scene) + "\""));
  EXPECT_TRUE(contains(xml, "modelIdentifier=\"Demo\""));
  for (const Variable& v : vars)
    EXPECT_TRUE(contains(xml, "name=\"" + v.name + "\" valueReference=\"" + std::to_string(v.vr) + "\"")) << v.name;
}

// The FMI 3.0 description from the same table: every variable as a scalar with its FMI 2
// name, value reference, unit and description, in FMI 3 types; the same token.
TEST_F(Description, Fmi3XmlHasTheSameVariablesInFmi3Types) {
  const std::string xml = rigidfmu::modelDescriptionXml(scene, rigidfmu::FmiVersion::Fmi3);
  EXPECT_TRUE(contains(xml, "fmiVersion=\"3.0\""));
  EXPECT_TRUE(contains(xml, "instantiationToken=\"" + rigidfmu::sceneGuid(scene) + "\""));
  EXPECT_FALSE(contains(xml, "ScalarVariable"));
  for (const Variable& v : vars) {
    const char* element = v.type == rigidfmu::BaseType::Enumeration ? "<Enumeration"
                          : v.type == rigidfmu::BaseType::Integer   ? "<Int32"
                                                                    : "<Float64";
    const std::string head = std::string(element) + " name=\"" + v.name + "\" valueReference=\"" +
                             std::to_string(v.vr) + "\" description=\"";
    EXPECT_TRUE(contains(xml, head)) << v.name;
    if (v.type == rigidfmu::BaseType::Real) {
      const size_t at = xml.find(head);
      EXPECT_TRUE(contains(xml.substr(at, xml.find('\n', at) - at), " unit=\"" + v.unit + "\"")) << v.name;
    }
  }
  // dependencies by value reference: b.linearMomentum[1] on b.velocity[1] and b.mass
  const Variable& p = find(vars, "b.linearMomentum[1]");
  EXPECT_TRUE(contains(xml, "<InitialUnknown valueReference=\"" + std::to_string(p.vr) + "\" dependencies=\""))
      << xml.substr(xml.find("<ModelStructure>"));
}

TEST(Guid, SameSceneTextGivesSameGuid) {
  const std::string a = rigidfmu::sceneGuid(rigid::parseScene(kScene));
  const std::string b = rigidfmu::sceneGuid(rigid::parseScene(kScene));
  EXPECT_EQ(a, b);
  EXPECT_EQ(a.size(), 38u);  // {8-4-4-4-12}
  EXPECT_EQ(a.front(), '{');
  EXPECT_EQ(a.back(), '}');
}

TEST(Guid, OneChangedNumberGivesAnotherGuid) {
  const std::string base = kScene;
  const std::string a = rigidfmu::sceneGuid(rigid::parseScene(base));
  std::string changed = base;
  const size_t at = changed.find("\"mass\": 2.0");
  ASSERT_NE(at, std::string::npos);
  changed.replace(at, 11, "\"mass\": 2.5");
  EXPECT_NE(rigidfmu::sceneGuid(rigid::parseScene(changed)), a);
  std::string step = base;
  const size_t s = step.find("0.002");
  ASSERT_NE(s, std::string::npos);
  step.replace(s, 5, "0.003");
  EXPECT_NE(rigidfmu::sceneGuid(rigid::parseScene(step)), a);
}

TEST_F(Description, WriteValueRefusesNaNNamingTheVariable) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const char* name :
       {"b.mass", "b.restitution", "gravity[2]", "solver.step", "b.force[1]", "b.position[3]", "solver.method"}) {
    const Variable& v = find(vars, name);
    const std::string why = rigidfmu::writeValue(v, nan, model, data, Phase::Setup);
    EXPECT_TRUE(contains(why, name)) << "\"" << why << "\"";
  }
  const std::string inf = rigidfmu::writeValue(find(vars, "b.torque[2]"), std::numeric_limits<double>::infinity(),
                                               model, data, Phase::Running);
  EXPECT_TRUE(contains(inf, "b.torque[2]")) << inf;
  EXPECT_EQ(model.bodies[0].mass, 2.0);
  EXPECT_EQ(model.gravity.y(), -0.25);
  EXPECT_EQ(data.input[0].torque.y(), 0.0);
}

TEST_F(Description, WriteValueRefusesNonPositiveMass) {
  const Variable& v = find(vars, "b.mass");
  for (double bad : {0.0, -1.0, -0.0}) {
    const std::string why = rigidfmu::writeValue(v, bad, model, data, Phase::Setup);
    EXPECT_TRUE(contains(why, "b.mass")) << why;
    EXPECT_TRUE(contains(why, "> 0")) << why;
  }
  EXPECT_EQ(model.bodies[0].mass, 2.0);
  EXPECT_EQ(rigidfmu::writeValue(v, 3.0, model, data, Phase::Setup), "");
  EXPECT_EQ(model.bodies[0].mass, 3.0);
}

TEST_F(Description, WriteValueRefusesRestitutionAboveOne) {
  const Variable& v = find(vars, "b.restitution");
  for (double bad : {1.0000001, 2.0, -0.1}) {
    const std::string why = rigidfmu::writeValue(v, bad, model, data, Phase::Setup);
    EXPECT_TRUE(contains(why, "b.restitution")) << why;
    EXPECT_TRUE(contains(why, "[0, 1]")) << why;
  }
  EXPECT_EQ(model.bodies[0].restitution, 0.8);
  EXPECT_EQ(rigidfmu::writeValue(v, 1.0, model, data, Phase::Setup), "");
  EXPECT_EQ(model.bodies[0].restitution, 1.0);
}

TEST_F(Description, WriteValueRefusesNonPositiveSolverStep) {
  const Variable& v = find(vars, "solver.step");
  for (double bad : {0.0, -1e-3}) {
    const std::string why = rigidfmu::writeValue(v, bad, model, data, Phase::Setup);
    EXPECT_TRUE(contains(why, "solver.step")) << why;
    EXPECT_TRUE(contains(why, "> 0")) << why;
  }
  EXPECT_EQ(model.maxStep, 0.002);
  EXPECT_EQ(rigidfmu::writeValue(v, 5e-4, model, data, Phase::Setup), "");
  EXPECT_EQ(model.maxStep, 5e-4);
}

TEST_F(Description, WriteValueRefusesUnknownSolverMethod) {
  const Variable& v = find(vars, "solver.method");
  ASSERT_EQ(model.method, rigid::Method::Euler);
  for (double bad : {0.0, 99.0, -1.0, 1.5, 1e10}) {
    const std::string why = rigidfmu::writeValue(v, bad, model, data, Phase::Setup);
    EXPECT_TRUE(contains(why, "solver.method")) << bad << ": " << why;
    EXPECT_TRUE(contains(why, "1 (euler)")) << why;
    EXPECT_TRUE(contains(why, "2 (rk4)")) << why;
    EXPECT_EQ(model.method, rigid::Method::Euler) << bad;
  }
  EXPECT_EQ(rigidfmu::writeValue(v, 2.0, model, data, Phase::Setup), "");
  EXPECT_EQ(model.method, rigid::Method::RK4);
}

TEST_F(Description, ReadValueInSetupGivesStartValues) {
  auto read = [&](const char* name) { return rigidfmu::readValue(find(vars, name), model, data, Phase::Setup); };
  EXPECT_EQ(read("gravity[1]"), 0.5);
  EXPECT_EQ(read("gravity[2]"), -0.25);
  EXPECT_EQ(read("gravity[3]"), -9.81);
  EXPECT_EQ(read("solver.method"), 1.0);  // euler
  EXPECT_EQ(read("solver.step"), 0.002);
  EXPECT_EQ(read("b.mass"), 2.0);
  EXPECT_EQ(read("b.restitution"), 0.8);
  EXPECT_EQ(read("c.restitution"), 0.5);
  const double pos[3] = {1, 2, 3}, vel[3] = {0.5, -1.5, 2.5}, w[3] = {0.3, -0.2, 0.7};
  const double q[4] = {0.6, 0.8, 0, 0};
  for (int i = 0; i < 3; ++i) {
    const std::string k = "[" + std::to_string(i + 1) + "]";
    EXPECT_EQ(read(("b.position" + k).c_str()), pos[i]);
    EXPECT_EQ(read(("b.velocity" + k).c_str()), vel[i]);
    EXPECT_EQ(read(("b.angularVelocity" + k).c_str()), w[i]);
    EXPECT_NEAR(read(("b.linearMomentum" + k).c_str()), 2.0 * vel[i], 1e-15);
    EXPECT_EQ(read(("c.linearMomentum" + k).c_str()), 0.0);
    EXPECT_EQ(read(("b.force" + k).c_str()), 0.0);
    EXPECT_EQ(read(("b.torque" + k).c_str()), 0.0);
  }
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(read(("b.orientation[" + std::to_string(i + 1) + "]").c_str()), q[i], 1e-15);

  // L = R Ibody R^T omega: q = (0.6, 0.8, 0, 0) turns by 2 acos(0.6) about x.
  // Box 0.2 x 0.4 x 0.6, 2 kg: Ibody = m/12 diag(ly^2+lz^2, lx^2+lz^2, lx^2+ly^2).
  const double m = 2.0;
  const rigid::Vec3 Ib = m / 12.0 * rigid::Vec3(0.16 + 0.36, 0.04 + 0.36, 0.04 + 0.16);
  const double c = 0.6 * 0.6 - 0.8 * 0.8, s = 2 * 0.6 * 0.8;  // cos, sin of the angle
  rigid::Mat3 R;
  R << 1, 0, 0, 0, c, -s, 0, s, c;
  const rigid::Mat3 I = R * rigid::Mat3(Ib.asDiagonal()) * R.transpose();
  const rigid::Vec3 L = I * rigid::Vec3(w[0], w[1], w[2]);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(read(("b.angularMomentum[" + std::to_string(i + 1) + "]").c_str()), L[i], 1e-14);

  // A new mass and velocity before the run starts: P = m v follows.
  ASSERT_EQ(rigidfmu::writeValue(find(vars, "b.mass"), 4.0, model, data, Phase::Setup), "");
  ASSERT_EQ(rigidfmu::writeValue(find(vars, "b.velocity[2]"), 3.0, model, data, Phase::Setup), "");
  EXPECT_NEAR(read("b.linearMomentum[2]"), 12.0, 1e-14);
  EXPECT_NEAR(read("b.linearMomentum[1]"), 2.0, 1e-14);
}

TEST_F(Description, OutputsCannotBeWrittenWhileRunning) {
  const std::string why = rigidfmu::writeValue(find(vars, "b.position[1]"), 5.0, model, data, Phase::Running);
  EXPECT_TRUE(contains(why, "b.position[1]")) << why;
  EXPECT_EQ(model.bodies[0].start.position.x(), 1.0);
  EXPECT_TRUE(contains(rigidfmu::writeValue(find(vars, "b.linearMomentum[1]"), 1.0, model, data, Phase::Setup),
                       "b.linearMomentum[1]"));
}

// Issue 18: every friction, a surface's restitution and a medium's density and viscosity
// are tunable parameters NAME.field, after the earlier variables (whose value
// references stay), with the scene's values as start values; bad values are refused
// naming the variable and the limit; mu_k <= mu_s is checked when both are set.
TEST(Parameters, MaterialAndFluidConstantsAreTunableParameters) {
  const rigid::Scene scene = rigid::parseScene(R"({"name": "P",
    "bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1.0,
                "staticFriction": 0.7, "kineticFriction": 0.5}],
    "surfaces": [{"name": "floor", "min": [-1, -1, -1], "max": [1, 1, 0],
                  "staticFriction": 0.4, "kineticFriction": 0.3, "restitution": 0.2}],
    "media": [{"name": "pool", "type": "water", "min": [-1, -1, 0], "max": [1, 1, 1]}]})");
  const std::vector<Variable> vars = rigidfmu::modelVariables(scene);
  struct Row {
    const char* name;
    double start;
    const char* unit;
  };
  const Row rows[] = {{"b.staticFriction", 0.7, "1"},      {"b.kineticFriction", 0.5, "1"},
                      {"floor.staticFriction", 0.4, "1"},  {"floor.kineticFriction", 0.3, "1"},
                      {"floor.restitution", 0.2, "1"},     {"pool.density", 998.2, "kg/m3"},
                      {"pool.viscosity", 1.002e-3, "Pa.s"}};
  rigid::WorldModel model = scene.model;
  rigid::WorldData data = rigid::initialData(model);
  for (const Row& r : rows) {
    SCOPED_TRACE(r.name);
    const Variable& v = find(vars, r.name);
    EXPECT_EQ(v.causality, Causality::Parameter);
    EXPECT_EQ(v.variability, rigidfmu::Variability::Tunable);
    EXPECT_EQ(v.unit, r.unit);
    EXPECT_FALSE(v.description.empty());
    EXPECT_DOUBLE_EQ(rigidfmu::readValue(v, model, data, Phase::Setup), r.start);
    EXPECT_EQ(rigidfmu::writeValue(v, 0.25, model, data, Phase::Running), "");
    EXPECT_EQ(rigidfmu::readValue(v, model, data, Phase::Running), 0.25);
    EXPECT_EQ(rigidfmu::writeValue(v, -0.1, model, data, Phase::Running).rfind(std::string(r.name) + ": must be", 0),
              0u);
    EXPECT_NE(rigidfmu::writeValue(v, std::nan(""), model, data, Phase::Running).find("finite"), std::string::npos);
  }
  EXPECT_EQ(rigidfmu::writeValue(find(vars, "floor.restitution"), 1.5, model, data, Phase::Running),
            "floor.restitution: must be in [0, 1], got 1.5");
  // the earlier variables keep their value references: the new ones come last
  EXPECT_LT(find(vars, "pool.viscosity").vr, find(vars, "floor.force[1]").vr);  // the loads come last
  EXPECT_EQ(vars.back().name, "floor.force[3]");
  EXPECT_LT(find(vars, "b.contacts").vr, find(vars, "b.staticFriction").vr);
  // mu_k above mu_s: refused when the pair takes effect, naming both
  EXPECT_EQ(rigidfmu::parameterConflict(model), "");
  model.surfaces[0].kineticFriction = 0.5;
  EXPECT_EQ(rigidfmu::parameterConflict(model),
            "floor.kineticFriction: must be <= floor.staticFriction (0.25), got 0.5");
}

// A conveyor's belt velocity is an input S.beltVelocity[1..3] (m/s) of the surfaces
// whose scene gives it, after every other variable, starting at the scene's value:
// before the run it sets the start value, in a run the belt's velocity. A scene without
// belts has the variables it had.
TEST(Parameters, ABeltVelocityIsAnInputOfTheConveyorsOnly) {
  const std::string bodies =
      R"("name": "C", "bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1.0}], )";
  const std::string wall = R"({"name": "wall", "min": [5, -1, 0], "max": [6, 1, 1]})";
  const rigid::Scene plain = rigid::parseScene("{" + bodies + R"("surfaces": [)" + wall + "]}");
  const rigid::Scene scene =
      rigid::parseScene("{" + bodies + R"("surfaces": [{"name": "belt", "min": [-1, -1, -1], "max": [1, 1, 0], )" +
                        R"("beltVelocity": [0.5, 0, 0]}, )" + wall + "]}");
  const std::vector<Variable> vars = rigidfmu::modelVariables(scene), before = rigidfmu::modelVariables(plain);
  for (const Variable& v : before) EXPECT_EQ(v.name.find("beltVelocity"), std::string::npos) << v.name;
  ASSERT_EQ(vars.size(), before.size() + 9u);  // the belt's friction, restitution, force and velocity
  rigid::WorldModel model = scene.model;
  rigid::WorldData data = rigid::initialData(model);
  for (int c = 0; c < 3; ++c) {
    const Variable& v = vars[vars.size() - 3 + static_cast<size_t>(c)];
    EXPECT_EQ(v.name, "belt.beltVelocity[" + std::to_string(c + 1) + "]");
    EXPECT_EQ(v.causality, Causality::Input);
    EXPECT_EQ(v.unit, "m/s");
    EXPECT_FALSE(v.description.empty());
    EXPECT_EQ(rigidfmu::readValue(v, model, data, Phase::Setup), c == 0 ? 0.5 : 0.0);
  }
  const Variable& x = find(vars, "belt.beltVelocity[1]");
  EXPECT_EQ(rigidfmu::writeValue(x, 2.0, model, data, Phase::Setup), "");
  EXPECT_EQ(rigid::initialData(model).beltVelocity[0], rigid::Vec3(2.0, 0, 0));  // the run starts there
  EXPECT_EQ(rigidfmu::writeValue(x, -1.0, model, data, Phase::Running), "");
  EXPECT_EQ(data.beltVelocity[0], rigid::Vec3(-1.0, 0, 0));
  EXPECT_EQ(rigidfmu::readValue(x, model, data, Phase::Running), -1.0);
  EXPECT_EQ(model.surfaces[0].beltVelocity, rigid::Vec3(2.0, 0, 0));
  EXPECT_EQ(rigidfmu::writeValue(x, std::numeric_limits<double>::infinity(), model, data, Phase::Running),
            "belt.beltVelocity[1]: must be finite, got inf");
  EXPECT_EQ(data.beltVelocity[1], rigid::Vec3::Zero());  // the wall has no belt
}

// Joints bring units of their own (rad, N.m/rad, N.s/m…): each Real's unit is defined in
// the XML of both versions, for a hinge and a slider with every option.
const char* const kJointScene = R"({
    "name": "Joints",
    "bodies": [
      {"name": "a", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "mass": 1.0, "position": [0, 0, -1]},
      {"name": "b", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "mass": 1.0, "position": [1, 0, -1]}
    ],
    "joints": [
      {"name": "hinge", "type": "revolute", "bodies": ["world", "a"], "anchor": [0, 0, 0], "axis": [0, 1, 0],
       "limits": [-1, 1], "motor": {"speed": 1, "maxTorque": 2}, "spring": {"stiffness": 3, "damping": 0.1}},
      {"name": "slider", "type": "prismatic", "bodies": ["a", "b"], "anchor": [1, 0, -1], "axis": [1, 0, 0],
       "limits": [-0.5, 0.5], "motor": {"speed": 1, "maxForce": 2}, "spring": {"stiffness": 3, "damping": 0.1}},
      {"name": "rod", "type": "distance", "bodies": ["world", "b"], "anchors": [[1, 0, 0], [0, 0, 0]],
       "limits": [0.5, 1.5], "restitution": 0.5}
    ]
  })";

TEST(JointDescription, EveryJointUnitIsDefinedInTheXml) {
  const rigid::Scene scene = rigid::parseScene(kJointScene);
  const std::vector<Variable> vars = rigidfmu::modelVariables(scene);
  for (rigidfmu::FmiVersion version : {rigidfmu::FmiVersion::Fmi2, rigidfmu::FmiVersion::Fmi3}) {
    const std::string xml = rigidfmu::modelDescriptionXml(scene, version);
    for (const Variable& v : vars) {
      if (v.type == rigidfmu::BaseType::Real) {
        EXPECT_TRUE(contains(xml, "<Unit name=\"" + v.unit + "\">")) << v.name;
      }
    }
  }
  for (const char* unit : {"rad", "N.m/rad", "N.m.s/rad", "N/m", "N.s/m"})
    EXPECT_NE(std::find_if(vars.begin(), vars.end(), [&](const Variable& v) { return v.unit == unit; }), vars.end())
        << unit;
}

// The joints' tunable parameters are checked when set, and the pairs when they take
// effect, each message naming the variable and its limit.
TEST(JointDescription, TunableParametersOutOfRangeAreRefusedNamingThem) {
  const rigid::Scene scene = rigid::parseScene(kJointScene);
  const std::vector<Variable> vars = rigidfmu::modelVariables(scene);
  rigid::WorldModel model = scene.model;
  rigid::WorldData data = rigid::initialData(model);
  auto write = [&](const char* name, double value) {
    return rigidfmu::writeValue(find(vars, name), value, model, data, Phase::Running);
  };
  EXPECT_EQ(write("hinge.maxMotorTorque", 0.0), "hinge.maxMotorTorque: must be > 0 N.m, got 0");
  EXPECT_EQ(write("slider.stiffness", -1.0), "slider.stiffness: must be >= 0 N/m, got -1");
  EXPECT_EQ(write("rod.restitution", 1.5), "rod.restitution: must be in [0, 1], got 1.5");
  EXPECT_EQ(model.joints[2].restitution, 0.5);
  EXPECT_EQ(write("rod.restitution", 1.0), "");
  EXPECT_EQ(model.joints[2].restitution, 1.0);
  EXPECT_EQ(rigidfmu::parameterConflict(model), "");
  EXPECT_EQ(write("hinge.lower", 2.0), "");
  EXPECT_EQ(rigidfmu::parameterConflict(model), "hinge.lower: must be <= hinge.upper (1), got 2");
  EXPECT_EQ(write("hinge.lower", -1.0), "");
  EXPECT_EQ(write("rod.lower", -0.25), "");
  EXPECT_EQ(rigidfmu::parameterConflict(model), "rod.lower: a length must be >= 0 m, got -0.25");
}
