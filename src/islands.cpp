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

void findIslands(const WorldModel& model, const std::vector<Contact>& contacts, Islands& islands) {
  const int n = static_cast<int>(model.bodies.size());
  auto isDriven = [&](int i) { return driven(model.bodies[i]); };
  std::vector<int>& root = islands.root;
  root.resize(n);
  std::iota(root.begin(), root.end(), 0);
  for (const Contact& c : contacts)
    if (c.b >= 0 && !isDriven(c.a) && !isDriven(c.b)) root[rootOf(root, c.a)] = rootOf(root, c.b);
  for (const JointConstants& j : model.joints)
    if (j.a >= 0 && !isDriven(j.a) && !isDriven(j.b)) root[rootOf(root, j.a)] = rootOf(root, j.b);
  for (int i = 0; i < n; ++i) root[i] = rootOf(root, i);
  islands.grounded.assign(n, 0);
  for (const Contact& c : contacts)
    if (c.b < 0) islands.grounded[root[c.a]] = 1;
  for (const Contact& c : contacts) {  // (a driven body meets no surface: c.b >= 0)
    if (c.b >= 0 && isDriven(c.a)) islands.grounded[root[c.b]] = 0;
    if (c.b >= 0 && isDriven(c.b)) islands.grounded[root[c.a]] = 0;
  }
  for (const JointConstants& j : model.joints) {  // a mechanism stays awake (a motor may turn it)
    if (j.a >= 0) islands.grounded[root[j.a]] = 0;
    islands.grounded[root[j.b]] = 0;
  }
}

}  // namespace rigid
