// Scenes of boxes on a floor and a world run step by step, as the FMU runs it: the
// builders shared by the contact solver's tests and the sleep tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "collision_detection.h"
#include "scene.h"
#include "world.h"

namespace test_scenes {

using json = nlohmann::json;
using rigid::Mat3;
using rigid::Quat;
using rigid::Vec3;

// The sanitizer build (scripts/sanitize.sh: GCC's -fsanitize=address defines the macro),
// where a test whose size only scales the work of smaller tests' code skips.
#ifdef __SANITIZE_ADDRESS__
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;

inline double radians(double degrees) { return degrees * kPi / 180.0; }

inline json floorSurface(double mus = 0.6, double muk = 0.6, double xi = 0.0) {
  return {{"name", "floor"},       {"min", {-20, -20, -1}},  {"max", {20, 20, 0}},
          {"staticFriction", mus}, {"kineticFriction", muk}, {"restitution", xi}};
}

// A slab 10 m x 2 m x 1 m centred at `centre` and turned by `turn` about it: a ramp.
inline json rampSurface(const Quat& turn, double mus, double muk, const Vec3& centre = Vec3::Zero()) {
  const Vec3 lo = centre - Vec3(5, 1, 0.5), hi = centre + Vec3(5, 1, 0.5);
  return {{"name", "ramp"},
          {"min", {lo.x(), lo.y(), lo.z()}},
          {"max", {hi.x(), hi.y(), hi.z()}},
          {"staticFriction", mus},
          {"kineticFriction", muk},
          {"restitution", 0.0},
          {"orientation", {turn.w(), turn.x(), turn.y(), turn.z()}}};
}

inline json box(const std::string& name, const Vec3& size, const Vec3& position, const Quat& q = Quat::Identity(),
                double xi = 0.0, double mus = 0.6, double muk = 0.6) {
  return {{"name", name},
          {"shape", {{"type", "box"}, {"size", {size.x(), size.y(), size.z()}}}},
          {"mass", 1.0},
          {"position", {position.x(), position.y(), position.z()}},
          {"orientation", {q.w(), q.x(), q.y(), q.z()}},
          {"restitution", xi},
          {"staticFriction", mus},
          {"kineticFriction", muk}};
}

// (A braced single object is that object to nlohmann::json, not a list: one is wrapped.)
// Sleep is off: the solver's tests judge its own rest, and a sleeping island would hide
// a pile that the solver leaves creeping slower than the sleep speed (test_sleep.cpp
// sets it on).
inline json sceneOf(const json& bodies, const json& surfaces, double step = 1e-3, const char* method = "rk4") {
  auto list = [](const json& j) { return j.is_array() ? j : json::array({j}); };
  return {{"name", "T"},
          {"solver", {{"method", method}, {"step", step}, {"sleep", false}}},
          {"bodies", list(bodies)},
          {"surfaces", list(surfaces)}};
}

// One world run step by step, as the FMU runs it.
struct Sim {
  explicit Sim(const json& scene) : model(rigid::parseScene(scene.dump()).model), data(rigid::initialData(model)) {}

  // Runs `seconds`; `each` (optional) is called after every step.
  template <class Each>
  void run(double seconds, Each each) {
    const long steps = std::lround(seconds / model.maxStep);
    for (long k = 0; k < steps; ++k) {
      const rigid::StepResult r = rigid::step(model, data, model.maxStep);
      ASSERT_TRUE(r.ok) << "step " << k << " refused (body " << r.body << ", " << rigid::causeName(r.cause) << ")";
      each();
    }
  }
  void run(double seconds) {
    run(seconds, [] {});
  }

  double fastest() const {
    double v = 0.0;
    for (const rigid::BodyAux& a : data.aux) v = std::max(v, a.V.norm());
    return v;
  }
  Mat3 R(int i) const { return data.Y[i].q.normalized().toRotationMatrix(); }

  // Mechanical energy (J): kinetic, rotational and potential in the scene's gravity.
  double energy() const {
    double e = 0.0;
    for (size_t i = 0; i < data.Y.size(); ++i) {
      const double m = model.bodies[i].mass;
      e += 0.5 * data.Y[i].P.squaredNorm() / m + 0.5 * data.aux[i].omega.dot(data.Y[i].L) -
           m * model.gravity.dot(data.Y[i].X);
    }
    return e;
  }

  // Deepest overlap of any touching pair or body and surface (m), freshly detected.
  double deepestOverlap() const {
    rigid::CollisionDetector probe(model, std::vector<bool>(model.bodies.size(), true));
    std::vector<rigid::Contact> contacts;
    probe.detect(data.Y, 0.0, contacts);
    double deepest = 0.0;
    for (const rigid::Contact& c : contacts) deepest = std::max({deepest, c.depth, c.pairOverlap});
    return deepest;
  }

  rigid::WorldModel model;
  rigid::WorldData data;
};

// Mechanical energy through a run of `seconds`: at its start and end, and the largest
// rise over one step (J).
struct EnergyRun {
  double start = 0.0, end = 0.0, worstRise = -1e300;
};
inline EnergyRun runWatchingEnergy(Sim& sim, double seconds) {
  EnergyRun e;
  e.start = e.end = sim.energy();
  sim.run(seconds, [&] {
    const double now = sim.energy();
    e.worstRise = std::max(e.worstRise, now - e.end);
    e.end = now;
  });
  std::printf("largest rise of one step %.3g J; %.3g J of %.3g J left\n", e.worstRise, e.end, e.start);
  return e;
}

// Runs `settle` s, then `seconds` more: the largest displacement of any body over the
// second run (m).
inline double driftAfterSettling(Sim& sim, double settle, double seconds) {
  sim.run(settle);
  const std::vector<rigid::BodyState> settled = sim.data.Y;
  sim.run(seconds);
  double drift = 0.0;
  for (size_t i = 0; i < settled.size(); ++i) drift = std::max(drift, (sim.data.Y[i].X - settled[i].X).norm());
  return drift;
}

constexpr double kEdge = 0.1;  // m, the cubes of stacks and piles

// n cubes set down in a column on the floor, each face on the one below.
inline json column(int n) {
  json bodies = json::array();
  for (int i = 0; i < n; ++i)
    bodies.push_back(box("c" + std::to_string(i), Vec3::Constant(kEdge), Vec3(0, 0, kEdge * (0.5 + i))));
  return bodies;
}

// The benchmark's pile (scripts/bench_scenes.py): columns of 0.1 m cubes 2 cm apart on
// a square grid, layers upwards, each tilted a little so that they land on edges.
inline json pile(int n, int side) {
  json bodies = json::array();
  const double gap = 0.02, pitch = kEdge + gap;
  for (int k = 0; k < n; ++k) {
    const int layer = k / (side * side), cell = k % (side * side), ix = cell / side, iy = cell % side;
    const Vec3 X((ix - 0.5 * (side - 1)) * pitch, (iy - 0.5 * (side - 1)) * pitch,
                 0.5 * kEdge + gap + layer * (pitch + gap));
    const Quat q = Quat(Eigen::AngleAxisd(0.05 * std::cos(2.3 * k), Vec3::UnitY())) *
                   Quat(Eigen::AngleAxisd(0.05 * std::sin(1.7 * k), Vec3::UnitX()));
    bodies.push_back(box("c" + std::to_string(k), Vec3::Constant(kEdge), X, q));
  }
  return bodies;
}

}  // namespace test_scenes
