#include "islands.h"

#include <numeric>

namespace rigid {

namespace {

// The root of body i's island, halving the paths it walks.
int rootOf(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

void findIslands(const std::vector<Contact>& contacts, int n, Islands& islands) {
  std::vector<int>& root = islands.root;
  root.resize(n);
  std::iota(root.begin(), root.end(), 0);
  for (const Contact& c : contacts)
    if (c.b >= 0) root[rootOf(root, c.a)] = rootOf(root, c.b);
  for (int i = 0; i < n; ++i) root[i] = rootOf(root, i);
  islands.grounded.assign(n, 0);
  for (const Contact& c : contacts)
    if (c.b < 0) islands.grounded[root[c.a]] = 1;
}

}  // namespace rigid
