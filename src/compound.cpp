#include <algorithm>
#include <limits>

#include "mesh_file.h"
#include "solid_mass.h"

namespace rigid {

std::shared_ptr<const CompoundShape> makeCompound(const std::vector<PlacedShape>& placed, const std::string&) {
  std::vector<PartMass> masses;  // per unit density, each about its own centre of mass
  auto compound = std::make_shared<CompoundShape>();
  for (const PlacedShape& p : placed) {
    ShapePart part;
    part.shape = p.shape;
    part.orientation = p.orientation.normalized();
    // a mesh's centre of mass lies at -fileOrigin from its file's origin
    part.position = p.shape.type == ShapeType::Mesh
                        ? Vec3(p.position - part.orientation.toRotationMatrix() * p.shape.mesh->fileOrigin)
                        : p.position;
    SolidMass solid;
    solid.volume = shapeVolume(p.shape);
    solid.inertia = solidInertia(p.shape, solid.volume);
    masses.push_back(placePart(solid, 1.0, part.position, part.orientation));
    compound->parts.push_back(part);
  }
  const PartMass whole = combineParts(masses);
  compound->origin = -whole.centre;
  compound->volume = whole.mass;
  compound->inertiaPerDensity = whole.inertia;
  compound->halfThickness = std::numeric_limits<double>::infinity();
  for (ShapePart& part : compound->parts) {
    part.position -= whole.centre;
    compound->halfThickness = std::min(compound->halfThickness, halfThickness(part.shape));
    compound->boundingRadius = std::max(compound->boundingRadius, part.position.norm() + boundingRadius(part.shape));
  }
  return compound;
}

}  // namespace rigid
