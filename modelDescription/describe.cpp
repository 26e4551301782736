// rigidfmu-describe SCENE.json OUT_DIR [--fmi 3]
// Checks a scene and writes OUT_DIR/modelDescription.xml (FMI 2.0, or 3.0 with --fmi 3), OUT_DIR/model_identifier
// (the scene's name, which names the FMU's binary) and OUT_DIR/modules (the mask of
// the physics modules the scene needs, src/modules.h) and OUT_DIR/warnings (notes for
// the user that break no rule, a line each: a mesh's hull much larger than its solid). Exit status 1 with the scene's
// error message on stderr when the scene breaks a rule.
#include <fstream>
#include <iostream>
#include <string>

#include "compound_shape.h"
#include "model_description_xml.h"
#include "modules.h"

namespace {

// A line per mesh or compound body: its file's (or compound's) origin in the body frame.
void writeFrames(const rigid::Scene& scene, const std::string& path) {
  std::ofstream out(path);
  out.precision(9);
  for (size_t i = 0; i < scene.model.bodies.size(); ++i) {
    const rigid::Shape& shape = scene.model.bodies[i].shape;
    if (shape.type != rigid::ShapeType::Mesh && shape.type != rigid::ShapeType::Compound) continue;
    const rigid::Vec3 o = shape.type == rigid::ShapeType::Mesh ? shape.mesh->fileOrigin : shape.compound->origin;
    out << "bodies[" << i << "] " << scene.model.bodies[i].name << ": the "
        << (shape.type == rigid::ShapeType::Mesh ? "file's" : "compound's") << " origin lies at (" << o.x() << ", "
        << o.y() << ", " << o.z() << ") m in the body frame (from the centre of mass)\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  const bool fmi3 = argc == 5 && std::string(argv[3]) == "--fmi" && std::string(argv[4]) == "3";
  const bool fmi2 = argc == 3 || (argc == 5 && std::string(argv[3]) == "--fmi" && std::string(argv[4]) == "2");
  if (!fmi2 && !fmi3) {
    std::cerr << "usage: " << argv[0] << " SCENE.json OUT_DIR [--fmi 2|3]\n";
    return 2;
  }
  try {
    const rigid::Scene scene = rigid::loadSceneFile(argv[1]);
    const std::string dir = argv[2];
    std::ofstream(dir + "/modelDescription.xml")
        << rigidfmu::modelDescriptionXml(scene, fmi3 ? rigidfmu::FmiVersion::Fmi3 : rigidfmu::FmiVersion::Fmi2);
    std::ofstream(dir + "/model_identifier") << scene.model.name;
    std::ofstream(dir + "/modules") << rigid::modulesNeeded(scene.model);
    std::ofstream warnings(dir + "/warnings");
    for (const std::string& w : scene.warnings) warnings << w << "\n";
    writeFrames(scene, dir + "/frames");
    return 0;
  } catch (const std::exception& e) {
    std::cerr << argv[1] << ": " << e.what() << "\n";
    return 1;
  }
}
