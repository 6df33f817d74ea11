#pragma once
// Object transforms: static ones compose like OpenGL's matrix stack (M = M * T, so the last
// written applies first), then the animations in order: M(frame) = M_static * A1(frame) * ...

#include <glm/glm.hpp>

#include "scene/scene_desc.h"

namespace penumbra {

glm::mat4 translationMatrix(glm::vec3 offset);
glm::mat4 rotationMatrix(float angleDegrees, glm::vec3 axis);  // like glRotate
glm::mat4 scaleMatrix(glm::vec3 factors);

// rotate: angle step*frame radians about axis; translate: axis * sin(step*frame).
glm::mat4 animationMatrix(const Animation& animation, int frame);
glm::mat4 worldFromObject(const ObjectDesc& object, int frame);

// Scene time of a frame, in seconds: frames are 1/30 s apart.
inline double sceneTime(int frame) {
  return frame / 30.0;
}

}  // namespace penumbra
