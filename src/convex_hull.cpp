#include <algorithm>
#include <utility>
#include <vector>

#include "mesh_shape.h"

namespace rigid {

bool addFace(ConvexHull& h, const std::vector<int>& loop) {
  Vec3 n = Vec3::Zero(), mean = Vec3::Zero();
  for (size_t k = 0; k < loop.size(); ++k) {
    n += h.vertices[loop[k]].cross(h.vertices[loop[(k + 1) % loop.size()]]);
    mean += h.vertices[loop[k]];
  }
  if (!(n.norm() > 0.0)) return false;
  n.normalize();
  if (h.faceStart.empty()) h.faceStart.push_back(0);
  h.faceVertex.insert(h.faceVertex.end(), loop.begin(), loop.end());
  h.faceStart.push_back(static_cast<int>(h.faceVertex.size()));
  h.faceNormal.push_back(n);
  h.faceOffset.push_back(n.dot(mean / static_cast<double>(loop.size())));
  return true;
}

void linkHull(ConvexHull& h) {
  const int n = static_cast<int>(h.vertices.size());
  std::vector<std::vector<int>> neighbours(n), faces(n);
  for (int f = 0; f < h.faceCount(); ++f) {
    for (int k = 0; k < h.faceSize(f); ++k) {
      const int a = h.faceVertex[h.faceStart[f] + k];
      const int b = h.faceVertex[h.faceStart[f] + (k + 1) % h.faceSize(f)];
      neighbours[a].push_back(b);
      neighbours[b].push_back(a);
      faces[a].push_back(f);
    }
  }
  auto flatten = [](std::vector<std::vector<int>>& lists, std::vector<int>& start, std::vector<int>& flat) {
    start.assign(1, 0);
    flat.clear();
    for (std::vector<int>& list : lists) {
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
      flat.insert(flat.end(), list.begin(), list.end());
      start.push_back(static_cast<int>(flat.size()));
    }
  };
  flatten(neighbours, h.neighbourStart, h.neighbour);
  flatten(faces, h.vertexFaceStart, h.vertexFace);
}

int supportVertex(const ConvexHull& h, const Vec3& d) {
  int best = 0;
  double most = h.vertices[0].dot(d);
  for (int at = -1; at != best;) {
    at = best;
    for (int k = h.neighbourStart[at]; k < h.neighbourStart[at + 1]; ++k) {
      const double along = h.vertices[h.neighbour[k]].dot(d);
      if (along > most) most = along, best = h.neighbour[k];
    }
  }
  return best;
}

}  // namespace rigid
