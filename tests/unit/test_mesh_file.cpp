// Mesh shapes: FILE.mesh.json read, checked and measured (src/mesh_file.h), in scenes,
// and colliding as hulls; against boxes worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "collision_detection.h"
#include "compound_shape.h"
#include "mesh_file.h"
#include "scene.h"

namespace {

using rigid::Mat3;
using rigid::Quat;
using rigid::Vec3;

// A folder of its own per test, removed after it.
class MeshFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() / ("rigid-mesh-" + std::string(info->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string folder() const { return dir_.string(); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(dir_ / name) << text; }
  std::filesystem::path dir_;
};

// The canonical file of the box from `lo` to `hi`: 8 vertices, 12 triangles wound
// outward, its hull the 6 faces (or `hullHi` as the hull's far corner).
std::string boxJson(const Vec3& lo, const Vec3& hi, const Vec3& hullHi) {
  auto corners = [](const Vec3& a, const Vec3& b) {
    std::string s;
    for (int i = 0; i < 8; ++i) {
      const Vec3 p((i & 1) ? b.x() : a.x(), (i & 2) ? b.y() : a.y(), (i & 4) ? b.z() : a.z());
      char buf[128];
      std::snprintf(buf, sizeof buf, "%s[%.17g,%.17g,%.17g]", i ? "," : "", p.x(), p.y(), p.z());
      s += buf;
    }
    return "[" + s + "]";
  };
  // Faces counter-clockwise seen from outside, by the corner bits (x 1, y 2, z 4).
  const char* quads = "[[0,2,3,1],[4,5,7,6],[0,1,5,4],[2,6,7,3],[0,4,6,2],[1,3,7,5]]";
  const char* tris =
      "[[0,2,3],[0,3,1],[4,5,7],[4,7,6],[0,1,5],[0,5,4],[2,6,7],[2,7,3],[0,4,6],[0,6,2],[1,3,7],[1,7,5]]";
  return std::string("{\"format\":\"rigidfmu-mesh\",\"version\":1,\"source\":\"box.stl\",\"vertices\":") +
         corners(lo, hi) + ",\"triangles\":" + tris + ",\"hull\":{\"vertices\":" + corners(lo, hullHi) +
         ",\"faces\":" + quads + "}}";
}
std::string boxJson(const Vec3& lo, const Vec3& hi) { return boxJson(lo, hi, hi); }

std::shared_ptr<const rigid::MeshShape> read(const std::string& folder, const std::string& file,
                                             const Vec3& scale = Vec3::Ones()) {
  std::string warning;
  return rigid::readMeshShape(folder, file, scale, "bodies[0].shape.file", warning);
}

void expectRefused(const std::string& folder, const std::string& file, const std::string& message) {
  try {
    read(folder, file);
    ADD_FAILURE() << file << ": not refused";
  } catch (const rigid::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

TEST_F(MeshFolder, ABoxOffTheOriginGivesItsVolumeCentreAndInertia) {
  write("box.stl.mesh.json", boxJson(Vec3(1, 2, 3), Vec3(1.4, 2.2, 3.1)));
  const auto m = read(folder(), "box.stl");
  const Vec3 size(0.4, 0.2, 0.1);
  EXPECT_NEAR(m->volume, size.prod(), 1e-15);
  EXPECT_LT((m->fileOrigin + Vec3(1.2, 2.1, 3.05)).norm(), 1e-12);  // the file's origin, seen from the centre
  const Vec3 sq = size.cwiseProduct(size);
  const Mat3 I =
      size.prod() / 12.0 * Vec3(sq.y() + sq.z(), sq.x() + sq.z(), sq.x() + sq.y()).asDiagonal().toDenseMatrix();
  EXPECT_LT((m->inertiaPerDensity - I).norm(), 1e-12 * I.norm());
  EXPECT_NEAR(m->hullVolume, m->volume, 1e-15);
  EXPECT_NEAR(m->halfThickness, 0.05, 1e-12);
  EXPECT_NEAR(m->boundingRadius, 0.5 * size.norm(), 1e-12);
  for (const Vec3& v : m->hull.vertices) EXPECT_LT((v.cwiseAbs() - 0.5 * size).norm(), 1e-12);
}

TEST_F(MeshFolder, AScaleStretchesTheSolidAlongEachAxis) {
  write("box.stl.mesh.json", boxJson(Vec3(0, 0, 0), Vec3(1, 1, 1)));
  const auto m = read(folder(), "box.stl", Vec3(0.4, 0.2, 0.1));
  EXPECT_NEAR(m->volume, 0.008, 1e-15);
  EXPECT_NEAR(m->inertiaPerDensity(0, 0), 0.008 / 12.0 * (0.04 + 0.01), 1e-15);
  EXPECT_NEAR(m->inertiaPerDensity(2, 2), 0.008 / 12.0 * (0.16 + 0.04), 1e-15);
}

TEST_F(MeshFolder, PathsThatLeaveTheScenesFolderAreRefused) {
  const std::string rule = "bodies[0].shape.file: must be a path inside the scene's folder";
  for (const char* file : {"../box.stl", "parts/../../box.stl", "/tmp/box.stl", "parts\\box.stl", "C:/box.stl", ""})
    expectRefused(folder(), file, rule);
}

TEST_F(MeshFolder, AMissingOrBrokenCanonicalFileIsRefusedNamingIt) {
  expectRefused(folder(), "box.stl", "bodies[0].shape.file: box.stl: no box.stl.mesh.json beside the scene");
  write("bad.stl.mesh.json", "{\"format\": \"rigidfmu-mesh\", \"version\": 1, \"vertices\": [[0, 0]]}");
  expectRefused(folder(), "bad.stl", "bodies[0].shape.file: bad.stl: a vertex must be 3 numbers");
  write("old.stl.mesh.json", "{\"format\": \"rigidfmu-mesh\", \"version\": 7}");
  expectRefused(folder(), "old.stl", "old.stl.mesh.json is not a \"rigidfmu-mesh\" file of version 1");
}

TEST_F(MeshFolder, AHullThatLeavesAVertexOutIsRefused) {
  write("box.stl.mesh.json", boxJson(Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(1, 1, 0.5)));
  expectRefused(folder(), "box.stl", "leaves part of the mesh outside: not its hull");
}

TEST_F(MeshFolder, ASceneReadsItsMeshesBesideItAndTakesMassFromTheDensity) {
  std::filesystem::create_directories(dir_ / "parts");
  write("parts/box.stl.mesh.json", boxJson(Vec3(0, 0, 0), Vec3(0.4, 0.2, 0.1)));
  write("scene.json", R"({"name": "m", "bodies": [{"name": "part", "density": 1000,
      "shape": {"type": "mesh", "file": "parts/box.stl"}}]})");
  const rigid::Scene s = rigid::loadSceneFile((dir_ / "scene.json").string());
  const rigid::BodyConstants& b = s.model.bodies[0];
  EXPECT_NEAR(b.mass, 8.0, 1e-12);
  EXPECT_NEAR(b.Ibody(0, 0), 8.0 / 12.0 * (0.04 + 0.01), 1e-12);
  EXPECT_NEAR(b.Ibody(1, 1), 8.0 / 12.0 * (0.16 + 0.01), 1e-12);
  EXPECT_NEAR(b.Ibody(2, 2), 8.0 / 12.0 * (0.16 + 0.04), 1e-12);
  EXPECT_TRUE(s.warnings.empty());
  // as text, without a folder, the mesh has nowhere to be read from
  try {
    rigid::parseScene(R"({"name": "m", "bodies": [{"name": "part", "mass": 1,
        "shape": {"type": "mesh", "file": "parts/box.stl"}}]})");
    ADD_FAILURE() << "not refused";
  } catch (const rigid::SceneError& e) {
    EXPECT_STREQ(e.what(), "bodies[0].shape.file: a mesh needs the scene's folder: read the scene from its file");
  }
}

