// rigid-bench-core SCENES_DIR [Google Benchmark flags]: the core without FMI, on the
// scenes of scripts/bench_scenes.py.
//   BM_Free/<method>/<N>: one world step of N free tumbling bodies; the counter
//     ns_per_body_step is the time per step divided by N.
//   BM_Pile/<N>: a pile of N cubes falling on a floor, 1 s of simulated time (500
//     steps of 2 ms) per iteration from the same start; counters split the time into
//     integration, broadphase, narrowphase and response (the solve), and into the
//     step's stages (us_stage_<name>, world.h's Stage; WorldData::profile), and give
//     the deepest penetration seen (m) and the fastest body's speed at the end (m/s).
//   BM_PileWindows/<N>: the same pile (pile_<N>.json), 3 s of simulated time per
//     iteration: the CPU time of the first second (falling) and of the third (at rest,
//     after 2 s), each split into the phases' and the step stages' wall times
//     (<window>_ns_stage_<name>, <window>_runs_stage_<name>) with the constraint solver's
//     solves and the contact points they answered; the deepest overlap in the output
//     state, the fastest body's speed at 1 s and 3 s, and the bodies asleep at 3 s
//     (sleep.h; the scene's default rules).
//   BM_PileAwake/<N>: BM_PileWindows with sleep off (solver.sleep false): the solver
//     alone, every body awake to the end.
//   BM_PileWide/<N>: BM_PileWindows on pile_wide_<N>.json, N cubes in columns of the
//     pile of 100's height: growth from 100 cubes at equal height.
//   BM_Chain/<N>/<ms>: chain_<N>.json (N links hinged end to end, issue 41) swinging
//     down from horizontal for <ms> simulated milliseconds from rest, once per
//     iteration: the steps' CPU time (each step timed by this thread's CPU clock, the
//     probes outside) with the stages' wall times (swing_*), the joints' drift (the
//     largest distance between a joint's two anchor points, and angle between a hinge's
//     two axes, over joints and steps), the energy (kinetic + potential, J) at the start
//     and its largest departure, and the tip's position at the end.
//   BM_PileHulls/<N>: BM_PileWindows on pile_hulls_<N>.json (reports/mesh_scenes.py): the
//     pile of N cubes with each cube a convex mesh, a pebble of 100 hull vertices, falling
//     into a bin (a static mesh surface, an open box); the overlap between two pebbles is
//     the detector's contact depth. With the bin: the pebbles inside it at 3 s
//     (inside_3s) and the farthest hull vertex beyond its walls and below its floor
//     over 0-3 s (max_beyond_wall_m, max_below_floor_m).
//   BM_Narrow/<shape>/<pair>: the narrowphase of one pair (issue 42): CollisionDetector::
//     detect on narrow_<shape>.json (reports/mesh_scenes.py: two bodies of one shape, a
//     hull of N vertices or the cube beside them, and a floor), posed by narrowPoses:
//     "surface", the first body on the floor, its lowest point 1 mm below the floor's
//     top; "body", the second on the first, 1 mm into it, away from the floor. Each
//     call finds that one pair (its broadphase of 2-3 boxes included): the counters
//     ns_per_pair and contacts_per_pair, and the hull's vertices and faces.
#include <benchmark/benchmark.h>
#include <time.h>  // clock_gettime, CLOCK_THREAD_CPUTIME_ID (POSIX)

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "collision_cache.h"
#include "collision_detection.h"
#include "scene.h"
#include "world.h"

