// The naive GPU renderer against closed-form answers and the spec's rules for light quads.

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "render/frame.h"
#include "render/render_test_scenes.h"
#include "test_files.h"

namespace penumbra {
namespace {

// Pixel (column, row from the top) whose centre the camera maps `world` to.
glm::ivec2 pixelOf(const Camera& camera, glm::vec3 world) {
  const glm::vec4 clip = camera.clipFromView() * camera.viewFromWorld() * glm::vec4(world, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return {static_cast<int>(std::floor((ndc.x * 0.5f + 0.5f) * static_cast<float>(camera.size.x))),
          static_cast<int>(std::floor((0.5f - ndc.y * 0.5f) * static_cast<float>(camera.size.y)))};
}

Image renderNaive(Renderer& renderer, RenderSettings settings = {}) {
  settings.mode = RenderMode::Naive;
  renderer.render(0, settings);
  return renderer.readRadiance();
}

const std::string kSquareLightOverFloor =
    "material floor\n  dif 1 1 1\nend\n"
    "material glow\n  emit 1 1 1\nend\n"
    "area_light square\n"
    "  pos1 -0.5 1 -0.5\n  pos2 0.5 1 -0.5\n  pos3 0.5 1 0.5\n  pos4 -0.5 1 0.5\n"
    "  at 0 0 0\n  mat glow\nend\n"
    "camera side\n  pos 0 0.6 2.5\n  at 0 0 0\n  screen_size 65 65\nend\n"
    "object floor.obj\n  mat floor\nend\n";

TEST(NaiveRenderer, SquareLightOverFloorMatchesTheClosedForm) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  Scene scene = test::loadSceneText(directory, kSquareLightOverFloor);
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings;
  settings.vplsPerLight = 1024;
  const Image image = renderNaive(renderer, settings);

  // With an odd size, the centre pixel's ray goes exactly through the `at` point (0,0,0), which
  // lies under the light's centre. Radiance = rho * L * F, F the sum of four corner form
  // factors of 0.5 x 0.5 rectangles at height 1.
  const glm::vec4 centre = image.at(32, 32);
  const double expected = 4.0 * test::cornerFormFactor(0.5, 0.5, 1.0);
  for (int c = 0; c < 3; ++c) {
    // 1%, as the issue asks: 1024 VPLs and the bounded form factor differ from the integral by
    // about 0.03% here; the rest is margin for float arithmetic.
    EXPECT_NEAR(centre[c], expected, 0.01 * expected) << "channel " << c;
  }
}

TEST(NaiveRenderer, LightQuadShowsItsEmissionFromTheFrontAndBlackFromBehind) {
  const auto directory = test::scratchDirectory();
  const std::string light =
      "material glow\n  emit 2 3 4\nend\n"
      "area_light square\n"
      "  pos1 -0.5 1 -0.5\n  pos2 0.5 1 -0.5\n  pos3 0.5 1 0.5\n  pos4 -0.5 1 0.5\n"
      "  at 0 0 0\n  mat glow\nend\n";
  Scene below = test::loadSceneText(
      directory,
      light + "camera c\n  pos 0 0.2 0\n  at 0 1 0\n  up 0 0 -1\n  screen_size 33 33\nend\n",
      "below.scene");
  Renderer fromBelow(below, below.camera.size);
  const glm::vec4 front = renderNaive(fromBelow).at(16, 16);
  EXPECT_EQ(glm::vec3(front), glm::vec3(2.0f, 3.0f, 4.0f));

  Scene above = test::loadSceneText(
      directory,
      light + "camera c\n  pos 0 2 0\n  at 0 1 0\n  up 0 0 -1\n  screen_size 33 33\nend\n",
      "above.scene");
  Renderer fromAbove(above, above.camera.size);
  EXPECT_EQ(glm::vec3(renderNaive(fromAbove).at(16, 16)), glm::vec3(0.0f));
}

TEST(NaiveRenderer, LightTextureIsUprightAndNotMirrored) {
  const auto directory = test::scratchDirectory();
  // Quadrants of 2x2 texels: red top left, green top right, blue bottom left, white bottom right.
  Image picture(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      picture.at(x, y) = y < 2 ? (x < 2 ? glm::vec4(1, 0, 0, 1) : glm::vec4(0, 1, 0, 1))
                               : (x < 2 ? glm::vec4(0, 0, 1, 1) : glm::vec4(1, 1, 1, 1));
  saveImage(picture, directory / "quadrants.exr");
  Scene scene = test::loadSceneText(
      directory,
      "material screen\n  emit 1 1 1\n  tex quadrants.exr\nend\n"
      "area_light tv\n  pos1 -1 0 0\n  pos2 1 0 0\n  pos3 1 2 0\n  pos4 -1 2 0\n"
      "  at 0 1 1\n  mat screen\nend\n"
      "camera c\n  pos 0 1 3\n  at 0 1 0\n  screen_size 64 64\nend\n");
  Renderer renderer(scene, scene.camera.size);
  const Image image = renderNaive(renderer);
  const auto colourAt = [&](glm::vec3 world) {
    const glm::ivec2 pixel = pixelOf(renderer.camera(), world);
    return glm::vec3(image.at(pixel.x, pixel.y));
  };
  EXPECT_EQ(colourAt({-0.5f, 1.5f, 0.0f}), glm::vec3(1, 0, 0));
  EXPECT_EQ(colourAt({0.5f, 1.5f, 0.0f}), glm::vec3(0, 1, 0));
  EXPECT_EQ(colourAt({-0.5f, 0.5f, 0.0f}), glm::vec3(0, 0, 1));
  EXPECT_EQ(colourAt({0.5f, 0.5f, 0.0f}), glm::vec3(1, 1, 1));
}

TEST(NaiveRenderer, DemoRendersFiniteLitAndIdenticalTwice) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes/demo.scene"));
  Renderer renderer(scene, {96, 96});
  RenderSettings settings;
  settings.vplsPerLight = 16;
  const Image first = renderNaive(renderer, settings);
  const Image second = renderNaive(renderer, settings);
  int litSurfacePixels = 0;
  for (const glm::vec4& pixel : first.pixels) {
    ASSERT_TRUE(std::isfinite(pixel.r) && std::isfinite(pixel.g) && std::isfinite(pixel.b));
    if (pixel.r > 0.01f && pixel.r < 1.0f)
      ++litSurfacePixels;
  }
  // The room's surfaces fill the frame and both lights face them: most pixels are lit.
  EXPECT_GT(litSurfacePixels, static_cast<int>(first.pixels.size()) / 2);
  ASSERT_EQ(first.pixels.size(), second.pixels.size());
  EXPECT_EQ(0, std::memcmp(first.pixels.data(), second.pixels.data(),
                           first.pixels.size() * sizeof(glm::vec4)));
}

TEST(NaiveRenderer, RejectsVplCountsThatAreNotSquares) {
  EXPECT_THROW(cellsPerSideFor(0), RenderError);
  EXPECT_THROW(cellsPerSideFor(200), RenderError);
  EXPECT_THROW(cellsPerSideFor(4096), RenderError);
  EXPECT_EQ(cellsPerSideFor(256), 16);
}

TEST(NaiveRenderer, RejectsSizesBeyondTheGlLimits) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  Scene scene = test::loadSceneText(directory, kSquareLightOverFloor);
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  EXPECT_THROW(Renderer(scene, {maxSize + 1, 16}), RenderError);
}

}  // namespace
}  // namespace penumbra
