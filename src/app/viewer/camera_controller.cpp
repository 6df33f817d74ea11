#include "app/viewer/camera_controller.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

namespace penumbra::app {
namespace {

// Crossing the home eye-to-target distance takes this long when flying.
constexpr float kSecondsPerHomeDistance = 2.0f;
// Each wheel step scales the eye-to-target distance by this factor.
constexpr float kZoomFactorPerStep = 0.85f;
// The eye stays at least this fraction of the home distance from the target.
constexpr float kMinimumDistanceFraction = 1e-3f;
// The orbit keeps the eye this far (in radians) from the up axis through the target.
constexpr float kPoleMargin = 0.01f;

float homeDistance(const Camera& camera) {
  const float distance = glm::length(camera.target - camera.position);
  return distance > 0.0f ? distance : 1.0f;
}

// A unit vector perpendicular to `axis`, for directions that have no component across it.
glm::vec3 anyPerpendicular(glm::vec3 axis) {
  const glm::vec3 helper =
      std::abs(axis.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  return glm::normalize(glm::cross(axis, helper));
}

}  // namespace

CameraController::CameraController(const Camera& home)
    : home_(home),
      camera_(home),
      flySpeed_(homeDistance(home) / kSecondsPerHomeDistance),
      minimumDistance_(homeDistance(home) * kMinimumDistanceFraction) {}

void CameraController::orbit(glm::vec2 dragPixels, glm::ivec2 viewportSize) {
  const float radiansPerPixel = glm::pi<float>() / static_cast<float>(std::max(viewportSize.y, 1));
  const glm::vec3 up = glm::normalize(camera_.up);
  const glm::vec3 offset = camera_.position - camera_.target;
  const float distance = glm::length(offset);
  if (distance == 0.0f)
    return;
  const glm::vec3 direction = offset / distance;

  // Spherical coordinates about `up`: the polar angle from up and the horizontal direction.
  const float polar = std::acos(std::clamp(glm::dot(direction, up), -1.0f, 1.0f));
  const glm::vec3 across = direction - up * glm::dot(direction, up);
  glm::vec3 horizontal =
      glm::length(across) > 1e-6f ? glm::normalize(across) : anyPerpendicular(up);

  // Dragging to the right turns the scene to the right, so the eye moves to the left.
  horizontal = glm::angleAxis(-dragPixels.x * radiansPerPixel, up) * horizontal;
  // Dragging down tilts the scene toward the viewer, so the eye rises.
  const float newPolar = std::clamp(polar - dragPixels.y * radiansPerPixel, kPoleMargin,
                                    glm::pi<float>() - kPoleMargin);
  camera_.position =
      camera_.target + distance * (std::cos(newPolar) * up + std::sin(newPolar) * horizontal);
}

void CameraController::fly(glm::vec3 axes, float seconds) {
  const glm::vec3 up = glm::normalize(camera_.up);
  const glm::vec3 forward = glm::normalize(camera_.target - camera_.position);
  const glm::vec3 across = glm::cross(forward, up);
  const glm::vec3 right =
      glm::length(across) > 1e-6f ? glm::normalize(across) : anyPerpendicular(up);
  const glm::vec3 step = (axes.x * right + axes.y * up + axes.z * forward) * (flySpeed_ * seconds);
  camera_.position += step;
  camera_.target += step;
}

void CameraController::zoom(float steps) {
  const glm::vec3 offset = camera_.position - camera_.target;
  const float distance = glm::length(offset);
  if (distance == 0.0f)
    return;
  const float newDistance =
      std::max(distance * std::pow(kZoomFactorPerStep, steps), minimumDistance_);
  camera_.position = camera_.target + offset * (newDistance / distance);
}

}  // namespace penumbra::app