namespace {

std::string scenesDir;

rigid::Scene load(const std::string& file) { return rigid::loadSceneFile(scenesDir + "/" + file); }

double stageTime(const rigid::StepProfile& p, rigid::Stage stage) { return p.time[static_cast<int>(stage)]; }

// What a profile gained from `before` to `after`, added to `sum`.
void addProfile(rigid::StepProfile& sum, const rigid::StepProfile& before, const rigid::StepProfile& after) {
  for (int k = 0; k < rigid::kStageCount; ++k) {
    sum.time[k] += after.time[k] - before.time[k];
    sum.runs[k] += after.runs[k] - before.runs[k];
  }
  sum.broadphase += after.broadphase - before.broadphase;
  sum.narrowphase += after.narrowphase - before.narrowphase;
  sum.steps += after.steps - before.steps;
  sum.solves += after.solves - before.solves;
  sum.points += after.points - before.points;
}

void freeBodies(benchmark::State& state, rigid::Method method, int n) {
  rigid::Scene scene = load("free_" + std::to_string(n) + ".json");
  scene.model.method = method;
  scene.model.energyGainLimit = 0.0;  // explicit Euler is timed, not audited
  rigid::WorldData data = rigid::initialData(scene.model);
  for (auto _ : state) {
    const rigid::StepResult r = rigid::step(scene.model, data, scene.model.maxStep);
    benchmark::DoNotOptimize(r.ok);
  }
  state.counters["ns_per_body_step"] =
      benchmark::Counter(static_cast<double>(n) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["substeps"] = static_cast<double>(data.steps) / static_cast<double>(state.iterations());
}

// Deepest overlap (m): between cubes as the step's last detection found it (before the
// response moved them apart, so an upper bound), and of any cube's lowest corner below
// the floor's top face (z = 0) after the step. (FCL's contacts with the floor's top are
// left to the surface module, which answers them exactly: the geometry measures those.)
double deepestPenetration(const rigid::Scene& scene, const rigid::WorldData& data) {
  double deepest = 0.0;
  for (const rigid::Contact& c : data.collision->contacts)
    if (c.b >= 0) deepest = std::max(deepest, c.depth);
  for (size_t i = 0; i < data.Y.size(); ++i) {
    const rigid::Vec3 half = 0.5 * scene.model.bodies[i].shape.size;
    const double reach = data.aux[i].R.row(2).cwiseAbs().dot(half);
    deepest = std::max(deepest, reach - data.Y[i].X.z());
  }
  return deepest;
}

// Penetration depth (m) of two boxes: the shortest translation that separates them,
// which for convex polyhedra is the smallest overlap of their projections over the
// separating-axis candidates (3 + 3 face normals, 9 edge crossings). This is the
// benchmark's own measure, written apart from the detector's.
double boxPenetration(const rigid::Vec3& halfA, const rigid::Mat3& Ra, const rigid::Vec3& pa, const rigid::Vec3& halfB,
                      const rigid::Mat3& Rb, const rigid::Vec3& pb) {
  const rigid::Vec3 d = pb - pa;
  double depth = std::numeric_limits<double>::infinity();
  auto consider = [&](const rigid::Vec3& axis) {
    const double len = axis.norm();
    if (len < 1e-9) return;
    const rigid::Vec3 u = axis / len;
    const double reach = (Ra.transpose() * u).cwiseAbs().dot(halfA) + (Rb.transpose() * u).cwiseAbs().dot(halfB);
    depth = std::min(depth, reach - std::abs(u.dot(d)));
  };
  for (int i = 0; i < 3; ++i) consider(Ra.col(i)), consider(Rb.col(i));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) consider(Ra.col(i).cross(Rb.col(j)));
  return depth;
}

// The points of a body's shape whose hull it is, in the body frame: a mesh's hull
// vertices, a box's corners (the benchmarks' scenes have no other shapes).
std::vector<rigid::Vec3> shapePoints(const rigid::Shape& s) {
  if (s.type == rigid::ShapeType::Mesh) return s.mesh->hull.vertices;
  std::vector<rigid::Vec3> corners;
  for (int k = 0; k < 8; ++k)
    corners.push_back(0.5 * s.size.cwiseProduct(rigid::Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1)));
  return corners;
}

// Deepest overlap (m) in the state the step hands back (what the FMU outputs): the
// penetration depth of every pair a fresh detection of Y finds touching (a probe
// detector of the benchmark's own), and each cube's lowest corner below the floor's
// top face. MuJoCo's -contact.dist is of its state too. (A contact point's depth from
// one box's face can exceed the pair's penetration when the two are tilted: it is not
// how far they overlap.)
double deepestOverlapOfState(const rigid::Scene& scene, const rigid::WorldData& data, rigid::CollisionDetector& probe,
                             std::vector<rigid::Contact>& contacts) {
  probe.detect(data.Y, 0.0, contacts);
  double deepest = 0.0;
  for (const rigid::Contact& c : contacts) {
    if (c.b < 0 || c.depth <= 0.0) continue;
    const rigid::BodyConstants& a = scene.model.bodies[c.a];
    const rigid::BodyConstants& b = scene.model.bodies[c.b];
    if (a.shape.type != rigid::ShapeType::Box || b.shape.type != rigid::ShapeType::Box) {
      deepest = std::max(deepest, c.depth);  // a mesh's pairs (pile_hulls_<N>): the detector's depth
      continue;
    }
    deepest = std::max(deepest, boxPenetration(0.5 * a.shape.size, data.aux[c.a].R, data.Y[c.a].X, 0.5 * b.shape.size,
                                               data.aux[c.b].R, data.Y[c.b].X));
  }
  for (size_t i = 0; i < data.Y.size(); ++i)  // the lowest corner or hull vertex
    for (const rigid::Vec3& p : shapePoints(scene.model.bodies[i].shape))
      deepest = std::max(deepest, -(data.Y[i].X + data.aux[i].R * p).z());
  return deepest;
}

