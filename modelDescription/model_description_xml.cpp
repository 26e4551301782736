#include "model_description_xml.h"

#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "guid.h"
#include "variables.h"

namespace rigidfmu {

const LogCategory kLogCategories[] = {
    {"logStatusWarning", "warnings"},
    {"logStatusDiscard", "steps that could not be completed (a Discard status)"},
    {"logStatusError", "errors: bad arguments, calls out of order, bad scenes"},
    {"logEvents", "instantiation, initialisation, resets and parameter changes"},
    {"logCalls", "every FMI call (verbose)"},
};
const int kLogCategoryCount = sizeof(kLogCategories) / sizeof(kLogCategories[0]);

namespace {

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// SI base-unit exponents of every unit a variable may carry.
struct UnitDef {
  int kg, m, s, rad;
};
const std::map<std::string, UnitDef> kUnits = {
    {"1", {0, 0, 0, 0}},         {"s", {0, 0, 1, 0}},           {"m", {0, 1, 0, 0}},      {"kg", {1, 0, 0, 0}},
    {"m/s", {0, 1, -1, 0}},      {"m/s2", {0, 1, -2, 0}},       {"rad/s", {0, 0, -1, 1}}, {"kg.m/s", {1, 1, -1, 0}},
    {"kg.m2/s", {1, 2, -1, 0}},  {"N", {1, 1, -2, 0}},          {"N.m", {1, 2, -2, 0}},   {"kg/m3", {1, -3, 0, 0}},
    {"Pa.s", {1, -1, -1, 0}},    {"rad", {0, 0, 0, 1}},         {"N/m", {1, 0, -2, 0}},   {"N.s/m", {1, 0, -1, 0}},
    {"N.m/rad", {1, 2, -2, -1}}, {"N.m.s/rad", {1, 2, -1, -1}},
};

const char* causalityName(Causality c) {
  switch (c) {
    case Causality::Parameter: return "parameter";
    case Causality::Input: return "input";
    case Causality::Output: return "output";
    case Causality::Independent: return "independent";
  }
  return "";
}

const char* variabilityName(Variability v) {
  switch (v) {
    case Variability::Fixed: return "fixed";
    case Variability::Tunable: return "tunable";
    case Variability::Discrete: return "discrete";
    case Variability::Continuous: return "continuous";
  }
  return "";
}

std::string joinIndices(const std::vector<unsigned>& idx) {
  std::string s;
  for (unsigned i : idx) s += (s.empty() ? "" : " ") + std::to_string(i);
  return s;
}

// ---- parts both versions write alike ----------------------------------------------

void writeUnits(std::ostringstream& x, const std::vector<Variable>& vars) {
  std::set<std::string> used;
  for (const Variable& v : vars)
    if (v.type == BaseType::Real) used.insert(v.unit);
  x << "  <UnitDefinitions>\n";
  for (const std::string& u : used) {
    const UnitDef& d = kUnits.at(u);
    x << "    <Unit name=\"" << escape(u) << "\"><BaseUnit";
    if (d.kg) x << " kg=\"" << d.kg << "\"";
    if (d.m) x << " m=\"" << d.m << "\"";
    if (d.s) x << " s=\"" << d.s << "\"";
    if (d.rad) x << " rad=\"" << d.rad << "\"";
    x << "/></Unit>\n";
  }
  x << "  </UnitDefinitions>\n";
}

void writeMethodItems(std::ostringstream& x, const char* indent) {
  for (const rigid::MethodInfo& m : rigid::methods())
    x << indent << "<Item name=\"" << m.name << "\" value=\"" << static_cast<int>(m.method) << "\" description=\""
      << escape(m.description) << "\"/>\n";
}

void writeLogCategories(std::ostringstream& x) {
  x << "  <LogCategories>\n";
  for (int i = 0; i < kLogCategoryCount; ++i)
    x << "    <Category name=\"" << kLogCategories[i].name << "\" description=\""
      << escape(kLogCategories[i].description) << "\"/>\n";
  x << "  </LogCategories>\n";
}

// Whether the XML gives the variable a start value (exact ones and inputs).
bool hasStart(const Variable& v) { return v.initial == Initial::Exact || v.causality == Causality::Input; }

std::string attributes(const Variable& v) {
  std::string a = " description=\"" + escape(v.description) + "\" causality=\"" + causalityName(v.causality) +
                  "\" variability=\"" + variabilityName(v.variability) + "\"";
  if (v.initial == Initial::Exact) a += " initial=\"exact\"";
  if (v.initial == Initial::Calculated) a += " initial=\"calculated\"";
  return a;
}

// ---- FMI 2.0 -------------------------------------------------------------------------

void writeVariable2(std::ostringstream& x, const Variable& v, double start) {
  x << "    <!-- index " << v.vr + 1 << " -->\n"
    << "    <ScalarVariable name=\"" << escape(v.name) << "\" valueReference=\"" << v.vr << "\"" << attributes(v)
    << ">\n      ";
  if (v.type == BaseType::Enumeration) {
    x << "<Enumeration declaredType=\"SolverMethod\" start=\"" << static_cast<int>(start) << "\"/>";
  } else if (v.type == BaseType::Integer) {
    x << "<Integer";
    if (hasStart(v)) x << " start=\"" << static_cast<int>(start) << "\"";
    x << "/>";
  } else {
    x << "<Real unit=\"" << escape(v.unit) << "\"";
    if (hasStart(v)) x << " start=\"" << fmt(start) << "\"";
    x << "/>";
  }
  x << "\n    </ScalarVariable>\n";
}

// Outputs at a communication point depend on the state only: inputs act through the
// integration of the step, never directly, hence empty dependencies.
void writeModelStructure2(std::ostringstream& x, const std::vector<Variable>& vars, const rigid::WorldModel& model) {
  std::ostringstream outputs;
  for (const Variable& v : vars)
    if (v.causality == Causality::Output)
      outputs << "      <Unknown index=\"" << v.vr + 1 << "\" dependencies=\"\"/>\n";
  x << "  <ModelStructure>\n";
  if (!outputs.str().empty()) x << "    <Outputs>\n" << outputs.str() << "    </Outputs>\n";
  // The schema wants at least one Unknown in a list: an empty list is left out.
  std::ostringstream initial;
  for (const Variable& v : vars)
    if (v.causality == Causality::Output && v.initial == Initial::Calculated)
      initial << "      <Unknown index=\"" << v.vr + 1 << "\" dependencies=\""
              << joinIndices(initialDependencies(vars, v, model)) << "\"/>\n";
  if (!initial.str().empty()) x << "    <InitialUnknowns>\n" << initial.str() << "    </InitialUnknowns>\n";
  x << "  </ModelStructure>\n";
}

std::string modelDescription2(const rigid::Scene& scene) {
  const rigid::WorldModel& model = scene.model;
  const std::vector<Variable> vars = modelVariables(scene);
  const rigid::WorldData data = rigid::initialData(model);
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"" << escape(model.name) << "\"\n"
    << "  guid=\"" << sceneGuid(scene) << "\"\n"
    << "  description=\"rigid bodies of scene " << escape(model.name) << " (state X, q, P, L per body)\"\n"
    << "  generationTool=\"rigidfmu\" variableNamingConvention=\"structured\""
    << " numberOfEventIndicators=\"0\">\n";
  x << "  <CoSimulation modelIdentifier=\"" << escape(model.name) << "\""
    << " canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"true\""
    << " maxOutputDerivativeOrder=\"1\" canRunAsynchronuously=\"false\""
    << " canBeInstantiatedOnlyOncePerProcess=\"false\" canNotUseMemoryManagementFunctions=\"true\""
    << " canGetAndSetFMUstate=\"true\" canSerializeFMUstate=\"true\""
    << " providesDirectionalDerivative=\"true\" needsExecutionTool=\"false\"/>\n";
  writeUnits(x, vars);
  x << "  <TypeDefinitions>\n    <SimpleType name=\"SolverMethod\">\n      <Enumeration>\n";
  writeMethodItems(x, "        ");
  x << "      </Enumeration>\n    </SimpleType>\n  </TypeDefinitions>\n";
  writeLogCategories(x);
  x << "  <DefaultExperiment startTime=\"0\" stepSize=\"" << fmt(model.maxStep) << "\"/>\n";
  x << "  <ModelVariables>\n";
  for (const Variable& v : vars) writeVariable2(x, v, readValue(v, model, data, Phase::Setup));
  x << "  </ModelVariables>\n";
  writeModelStructure2(x, vars, model);
  x << "</fmiModelDescription>\n";
  return x.str();
}

// ---- FMI 3.0 -------------------------------------------------------------------------
// The same table: every variable a scalar with the FMI 2 name, value reference, unit
// and description (docs/scene-format.md, "FMI 3.0"), in FMI 3 types: Real -> Float64,
// Integer -> Int32, the method -> Enumeration (read and written with fmi3Get/SetInt64).

void writeVariable3(std::ostringstream& x, const Variable& v, double start) {
  const char* element = v.type == BaseType::Enumeration ? "Enumeration"
                        : v.type == BaseType::Integer   ? "Int32"
                                                        : "Float64";
  x << "    <" << element << " name=\"" << escape(v.name) << "\" valueReference=\"" << v.vr << "\"" << attributes(v);
  if (v.type == BaseType::Enumeration)
    x << " declaredType=\"SolverMethod\" start=\"" << static_cast<int>(start) << "\"";
  if (v.type == BaseType::Integer && hasStart(v)) x << " start=\"" << static_cast<int>(start) << "\"";
  if (v.type == BaseType::Real) {
    x << " unit=\"" << escape(v.unit) << "\"";
    if (hasStart(v)) x << " start=\"" << fmt(start) << "\"";
  }
  x << "/>\n";
}

// Dependencies by value reference (FMI 3), as FMI 2's by index: outputs depend on
// the state only.
void writeModelStructure3(std::ostringstream& x, const std::vector<Variable>& vars, const rigid::WorldModel& model) {
  x << "  <ModelStructure>\n";
  for (const Variable& v : vars)
    if (v.causality == Causality::Output) x << "    <Output valueReference=\"" << v.vr << "\" dependencies=\"\"/>\n";
  for (const Variable& v : vars) {
    if (v.causality != Causality::Output || v.initial != Initial::Calculated) continue;
    std::vector<unsigned> refs;
    for (unsigned index : initialDependencies(vars, v, model)) refs.push_back(index - 1);
    x << "    <InitialUnknown valueReference=\"" << v.vr << "\" dependencies=\"" << joinIndices(refs) << "\"/>\n";
  }
  x << "  </ModelStructure>\n";
}

std::string modelDescription3(const rigid::Scene& scene) {
  const rigid::WorldModel& model = scene.model;
  const std::vector<Variable> vars = modelVariables(scene);
  const rigid::WorldData data = rigid::initialData(model);
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<fmiModelDescription fmiVersion=\"3.0\" modelName=\"" << escape(model.name) << "\"\n"
    << "  instantiationToken=\"" << sceneGuid(scene) << "\"\n"
    << "  description=\"rigid bodies of scene " << escape(model.name) << " (state X, q, P, L per body)\"\n"
    << "  generationTool=\"rigidfmu\" variableNamingConvention=\"structured\">\n";
  x << "  <CoSimulation modelIdentifier=\"" << escape(model.name) << "\""
    << " canHandleVariableCommunicationStepSize=\"true\" maxOutputDerivativeOrder=\"1\""
    << " canBeInstantiatedOnlyOncePerProcess=\"false\" canGetAndSetFMUState=\"true\""
    << " canSerializeFMUState=\"true\" providesDirectionalDerivatives=\"true\""
    << " mightReturnEarlyFromDoStep=\"true\" needsExecutionTool=\"false\"/>\n";
  writeUnits(x, vars);
  x << "  <TypeDefinitions>\n    <EnumerationType name=\"SolverMethod\">\n";
  writeMethodItems(x, "      ");
  x << "    </EnumerationType>\n  </TypeDefinitions>\n";
  writeLogCategories(x);
  x << "  <DefaultExperiment startTime=\"0\" stepSize=\"" << fmt(model.maxStep) << "\"/>\n";
  x << "  <ModelVariables>\n";
  for (const Variable& v : vars) writeVariable3(x, v, readValue(v, model, data, Phase::Setup));
  x << "  </ModelVariables>\n";
  writeModelStructure3(x, vars, model);
  x << "</fmiModelDescription>\n";
  return x.str();
}

}  // namespace

std::string modelDescriptionXml(const rigid::Scene& scene, FmiVersion version) {
  return version == FmiVersion::Fmi3 ? modelDescription3(scene) : modelDescription2(scene);
}

}  // namespace rigidfmu
