// The seed's answer to collisions: an impulse j along the contact normal, with
// restitution xi, only while the bodies approach; Coulomb friction impulses; and
// penetration removed by moving bodies apart (positions only: no energy is added).
#pragma once

#include <vector>

#include "collision_detection.h"
#include "contact_solver.h"

namespace rigid {

// Collision state of one world instance: the detector and the contacts it found.
struct CollisionCache {
  CollisionDetector detector;
  std::vector<Contact> contacts;
  std::vector<double> halfThickness;    // m, per body (0 for bodies that do not collide)
  std::vector<double> boundingRadius;   // m, per body (0 for bodies that do not collide)
  std::vector<double> travel;           // m, scratch: each body's reach in a step
  ContactScratchPtr solver;             // the manifold solver's buffers
};

// Whether some contact is an impact: overlapping while approaching faster than
// restingSpeed (m/s). The step then locates the instant of impact.
bool anyContactImpact(const WorldModel& model, const std::vector<Contact>& contacts,
                      const std::vector<BodyState>& Y, double restingSpeed);

// Impulses at every contact of Y until none approaches (Gauss-Seidel passes, so that
// a chain of touching bodies passes an impact on, as in Newton's cradle), then moves
// overlapping bodies apart along the normal in inverse proportion to their masses
// (separateOverlaps). h (s) is the step: approaches slower than a resting body's
// (restingNormalSpeed) are not bounced. `contacts` may hold pairs apart by up to
// `reach` (m, detected with a speculative distance): an inelastic pair (xi = 0) among
// them takes the impulse that keeps it from closing more than its gap in the next
// step; no move of the correction pushes them into each other, and bodies within
// reach of a surface's top face are not pushed into it. Adds each body's body-body
// contact points to count. Returns how far the correction can have closed the gap of
// a pair that was not among the contacts (m): from the reach on, such a pair may have
// been pushed into overlap, and the caller detects again.
double resolveContacts(const WorldModel& model, const std::vector<Contact>& contacts, double h, double reach,
                       std::vector<BodyState>& Y, std::vector<int>& count);

// The position correction alone (positions only, no impulse): overlaps of Y's contacts
// removed as resolveContacts does. Returns what resolveContacts returns.
double separateOverlaps(const WorldModel& model, const std::vector<Contact>& contacts, double reach,
                        std::vector<BodyState>& Y);

}  // namespace rigid