// The pile's bin (pile_hulls_<N>.json: its first surface a mesh, an open box): the
// bodies whose centre is inside the box its triangles bound (in x and y, above its
// floor: open at the top), and how far the farthest hull vertex lies beyond a wall and
// below the floor (m). Zeros when the first surface is not a mesh.
struct BinCheck {
  double inside = 0.0, wall = 0.0, floor = 0.0;
};
BinCheck binCheck(const rigid::Scene& scene, const rigid::WorldData& data) {
  BinCheck out;
  if (scene.model.surfaces.empty() || !scene.model.surfaces[0].mesh) return out;
  const rigid::Vec3 lo = scene.model.surfaces[0].min, hi = scene.model.surfaces[0].max;
  for (size_t i = 0; i < data.Y.size(); ++i) {
    const rigid::Vec3& X = data.Y[i].X;
    if (X.x() > lo.x() && X.x() < hi.x() && X.y() > lo.y() && X.y() < hi.y() && X.z() > lo.z()) out.inside += 1.0;
    for (const rigid::Vec3& p : shapePoints(scene.model.bodies[i].shape)) {
      const rigid::Vec3 w = X + data.aux[i].R * p;
      out.wall = std::max({out.wall, lo.x() - w.x(), w.x() - hi.x(), lo.y() - w.y(), w.y() - hi.y()});
      out.floor = std::max(out.floor, lo.z() - w.z());
    }
  }
  return out;
}

void binCounters(benchmark::State& state, const rigid::Scene& scene, const BinCheck& bin) {
  if (scene.model.surfaces.empty() || !scene.model.surfaces[0].mesh) return;
  state.counters["inside_3s"] = bin.inside;
  state.counters["max_beyond_wall_m"] = bin.wall;
  state.counters["max_below_floor_m"] = bin.floor;
}

void pile(benchmark::State& state, int n) {
  const rigid::Scene scene = load("pile_" + std::to_string(n) + ".json");
  const double h = scene.model.maxStep;
  const int steps = static_cast<int>(1.0 / h + 0.5);
  rigid::StepProfile total;
  double deepest = 0.0, deepestOfState = 0.0;
  double fastest = 0.0;
  long ok = 0;
  rigid::CollisionDetector probe(scene.model, std::vector<bool>(scene.model.bodies.size(), true));
  std::vector<rigid::Contact> probed;
  for (auto _ : state) {
    state.PauseTiming();
    rigid::WorldData data = rigid::initialData(scene.model);
    data.profiling = true;
    state.ResumeTiming();
    for (int k = 0; k < steps; ++k) {
      if (!rigid::step(scene.model, data, h).ok) break;
      ++ok;
      // the contacts of the last detection: those after this step's response (a probe
      // of the benchmark, not part of the step: kept out of the timed region)
      state.PauseTiming();
      deepest = std::max(deepest, deepestPenetration(scene, data));
      deepestOfState = std::max(deepestOfState, deepestOverlapOfState(scene, data, probe, probed));
      state.ResumeTiming();
    }
    state.PauseTiming();
    // how settled the pile is at the end: the fastest body's speed (m/s); MuJoCo's
    // figure (scripts/bench_peers.py) is the same
    for (const rigid::BodyAux& a : data.aux) fastest = std::max(fastest, a.V.norm());
    state.ResumeTiming();
    addProfile(total, rigid::StepProfile{}, data.profile);
  }
  const double runs = static_cast<double>(state.iterations());
  const double perStep = 1e-3 / (runs * steps);  // ns summed over runs -> us per step
  state.counters["us_integration"] = stageTime(total, rigid::Stage::Integrate) * perStep;
  state.counters["us_broadphase"] = total.broadphase * perStep;
  state.counters["us_narrowphase"] = total.narrowphase * perStep;
  state.counters["us_response"] = stageTime(total, rigid::Stage::Solve) * perStep;
  for (int k = 0; k < rigid::kStageCount; ++k)
    state.counters[std::string("us_stage_") + rigid::stageName(static_cast<rigid::Stage>(k))] = total.time[k] * perStep;
  state.counters["internal_steps"] = static_cast<double>(total.steps) / runs;
  state.counters["steps_ok"] = static_cast<double>(ok) / runs;
  state.counters["max_penetration_m"] = deepest;
  state.counters["max_overlap_state_m"] = deepestOfState;
  state.counters["max_speed_end_mps"] = fastest;
  state.counters["sim_seconds"] = steps * h;
}