TEST_F(MeshFolder, AMeshCubeOnTheFloorTouchesAtItsFourCornersAsTheBoxDoes) {
  write("cube.stl.mesh.json", boxJson(Vec3(-0.1, -0.1, -0.1), Vec3(0.1, 0.1, 0.1)));
  rigid::WorldModel m;
  rigid::BodyConstants mesh, box;
  mesh.shape.type = rigid::ShapeType::Mesh;
  mesh.shape.mesh = read(folder(), "cube.stl");
  box.shape.type = rigid::ShapeType::Box;
  box.shape.size = Vec3::Constant(0.2);
  m.bodies = {mesh, box};
  rigid::Surface floor;
  floor.min = Vec3(-5, -5, -1);
  floor.max = Vec3(5, 5, 0);
  rigid::finishSurface(floor);
  m.surfaces = {floor};
  std::vector<rigid::BodyState> Y(2);
  const Quat turn(Eigen::AngleAxisd(0.3, Vec3::UnitZ()));
  Y[0].X = Vec3(0, 0, 0.099), Y[0].q = turn;
  Y[1].X = Vec3(1, 0, 0.099), Y[1].q = turn;
  rigid::CollisionDetector detector(m, {true, true});
  std::vector<rigid::Contact> out;
  detector.detect(Y, 0.0, out);
  ASSERT_EQ(out.size(), 8u);
  for (int k = 0; k < 4; ++k) {  // the mesh's four points are the box's, moved by 1 m in x
    const rigid::Contact& c = out[k];
    const rigid::Contact& d = out[k + 4];
    EXPECT_EQ(c.a, 0);
    EXPECT_EQ(d.a, 1);
    EXPECT_NEAR(c.depth, 0.001, 1e-12);
    EXPECT_LT((c.normal - Vec3(0, 0, -1)).norm(), 1e-12);
    double nearest = 1e300;
    for (int j = 4; j < 8; ++j) nearest = std::min(nearest, (out[j].point - Vec3(1, 0, 0) - c.point).norm());
    EXPECT_LT(nearest, 1e-12);
    EXPECT_NEAR(c.patchRadius, d.patchRadius, 1e-12);
  }
}

}  // namespace

