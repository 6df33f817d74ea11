// The GPU VPL pass against the CPU definition (makeVpls) and against energy conservation.

#include <gtest/gtest.h>

#include "render/render_test_scenes.h"
#include "render/scene_gpu.h"
#include "render/vpls.h"
#include "shared.h"
#include "test_files.h"

namespace penumbra {
namespace {

std::vector<gpu::GpuVpl> gpuVpls(Scene& scene, int cellsPerSide) {
  SceneGpu sceneGpu(scene);
  sceneGpu.update(0, 0.0, cellsPerSide);
  VplPass pass;
  VplBuffer vpls;
  pass.run({sceneGpu}, {vpls});
  return readVpls(vpls);
}

// A tilted, non-square light, so that no axis or size is special.
const char* kLightBlock =
    "area_light panel\n"
    "  pos1 -0.6 1 -0.3\n  pos2 0.5 1.2 -0.3\n  pos3 0.5 1.2 0.4\n  pos4 -0.6 1 0.4\n"
    "  at 0 0 0\n  mat glow\nend\n";

TEST(Vpls, UniformLightPowerEqualsTheLights) {
  const auto directory = test::scratchDirectory();
  Scene scene = test::loadSceneText(
      directory, std::string("material glow\n  emit 2 3 4\nend\n") + kLightBlock);
  const Light& light = scene.lights.at(0);
  for (int cells : {1, 4, 16, 32}) {
    glm::dvec3 power(0.0);
    for (const gpu::GpuVpl& vpl : gpuVpls(scene, cells))
      power += glm::dvec3(vpl.radiance) * static_cast<double>(vpl.positionArea.w);
    const glm::dvec3 expected = glm::dvec3(light.emission) * static_cast<double>(light.quad.area);
    for (int c = 0; c < 3; ++c) {
      // 1e-5 relative: float sums of up to 1024 terms, each exact to float precision.
      EXPECT_NEAR(power[c], expected[c], 1e-5 * expected[c]) << cells << " cells, channel " << c;
    }
  }
}

TEST(Vpls, TexturedLightMatchesTheCpuCellMeans) {
  const auto directory = test::scratchDirectory();
  // 7x5 checkerboard: cells of a 4x4 grid cover fractions of texels, so the overlap weights
  // matter. EXR keeps the values exact.
  Image checker(7, 5);
  for (int y = 0; y < checker.height; ++y)
    for (int x = 0; x < checker.width; ++x)
      checker.at(x, y) =
          (x + y) % 2 == 0 ? glm::vec4(1.0f, 0.5f, 0.25f, 1.0f) : glm::vec4(0.0f, 0.1f, 3.0f, 1.0f);
  saveImage(checker, directory / "checker.exr");
  Scene scene = test::loadSceneText(
      directory,
      std::string("material glow\n  emit 1 2 1\n  tex checker.exr\nend\n") + kLightBlock);
  const Light& light = scene.lights.at(0);
  const Image& texture = scene.textures.at(static_cast<std::size_t>(light.texture))->frameAt(0.0);
  const int cells = 4;
  const std::vector<Vpl> expected = makeVpls(light.quad, light.emission, &texture, cells);
  const std::vector<gpu::GpuVpl> actual = gpuVpls(scene, cells);
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    // 1e-5: float arithmetic in a different order on the GPU and the CPU.
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(actual[i].radiance[c], expected[i].radiance[c], 1e-5f) << "VPL " << i;
      EXPECT_NEAR(actual[i].positionArea[c], expected[i].position[c], 1e-5f) << "VPL " << i;
      EXPECT_NEAR(actual[i].normal[c], expected[i].normal[c], 1e-5f) << "VPL " << i;
    }
    EXPECT_NEAR(actual[i].positionArea.w, expected[i].area, 1e-7f) << "VPL " << i;
  }
}

}  // namespace
}  // namespace penumbra