// CPU seconds of this thread: the clock Google Benchmark's CPU time reads on Linux, so
// that a window timed here and BM_Pile's timed second are the same kind of figure.
double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// One timed window of BM_PileWindows (a simulated second), summed over the runs: the
// steps' CPU and wall time, and what WorldData::profile gained over them. The profile
// reads the wall clock, so the stages are shares of the steps' wall time.
struct Window {
  double cpu = 0.0;   // s
  double wall = 0.0;  // ns, steady_clock: the profile's clock
  rigid::StepProfile profile;
  long steps = 0;
  void add(double cpuSeconds, double wallNs, const rigid::StepProfile& before, const rigid::StepProfile& after) {
    cpu += cpuSeconds;
    wall += wallNs;
    addProfile(profile, before, after);
    ++steps;
  }
};

void windowCounters(benchmark::State& state, const std::string& name, const Window& w, double runs) {
  // per run: the window is one simulated second, so its CPU time is the time per
  // simulated second; the stages stay in ns so that the report (performance.py) takes
  // their shares of the wall time from the same (median) figures and "other" is the
  // rest of it
  state.counters[name + "_cpu_s"] = w.cpu / runs;
  state.counters[name + "_wall_ns"] = w.wall / runs;
  state.counters[name + "_ns_integration"] = stageTime(w.profile, rigid::Stage::Integrate) / runs;
  state.counters[name + "_ns_broadphase"] = w.profile.broadphase / runs;
  state.counters[name + "_ns_narrowphase"] = w.profile.narrowphase / runs;
  state.counters[name + "_ns_response"] = stageTime(w.profile, rigid::Stage::Solve) / runs;
  for (int k = 0; k < rigid::kStageCount; ++k) {  // the step's stages (world.h), each with its runs
    const std::string stage = rigid::stageName(static_cast<rigid::Stage>(k));
    state.counters[name + "_ns_stage_" + stage] = w.profile.time[k] / runs;
    state.counters[name + "_runs_stage_" + stage] = static_cast<double>(w.profile.runs[k]) / runs;
  }
  state.counters[name + "_steps"] = static_cast<double>(w.steps) / runs;
  state.counters[name + "_solves"] = static_cast<double>(w.profile.solves) / runs;
  // the solver's work: its sub-steps and relax passes are fixed, so what a solve costs
  // grows with the points it answers (0 when every island is asleep)
  state.counters[name + "_points_per_solve"] =
      w.profile.solves ? static_cast<double>(w.profile.points) / static_cast<double>(w.profile.solves) : 0.0;
}

