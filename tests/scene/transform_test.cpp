#include "scene/transform.h"

#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

namespace penumbra {
namespace {

// Matrices are built in float from values of order 1: a few float roundings (about 1e-7 each)
// stay far below this.
constexpr float kFloatTolerance = 1e-6f;

glm::vec3 apply(const glm::mat4& matrix, glm::vec3 point) {
  return glm::vec3(matrix * glm::vec4(point, 1.0f));
}

void expectNear(glm::vec3 actual, glm::vec3 expected, float tolerance = kFloatTolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(Transform, TranslationAndScale) {
  expectNear(apply(translationMatrix({1, 2, 3}), {1, 1, 1}), {2, 3, 4});
  expectNear(apply(scaleMatrix({1, 2, 3}), {1, 1, 1}), {1, 2, 3});
}

TEST(Transform, RotationIsCounterClockwiseInDegreesLikeGlRotate) {
  expectNear(apply(rotationMatrix(90, {0, 0, 1}), {1, 0, 0}), {0, 1, 0});
  expectNear(apply(rotationMatrix(90, {1, 0, 0}), {0, 1, 0}), {0, 0, 1});
  // The axis is normalised: a long axis rotates by the same angle.
  expectNear(apply(rotationMatrix(90, {0, 0, 5}), {1, 0, 0}), {0, 1, 0});
  // 120 degrees about the diagonal cycles the coordinate axes x -> y -> z -> x.
  expectNear(apply(rotationMatrix(120, {2, 2, 2}), {1, 0, 0}), {0, 1, 0});
  expectNear(apply(rotationMatrix(120, {2, 2, 2}), {0, 1, 0}), {0, 0, 1});
}

TEST(Transform, AnimatedRotationAdvancesStepRadiansPerFrame) {
  const Animation spin{Animation::Kind::Rotate, {0, 2, 0}, 0.5f};
  expectNear(apply(animationMatrix(spin, 0), {1, 0, 0}), {1, 0, 0});
  expectNear(apply(animationMatrix(spin, 1), {1, 0, 0}), {std::cos(0.5f), 0.0f, -std::sin(0.5f)});
  // 50 radians: the angle is wrapped in double, so only the float matrix rounding remains.
  expectNear(apply(animationMatrix(spin, 100), {1, 0, 0}),
             {static_cast<float>(std::cos(50.0)), 0.0f, static_cast<float>(-std::sin(50.0))});
}

TEST(Transform, AnimatedTranslationOscillatesWithSine) {
  const Animation sway{Animation::Kind::Translate, {1, 2, 0}, 0.1f};
  expectNear(apply(animationMatrix(sway, 0), {0, 0, 0}), {0, 0, 0});
  const float atOne = static_cast<float>(std::sin(0.1));
  expectNear(apply(animationMatrix(sway, 1), {0, 0, 0}), {atOne, 2 * atOne, 0});
  const float atHundred = static_cast<float>(std::sin(10.0));
  expectNear(apply(animationMatrix(sway, 100), {0, 0, 0}), {atHundred, 2 * atHundred, 0});
}

TEST(Transform, WorldFromObjectAppliesAnimationsInReverseOrderThenStatic) {
  ObjectDesc object;
  object.staticTransform = translationMatrix({0, 1, 0});
  object.animations = {{Animation::Kind::Rotate, {0, 1, 0}, 0.5f},
                       {Animation::Kind::Translate, {1, 0, 0}, glm::pi<float>() / 2}};
  // Frame 1: the translation (written last) moves the origin to (1,0,0) first, the spin turns
  // it by 0.5 rad about y, then the static translation lifts it by 1.
  expectNear(apply(worldFromObject(object, 1), {0, 0, 0}), {std::cos(0.5f), 1.0f, -std::sin(0.5f)});
  expectNear(apply(worldFromObject(object, 0), {0, 0, 0}), {0, 1, 0});
}

TEST(Transform, SceneTimeIsThirtyFramesPerSecond) {
  EXPECT_DOUBLE_EQ(sceneTime(0), 0.0);
  EXPECT_DOUBLE_EQ(sceneTime(45), 1.5);
}

}  // namespace
}  // namespace penumbra
