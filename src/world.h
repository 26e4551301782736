// The world: its constants (WorldModel) and everything that changes in a run
// (WorldData), kept apart as MuJoCo keeps mjModel and mjData.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "body.h"
#include "contact_memory.h"
#include "drive.h"
#include "integrator.h"
#include "joint.h"
#include "medium.h"
#include "sleep_state.h"
#include "surface.h"

namespace rigid {

struct CollisionCache;  // collision_cache.h: the FCL detector and its contacts

// Constants of one scene. Parameters of the FMU (mass, gravity, method, ...) change
// them only between runs or, for tunable ones, between communication steps.
struct WorldModel {
  std::string name;
  Vec3 gravity = Vec3(0.0, 0.0, -9.81);  // m/s^2
  Method method = Method::RK4;
  double maxStep = 1e-3;    // s, largest internal step
  double tolerance = 1e-6;  // 1, local error tolerance of adaptive methods (0: fixed steps)
  // 1, largest relative gain of a torque-free body's rotational energy over a run
  // before a step is refused (0: unchecked); explicit Euler gains ~(h |omega|)^2 a step.
  double energyGainLimit = 1e-3;
  SleepRules sleep;  // when islands at rest sleep (sleep.h)
  std::vector<BodyConstants> bodies;
  std::vector<Surface> surfaces;
  std::vector<Medium> media;
  std::vector<JointConstants> joints;
};

// Work buffers of the integrators, sized once so that a step allocates nothing. They
// hold no state of the run (awake is derived from the sleep flags at each step): what
// one step hands the next, the adaptive step included, is in WorldData.
struct Scratch {
  std::vector<BodyState> stage;  // Y + c h k, a Runge-Kutta stage
  std::vector<BodyState> next;   // Y(t + h) before it is accepted
  std::vector<BodyDerivative> k[7];
  std::vector<BodyState> y, y4;  // the adaptive method's current state and its 4th-order solution
  std::vector<Vec3> u;           // Lie-group stages: rotation vector of each body
  std::vector<int> awake;        // the bodies not asleep, ascending: what a step moves, checks and refreshes
  std::vector<int> free;         // the awake free bodies (not driven), ascending: what the integrator moves
  std::vector<int> held, felt;   // RK4: bodies whose forces are held over the step, and the others
};

// The stages of a step, in the order step() runs them: the plan of sub-steps (an
// explicit method's stability, fast bodies), waking the islands that inputs drive; then
// in each internal step: collide (the contacts of its start), integrate (the method's
// free motion of every awake body), solve (the constraint solver: impacts, sub-steps,
// store), impacts (is there a bouncing impact inside the step, and when: trial steps),
// commit (the new state's checks), islands (of the step's contacts, when islands may
// sleep) and sleep (contact loads, who sleeps).
enum class Stage { Plan, Wake, Collide, Integrate, Solve, Impacts, Commit, Islands, Sleep };
constexpr int kStageCount = 9;
const char* stageName(Stage stage);  // "plan", "wake", "collide", ...

// Where a step's time goes (ns, summed over steps), for the benchmarks: filled only
// while WorldData::profiling is set, so that a normal run pays no clock reads.
struct StepProfile {
  // per Stage: its time, and how often it ran; a stage run inside another (the trial
  // steps of impacts) is that one's time
  double time[kStageCount] = {};
  long runs[kStageCount] = {};
  double broadphase = 0.0;   // of every detection: poses, bounding boxes, the sweep in grid rows
  double narrowphase = 0.0;  // of every detection: contact points of the candidate pairs
  long steps = 0;            // internal steps profiled
  long integrated = 0;       // bodies the integrator moved, summed over its calls (sleepers are not)
  long boxes = 0;            // bodies whose bounding boxes detection placed, summed over detections
  long solves = 0;           // constraint solves
  long points = 0;           // contact points answered, summed over the solves
  int running = -1;          // the Stage being timed, -1 when none
};

// Everything that changes during a run.
struct WorldData {
  std::vector<BodyState> Y;      // state vectors
  std::vector<BodyInput> input;  // external loads (FMU inputs)
  // Their rates of change over the current communication step (N/s, N m/s): the FMU's
  // input derivatives; zero unless a master sets them.
  std::vector<BodyInput> inputRate;
  // What the inputs of the driven bodies say (drive.h), one per body (a free body's is
  // unused). The FMU turns them into the driven bodies' velocities of each internal step.
  std::vector<DriveInput> drive;
  // Per surface, the velocity of its material (m/s, world frame; a conveyor's belt, the
  // FMU input S.beltVelocity, zero for other surfaces) and its rate over the current
  // communication step (m/s^2, the input's derivative; zero unless a master sets it).
  // Only its part along a contact's plane acts (constraint_solver.cpp, Manifold::belt).
  std::vector<Vec3> beltVelocity, beltRate;
  std::vector<BodyAux> aux;   // V, R and omega of Y, valid after initialise() and step()
  std::vector<int> contacts;  // contact points of each body at the end of the last step
  // The energy audit (world.cpp), per body: twice the rotational energy of Y, that at
  // the start of the current stretch of steps free of torques and impulses, and the
  // gain factor of the earlier stretches. carried * energy / reference - 1 is the
  // relative energy the method itself has added.
  struct EnergyAudit {
    std::vector<double> energy, reference, carried;
  } audit;
  long steps = 0;  // internal steps taken since the counter was last cleared
  // The adaptive method's next step and last error estimate (integrator.h). Part of the
  // FMU state.
  IntegratorState integrator;
  // Body-body collision detection, when at least two bodies can collide; shared by
  // copies of the data (it holds no state between steps but FCL's objects).
  std::shared_ptr<CollisionCache> collision;
  // The contact points of the last step with their accumulated impulses, for the
  // next step's warm start. Part of the FMU state.
  std::vector<ContactMemory> contactMemory;
  // Which bodies sleep (sleep.h). Part of the FMU state.
  SleepState sleep;
  // The contact impulses summed since the last clearContactLoads (the FMU clears them
  // at each communication step and reports them over its length as mean forces):
  // per body the linear one and its moment about the centre of mass (N s, N m s, world
  // frame), per surface the impulse the bodies gave it, and the time they cover.
  struct ContactLoads {
    std::vector<Vec3> impulse, angularImpulse, surfaceImpulse;
    double duration = 0.0;  // s
  } contactLoads;
  // The joints' memory, inputs, reactions and coordinates (joint.h). Partly FMU state.
  JointData joints;
  Scratch scratch;
  bool profiling = false;
  StepProfile profile;
};

// Data for the start of a run: every body at its start values, inputs zero but the
// belts' velocities (the scene's, Surface::beltVelocity).
WorldData initialData(const WorldModel& model);

// Zeroes WorldData::contactLoads and the joints' reaction sums.
void clearContactLoads(WorldData& data);

// Refreshes V, R and omega of the current Y (outputs, the energy audit, the stability
// limits). I(t)^-1 is left out: only contacts use it, and they form their own.
void refreshAuxiliaries(const WorldModel& model, WorldData& data);

// Why a step was split into sub-steps or refused: an explicit method outside its
// stability region (its spin, drag or buoyancy heave rate), a fast body that could pass
// through what it can hit, or a torque-free body's rotational energy grown beyond
// WorldModel::energyGainLimit.
enum class StepCause { None, Spin, Drag, BuoyancyHeave, FastBody, EnergyGain };

// The cause in words: "spin", "drag", "buoyancy heave", "fast body",
// "rotational energy gain" ("" for None).
const char* causeName(StepCause cause);

struct StepResult {
  bool ok = true;
  int body = -1;      // when !ok: first body whose new state is not finite, or -1 when the
                      // adaptive method could not meet its tolerance or sub-steps would not do
  long substeps = 1;  // the sub-steps the step was split into, for `cause`
  StepCause cause = StepCause::None;
  double stableStep = 0.0;  // s, the largest step that cause allows (when cause is set)
  double energyGain = 0.0;  // when cause is EnergyGain: the body's relative gain it would reach
  // With stopAtImpact: s into the step at which a bouncing impact was located and
  // answered, the step ending there; < 0 when the step ran to its end.
  double impactAt = -1.0;
};

// Advances the world by one internal step h (s). On a non-finite result the step is
// not taken: Y stays as it was and the result names the body. With stopAtImpact, the
// step ends at the first bouncing impact it locates inside it (the impulse applied),
// and StepResult::impactAt says when (the FMI 3 FMU's early return).
StepResult step(const WorldModel& model, WorldData& data, double h, bool stopAtImpact = false);

// The largest ratio of two colliding bodies' masses that contacts are made for: a light
// body under a heavy one sinks into it by (M/m) g / omega^2 (omega = 2 pi 0.4 / h, the
// contact's stiffness between bodies), 1.55 mm at 1e3 and h = 1 ms.
constexpr double kMaxMassRatio = 1e3;

// What a scene whose colliding bodies' masses differ by more than kMaxMassRatio is told
// (the two bodies, the ratio and the sinking it gives at the solver step); empty when
// they do not.
std::string massRatioWarning(const WorldModel& model);

}  // namespace rigid