// The pile of BM_Pile over 3 simulated seconds from the same start. BM_Pile's first
// second (falling, impacts) is only half the story: the third second, after 2 s, times
// the pile at rest, where the solver's warm start and sleeping islands are meant to
// pay. Each window is timed
// step by step with this thread's CPU clock, the probes outside it; the State's own
// timed region is the first second (as BM_Pile's), so the console's CPU column reads
// like BM_Pile's, but the report takes the windows' counters.
void pileWindows(benchmark::State& state, const std::string& file, bool sleep) {
  rigid::Scene scene = load(file);
  scene.model.sleep.enabled = sleep;
  const double h = scene.model.maxStep;
  const int perSecond = static_cast<int>(1.0 / h + 0.5);
  const int steps = 3 * perSecond;
  Window fall, rest;
  double deepest = 0.0, deepestAtRest = 0.0, fastest1 = 0.0, fastest3 = 0.0, asleep3 = 0.0;
  BinCheck bin;  // the bin's (BM_PileHulls): inside at 3 s, farthest out over 0-3 s
  long ok = 0;
  rigid::CollisionDetector probe(scene.model, std::vector<bool>(scene.model.bodies.size(), true));
  std::vector<rigid::Contact> probed;
  auto fastest = [](const rigid::WorldData& data) {
    double v = 0.0;
    for (const rigid::BodyAux& a : data.aux) v = std::max(v, a.V.norm());
    return v;
  };
  for (auto _ : state) {
    state.PauseTiming();
    rigid::WorldData data = rigid::initialData(scene.model);
    data.profiling = true;
    state.ResumeTiming();
    bool timing = true;  // the State's timer: on only for the first second's steps
    for (int k = 0; k < steps; ++k) {
      Window* window = k < perSecond ? &fall : k >= 2 * perSecond ? &rest : nullptr;
      const rigid::StepProfile before = data.profile;
      const double cpu0 = threadCpuSeconds();
      const auto wall0 = std::chrono::steady_clock::now();
      const bool stepped = rigid::step(scene.model, data, h).ok;
      const double wallNs = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - wall0).count();
      const double cpu = threadCpuSeconds() - cpu0;
      if (timing) state.PauseTiming(), timing = false;
      if (!stepped) break;
      ++ok;
      if (window) window->add(cpu, wallNs, before, data.profile);
      // probes of the benchmark, not part of the step: out of both timed regions;
      // seconds 1-2 let the pile settle, untimed
      const double overlap = deepestOverlapOfState(scene, data, probe, probed);
      deepest = std::max(deepest, overlap);
      if (window == &rest) deepestAtRest = std::max(deepestAtRest, overlap);
      if (k + 1 == perSecond) fastest1 = std::max(fastest1, fastest(data));
      if (k + 1 == steps) fastest3 = std::max(fastest3, fastest(data)), asleep3 = data.sleep.sleeping;
      const BinCheck now = binCheck(scene, data);
      bin = {now.inside, std::max(bin.wall, now.wall), std::max(bin.floor, now.floor)};
      if (k + 1 < perSecond) state.ResumeTiming(), timing = true;
    }
    if (!timing) state.ResumeTiming();
  }
  const double runs = static_cast<double>(state.iterations());
  windowCounters(state, "fall", fall, runs);
  windowCounters(state, "rest", rest, runs);
  state.counters["steps_ok"] = static_cast<double>(ok) / runs;
  state.counters["steps_planned"] = steps;
  state.counters["max_overlap_state_m"] = deepest;
  state.counters["max_overlap_rest_m"] = deepestAtRest;
  state.counters["max_speed_1s_mps"] = fastest1;
  state.counters["max_speed_3s_mps"] = fastest3;
  state.counters["asleep_3s"] = asleep3;
  binCounters(state, scene, bin);
}

// A joint's anchor on body `i` (-1: the world, whose frame is the world frame), in the
// world frame; and a body frame's vector in the world frame.
rigid::Vec3 anchorOf(const rigid::WorldData& data, int i, const rigid::Vec3& local) {
  return i < 0 ? local : rigid::Vec3(data.Y[i].X + data.aux[i].R * local);
}
rigid::Vec3 axisOf(const rigid::WorldData& data, int i, const rigid::Vec3& local) {
  return i < 0 ? local : rigid::Vec3(data.aux[i].R * local);
}

// Kinetic + potential energy (J) of the bodies, the potential zero at the origin.
double energyOf(const rigid::WorldModel& model, const rigid::WorldData& data) {
  double e = 0.0;
  for (size_t i = 0; i < data.Y.size(); ++i) {
    const rigid::BodyConstants& b = model.bodies[i];
    const rigid::BodyAux& a = data.aux[i];
    e += 0.5 * b.mass * a.V.squaredNorm() + 0.5 * a.omega.dot(data.Y[i].L) - b.mass * model.gravity.dot(data.Y[i].X);
  }
  return e;
}

