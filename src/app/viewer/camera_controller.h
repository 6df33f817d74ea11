#pragma once
// The viewer's camera: an orbit around the target with the mouse, flying with the keys, zooming
// with the wheel, and a reset to the scene's camera. No GL and no window: the viewer turns its
// input into these calls, and tests call them directly.

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace penumbra::app {

class CameraController {
 public:
  explicit CameraController(const Camera& home);

  const Camera& camera() const { return camera_; }

  // Turns the eye about the target, keeping its distance: a horizontal drag turns about the
  // camera's up vector, a vertical one tilts up or down, stopping short of the poles so that the
  // view direction never becomes parallel to up. Dragging by the viewport's height turns by
  // half a turn.
  void orbit(glm::vec2 dragPixels, glm::ivec2 viewportSize);

  // Turns the eye about the line along up through the target by `radians`, keeping its height
  // and distance: a step of the automated orbit (`view --orbit`).
  void turn(float radians) { camera_ = camera_.turnedAboutTarget(radians); }

  // Moves the eye and the target together: axes.x to the right, axes.y along up, axes.z
  // forward, each in [-1, 1], at a speed proportional to the scene camera's eye-to-target
  // distance.
  void fly(glm::vec3 axes, float seconds);

  // Moves the eye toward the target (positive steps) or away from it, by a fixed factor per
  // step; the eye never reaches the target.
  void zoom(float steps);

  // Back to the scene's camera.
  void reset() { camera_ = home_; }

  // World units per second of fly().
  float flySpeed() const { return flySpeed_; }

 private:
  Camera home_;
  Camera camera_;
  float flySpeed_;
  float minimumDistance_;
};

}  // namespace penumbra::app
