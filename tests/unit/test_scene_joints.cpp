// The scene's joints[]: what is read into each body's frame, and what is refused, with
// the field it names.
#include <gtest/gtest.h>

#include <string>

#include "scene.h"

namespace {

// Two boxes, "a" at (0, 0, -1) turned a quarter about z and "b" at (1, 0, -1), and the
// joints `joints` (the inside of the array).
std::string sceneWith(const std::string& joints) {
  return R"({"name": "S", "bodies": [
    {"name": "a", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "mass": 1.0, "position": [0, 0, -1],
     "orientation": [0.7071067811865476, 0, 0, 0.7071067811865476]},
    {"name": "b", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "mass": 1.0, "position": [1, 0, -1]}],
    "joints": [)" +
         joints + "]}";
}

// The message of the SceneError that the joints raise, or "(accepted)".
std::string refusal(const std::string& joints) {
  try {
    rigid::parseScene(sceneWith(joints));
  } catch (const rigid::SceneError& e) {
    return e.what();
  }
  return "(accepted)";
}

const std::string kHinge = R"({"name": "h", "type": "revolute", "bodies": ["a", "b"], "anchor": [0.5, 0, -1], )";

}  // namespace

TEST(SceneJoints, AWorldAnchorAndAxisAreTurnedIntoEachBodysFrame) {
  const rigid::WorldModel m = rigid::parseScene(sceneWith(kHinge + R"("axis": [0, 2, 0]})")).model;
  ASSERT_EQ(m.joints.size(), 1u);
  const rigid::JointConstants& j = m.joints[0];
  EXPECT_EQ(j.a, 0);
  EXPECT_EQ(j.b, 1);
  // a is turned +90 deg about z: the world's +x is its -y, the world's +y its +x
  EXPECT_NEAR((j.anchorA - rigid::Vec3(0, -0.5, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((j.anchorB - rigid::Vec3(-0.5, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((j.axisA - rigid::Vec3(1, 0, 0)).norm(), 0.0, 1e-15);  // normalised
  EXPECT_NEAR((j.axisB - rigid::Vec3(0, 1, 0)).norm(), 0.0, 1e-15);
  EXPECT_FALSE(j.collide);
  EXPECT_FALSE(j.motor || j.spring || j.limited);
}

TEST(SceneJoints, ADistanceJointsLengthIsTheStartDistanceUnlessGiven) {
  const std::string rod = R"({"name": "r", "type": "distance", "bodies": ["world", "b"], "anchors": [[1, 0, 2], )";
  EXPECT_DOUBLE_EQ(rigid::parseScene(sceneWith(rod + "[0, 0, 0]]}")).model.joints[0].length, 3.0);
  const rigid::JointConstants rope =
      rigid::parseScene(sceneWith(rod + R"([0, 0, 0]], "length": 2.5, "rope": true})")).model.joints[0];
  EXPECT_EQ(rope.a, -1);
  EXPECT_DOUBLE_EQ(rope.length, 2.5);
  EXPECT_TRUE(rope.rope);
}

TEST(SceneJoints, AJointToAnUnknownBodyIsRefusedNamingTheField) {
  EXPECT_EQ(refusal(R"({"name": "h", "type": "fixed", "bodies": ["a", "ghost"], "anchor": [0, 0, 0]})"),
            "joints[0].bodies[1]: no body is named \"ghost\"");
  EXPECT_EQ(refusal(R"({"name": "h", "type": "fixed", "bodies": ["b", "world"], "anchor": [0, 0, 0]})"),
            "joints[0].bodies[1]: only the first body may be \"world\"");
  EXPECT_EQ(refusal(R"({"name": "h", "type": "fixed", "bodies": ["a", "a"], "anchor": [0, 0, 0]})"),
            "joints[0].bodies: a joint joins two different bodies");
}

TEST(SceneJoints, AZeroAxisIsRefusedNamingTheField) {
  EXPECT_EQ(refusal(kHinge + R"("axis": [0, 0, 0]})"), "joints[0].axis: must not be zero");
  EXPECT_EQ(refusal(kHinge.substr(0, kHinge.find("\"anchor\"")) +
                    R"("anchors": [[0, 0, 0], [0, 0, 0]], "axes": [[0, 0, 1], [0, 0, 0]]})"),
            "joints[0].axes: must not be zero");
}

TEST(SceneJoints, ALimitsLowerAboveItsUpperIsRefusedNamingTheField) {
  EXPECT_EQ(refusal(kHinge + R"("axis": [0, 1, 0], "limits": [0.5, -0.5]})"),
            "joints[0].limits: lower (0.5) must be <= upper (-0.5)");
}

TEST(SceneJoints, FieldsThatTheTypeHasNotAreRefused) {
  EXPECT_EQ(
      refusal(R"({"name": "h", "type": "spherical", "bodies": ["a", "b"], "anchor": [0, 0, 0], "axis": [1, 0, 0]})"),
      "joints[0].axis: only revolute and prismatic joints have an axis");
  EXPECT_EQ(refusal(R"({"name": "h", "type": "fixed", "bodies": ["a", "b"], "anchor": [0, 0, 0], "limits": [0, 1]})"),
            "joints[0].limits: a spherical or fixed joint has no coordinate to limit, drive or spring");
  EXPECT_EQ(refusal(kHinge + R"("axis": [0, 1, 0], "length": 1})"),
            "joints[0].length: only a distance joint has a length");
  EXPECT_EQ(refusal(kHinge + R"("axis": [0, 1, 0], "motor": {"speed": 1, "maxForce": 2}})"),
            "joints[0].motor.maxForce: unknown field (known: speed, maxTorque)");
  EXPECT_EQ(refusal(R"({"name": "h", "type": "hinge", "bodies": ["a", "b"]})"),
            "joints[0].type: must be one of revolute, prismatic, spherical, fixed, distance, got \"hinge\"");
}

TEST(SceneJoints, OnlyAJointWithStopsHasARestitutionWithinZeroAndOne) {
  EXPECT_EQ(
      rigid::parseScene(sceneWith(kHinge + R"("axis": [0, 1, 0], "limits": [-1, 1]})")).model.joints[0].restitution,
      0.0);
  EXPECT_EQ(rigid::parseScene(sceneWith(kHinge + R"("axis": [0, 1, 0], "limits": [-1, 1], "restitution": 0.25})"))
                .model.joints[0]
                .restitution,
            0.25);
  EXPECT_EQ(refusal(kHinge + R"("axis": [0, 1, 0], "restitution": 0.5})"),
            "joints[0].restitution: only a joint with limits (or a rope without a spring) has stops to bounce at");
  EXPECT_EQ(refusal(kHinge + R"("axis": [0, 1, 0], "limits": [-1, 1], "restitution": 1.5})"),
            "joints[0].restitution: must be in [0, 1], got 1.5");
}