void chain(benchmark::State& state, const std::string& file, int milliseconds) {
  const rigid::Scene scene = load(file);
  const rigid::WorldModel& model = scene.model;
  const double h = model.maxStep;
  const int steps = static_cast<int>(1e-3 * milliseconds / h + 0.5);
  Window swing;
  double drift = 0.0, twist = 0.0, e0 = 0.0, worst = 0.0, endGain = 0.0, fastest = 0.0;
  rigid::Vec3 tip = rigid::Vec3::Zero();
  long ok = 0;
  for (auto _ : state) {
    // the State's timer stays paused: the report reads the steps' own CPU time (swing_*)
    state.PauseTiming();
    rigid::WorldData data = rigid::initialData(model);
    data.profiling = true;
    e0 = energyOf(model, data);
    for (int k = 0; k < steps; ++k) {
      const rigid::StepProfile before = data.profile;
      const double cpu0 = threadCpuSeconds();
      const auto wall0 = std::chrono::steady_clock::now();
      const bool stepped = rigid::step(model, data, h).ok;
      const double wallNs = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - wall0).count();
      const double cpu = threadCpuSeconds() - cpu0;
      if (!stepped) break;
      ++ok;
      swing.add(cpu, wallNs, before, data.profile);
      // probes of the benchmark, not part of the step: out of the timed steps
      for (const rigid::JointConstants& j : model.joints) {
        drift = std::max(drift, (anchorOf(data, j.b, j.anchorB) - anchorOf(data, j.a, j.anchorA)).norm());
        if (j.type == rigid::JointType::Revolute) {
          const rigid::Vec3 u = axisOf(data, j.a, j.axisA), v = axisOf(data, j.b, j.axisB);
          twist = std::max(twist, std::atan2(u.cross(v).norm(), u.dot(v)));
        }
      }
      const double gain = energyOf(model, data) - e0;
      worst = std::max(worst, std::abs(gain));
      endGain = gain;
      for (const rigid::BodyAux& a : data.aux) fastest = std::max(fastest, a.V.norm());
    }
    const rigid::JointConstants& last = model.joints.back();
    tip = anchorOf(data, last.b, -last.anchorB);  // the last link's free end: its hinge's mirror
    state.ResumeTiming();
  }
  const double runs = static_cast<double>(state.iterations());
  windowCounters(state, "swing", swing, runs);
  state.counters["steps_ok"] = static_cast<double>(ok) / runs;
  state.counters["steps_planned"] = steps;
  state.counters["sim_seconds"] = steps * h;
  state.counters["step_s"] = h;
  state.counters["joints"] = static_cast<double>(model.joints.size());
  state.counters["max_drift_m"] = drift;
  state.counters["max_axis_drift_rad"] = twist;
  state.counters["energy_start_j"] = e0;
  state.counters["max_energy_error_j"] = worst;
  state.counters["energy_error_end_j"] = endGain;
  state.counters["max_speed_mps"] = fastest;
  state.counters["tip_x_m"] = tip.x();
  state.counters["tip_z_m"] = tip.z();
}

// The point of the shape farthest along world direction d, relative to the centre of
// mass, in the world frame, at orientation q.
rigid::Vec3 extremePoint(const rigid::Shape& s, const rigid::Quat& q, const rigid::Vec3& d) {
  const rigid::Mat3 R = q.toRotationMatrix();
  const std::vector<rigid::Vec3> points = shapePoints(s);
  rigid::Vec3 best = R * points.front();
  for (const rigid::Vec3& p : points)
    if ((R * p).dot(d) > best.dot(d)) best = R * p;
  return best;
}

// The poses of BM_Narrow's two bodies. A hull is turned by a rotation of no symmetry
// (the second otherwise than the first); a cube stays square to the floor, as in a pile
// at rest (a face patch of four points). "surface": the first body on the floor, its
// lowest point 1 mm below z = 0, the second far above. "body": the first 1 m up, the
// second above it, its lowest point 1 mm below the first's highest; hulls are shifted
// sideways so that those two points lie on one vertical (a hull's highest vertex is off
// its centre), cubes stand centre over centre.
void narrowPoses(const rigid::WorldModel& model, bool onSurface, std::vector<rigid::BodyState>& Y) {
  const rigid::Shape& a = model.bodies[0].shape;
  const rigid::Shape& b = model.bodies[1].shape;
  const bool hull = a.type == rigid::ShapeType::Mesh;
  const rigid::Vec3 up = rigid::Vec3::UnitZ();
  const double overlap = 1e-3;
  Y[0].q = hull ? rigid::Quat(Eigen::AngleAxisd(0.7, rigid::Vec3(1, 2, 3).normalized())) : rigid::Quat::Identity();
  Y[1].q = hull ? rigid::Quat(Eigen::AngleAxisd(2.1, rigid::Vec3(-2, 1, 0.5).normalized())) : rigid::Quat::Identity();
  if (onSurface) {
    Y[0].X = rigid::Vec3(0, 0, -extremePoint(a, Y[0].q, -up).z() - overlap);
    Y[1].X = rigid::Vec3(0, 0, 10.0);
    return;
  }
  Y[0].X = rigid::Vec3(0, 0, 1.0);
  const rigid::Vec3 top = Y[0].X + extremePoint(a, Y[0].q, up);
  const rigid::Vec3 low = extremePoint(b, Y[1].q, -up);
  Y[1].X = rigid::Vec3(hull ? top.x() - low.x() : 0.0, hull ? top.y() - low.y() : 0.0, top.z() - low.z() - overlap);
}

