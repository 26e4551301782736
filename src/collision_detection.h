// Collision detection of one world instance: which bodies touch each other or a
// surface, where, along which normal and how deep. A sort and sweep finds the
// candidate pairs (broadphase.h), a separating-axis test and FCL the contact of each
// pair; face contacts (a box, a cylinder's end or side, a capsule's side against a
// box face) get the corners of their contact patch so that a resting body is held
// without rocking.
#pragma once

#include <memory>
#include <vector>

#include "broadphase.h"
#include "world.h"  // WorldModel (bodies, surfaces), BodyState

namespace rigid {

// One contact point between two bodies, or between a body and a surface.
struct Contact {
  int a = -1;                  // body index (always a body)
  int b = -1;                  // other body index, or -1 when the other is a surface
  int surface = -1;            // surface index when b == -1, else -1
  Vec3 point = Vec3::Zero();   // m, world frame: midway in the overlap (in the gap when depth < 0)
  Vec3 normal = Vec3::Zero();  // unit, world frame, FROM a TO b (from body a into the surface when
                               // b == -1): the direction along which b must move to separate
  double depth = 0.0;          // m, penetration depth; < 0 only with a margin: -gap
  // m: the translation of b along the normal that separates the pair, where the
  // detection knows it (box pairs: the overlap of their projections on the normal, by
  // the separating-axis test), else 0. A tilted box's corner beyond the other's face
  // counts there but not in the patch's depths.
  double pairOverlap = 0.0;
  // m: the mean distance from the centre of the pair's contact patch, under uniform
  // pressure, of the patch's area (every point of a face contact carries it): the lever
  // arm of friction against spin about the normal. 0.3826 a for a square face of side a,
  // 2/3 R for a disc, a quarter of a line's length; 0 for a single point.
  double patchRadius = 0.0;
};

// A touching pair's restitution xi and friction mu_s, mu_k: each the combination of its
// two partners' (contact_rules.h); and its rolling resistance, the larger of the two
// partners' (m: rolling is resisted by a moment of at most rolling lambda_N).
struct Coefficients {
  double xi = 0.0, mus = 0.0, muk = 0.0, rolling = 0.0;
};
Coefficients coefficientsOf(const WorldModel& model, const Contact& c);

// The sleeping bodies as detect() sees them: a flag per body, and their boxes.
struct Sleepers {
  const std::vector<char>& asleep;
  const FixedBoxes& boxes;
};

// Collision detection of one world instance: FCL geometry for every body that
// collides and every surface (a box, turned about its centre), and one broadphase
// (its kept sort order) per instance. No global state: many detectors run side by
// side in threads.
class CollisionDetector {
 public:
  // `collides[i]` false: body i takes no part (scene switch), unless
  // `meetsSurfaces[i]`: then it meets surfaces but no other body. Surfaces always
  // take part. `collides` and a non-empty `meetsSurfaces` must have one entry per
  // body (std::invalid_argument otherwise).
  CollisionDetector(const WorldModel& model, const std::vector<bool>& collides,
                    const std::vector<bool>& meetsSurfaces = {});
  ~CollisionDetector();
  CollisionDetector(CollisionDetector&&) noexcept;
  CollisionDetector& operator=(CollisionDetector&&) noexcept;

  // Contacts of the poses Y (X, q of every body; q need not be unit): updates the
  // transforms and AABBs, the broadphase, runs the narrowphase on candidate pairs and
  // REPLACES `out`, sorted by (a, bodies before surfaces, b or surface).
  // Body-body and body-surface pairs; surface-surface pairs are skipped. In a pair of
  // two bodies, a is the lower index.
  // Face contacts give several points (up to 4: the corners of the contact patch),
  // each with its own depth; other contacts one point.
  // `margin` (m, >= 0): pairs closer than this are reported too, with
  // depth = -distance (a gap); with margin 0 only touching or overlapping pairs.
  // With `profile`, the time of the broadphase and of the narrowphase is added to it.
  // `speculative` (m, > margin to take effect): pairs apart by less than this are
  // reported too, for the position correction to know what its moves could push into:
  // box pairs as ONE contact along their separating axis with depth = -(the gap along
  // it, a lower bound of their distance), other pairs as with the margin.
  // `sleepers` (or null): the sleeping bodies (sleep.h) are not in the sweep; only their
  // pairs with awake bodies are found, by asking their boxes (fixedBoxes(), built at
  // the poses they sleep in, which Y holds too).
  void detect(const std::vector<BodyState>& Y, double margin, std::vector<Contact>& out, StepProfile* profile = nullptr,
              double speculative = 0.0, const Sleepers* sleepers = nullptr);

  // The bounding boxes of the bodies asleep (per body) at their poses in Y, for detect().
  std::shared_ptr<const FixedBoxes> fixedBoxes(const std::vector<BodyState>& Y, const std::vector<char>& asleep);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rigid
