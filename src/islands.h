// Islands: the sets of bodies that the step's contacts join (a surface joins none),
// found once a step by union-find, for sleep (sleep.h) to put to rest or keep awake
// whole. The constraint solver needs none: it sweeps every awake contact in one order,
// as Box2D v3's solver does (its islands too serve sleep alone).
#pragma once

#include <vector>

#include "collision_detection.h"

namespace rigid {

struct Islands {
  std::vector<int> root;       // per body: its island's root body
  std::vector<char> grounded;  // per root: the island touches a surface
};

// The islands of n bodies joined by `contacts`, into islands (its buffers reused).
void findIslands(const std::vector<Contact>& contacts, int n, Islands& islands);

}  // namespace rigid
