#include "surface.h"

namespace rigid {

void finishSurface(Surface& s) {
  s.halfExtent = 0.5 * (s.max - s.min);
  s.R_WS = s.orientation.normalized().toRotationMatrix();
  s.centre = 0.5 * (s.max + s.min);  // the turn is about the centre, which stays put
}

}  // namespace rigid
