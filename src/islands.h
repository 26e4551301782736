// Islands: the sets of bodies that the step's contacts join (a surface or a driven
// body joins none), found once a step by union-find, for sleep (sleep.h) to put to
// rest or keep awake whole. A joint joins its two bodies' islands, and an island that
// holds a joint never sleeps. The constraint solver needs none: it sweeps every awake
// contact in one order, as Box2D v3's solver does (its islands too serve sleep alone).
#pragma once

#include <vector>

#include "collision_detection.h"

namespace rigid {

struct Islands {
  std::vector<int> root;       // per body: its island's root body
  std::vector<char> grounded;  // per root: the island rests on a surface and on no driven body
};

// The islands of the model's bodies joined by `contacts`, into islands (its buffers
// reused). A driven body, like a surface, joins no island; one that rests on a driven
// body is not grounded, since that body may move at any time: it stays awake.
void findIslands(const WorldModel& model, const std::vector<Contact>& contacts, Islands& islands);

}  // namespace rigid
