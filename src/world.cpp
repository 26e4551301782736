#include "world.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <utility>

#include "body_packs.h"
#include "dynamics.h"
#include "modules.h"

#include "collision_cache.h"
#include "constraint_solver.h"
#include "contact_rules.h"
#include "joint_rows.h"
#include "module_switches.h"
#include "sleep.h"

namespace rigid {

unsigned modulesBuilt() {
  return (modules::kSurfaces ? kModuleSurfaces : 0u) | (modules::kMedia ? kModuleMedia : 0u) |
         (modules::kCollisions ? kModuleCollisions : 0u) | (modules::kJoints ? kModuleJoints : 0u) |
         (modules::kMeshes ? kModuleMeshes : 0u);
}

WorldData initialData(const WorldModel& model) {
  const size_t n = model.bodies.size();
  WorldData d;
  d.Y.reserve(n);
  for (const BodyConstants& body : model.bodies) d.Y.push_back(initialState(body));
  for (const BodyConstants& body : model.bodies) {
    d.input.push_back(zeroInput(body.loads.size()));
    d.inputRate.push_back(zeroInput(body.loads.size()));
  }
  for (const Surface& s : model.surfaces) d.beltVelocity.push_back(s.beltVelocity);
  d.beltRate.assign(model.surfaces.size(), Vec3::Zero());
  d.aux.resize(n);
  d.contacts.assign(n, 0);
  d.sleep = awakeState(n);
  d.contactLoads.impulse.assign(n, Vec3::Zero());
  d.contactLoads.angularImpulse.assign(n, Vec3::Zero());
  d.contactLoads.surfaceImpulse.assign(model.surfaces.size(), Vec3::Zero());
  if constexpr (modules::kCollisions) {
    std::vector<bool> collides, meetsSurfaces;
    for (const BodyConstants& body : model.bodies) {
      collides.push_back(body.collides);
      // Surfaces are static boxes of the contact solve: a body that takes no part in
      // collisions ("collision": false) still rests on them.
      meetsSurfaces.push_back(body.collides || !model.surfaces.empty());
    }
    const long colliding = std::count(collides.begin(), collides.end(), true);
    const long onSurfaces = model.surfaces.empty() ? 0 : std::count(meetsSurfaces.begin(), meetsSurfaces.end(), true);
    // (joints are rows of the contacts' solver: a jointed world has its cache)
    if (colliding >= 2 || onSurfaces >= 1 || !model.joints.empty()) {
      d.collision = std::make_shared<CollisionCache>(CollisionDetector(model, collides, meetsSurfaces));
      for (size_t i = 0; i < model.bodies.size(); ++i) {
        const Shape& shape = model.bodies[i].shape;
        d.collision->halfThickness.push_back(meetsSurfaces[i] ? halfThickness(shape) : 0.0);
        d.collision->boundingRadius.push_back(meetsSurfaces[i] ? boundingRadius(shape) : 0.0);
        if (meetsSurfaces[i]) d.collision->thinnest = std::min(d.collision->thinnest, halfThickness(shape));
      }
      for (const Surface& s : model.surfaces)
        d.collision->thinnest = std::min(d.collision->thinnest, surfaceHalfThickness(s));
    }
  }
  d.scratch.stage.resize(n);
  d.scratch.next.resize(n);
  d.scratch.y.resize(n);
  d.scratch.y4.resize(n);
  d.scratch.u.resize(n);
  d.scratch.awake.resize(n);
  std::iota(d.scratch.awake.begin(), d.scratch.awake.end(), 0);
  for (size_t i = 0; i < n; ++i)
    if (!driven(model.bodies[i])) d.scratch.free.push_back(static_cast<int>(i));
  d.drive = startDrive(model);
  d.scratch.held.reserve(n);
  d.scratch.felt.reserve(n);
  for (auto& k : d.scratch.k) k.resize(n);
  refreshAuxiliaries(model, d);
  d.audit.carried.assign(n, 1.0);
  d.audit.energy.resize(n);
  for (size_t i = 0; i < n; ++i) d.audit.energy[i] = d.aux[i].omega.dot(d.Y[i].L);
  d.audit.reference = d.audit.energy;
  if constexpr (modules::kJoints) {
    startJoints(model, d);
    if (d.collision && !model.joints.empty()) d.collision->joints = makeJointRows(model);
  }
  return d;
}

void clearContactLoads(WorldData& data) {
  WorldData::ContactLoads& loads = data.contactLoads;
  for (auto* v : {&loads.impulse, &loads.angularImpulse, &loads.surfaceImpulse, &data.joints.impulse,
                  &data.joints.angularImpulse})
    v->assign(v->size(), Vec3::Zero());
  loads.duration = 0.0;
}

namespace {

// computeVelocities() of n bodies, bodyAt(k) the k-th, four at a time (body_packs.h).
template <class BodyAt>
void refreshPacked(const WorldModel& model, size_t n, BodyAt bodyAt, WorldData& data) {
  for (size_t first = 0; first < n; first += kLanes) {
    QuatPack q;
    Pack L[3], Iinv[9];
    for (int lane = 0; lane < kLanes; ++lane) {
      const size_t i = bodyAt(laneBody(first, lane, n));
      setLane(Iinv, lane, model.bodies[i].IbodyInv);
      setLane(q, lane, data.Y[i].q);
      setLane(L, lane, data.Y[i].L);
    }
    const RotationPack R = rotationOf(q);
    Pack Lbody[3], omegaBody[3], omega[3];
    multiplyTransposed(R.r, L, Lbody);
    multiply(Iinv, Lbody, omegaBody);
    multiply(R.r, omegaBody, omega);
    for (int lane = 0; lane < kLanes && first + lane < n; ++lane) {
      const size_t i = bodyAt(first + lane);
      BodyAux& aux = data.aux[i];
      aux.V = data.Y[i].P / model.bodies[i].mass;
      for (int e = 0; e < 9; ++e) aux.R(e / 3, e % 3) = R.r[e][lane];
      aux.omega = Vec3(omega[0][lane], omega[1][lane], omega[2][lane]);
    }
  }
}

}  // namespace

void refreshAuxiliaries(const WorldModel& model, WorldData& data) {
  refreshPacked(
      model, data.Y.size(), [](size_t k) { return k; }, data);
}

namespace {

// refreshAuxiliaries() of the awake bodies.
void refreshAwake(const WorldModel& model, WorldData& data) {
  const std::vector<int>& awake = data.scratch.awake;
  if (data.sleep.sleeping == 0)  // (the same, with no list to read)
    refreshAuxiliaries(model, data);
  else
    refreshPacked(
        model, awake.size(), [&](size_t k) { return static_cast<size_t>(awake[k]); }, data);
}

// Adds the time of its scope to its stage's in the profile, when profiling and no other
// stage is being timed (a stage run inside another is that one's).
class StageTimer {
 public:
  StageTimer(WorldData& data, Stage stage)
      : profile_(data.profiling && data.profile.running < 0 ? &data.profile : nullptr), stage_(stage) {
    if (!profile_) return;
    profile_->running = static_cast<int>(stage);
    start_ = std::chrono::steady_clock::now();
  }
  ~StageTimer() {
    if (!profile_) return;
    const int k = static_cast<int>(stage_);
    profile_->time[k] += std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start_).count();
    ++profile_->runs[k];
    profile_->running = -1;
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  StepProfile* profile_;
  Stage stage_;
  std::chrono::steady_clock::time_point start_;
};

StepProfile* profileOf(WorldData& data) { return data.profiling ? &data.profile : nullptr; }

// Pairs apart by less than this (m) are detected too, speculatively: an inelastic one
// takes the impulse that keeps it from closing more than its gap in the next step, and
// a box falling flat meets the floor with its far corners too. (4 mm: a cube falling
// at 2 m/s closes 4 mm in a 2 ms step; faster bodies widen it, speculativeMargin.)
constexpr double kSpeculativeMargin = 4e-3;

// A state the physics can still answer: finite, and positions within 1e12 m of the
// origin (collision detection's geometry fails far beyond, and no scene is that big).
constexpr double kMaxDistance = 1e12;  // m

bool answerable(const BodyState& y) {
  // v - v is 0 for a finite v and NaN otherwise: one sum tests all 13 values at once
  const double zero = (y.X - y.X).sum() + (y.q.coeffs() - y.q.coeffs()).sum() + (y.P - y.P).sum() + (y.L - y.L).sum();
  return zero == 0.0 && y.X.cwiseAbs().maxCoeff() <= kMaxDistance;
}

// f(i) of each awake body i, ascending (Scratch::awake; every body, with no list to
// read, when none sleeps: free bodies are the common case).
template <class F>
void forEachAwake(const WorldData& data, F f) {
  if (data.sleep.sleeping == 0)
    for (int i = 0; i < static_cast<int>(data.Y.size()); ++i) f(i);
  else
    for (int i : data.scratch.awake) f(i);
}

// The first awake body whose state in Y is not answerable, -1 when none.
int firstNonFinite(const WorldData& data, const std::vector<BodyState>& Y) {
  int bad = -1;
  forEachAwake(data, [&](int i) {
    if (bad < 0 && !answerable(Y[i])) bad = i;
  });
  return bad;
}

// Scratch::awake and Scratch::free from the sleep flags, after they changed.
void listAwake(const WorldModel& model, WorldData& data) {
  std::vector<int>& awake = data.scratch.awake;
  if (data.sleep.sleeping == 0 && awake.size() == data.Y.size()) return;  // every body, as listed
  awake.clear();
  data.scratch.free.clear();
  for (size_t i = 0; i < data.Y.size(); ++i) {
    if (data.sleep.asleep[i]) continue;
    awake.push_back(static_cast<int>(i));
    if (!driven(model.bodies[i])) data.scratch.free.push_back(static_cast<int>(i));
  }
}

// Y(t + tau) into next: auxiliaries -> forces -> derivative per stage, then unit q.
StepResult failed(int body) {
  StepResult r;
  r.ok = false;
  r.body = body;
  return r;
}

// Returns the integrator's steps (0: the adaptive method failed its tolerance).
// Sleeping bodies are not integrated: their entries of next are not theirs (commit
// leaves them out).
// Driven bodies move at their velocities (drive.h), never asleep.
int advance(const WorldModel& model, WorldData& data, double tau, std::vector<BodyState>& next) {
  StageTimer timer(data, Stage::Integrate);
  const std::vector<int>& free = data.scratch.free;
  const int steps = integrate(model, data, free, tau, next);
  if (free.size() < data.scratch.awake.size())
    for (size_t i = 0; i < data.Y.size(); ++i)
      if (driven(model.bodies[i])) next[i] = driveStep(data.Y[i], tau);
  if (data.profiling) data.profile.integrated += static_cast<long>(data.scratch.awake.size());
  forEachAwake(data, [&](int i) { next[i].q.normalize(); });
  return steps;
}

// One internal step's context, passed down the stages.
struct StepContext {
  const WorldModel& model;
  WorldData& data;
  double h;                   // s, the internal step
  bool bouncy;                // some body of xi > 0 meets something: impacts are located
  bool stopAtImpact = false;  // end the step at the first located impact
};

// The contacts of Y into the collision cache: pairs closer than `margin` too. The
// pairs among sleeping bodies and surfaces are left out; a sleeping island that an
// awake body reaches wakes, and its own contacts are then detected too.
void detectContacts(StepContext& s, const std::vector<BodyState>& Y, double margin) {
  if constexpr (modules::kCollisions) {
    CollisionCache* c = s.data.collision.get();
    if (!c) return;
    SleepState& sleep = s.data.sleep;
    const std::vector<int>& awake = s.data.scratch.awake;
    if (std::none_of(awake.begin(), awake.end(), [&](int i) { return c->boundingRadius[i] > 0.0; })) {
      c->contacts.clear();  // every body that meets something sleeps: nothing to detect
      return;
    }
    auto detect = [&] {
      if (sleep.sleeping == 0) return c->detector.detect(Y, margin, c->contacts, profileOf(s.data), margin);
      if (!sleep.boxes) sleep.boxes = c->detector.fixedBoxes(s.data.Y, sleep.asleep);
      const Sleepers sleepers{sleep.asleep, *sleep.boxes};
      c->detector.detect(Y, margin, c->contacts, profileOf(s.data), margin, &sleepers);
    };
    detect();
    if (!wakeTouched(c->contacts, s.data)) return;
    listAwake(s.model, s.data);
    detect();
  }
}

// Whether the contacts in the collision cache (detected for Y) hold a bouncing impact.
bool bouncingImpact(StepContext& s, const std::vector<BodyState>& Y) {
  if constexpr (modules::kCollisions) {
    if (const CollisionCache* c = s.data.collision.get())
      return anyBouncingImpact(s.model, c->contacts, Y, restingNormalSpeed(s.model.gravity, s.h));
  }
  return false;
}

// Whether some body strikes a surface or another body in a trial state `next`
// (detected afresh; its sleeping bodies where they sleep). Only bouncing impacts are
// located; restitutions combine by geometric mean, so without a bouncy body (a pile of
// inelastic cubes) there is nothing to detect.
bool impactIn(StepContext& s, std::vector<BodyState>& next) {
  if (!s.bouncy) return false;
  if constexpr (modules::kCollisions) holdSleepers(s.data.sleep, s.data.Y, next);
  detectContacts(s, next, 0.0);
  return bouncingImpact(s, next);
}

// A solve's impulses on the bodies and the surfaces into the contact loads.
void addImpulses(const ContactImpulses& impulses, WorldData::ContactLoads& loads) {
  for (size_t i = 0; i < impulses.linear.size(); ++i) {
    loads.impulse[i] += impulses.linear[i];
    loads.angularImpulse[i] += impulses.angular[i];
  }
  for (const SurfacePush& p : impulses.pushes) loads.surfaceImpulse[p.surface] += p.impulse;
}

// After a step of `taken` is committed (a refused one adds nothing): its contact
// impulses and the sleeping bodies' loads into WorldData::contactLoads, then the
// islands of its contacts, of which those that have come to rest fall asleep.
void addLoadsAndSleep(StepContext& s, CollisionCache& c, double taken) {
  // (no island can fall asleep with every body asleep, or without a surface to rest on)
  const bool mayFallAsleep = s.model.sleep.enabled && !s.data.scratch.awake.empty() && !s.model.surfaces.empty();
  if (mayFallAsleep && !c.contacts.empty()) {
    StageTimer timer(s.data, Stage::Islands);
    findIslands(s.model, c.contacts, c.islands);
  }
  StageTimer timer(s.data, Stage::Sleep);
  addImpulses(c.impulses, s.data.contactLoads);
  s.data.contactLoads.duration += taken;
  addRestingLoads(s.data, taken);
  if (mayFallAsleep && updateSleep(s.model, s.data, taken, c)) listAwake(s.model, s.data);
}

// The energy audit: a body whose angular momentum the step left bitwise unchanged had
// no torque and no impulse, so any change of its rotational energy is the method's
// own. Over the run, a gain beyond the limit refuses the step, naming the body and a
// step that would have kept the gain to half the limit (the gain grows with h). Reads
// Y and the auxiliaries after the step, `before` the state before it; updates the
// audit only when the step is accepted.
StepResult auditRotationalEnergy(const WorldModel& model, WorldData& data, const std::vector<BodyState>& before,
                                 double h) {
  WorldData::EnergyAudit& a = data.audit;  // (a sleeping body neither turns nor gains)
  StepResult r;
  if (model.energyGainLimit > 0.0) {
    forEachAwake(data, [&](int i) {
      if (!r.ok || data.Y[i].L != before[i].L || !(a.reference[i] > 0.0)) return;
      if (driven(model.bodies[i])) return;  // its turning is given, not integrated
      const double gain = a.carried[i] * data.aux[i].omega.dot(data.Y[i].L) / a.reference[i] - 1.0;
      if (!(gain > model.energyGainLimit)) return;
      r = failed(i);
      r.cause = StepCause::EnergyGain;
      r.energyGain = gain;
      r.stableStep = h * 0.5 * model.energyGainLimit / gain;
    });
    if (!r.ok) return r;
  }
  forEachAwake(data, [&](int i) {
    const double energy = data.aux[i].omega.dot(data.Y[i].L);
    if (data.Y[i].L != before[i].L) {  // a torque or an impulse: a new stretch starts here
      if (a.reference[i] > 0.0) a.carried[i] *= a.energy[i] / a.reference[i];
      a.reference[i] = energy;
    }
    a.energy[i] = energy;
  });
  return r;
}

// Accepts the awake bodies' states in next as theirs if they are finite and the energy
// audit passes; a refused state is swapped back out.
StepResult commit(const WorldModel& model, WorldData& data, std::vector<BodyState>& next, double h) {
  if (const int bad = firstNonFinite(data, next); bad >= 0) return failed(bad);
  // next: the awake bodies' states before the step (all of them when none sleeps)
  auto exchange = [&] {
    if (data.sleep.sleeping == 0)
      std::swap(data.Y, next);
    else
      for (int i : data.scratch.awake) std::swap(data.Y[i], next[i]);
  };
  exchange();
  refreshAwake(model, data);
  if (StepResult r = auditRotationalEnergy(model, data, next, h); !r.ok) {
    exchange();
    refreshAwake(model, data);
    return r;
  }
  return {};
}

// The speed of the fastest point of a body (m/s) of auxiliaries aux and bounding
// radius r: |V| + |omega| r.
double pointSpeed(const BodyAux& aux, double r) { return aux.V.norm() + aux.omega.norm() * r; }

// A bound of the awake bodies' pointSpeed (m/s), of those that meet something, with no
// square root a body: (|V| + |omega| r)^2 <= 2 (|V|^2 + |omega|^2 r^2). Most steps need
// no more than it to know that no body is fast.
double fastestPointBound(const WorldData& data, const CollisionCache& c) {
  double most = 0.0;
  for (int i : data.scratch.awake) {
    const double r = c.boundingRadius[i];
    if (r > 0.0) most = std::max(most, data.aux[i].V.squaredNorm() + data.aux[i].omega.squaredNorm() * r * r);
  }
  return std::sqrt(2.0 * most);
}

// Continuous collision by sub-stepping: between two detections no colliding body may
// move (translation plus rotation of its farthest point) more than the half thickness
// of the thinner of itself and anything it could reach within the step, so that no
// overlap can be stepped over. Bodies far from everything cost nothing. Motion within
// the step is bounded by the velocities at its start.
int collisionSubsteps(const WorldModel& model, const WorldData& data, double h) {
  const CollisionCache* c = modules::kCollisions ? data.collision.get() : nullptr;
  if (!c || !(fastestPointBound(data, *c) * h > c->thinnest)) return 1;
  const size_t n = data.Y.size();
  std::vector<double>& travel = data.collision->travel;
  travel.assign(n, 0.0);
  for (int i : data.scratch.awake)
    if (c->boundingRadius[i] > 0.0)
      travel[i] = (data.aux[i].V.norm() + data.aux[i].omega.norm() * c->boundingRadius[i]) * h;
  double substeps = 1.0;
  auto need = [&](double move, double thickness) {
    if (move > thickness) substeps = std::max(substeps, std::ceil(move / thickness));
  };
  // A pair needs sub-steps only when the faster of the two moves more than the thinner
  // one's half thickness, so only bodies moving more than the thinnest thing they could
  // hit (any colliding body or surface) are checked, each against everything it can
  // reach: none in a pile of slow cubes, a few when something is thrown.
  const double thinnest = c->thinnest;
  for (int i : data.scratch.awake) {
    if (c->boundingRadius[i] <= 0.0 || !(travel[i] > thinnest)) continue;
    const double reach = c->boundingRadius[i] + travel[i];
    for (size_t j = 0; j < n; ++j) {
      if (j == static_cast<size_t>(i) || c->boundingRadius[j] <= 0.0) continue;
      if ((data.Y[i].X - data.Y[j].X).norm() > reach + c->boundingRadius[j] + travel[j]) continue;
      need(std::max(travel[i], travel[j]), std::min(c->halfThickness[i], c->halfThickness[j]));
    }
    for (const Surface& s : model.surfaces) {
      const Vec3 p = (s.R_WS.transpose() * (data.Y[i].X - s.centre)).cwiseAbs() - s.halfExtent;
      if (p.cwiseMax(0.0).norm() > reach) continue;
      need(travel[i], std::min(c->halfThickness[i], surfaceHalfThickness(s)));
    }
  }
  constexpr double kMaxSubsteps = 100000;
  return static_cast<int>(std::min(kMaxSubsteps, substeps));
}

// The speculative distance for the contacts of Y: at least kSpeculativeMargin, and
// what two of the fastest bodies can close in the next step, so that a cube falling
// at 5 m/s (1 cm a 2 ms step) is caught as it lands instead of sinking in and being
// pushed out. At most kMaxSpeculativeMargin: faster bodies are sub-stepped.
constexpr double kMaxSpeculativeMargin = 0.05;  // m

double speculativeMargin(const StepContext& s) {
  const CollisionCache* c = modules::kCollisions ? s.data.collision.get() : nullptr;
  if (!c || !(2.0 * fastestPointBound(s.data, *c) * s.h > kSpeculativeMargin)) return kSpeculativeMargin;
  double fastest = 0.0;  // m/s, the largest speed of a point of a body that meets something
  for (int i : s.data.scratch.awake)
    if (c->boundingRadius[i] > 0.0) fastest = std::max(fastest, pointSpeed(s.data.aux[i], c->boundingRadius[i]));
  return std::clamp(2.0 * fastest * s.h, kSpeculativeMargin, kMaxSpeculativeMargin);
}

// The integrator's free motion of every awake body over tau, then the constraint
// solver's motion of the bodies that the step's contacts join (constraint_solver.h),
// from the state and contact memory of the step's start.
// Returns the integrator's steps (0: the adaptive method failed its tolerance).
int moveBodies(StepContext& s, CollisionCache& c, double tau, std::vector<BodyState>& next) {
  const int steps = advance(s.model, s.data, tau, next);
  if (steps == 0) return 0;
  StageTimer timer(s.data, Stage::Solve);
  for (int i : s.data.scratch.awake) s.data.contacts[i] = 0;  // a sleeping body keeps its count
  if (c.stepContacts.empty() && !c.joints) {                  // nothing to solve, nothing to remember
    c.impulses.clear();
    c.storedMemory.clear();
    return steps;
  }
  const ConstraintReport report =
      solveConstraints(s.model, s.data, c.stepContacts, tau, s.data.contactMemory, c.storedMemory, next,
                       s.data.contacts, c.constraints, c.impulses, modules::kJoints ? c.joints.get() : nullptr);
  if (s.data.profiling) {
    ++s.data.profile.solves;
    s.data.profile.points += report.points;
  }
  return steps;
}

// The instant of the first impact within (0, tau], by bisection on trial steps from
// the step's start (the integrator, then the constraint solver) to 1e-15 of the step:
// the bounce then happens where and when it should, whatever the step size. An impact
// that no positive instant precedes is the step start's, which the solver's impacts
// stage answers: the step is then taken whole (a step of length 0 has no motion to
// solve).
double locateImpact(StepContext& s, CollisionCache& c, double tau, std::vector<BodyState>& next) {
  double lo = 0.0, hi = tau;
  while (hi - lo > 1e-15 * tau) {
    const double mid = 0.5 * (lo + hi);
    moveBodies(s, c, mid, next);
    (impactIn(s, next) ? hi : lo) = mid;
  }
  if (lo == 0.0) lo = tau;
  moveBodies(s, c, lo, next);
  return lo;
}

// The impact at which a step returns early (FMI 3), answered before it returns: the
// impacts stage at the located instant, whose impulses join the contact loads.
StepResult answerLocatedImpact(StepContext& s, CollisionCache& c) {
  StageTimer timer(s.data, Stage::Impacts);
  detectContacts(s, s.data.Y, speculativeMargin(s));
  std::vector<BodyState>& next = s.data.scratch.next;
  next = s.data.Y;
  answerImpactsNow(s.model, s.data, c.contacts, s.h, next, c.constraints, c.impulses);
  if (const StepResult r = commit(s.model, s.data, next, s.h); !r.ok) return r;
  addImpulses(c.impulses, s.data.contactLoads);
  return {};
}

// The contacts of the step's start into the cache's stepContacts, with the speculative
// margin (the cache's `contacts` then serve the impacts' probes).
// Returns whether an impact can happen within the step: no pair can close more than the
// margin in it (twice the fastest point's travel), so with no pair within the margin
// there is none, unless the margin was capped.
bool collide(StepContext& s, CollisionCache& c) {
  StageTimer timer(s.data, Stage::Collide);
  const double margin = speculativeMargin(s);
  detectContacts(s, s.data.Y, margin);
  std::swap(c.contacts, c.stepContacts);
  return !c.stepContacts.empty() || margin >= kMaxSpeculativeMargin;
}

// How much of the rest of the step to take: all of it, or up to the instant of a
// bouncing impact inside it (next then holds the state there), when one can happen.
double impactInstant(StepContext& s, CollisionCache& c, bool reachable, double rest, std::vector<BodyState>& next) {
  if (!s.bouncy || !reachable || firstNonFinite(s.data, next) >= 0) return rest;
  StageTimer timer(s.data, Stage::Impacts);
  return impactIn(s, next) ? locateImpact(s, c, rest, next) : rest;
}

// The step's contacts and memory back in place, and next as the new state if it passes
// the checks (commit).
StepResult commitStep(StepContext& s, CollisionCache& c, int steps, std::vector<BodyState>& next) {
  StageTimer timer(s.data, Stage::Commit);
  std::swap(c.contacts, c.stepContacts);                           // the step's contacts, for sleep
  if (steps > 0) std::swap(s.data.contactMemory, c.storedMemory);  // else no solve stored any
  if (steps == 0) return failed(-1);
  const StepResult r = commit(s.model, s.data, next, s.h);
  if constexpr (modules::kJoints) {
    if (r.ok && c.joints) {  // the last solve's joint rows are the step's
      commitJoints(*c.joints, s.data, c.impulses);
      measureJoints(s.model, s.data);
    }
  }
  return r;
}

// One internal step with contacts, as its stages: collide, integrate and solve
// (moveBodies), impacts (the step is split at a bouncing impact inside it), commit, and
// sleep; again from the impact for the rest of the step.
StepResult stepWithContacts(StepContext& s, CollisionCache& c) {
  std::vector<BodyState>& next = s.data.scratch.next;
  constexpr int kMaxImpactsPerStep = 16;
  double done = 0.0;
  for (int impacts = 0;; ++impacts) {
    const double rest = s.h - done;
    const bool reachable = collide(s, c);
    const int steps = moveBodies(s, c, rest, next);
    const double taken = steps > 0 && impacts < kMaxImpactsPerStep ? impactInstant(s, c, reachable, rest, next) : rest;
    if (const StepResult r = commitStep(s, c, steps, next); !r.ok) return r;
    addLoadsAndSleep(s, c, taken);
    s.data.steps += steps;
    done += taken;
    if (taken == rest || impacts >= kMaxImpactsPerStep) return {};
    if (s.stopAtImpact && done > 0.0) {  // an impact inside the step, after its start
      StepResult r = answerLocatedImpact(s, c);
      r.impactAt = done;
      return r;
    }
  }
}

// One internal step: the contact step when something can touch, else the integrator
// alone.
StepResult stepOnce(StepContext& s) {
  if constexpr (modules::kCollisions)
    if (s.data.collision) return stepWithContacts(s, *s.data.collision);
  std::vector<BodyState>& next = s.data.scratch.next;
  const int steps = advance(s.model, s.data, s.h, next);
  if (steps == 0) return failed(-1);
  s.data.steps += steps;
  StageTimer timer(s.data, Stage::Commit);
  return commit(s.model, s.data, next, s.h);
}

// Whether some body of xi > 0 meets something (another colliding body or a surface).
bool bouncyWorld(const WorldModel& model) {
  return std::any_of(model.bodies.begin(), model.bodies.end(), [&](const BodyConstants& b) {
    return (b.collides || !model.surfaces.empty()) && b.restitution > 0.0;
  });
}

// Explicit fixed-step methods outside their stability region sub-step: the step is
// split so that h |omega|, h times the drag rate and h times the heave frequency of
// every body stay within the method's region (integrator.h). Fills result's cause,
// stable step and sub-step count.
void stabilitySubsteps(const WorldModel& model, const WorldData& data, double h, StepResult& r) {
  const StabilityLimits limits = stabilityLimits(model.method);
  auto consider = [&](double rate, double limit, StepCause cause) {
    if (!(rate > 0.0) || !std::isfinite(limit)) return;
    if (limit == 0.0) {  // no step is stable: refuse
      r.substeps = std::numeric_limits<long>::max();
      r.cause = cause;
      r.stableStep = 0.0;
      return;
    }
    // (a rate so large that the stable step underflows still gets a step > 0)
    const double stable = std::max(limit / rate, std::numeric_limits<double>::denorm_min());
    if (h <= stable) return;
    const double n = std::ceil(h / stable - 1e-9);  // a step at the limit within rounding is fine
    if (n > static_cast<double>(r.substeps)) {
      r.substeps = n > 1e15 ? std::numeric_limits<long>::max() : static_cast<long>(n);
      r.cause = cause;
      r.stableStep = stable;
    }
  };
  // the fastest spin sets the sub-steps: one square root, not one per body
  double spin2 = 0.0;
  for (int i : data.scratch.free) spin2 = std::max(spin2, data.aux[i].omega.squaredNorm());
  consider(std::sqrt(spin2), limits.spin, StepCause::Spin);
  if constexpr (modules::kMedia) {
    for (int i : data.scratch.free) {
      for (const Medium& medium : model.media) {
        const MediumRates rates = mediumRates(medium, model.bodies[i], data.Y[i], data.aux[i], model.gravity);
        consider(rates.damping, limits.damping, StepCause::Drag);
        consider(rates.oscillation, limits.oscillation, StepCause::BuoyancyHeave);
      }
    }
  }
}

// The sub-steps a step of h needs (stabilitySubsteps, collisionSubsteps) and why.
StepResult substepPlan(const WorldModel& model, WorldData& data, double h) {
  StageTimer timer(data, Stage::Plan);
  StepResult plan;
  stabilitySubsteps(model, data, h, plan);
  const long fast = collisionSubsteps(model, data, h);
  if (fast > plan.substeps) {
    plan.substeps = fast;
    plan.cause = StepCause::FastBody;
    plan.stableStep = h / fast;
  }
  return plan;
}

}  // namespace

const char* stageName(Stage stage) {
  static constexpr const char* kNames[kStageCount] = {"plan",    "wake",   "collide", "integrate", "solve",
                                                      "impacts", "commit", "islands", "sleep"};
  return kNames[static_cast<int>(stage)];
}

const char* causeName(StepCause cause) {
  switch (cause) {
    case StepCause::Spin: return "spin";
    case StepCause::Drag: return "drag";
    case StepCause::BuoyancyHeave: return "buoyancy heave";
    case StepCause::FastBody: return "fast body";
    case StepCause::EnergyGain: return "rotational energy gain";
    default: return "";
  }
}

StepResult step(const WorldModel& model, WorldData& data, double h, bool stopAtImpact) {
  // More than this many sub-steps in one step is refused: the step should be smaller.
  // (Fast bodies cost a collision detection per sub-step, hence their lower cap.)
  constexpr long kMaxSubsteps = 1000000;
  constexpr long kMaxFastSubsteps = 10000;
  listAwake(model, data);  // between steps the FMU may restore a state or wake every body
  StepResult plan = substepPlan(model, data, h);
  if (plan.substeps > (plan.cause == StepCause::FastBody ? kMaxFastSubsteps : kMaxSubsteps)) {
    plan.ok = false;
    return plan;
  }
  if (data.profiling) data.profile.steps += plan.substeps;
  if constexpr (modules::kCollisions) {
    StageTimer timer(data, Stage::Wake);
    if (wakeDriven(data)) listAwake(model, data);
  }
  StepContext context{model, data, h / static_cast<double>(plan.substeps), bouncyWorld(model), stopAtImpact};
  for (long k = 0; k < plan.substeps; ++k) {
    StepResult r = stepOnce(context);
    if (!r.ok) return r;
    if (r.impactAt >= 0.0) {
      plan.impactAt = static_cast<double>(k) * context.h + r.impactAt;
      return plan;
    }
  }
  return plan;
}

std::string massRatioWarning(const WorldModel& model) {
  int light = -1, heavy = -1;
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    if (!model.bodies[i].collides || driven(model.bodies[i])) continue;
    const int k = static_cast<int>(i);
    if (light < 0 || model.bodies[i].mass < model.bodies[light].mass) light = k;
    if (heavy < 0 || model.bodies[i].mass > model.bodies[heavy].mass) heavy = k;
  }
  if (light < 0 || light == heavy) return {};
  const double ratio = model.bodies[heavy].mass / model.bodies[light].mass;
  if (!(ratio > kMaxMassRatio)) return {};
  const double omega = 2.0 * 3.14159265358979323846 * 0.4 / model.maxStep;
  const double sink = ratio * model.gravity.norm() / (omega * omega);
  char text[400];
  std::snprintf(text, sizeof text,
                "bodies %s (%g kg) and %s (%g kg) can collide with a mass ratio of %g, above the %g that contacts are "
                "made for: under %s, %s would sink in by up to %.3g m at the step of %g s (the sinking scales with "
                "the ratio and the step squared)",
                model.bodies[heavy].name.c_str(), model.bodies[heavy].mass, model.bodies[light].name.c_str(),
                model.bodies[light].mass, ratio, kMaxMassRatio, model.bodies[heavy].name.c_str(),
                model.bodies[light].name.c_str(), sink, model.maxStep);
  return text;
}

}  // namespace rigid