void narrow(benchmark::State& state, const std::string& file, bool onSurface) {
  const rigid::Scene scene = load(file);
  rigid::WorldData data = rigid::initialData(scene.model);
  narrowPoses(scene.model, onSurface, data.Y);
  // the surface case: the second body takes no part, so the pair is the first's with the floor
  rigid::CollisionDetector detector(scene.model, {true, !onSurface});
  std::vector<rigid::Contact> contacts;
  for (auto _ : state) {
    detector.detect(data.Y, 0.0, contacts);
    benchmark::DoNotOptimize(contacts.data());
  }
  if (contacts.empty()) state.SkipWithError("the posed pair does not touch");
  state.counters["ns_per_pair"] = benchmark::Counter(static_cast<double>(state.iterations()),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["contacts_per_pair"] = static_cast<double>(contacts.size());
  const rigid::Shape& s = scene.model.bodies[0].shape;
  state.counters["hull_vertices"] = s.mesh ? static_cast<double>(s.mesh->hull.vertices.size()) : 8.0;
  state.counters["hull_faces"] = s.mesh ? static_cast<double>(s.mesh->hull.faceCount()) : 6.0;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: rigid-bench-core SCENES_DIR [benchmark flags]\n"
                 "  (scenes: .venv/bin/python scripts/bench_scenes.py SCENES_DIR)\n");
    return 2;
  }
  scenesDir = argv[1];
  for (const rigid::MethodInfo& m : rigid::methods())
    for (int n : {1, 10, 100, 1000, 10000})
      benchmark::RegisterBenchmark(("BM_Free/" + std::string(m.name) + "/" + std::to_string(n)).c_str(), freeBodies,
                                   m.method, n);
  for (int n : {10, 100, 1000})
    benchmark::RegisterBenchmark(("BM_Pile/" + std::to_string(n)).c_str(), pile, n)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
  // sleep on with the scene's rules (the default), and sleep off: the solver alone
  for (int n : {10, 100, 1000})
    for (bool sleep : {true, false})
      benchmark::RegisterBenchmark(((sleep ? "BM_PileWindows/" : "BM_PileAwake/") + std::to_string(n)).c_str(),
                                   pileWindows, "pile_" + std::to_string(n) + ".json", sleep)
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
  // the wide pile's count: bench.py's WIDE_PILE
  benchmark::RegisterBenchmark("BM_PileWide/1024", pileWindows, std::string("pile_wide_1024.json"), true)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1);
  // the chain (reports/scenes.py's CHAIN_LINKS): 0.2 s for --quick, 2 s for the report
  for (int ms : {200, 2000})
    benchmark::RegisterBenchmark(("BM_Chain/100/" + std::to_string(ms)).c_str(), chain, std::string("chain_100.json"),
                                 ms)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
  // the pile of pebbles (reports/mesh_scenes.py's PILE_COUNTS)
  benchmark::RegisterBenchmark("BM_PileHulls/100", pileWindows, std::string("pile_hulls_100.json"), true)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1);
  // the narrowphase of one pair: hulls of reports/mesh_scenes.py's HULL_VERTICES, and the cube
  std::vector<std::string> shapes{"cube"};
  for (int n : {100, 300, 1000}) shapes.push_back("hull_" + std::to_string(n));
  for (const std::string& shape : shapes)
    for (bool onSurface : {true, false})
      benchmark::RegisterBenchmark(("BM_Narrow/" + shape + (onSurface ? "/surface" : "/body")).c_str(), narrow,
                                   "narrow_" + shape + ".json", onSurface);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
