#include "scene/transform.h"

#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace penumbra {

glm::mat4 translationMatrix(glm::vec3 offset) {
  return glm::translate(glm::mat4(1.0f), offset);
}

// The axis must not be zero (the parser rejects it); glm::rotate normalises it, as glRotate does.
glm::mat4 rotationMatrix(float angleDegrees, glm::vec3 axis) {
  return glm::rotate(glm::mat4(1.0f), glm::radians(angleDegrees), axis);
}

glm::mat4 scaleMatrix(glm::vec3 factors) {
  return glm::scale(glm::mat4(1.0f), factors);
}

glm::mat4 animationMatrix(const Animation& animation, int frame) {
  // The phase is formed and wrapped in double: step * frame in float loses digits on long
  // animations, and only the angle modulo a full turn matters for a rotation.
  const double phase = static_cast<double>(animation.step) * frame;
  switch (animation.kind) {
    case Animation::Kind::Rotate: {
      const double angle = std::remainder(phase, 2.0 * glm::pi<double>());
      return glm::rotate(glm::mat4(1.0f), static_cast<float>(angle), animation.axis);
    }
    case Animation::Kind::Translate:
      return translationMatrix(animation.axis * static_cast<float>(std::sin(phase)));
  }
  return glm::mat4(1.0f);
}

glm::mat4 worldFromObject(const ObjectDesc& object, int frame) {
  glm::mat4 world = object.staticTransform;
  for (const Animation& animation : object.animations)
    world *= animationMatrix(animation, frame);
  return world;
}

}  // namespace penumbra
