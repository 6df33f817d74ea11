#include "app/viewer/camera_controller.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

namespace penumbra::app {
namespace {

// Float arithmetic on coordinates of order 1 to 10: a few ulps of error per operation.
constexpr float kTolerance = 1e-4f;

Camera homeCamera() {
  Camera camera;
  camera.position = {0.0f, 1.0f, 4.0f};
  camera.target = {0.0f, 1.0f, 0.0f};
  camera.up = {0.0f, 1.0f, 0.0f};
  camera.size = {200, 100};
  return camera;
}

void expectNear(glm::vec3 actual, glm::vec3 expected) {
  EXPECT_NEAR(actual.x, expected.x, kTolerance);
  EXPECT_NEAR(actual.y, expected.y, kTolerance);
  EXPECT_NEAR(actual.z, expected.z, kTolerance);
}

float distanceToTarget(const Camera& camera) {
  return glm::length(camera.position - camera.target);
}

TEST(CameraController, StartsAtTheSceneCamera) {
  const CameraController controller(homeCamera());
  expectNear(controller.camera().position, homeCamera().position);
  expectNear(controller.camera().target, homeCamera().target);
  EXPECT_EQ(controller.camera().size, homeCamera().size);
}

TEST(CameraController, HorizontalDragOfTheViewportHeightTurnsHalfWayAround) {
  CameraController controller(homeCamera());
  controller.orbit({100.0f, 0.0f}, {200, 100});
  expectNear(controller.camera().position, {0.0f, 1.0f, -4.0f});
  expectNear(controller.camera().target, homeCamera().target);
}

TEST(CameraController, DraggingRightMovesTheEyeToTheLeft) {
  CameraController controller(homeCamera());
  controller.orbit({50.0f, 0.0f}, {200, 100});
  // A quarter turn: from +z to -x (the camera's left when it looks down -z).
  expectNear(controller.camera().position, {-4.0f, 1.0f, 0.0f});
}

TEST(CameraController, TurningKeepsTheEyesHeightAndDistance) {
  CameraController controller(homeCamera());
  controller.turn(-glm::half_pi<float>());
  // The same quarter turn as a drag of half the viewport's height to the right.
  expectNear(controller.camera().position, {-4.0f, 1.0f, 0.0f});
  expectNear(controller.camera().target, homeCamera().target);
}

TEST(CameraController, DraggingDownRaisesTheEyeAndKeepsItsDistance) {
  CameraController controller(homeCamera());
  controller.orbit({0.0f, 25.0f}, {200, 100});
  const Camera& camera = controller.camera();
  EXPECT_NEAR(distanceToTarget(camera), 4.0f, kTolerance);
  // An eighth of a turn up from the horizon.
  const float angle = glm::quarter_pi<float>();
  expectNear(camera.position, {0.0f, 1.0f + 4.0f * std::sin(angle), 4.0f * std::cos(angle)});
}

TEST(CameraController, OrbitStopsShortOfThePole) {
  CameraController controller(homeCamera());
  controller.orbit({0.0f, 10000.0f}, {200, 100});
  const Camera& camera = controller.camera();
  const glm::vec3 forward = glm::normalize(camera.target - camera.position);
  EXPECT_GT(glm::length(glm::cross(forward, camera.up)), 0.005f);
  EXPECT_GT(camera.position.y, camera.target.y);
  EXPECT_NEAR(distanceToTarget(camera), 4.0f, kTolerance);
}

TEST(CameraController, FlyingForwardMovesEyeAndTargetTogether) {
  CameraController controller(homeCamera());
  // Home distance 4: the controller crosses it in two seconds, so 2 units in one second.
  controller.fly({0.0f, 0.0f, 1.0f}, 1.0f);
  expectNear(controller.camera().position, {0.0f, 1.0f, 2.0f});
  expectNear(controller.camera().target, {0.0f, 1.0f, -2.0f});
}

TEST(CameraController, FlyingRightAndUpFollowTheCameraAxes) {
  CameraController controller(homeCamera());
  controller.fly({1.0f, 0.0f, 0.0f}, 0.5f);
  expectNear(controller.camera().position, {1.0f, 1.0f, 4.0f});
  controller.fly({0.0f, -1.0f, 0.0f}, 0.5f);
  expectNear(controller.camera().position, {1.0f, 0.0f, 4.0f});
  expectNear(controller.camera().target, {1.0f, 0.0f, 0.0f});
}

TEST(CameraController, ZoomInAndOutAgainRestoresTheDistance) {
  CameraController controller(homeCamera());
  controller.zoom(3.0f);
  EXPECT_LT(distanceToTarget(controller.camera()), 4.0f);
  expectNear(controller.camera().target, homeCamera().target);
  controller.zoom(-3.0f);
  expectNear(controller.camera().position, homeCamera().position);
}

TEST(CameraController, ZoomNeverReachesTheTarget) {
  CameraController controller(homeCamera());
  controller.zoom(1000.0f);
  EXPECT_GT(distanceToTarget(controller.camera()), 0.0f);
  // The direction from the target to the eye is kept.
  expectNear(glm::normalize(controller.camera().position - controller.camera().target),
             {0.0f, 0.0f, 1.0f});
}

TEST(CameraController, ResetReturnsToTheSceneCamera) {
  CameraController controller(homeCamera());
  controller.orbit({37.0f, -12.0f}, {200, 100});
  controller.fly({0.3f, 0.5f, -1.0f}, 0.7f);
  controller.zoom(2.0f);
  controller.reset();
  expectNear(controller.camera().position, homeCamera().position);
  expectNear(controller.camera().target, homeCamera().target);
}

}  // namespace
}  // namespace penumbra::app
