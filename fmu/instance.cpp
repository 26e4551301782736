#include "instance.h"

#include <cmath>
#include <cstdio>
#include <numeric>
#include <utility>

#include "dynamics.h"
#include "guid.h"
#include "model_description_xml.h"
#include "modules.h"
#include "resource_location.h"

namespace rigidfmu {

namespace {

// How far from unit a driven body's orientation input may be: a master's rounding or
// interpolation of a quaternion, normalised; beyond it the input is not an orientation.
constexpr double kUnitTolerance = 1e-3;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

const char* stateName(unsigned state) {
  switch (state) {
    case kInstantiated: return "Instantiated";
    case kInitializationMode: return "InitializationMode";
    case kStepComplete: return "StepComplete";
    case kStepFailed: return "StepFailed";
    case kTerminated: return "Terminated";
    case kError: return "Error";
  }
  return "?";
}

// The log category of a status's messages (kLogCategories).
const char* categoryOf(Status status) {
  switch (status) {
    case Status::OK: return "logEvents";
    case Status::Warning: return "logStatusWarning";
    case Status::Discard: return "logStatusDiscard";
    case Status::Error: return "logStatusError";
    case Status::Fatal: return "logStatusError";
  }
  return "logStatusError";
}

}  // namespace

Instance* Instance::create(const char* function, const char* instanceName, const char* guid,
                           const char* resourceLocation, bool loggingOn, Adapter adapter) {
  const std::string name = instanceName ? instanceName : "";
  auto refuse = [&](const std::string& why) -> Instance* {
    if (adapter.logger) adapter.logger(Status::Error, "logStatusError", std::string(function) + ": " + why);
    return nullptr;
  };
  if (name.empty()) return refuse("instanceName must be a non-empty string");
  std::string why;
  const auto dir = resourceDirectory(resourceLocation, why);
  if (!dir) return refuse(why);
  rigid::Scene scene;
  try {
    scene = rigid::loadSceneFile(*dir + "/scene.json");
  } catch (const rigid::SceneError& e) {
    return refuse(std::string("the scene in the resources is refused: ") + e.what());
  }
  const unsigned missing = rigid::modulesNeeded(scene.model) & ~rigid::modulesBuilt();
  if (missing)
    return refuse("the scene needs the " + rigid::moduleNames(missing) +
                  " module(s), which this binary was built without; rebuild the FMU with build_fmu.sh");
  const std::string expected = sceneGuid(scene);
  if (!guid || expected != guid)
    return refuse("GUID " + std::string(guid ? guid : "(null)") + " does not match this FMU's scene, whose GUID is " +
                  expected);
  Instance* instance = new Instance(name, std::move(adapter), loggingOn, std::move(scene), function);
  instance->guid_ = expected;
  return instance;
}

Instance::Instance(std::string name, Adapter adapter, bool loggingOn, rigid::Scene scene, const char* function)
    : name_(std::move(name)),
      adapter_(std::move(adapter)),
      loggingOn_(loggingOn),
      function_(function),
      scene_(std::move(scene)),
      vars_(modelVariables(scene_)) {
  for (int i = 0; i < kLogCategoryCount; ++i) categories_.insert(kLogCategories[i].name);
  restart();
  log(Status::OK, "logEvents",
      "instantiated scene " + scene_.model.name + " with " + std::to_string(model_.bodies.size()) + " bodies");
}

void Instance::restart() {
  model_ = scene_.model;
  data_ = rigid::initialData(model_);
  state_ = kInstantiated;
  startTime_ = 0.0;
  clock_.restartAt(0.0);
  wantsToTerminate_ = false;
  substepNote_.clear();
}

void Instance::log(Status status, const char* category, const std::string& message) const {
  if (!adapter_.logger) return;
  if (status == Status::OK && !(loggingOn_ && categories_.count(category))) return;
  adapter_.logger(status, category, message);
}

std::string Instance::inCall(const std::string& message) const { return std::string(function_) + ": " + message; }

Status Instance::report(Status status, const std::string& message) const {
  log(status, categoryOf(status), inCall(message));
  return status;
}

bool Instance::enter(const char* function, unsigned allowed) {
  function_ = function;
  if (state_ & allowed) {
    log(Status::OK, "logCalls", function);
    return true;
  }
  error(std::string("not allowed in state ") + stateName(state_));
  return false;
}

Status Instance::setDebugLogging(bool loggingOn, size_t n, const char* const categories[]) {
  loggingOn_ = loggingOn;
  if (n == 0) return Status::OK;  // all categories keep their setting
  if (!categories) return error("categories is NULL with nCategories > 0");
  std::set<std::string> chosen;
  for (size_t i = 0; i < n; ++i) {
    const std::string c = categories[i] ? categories[i] : "";
    bool known = false;
    for (int k = 0; k < kLogCategoryCount; ++k) known |= c == kLogCategories[k].name;
    if (!known) return error("unknown log category \"" + c + "\"");
    chosen.insert(c);
  }
  categories_ = chosen;
  return Status::OK;
}

Status Instance::setupExperiment(bool toleranceDefined, double tolerance, double startTime) {
  if (!std::isfinite(startTime)) return error("startTime must be finite, got " + num(startTime));
  if (toleranceDefined)
    log(Status::OK, "logEvents",
        "tolerance " + num(tolerance) + " noted; the fixed-step methods use solver.step instead");
  startTime_ = startTime;
  clock_.restartAt(startTime);
  return Status::OK;
}

Status Instance::enterInitializationMode() {
  state_ = kInitializationMode;
  return Status::OK;
}

Status Instance::exitInitializationMode() {
  for (const rigid::BodyConstants& b : model_.bodies)
    if (b.start.orientation.norm() < 1e-12) return error(b.name + ".orientation: must not be the zero quaternion");
  if (const std::string why = parameterConflict(model_); !why.empty()) return error(why);
  data_ = rigid::initialData(model_);
  clock_.restartAt(startTime_);
  state_ = kStepComplete;
  if (const std::string why = rigid::massRatioWarning(model_); !why.empty()) report(Status::Warning, why);
  log(Status::OK, "logEvents",
      "initialised at t = " + num(clock_.now()) + " with method " + rigid::methodName(model_.method) + ", step " +
          num(model_.maxStep) + " s");
  return Status::OK;
}

Status Instance::terminate() {
  state_ = kTerminated;
  return Status::OK;
}

Status Instance::reset() {
  restart();
  log(Status::OK, "logEvents", "reset to the just-instantiated state");
  return Status::OK;
}

const Variable* Instance::lookup(uint32_t vr, bool integer) const {
  if (vr >= vars_.size()) {
    error("unknown value reference " + std::to_string(vr) + " (this FMU has 0.." + std::to_string(vars_.size() - 1) +
          ")");
    return nullptr;
  }
  const Variable& v = vars_[vr];
  if ((v.type != BaseType::Real) != integer) {
    error("value reference " + std::to_string(vr) + " (" + v.name + ") is " + adapter_.typeAdvice(v.type));
    return nullptr;
  }
  return &v;
}

double Instance::read(const Variable& v) const {
  if (v.quantity == Quantity::Time) return clock_.now();
  return readValue(v, model_, data_, setupPhase() ? Phase::Setup : Phase::Running);
}

bool Instance::writable(const Variable& v) const {
  const bool input = v.causality == Causality::Input;
  if (setupPhase()) {
    if (input || v.initial == Initial::Exact) return true;
    error(v.name + ": has no start value to set (causality " +
          (v.causality == Causality::Output ? "output, initial calculated" : "independent") + ")");
    return false;
  }
  if (input || (v.causality == Causality::Parameter && v.variability == Variability::Tunable)) return true;
  error(v.name + ": only inputs and tunable parameters can be set after initialisation");
  return false;
}

Status Instance::write(const Variable& v, double value) {
  if (!writable(v)) return Status::Error;
  const std::string why = writeValue(v, value, model_, data_, setupPhase() ? Phase::Setup : Phase::Running);
  if (!why.empty()) return error(why);
  // A change of tunable parameter between steps moves the auxiliaries' inputs only;
  // mass-dependent outputs are refreshed so that a Get sees the new values. Sleeping
  // islands wake: their rest was under the old parameters (an input wakes its body
  // at the next step by itself).
  if (!setupPhase()) {
    rigid::refreshAuxiliaries(model_, data_);
    if (v.causality == Causality::Parameter) rigid::wakeAll(data_.sleep, data_.contactMemory);
  }
  return Status::OK;
}

Status Instance::getReal(const uint32_t vr[], size_t n, double value[]) {
  if (n && (!vr || !value)) return error("vr or value is NULL");
  for (size_t i = 0; i < n; ++i) {
    const Variable* v = lookup(vr[i], false);
    if (!v) return Status::Error;
    value[i] = read(*v);
  }
  return Status::OK;
}

Status Instance::getInteger(const uint32_t vr[], size_t n, int32_t value[]) {
  if (n && (!vr || !value)) return error("vr or value is NULL");
  for (size_t i = 0; i < n; ++i) {
    const Variable* v = lookup(vr[i], true);
    if (!v) return Status::Error;
    value[i] = static_cast<int32_t>(read(*v));
  }
  return Status::OK;
}

Status Instance::setReal(const uint32_t vr[], size_t n, const double value[]) {
  if (n && (!vr || !value)) return error("vr or value is NULL");
  for (size_t i = 0; i < n; ++i) {
    const Variable* v = lookup(vr[i], false);
    if (!v) return Status::Error;
    if (const Status s = write(*v, value[i]); s != Status::OK) return s;
  }
  return Status::OK;
}

Status Instance::setInteger(const uint32_t vr[], size_t n, const int32_t value[]) {
  if (n && (!vr || !value)) return error("vr or value is NULL");
  for (size_t i = 0; i < n; ++i) {
    const Variable* v = lookup(vr[i], true);
    if (!v) return Status::Error;
    if (const Status s = write(*v, value[i]); s != Status::OK) return s;
  }
  return Status::OK;
}

Status Instance::noVariablesOfType(const uint32_t vr[], size_t n) {
  if (n == 0) return Status::OK;
  return error("unknown value reference " + (vr ? std::to_string(vr[0]) : std::string("(NULL)")) +
               " (this FMU has no variables of this type)");
}

Status Instance::doStep(double tc, double h, bool returnEarlyAtImpact) {
  returnedEarly_ = false;
  if (const Status s = checkStep(tc, h); s != Status::OK) return s;
  // From here on the FMU's own time and step, not the importer's rounding of them.
  const double t = clock_.now(), step = clock_.take(h);
  rigid::clearContactLoads(data_);  // the contact loads are this step's
  const Interval run = advance(step, true, returnEarlyAtImpact);
  lastStepSize_ = run.impactAt >= 0.0 ? run.impactAt : step;
  if (!run.result.ok) return discardStep(t, run);
  if (run.impactAt >= 0.0) {
    returnedEarly_ = true;
    clock_.restartAt(t + run.impactAt);
    log(Status::OK, "logEvents", inCall("returned early at the impact at t = " + num(clock_.now()) + " s"));
    return Status::OK;
  }
  clock_.advance(h);
  return Status::OK;
}

Status Instance::checkStep(double tc, double h) const {
  if (!std::isfinite(tc)) return error("currentCommunicationPoint must be finite, got " + num(tc));
  if (!std::isfinite(h) || h <= 0.0) return error("communicationStepSize must be > 0 and finite, got " + num(h));
  // Masters that accumulate time send points that jitter by a few ulps: accept them.
  const double time = clock_.now(), tolerance = 1e-9 * std::max(1.0, std::abs(time));
  if (std::abs(tc - time) > tolerance)
    return error("currentCommunicationPoint " + num(tc) + " is not the FMU's time " + num(time) + " (tolerance " +
                 num(tolerance) + ")");
  // friction set since the last step: mu_k <= mu_s, checked now that both are set
  if (const std::string why = parameterConflict(model_); !why.empty()) return error(why);
  // a driven body's orientation, set a component at a time, is whole now
  for (size_t i = 0; i < model_.bodies.size(); ++i) {
    const double norm = data_.drive[i].orientation.norm();
    if (rigid::driven(model_.bodies[i]) && !(std::abs(norm - 1.0) <= kUnitTolerance))
      return error(model_.bodies[i].name + ".orientation: must be a unit quaternion (its norm within " +
                   num(kUnitTolerance) + " of 1; it is then normalised), got norm " + num(norm));
  }
  const double ratio = h / model_.maxStep;
  if (ratio > 1e12)
    return error("communicationStepSize " + num(h) +
                 " s needs more than 1e12 steps of solver.step = " + num(model_.maxStep) + " s");
  return Status::OK;
}

Status Instance::discardStep(double tc, const Interval& run) {
  const rigid::StepResult& r = run.result;
  clock_.restartAt(tc + run.from);
  state_ = kStepFailed;
  wantsToTerminate_ = true;
  const std::string hint = r.body >= 0 && r.cause == rigid::StepCause::None
                               ? " (inputs or parameters out of range, e.g. " + model_.bodies[r.body].name + ".force)"
                               : "";
  return report(Status::Discard, stepFailure(r, run.to - run.from) +
                                     " after the internal step from t = " + num(tc + run.from) + " to " +
                                     num(tc + run.to) + " s" + hint + "; the FMU stays at t = " + num(clock_.now()) +
                                     " s and must be reset or terminated");
}

std::string Instance::stepFailure(const rigid::StepResult& r, double internalStep) const {
  if (r.cause == rigid::StepCause::EnergyGain)
    return "body " + model_.bodies[r.body].name + ", turning free of torques, has gained " + num(r.energyGain) +
           " of its rotational energy, beyond solver.energyGainLimit = " + num(model_.energyGainLimit) + ": method " +
           rigid::methodName(model_.method) +
           " adds energy to a free rotation (about (h |omega|)^2 a step); the methods "
           "splitting, symplecticEuler, rk4 or lieRk4 keep it, or a solver.step of " +
           num(r.stableStep) + " s would have kept it within half the limit so far;";
  if (r.body >= 0) return "the state of body " + model_.bodies[r.body].name + " is not finite or beyond 1e12 m";
  if (r.cause == rigid::StepCause::FastBody)
    return "a body moves so fast that the internal step of " + num(internalStep) +
           " s would need more than 1e4 collision sub-steps; a solver.step of " + num(r.stableStep) + " s would work";
  if (r.cause == rigid::StepCause::None)
    return "the adaptive method could not meet solver.tolerance = " + num(model_.tolerance) +
           " (its step fell below 1e-14 of the step; raise the tolerance)";
  // An explicit method outside its stability region: sub-stepping would need too many
  // steps, or (a stableStep of 0) no step is small enough.
  const std::string unstable = std::string("method ") + rigid::methodName(model_.method) +
                               " is outside its stability region (" + rigid::causeName(r.cause) + ")";
  if (r.stableStep > 0.0)
    return unstable + ": the internal step of " + num(internalStep) +
           " s would need more than 1e6 sub-steps; a solver.step of " + num(r.stableStep) +
           " s, or the method rosenbrock or dopri5, would work";
  return unstable +
         ": it grows on every oscillation at any step; the methods rk4, symplecticEuler, splitting or "
         "rosenbrock would work";
}

Instance::Interval Instance::advance(double h, bool reportSubsteps, bool stopAtImpact) {
  // Internal steps of solver.step, the last one shortened; a remainder within
  // rounding of zero is not a step of its own. Times are tc + k*step, never summed.
  const long n = std::max(1L, static_cast<long>(std::ceil(h / model_.maxStep - 1e-9)));
  data_.steps = 0;
  // Inputs with derivatives vary over the step: each internal step holds them at its
  // midpoint, which gives a ramp's impulse exactly. Afterwards the inputs are again
  // the values the master set, and the derivatives are spent.
  const std::vector<rigid::BodyInput> setInputs = data_.input;
  const std::vector<rigid::Vec3> setBelts = data_.beltVelocity;
  const std::vector<double> setMotors = data_.joints.motorSpeed, setTargets = data_.joints.targetPosition;
  struct Restore {
    rigid::WorldData& d;
    const std::vector<rigid::BodyInput>& inputs;
    const std::vector<rigid::Vec3>& belts;
    const std::vector<double>&motors, &targets;
    ~Restore() {
      d.input = inputs;
      for (rigid::BodyInput& rate : d.inputRate) rate = rigid::zeroInput(rate.loads.size());
      d.beltVelocity = belts;
      d.beltRate.assign(belts.size(), rigid::Vec3::Zero());
      d.joints.motorSpeed = motors, d.joints.targetPosition = targets;
      d.joints.motorSpeedRate.assign(motors.size(), 0.0);
      d.joints.targetPositionRate.assign(targets.size(), 0.0);
    }
  } restore{data_, setInputs, setBelts, setMotors, setTargets};
  // Driven bodies move from where they are to where their inputs take them (drive.h).
  const std::vector<rigid::DrivePath> paths = drivePaths(h, reportSubsteps);
  struct SpendRates {
    std::vector<rigid::DriveInput>& drive;
    ~SpendRates() {
      for (rigid::DriveInput& in : drive) in.acceleration = in.angularAcceleration = rigid::Vec3::Zero();
    }
  } spend{data_.drive};
  for (long k = 0; k < n; ++k) {
    const double from = static_cast<double>(k) * model_.maxStep;
    const double to = k + 1 == n ? h : static_cast<double>(k + 1) * model_.maxStep;
    const double mid = 0.5 * (from + to);
    if (!paths.empty()) rigid::setDriveVelocities(model_, data_, data_.drive, paths, from, to);
    for (size_t b = 0; b < data_.input.size(); ++b) {
      data_.input[b].force = setInputs[b].force + mid * data_.inputRate[b].force;
      data_.input[b].torque = setInputs[b].torque + mid * data_.inputRate[b].torque;
      for (size_t k = 0; k < data_.input[b].loads.size(); ++k)
        data_.input[b].loads[k] = setInputs[b].loads[k] + mid * data_.inputRate[b].loads[k];
    }
    for (size_t s = 0; s < setBelts.size(); ++s) data_.beltVelocity[s] = setBelts[s] + mid * data_.beltRate[s];
    for (size_t j = 0; j < setMotors.size(); ++j) {
      data_.joints.motorSpeed[j] = setMotors[j] + mid * data_.joints.motorSpeedRate[j];
      data_.joints.targetPosition[j] = setTargets[j] + mid * data_.joints.targetPositionRate[j];
    }
    const rigid::StepResult r = rigid::step(model_, data_, to - from, stopAtImpact);
    if (!r.ok) return {r, from, to};
    if (reportSubsteps) noteSubsteps(r, to - from);
    if (r.impactAt >= 0.0) return {r, from, to, from + r.impactAt};
  }
  return {};
}

std::vector<rigid::DrivePath> Instance::drivePaths(double h, bool reportJumps) const {
  std::vector<rigid::DrivePath> paths;
  for (size_t i = 0; i < model_.bodies.size(); ++i) {
    const rigid::BodyConstants& body = model_.bodies[i];
    if (!rigid::driven(body)) continue;
    paths.resize(model_.bodies.size());
    paths[i] = rigid::drivePath(data_.Y[i], data_.drive[i], h);
    const double half = rigid::halfThickness(body.shape);
    if (!reportJumps || !(paths[i].jump > half)) continue;
    char text[160];
    std::snprintf(text, sizeof text, "%.4g m, more than its half thickness %.4g m", paths[i].jump, half);
    report(Status::Warning, body.name + ".position: the inputs moved the body by " + text +
                                "; it moves there within the step, pushing what it meets");
  }
  return paths;
}

Status Instance::getDirectionalDerivative(const uint32_t unknown[], size_t nUnknown, const uint32_t known[],
                                          size_t nKnown, const double dvKnown[], double dvUnknown[]) {
  if ((nUnknown && (!unknown || !dvUnknown)) || (nKnown && (!known || !dvKnown))) return error("an array is NULL");
  std::vector<const Variable*> ins, outs;
  for (size_t i = 0; i < nKnown; ++i) {
    const Variable* v = lookup(known[i], false);
    if (!v) return Status::Error;
    if (v->causality != Causality::Input) return error(v->name + " is not an input (knowns must be inputs)");
    if (!std::isfinite(dvKnown[i])) return error("the seed of " + v->name + " must be finite");
    ins.push_back(v);
  }
  for (size_t i = 0; i < nUnknown; ++i) {
    const Variable* v = lookup(unknown[i], false);
    if (!v) return Status::Error;
    if (v->causality != Causality::Output) return error(v->name + " is not an output (unknowns must be outputs)");
    outs.push_back(v);
  }
  // d(outputs after the next communication step)/d(inputs) . seed, by central
  // differences through the FMU's own step: the step is as long as the last one
  // (solver.step before the first). Outputs at a communication point do not depend
  // on the inputs of that instant (no feed-through), so this is what couples.
  const double h = lastStepSize_ > 0.0 ? lastStepSize_ : model_.maxStep;
  double seedNorm = 0.0;
  for (size_t i = 0; i < nKnown; ++i) seedNorm = std::max(seedNorm, std::abs(dvKnown[i]));
  if (seedNorm == 0.0) {
    std::fill(dvUnknown, dvUnknown + nUnknown, 0.0);
    return Status::OK;
  }
  const rigid::WorldData saved = data_;
  double scale = 1.0;
  for (const Variable* v : ins) scale = std::max(scale, std::abs(read(*v)));
  const double eps = 1e-6 * scale / seedNorm;
  std::vector<double> plus(nUnknown), minus(nUnknown);
  for (double sign : {1.0, -1.0}) {
    data_ = saved;
    for (size_t i = 0; i < nKnown; ++i)
      writeValue(*ins[i], read(*ins[i]) + sign * eps * dvKnown[i], model_, data_, Phase::Running);
    const Interval run = advance(h, false);
    if (!run.result.ok) {
      data_ = saved;
      return report(Status::Discard, "the perturbed step failed; no derivative");
    }
    std::vector<double>& out = sign > 0 ? plus : minus;
    for (size_t i = 0; i < nUnknown; ++i) out[i] = read(*outs[i]);
  }
  data_ = saved;
  for (size_t i = 0; i < nUnknown; ++i) dvUnknown[i] = (plus[i] - minus[i]) / (2.0 * eps);
  return Status::OK;
}

Snapshot* Instance::ownState(void* state) const {
  Snapshot* s = static_cast<Snapshot*>(state);
  if (!s || !states_.count(s)) {
    error("not an FMU state of this instance (NULL, freed, or another's)");
    return nullptr;
  }
  return s;
}

Status Instance::getState(void** state) {
  if (!state) return error("FMUstate is NULL");
  Snapshot* s = static_cast<Snapshot*>(*state);
  if (s && !states_.count(s)) return error("*FMUstate is not a state of this instance");
  if (!s) {
    owned_.push_back(std::make_unique<Snapshot>());
    s = owned_.back().get();
    states_.insert(s);
  }
  *s = Snapshot{model_, data_, state_, startTime_, clock_, wantsToTerminate_, lastStepSize_};
  *state = s;
  return Status::OK;
}

Status Instance::setState(void* state) {
  const Snapshot* s = ownState(state);
  if (!s) return Status::Error;
  model_ = s->model;
  data_ = s->data;
  state_ = s->machineState;
  startTime_ = s->startTime;
  clock_ = s->clock;
  wantsToTerminate_ = s->wantsToTerminate;
  lastStepSize_ = s->lastStepSize;
  substepNote_.clear();
  return Status::OK;
}

Status Instance::freeState(void** state) {
  if (!state) return error("FMUstate is NULL");
  if (!*state) return Status::OK;  // nothing to free
  Snapshot* s = ownState(*state);
  if (!s) return Status::Error;
  states_.erase(s);
  for (auto it = owned_.begin(); it != owned_.end(); ++it)
    if (it->get() == s) {
      owned_.erase(it);
      break;
    }
  *state = nullptr;
  return Status::OK;
}

Status Instance::serializedStateSize(void* state, size_t* size) {
  const Snapshot* s = ownState(state);
  if (!s) return Status::Error;
  if (!size) return error("size is NULL");
  *size = serialize(*s, guid_).size();
  return Status::OK;
}

Status Instance::serializeState(void* state, char bytes[], size_t size) {
  const Snapshot* s = ownState(state);
  if (!s) return Status::Error;
  const std::vector<char> b = serialize(*s, guid_);
  if (!bytes || size < b.size())
    return error("the buffer holds " + std::to_string(size) + " bytes, the state needs " + std::to_string(b.size()) +
                 " (" + adapter_.stateSizeFunction + ")");
  std::copy(b.begin(), b.end(), bytes);
  return Status::OK;
}

Status Instance::deserializeState(const char bytes[], size_t size, void** state) {
  if (!state) return error("FMUstate is NULL");
  // A fresh instance of the same scene is the frame the bytes are read into.
  Snapshot s{scene_.model, rigid::initialData(scene_.model), kInstantiated, 0.0, {}, false, 0.0};
  const std::string why = deserialize(bytes, size, guid_, s);
  if (!why.empty()) return error(why);
  const unsigned known = kInstantiated | kInitializationMode | kStepComplete | kStepFailed | kTerminated | kError;
  if (__builtin_popcount(s.machineState) != 1 || !(s.machineState & known))
    return error("the state holds an unknown machine state " + std::to_string(s.machineState));
  Snapshot* target = static_cast<Snapshot*>(*state);
  if (target && !states_.count(target)) return error("*FMUstate is not a state of this instance");
  if (!target) {
    owned_.push_back(std::make_unique<Snapshot>());
    target = owned_.back().get();
    states_.insert(target);
  }
  *target = std::move(s);
  *state = target;
  return Status::OK;
}

Status Instance::setInputDerivatives(const uint32_t vr[], size_t n, const int32_t order[], const double value[]) {
  if (n && (!vr || !order || !value)) return error("an array is NULL");
  for (size_t i = 0; i < n; ++i) {
    const Variable* v = lookup(vr[i], false);
    if (!v) return Status::Error;
    if (v->causality != Causality::Input) return error(v->name + " is not an input");
    if (order[i] != 1)
      return error(v->name + ": only first-order derivatives (order 1) are interpolated, got order " +
                   std::to_string(order[i]));
    if (!std::isfinite(value[i])) return error(v->name + ": must be finite, got " + num(value[i]));
    if (v->quantity == Quantity::BeltVelocity) {  // the belt's acceleration over the step
      data_.beltRate[v->body][v->component] = value[i];
      continue;
    }
    if (v->quantity == Quantity::JointMotorSpeed || v->quantity == Quantity::JointTargetPosition) {
      const size_t joint = static_cast<size_t>(v->body);  // a joint's variables name its index
      (v->quantity == Quantity::JointMotorSpeed ? data_.joints.motorSpeedRate
                                                : data_.joints.targetPositionRate)[joint] = value[i];
      continue;
    }
    // A driven body's motion over the step follows its velocities and their rates;
    // its pose's derivatives are those velocities, taken from their own inputs.
    rigid::DriveInput& drive = data_.drive[v->body];
    if (v->quantity == Quantity::Velocity) drive.acceleration[v->component] = value[i];
    if (v->quantity == Quantity::AngularVelocity) drive.angularAcceleration[v->component] = value[i];
    if (v->quantity != Quantity::Force && v->quantity != Quantity::Torque && v->quantity != Quantity::LoadForce)
      continue;
    rigid::BodyInput& rate = data_.inputRate[v->body];
    rigid::Vec3& of = v->quantity == Quantity::Force    ? rate.force
                      : v->quantity == Quantity::Torque ? rate.torque
                                                        : rate.loads[static_cast<size_t>(v->load)];
    of[v->component] = value[i];
  }
  return Status::OK;
}

Status Instance::getOutputDerivatives(const uint32_t vr[], size_t n, const int32_t order[], double value[]) {
  if (n && (!vr || !order || !value)) return error("an array is NULL");
  // dY/dt at the current state and inputs: the same force stage as the integrators.
  std::vector<rigid::BodyAux> aux(data_.Y.size());
  std::vector<rigid::BodyDerivative> dY(data_.Y.size());
  std::vector<int> every(data_.Y.size());
  std::iota(every.begin(), every.end(), 0);
  rigid::evaluateDerivative(model_, every, data_.input, data_.Y, aux, dY);
  for (size_t i = 0; i < n; ++i) {
    const Variable* v = lookup(vr[i], false);
    if (!v) return Status::Error;
    if (v->causality != Causality::Output) return error(v->name + " is not an output");
    if (order[i] != 1) return error(v->name + ": MaxOutputDerivativeOrder is 1, got order " + std::to_string(order[i]));
    const int b = v->body, c = v->component;
    const rigid::BodyAux& a = aux[b];
    switch (v->quantity) {
      case Quantity::Position: value[i] = dY[b].dX[c]; break;
      case Quantity::Orientation: value[i] = dY[b].dq[(c + 3) % 4]; break;  // (w,x,y,z) from (x,y,z,w)
      case Quantity::Velocity: value[i] = dY[b].dP[c] / model_.bodies[b].mass; break;
      case Quantity::AngularVelocity:
        // d(I^-1 L)/dt = I^-1 (T - omega x L) for a rigid body, I^-1 = R Ibody^-1 R^T
        // (the force stage forms I(t)^-1 only when surfaces need it)
        value[i] = (a.R * (model_.bodies[b].IbodyInv * (a.R.transpose() * (a.T - a.omega.cross(data_.Y[b].L)))))[c];
        break;
      case Quantity::LinearMomentum: value[i] = dY[b].dP[c]; break;
      case Quantity::AngularMomentum: value[i] = dY[b].dL[c]; break;
      default: value[i] = 0.0;  // solver.errorEstimate: piecewise constant
    }
  }
  return Status::OK;
}

void Instance::noteSubsteps(const rigid::StepResult& r, double h) {
  const std::string note =
      r.substeps > 1 ? std::string(rigid::causeName(r.cause)) + ":" + std::to_string(r.substeps) : std::string();
  if (note == substepNote_) return;
  substepNote_ = note;
  const std::string why = r.cause == rigid::StepCause::FastBody
                              ? std::string("a fast body could pass through what it can hit")
                              : std::string("method ") + rigid::methodName(model_.method) +
                                    " is outside its stability region (" + rigid::causeName(r.cause) + ")";
  if (r.substeps > 1)
    report(Status::Warning, why + " at the internal step of " + num(h) + " s; sub-stepping it " +
                                std::to_string(r.substeps) + " times (steps of at most " + num(r.stableStep) +
                                " s; see solver.steps)");
  else
    log(Status::OK, "logEvents", inCall("no sub-stepping needed any more"));
}

}  // namespace rigidfmu
