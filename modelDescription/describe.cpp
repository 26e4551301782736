// rigidfmu-describe SCENE.json OUT_DIR
// Checks a scene and writes OUT_DIR/modelDescription.xml, OUT_DIR/model_identifier
// (the scene's name, which names the FMU's binary) and OUT_DIR/modules (the mask of
// the physics modules the scene needs, src/modules.h). Exit status 1 with the scene's
// error message on stderr when the scene breaks a rule.
#include <fstream>
#include <iostream>

#include "model_description_xml.h"
#include "modules.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: " << argv[0] << " SCENE.json OUT_DIR\n";
    return 2;
  }
  try {
    const rigid::Scene scene = rigid::loadSceneFile(argv[1]);
    const std::string dir = argv[2];
    std::ofstream(dir + "/modelDescription.xml") << rigidfmu::modelDescriptionXml(scene);
    std::ofstream(dir + "/model_identifier") << scene.model.name;
    std::ofstream(dir + "/modules") << rigid::modulesNeeded(scene.model);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << argv[1] << ": " << e.what() << "\n";
    return 1;
  }
}
