// Islands of bodies joined by contacts, by union-find: the contact solver's islands
// (contact_rows.h, groupRowsByIsland) and the sleeping islands (sleep.h) are found the
// same way.
#pragma once

#include <vector>

namespace rigid {

// The root of body i's island, halving the paths it walks.
inline int islandRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace rigid