namespace {

// The inertia of a solid box of density 1 about its centre.
Mat3 boxInertia(const Vec3& size) {
  const Vec3 sq = size.cwiseProduct(size);
  return size.prod() / 12.0 * Vec3(sq.y() + sq.z(), sq.x() + sq.z(), sq.x() + sq.y()).asDiagonal().toDenseMatrix();
}

// The inertia of that box, centred at `at`, about `centre` (parallel axes).
Mat3 shifted(const Vec3& size, const Vec3& at, const Vec3& centre) {
  Vec3 d = at;
  d -= centre;
  return boxInertia(size) + size.prod() * (d.dot(d) * Mat3::Identity() - d * d.transpose());
}

TEST_F(MeshFolder, AnLCompoundOfABoxAndAMeshHasTheParallelAxisSum) {
  // an arm 0.2 x 0.1 x 0.1 m (primitive, centred at the origin) and a leg 0.1 x 0.1 x 0.1 m
  // (a mesh whose file puts its corner at its origin, placed at (-0.1, -0.05, 0.05))
  write("leg.stl.mesh.json", boxJson(Vec3(0, 0, 0), Vec3(0.1, 0.1, 0.1)));
  write("scene.json", R"({"name": "l", "bodies": [{"name": "ell", "density": 2,
      "shape": {"type": "compound", "parts": [
        {"shape": {"type": "box", "size": [0.2, 0.1, 0.1]}},
        {"shape": {"type": "mesh", "file": "leg.stl"}, "position": [-0.1, -0.05, 0.05]}]}}]})");
  const rigid::Scene scene = rigid::loadSceneFile((dir_ / "scene.json").string());
  const rigid::BodyConstants& b = scene.model.bodies[0];
  const rigid::CompoundShape& c = *b.shape.compound;
  // by hand: volumes 0.002 and 0.001 m^3, centres (0, 0, 0) and (-0.05, 0, 0.1)
  const Vec3 centre = (0.001 * Vec3(-0.05, 0, 0.1)) / 0.003;
  EXPECT_NEAR(b.mass, 2 * 0.003, 1e-15);
  EXPECT_LT((c.origin + centre).norm(), 1e-15);
  EXPECT_LT((c.parts[0].position - (Vec3(0, 0, 0) - centre)).norm(), 1e-15);
  EXPECT_LT((c.parts[1].position - (Vec3(-0.05, 0, 0.1) - centre)).norm(), 1e-15);
  const Mat3 I = 2.0 * (shifted(Vec3(0.2, 0.1, 0.1), Vec3(0, 0, 0), centre) +
                        shifted(Vec3(0.1, 0.1, 0.1), Vec3(-0.05, 0, 0.1), centre));
  EXPECT_LT((b.Ibody - I).norm(), 1e-12 * I.norm());
  EXPECT_NEAR(c.halfThickness, 0.05, 1e-15);
}

TEST_F(MeshFolder, ACompoundInACompoundOrInAMediumIsRefused) {
  EXPECT_THROW(
      {
        try {
          rigid::parseScene(R"({"name": "c", "bodies": [{"name": "c", "mass": 1, "shape": {"type": "compound",
              "parts": [{"shape": {"type": "compound", "parts": [{"shape": {"type": "sphere", "radius": 1}}]}}]}}]})");
        } catch (const rigid::SceneError& e) {
          EXPECT_STREQ(e.what(), "bodies[0].shape.parts[0].shape.type: a part cannot be a compound");
          throw;
        }
      },
      rigid::SceneError);
  try {
    rigid::parseScene(R"({"name": "c", "media": [{"name": "w", "type": "water", "min": [0, 0, 0], "max": [1, 1, 1]}],
        "bodies": [{"name": "c", "mass": 1, "shape": {"type": "compound", "parts": [{"shape": {"type": "sphere",
        "radius": 1}}]}}]})");
    ADD_FAILURE() << "not refused";
  } catch (const rigid::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("bodies[0].shape: a compound body in a scene with media: not yet"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
