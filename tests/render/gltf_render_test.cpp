// A glTF scene renders as its equivalent scene file: the .gltf with external files and the .glb
// with embedded ones give the same image, and both that of the scene file written with OBJ
// models, material blocks and a camera block. The glTF's emissive screen is a mesh light: the
// scenes render lit by it alone, and with a quad light added over them. The room Blender 3.4
// exported (scenes/gltf/blender_tv_room.glb, from examples/blender/make_tv_room.py) keeps
// Blender's camera and is lit by its Screen material alone.

#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "render/frame.h"
#include "scene/gltf_test_scene.h"
#include "scene/scene.h"
#include "test_files.h"

namespace penumbra {
namespace {

Image render(const std::filesystem::path& sceneFile) {
  Scene scene = loadScene(parseSceneFile(sceneFile));
  // The glTF camera's aspect (1.5) at a test's size.
  Renderer renderer(scene, {96, 64});
  RenderSettings settings;
  settings.mode = RenderMode::Naive;
  settings.vplsPerLight = 16;
  renderer.render(0, settings);
  return renderer.readRadiance();
}

void expectTheSameImages(const std::filesystem::path& directory, const std::string& light) {
  const Image gltf =
      render(test::writeFile(directory, "gltf.scene", "scene scene.gltf\nend\n" + light));
  const Image glb =
      render(test::writeFile(directory, "glb.scene", "scene scene.glb\nend\n" + light));
  const Image equivalent = render(test::writeFile(directory, "equivalent.scene",
                                                  test::equivalentSceneBlocks(directory) + light));
  ASSERT_EQ(gltf.pixels.size(), glb.pixels.size());
  ASSERT_EQ(gltf.pixels.size(), equivalent.pixels.size());
  int lit = 0;
  int differing = 0;
  for (std::size_t i = 0; i < gltf.pixels.size(); ++i) {
    // Exact: the same bytes of geometry and texture in both files.
    ASSERT_EQ(gltf.pixels[i], glb.pixels[i]) << "pixel " << i;
    lit += gltf.pixels[i].r > 0.0f ? 1 : 0;
    const glm::vec4 difference = glm::abs(gltf.pixels[i] - equivalent.pixels[i]);
    differing += glm::max(difference.r, glm::max(difference.g, difference.b)) > 1e-3f ? 1 : 0;
  }
  // The comparison means something only if much of the picture is lit: the floor, the box and
  // the screen cover about a third of it, the rest is the black background.
  EXPECT_GT(lit, static_cast<int>(gltf.pixels.size()) / 4);
  // The import bakes node transforms into the vertices, the scene file transforms them per
  // frame: rounding may move an edge across a pixel centre on a few edge pixels (none on
  // llvmpipe, where the images are identical; the allowance is for other drivers).
  EXPECT_LE(differing, static_cast<int>(gltf.pixels.size()) / 100);
}

TEST(GltfRender, GltfGlbAndTheEquivalentSceneFileGiveTheSameImage) {
  const auto directory = test::scratchDirectory();
  test::writeGltfTestScene(directory);
  test::writeGltfTestScene(directory, {.binary = true});
  {
    SCOPED_TRACE("lit by the glTF's emissive screen alone");
    expectTheSameImages(directory, "");
  }
  {
    SCOPED_TRACE("with a quad light over the scene");
    expectTheSameImages(directory, test::overheadLightBlocks());
  }
}

// The camera examples/blender/make_tv_room.py placed, worked out from its Blender settings rather
// than from the file: location (-1.2, -2.3, 1.6) and XYZ Euler rotation (1.45, 0, -0.35) with
// Blender's z up, seen along -z; glTF's +y up maps Blender's (x, y, z) to (x, z, -y). Its field
// of view is 1.2 rad across the wider side of a 640x360 render.
TEST(GltfRender, TheBlenderExportKeepsBlendersCameraAndIsLitByItsScreen) {
  Scene scene =
      loadScene(parseSceneFile(test::sourceDirectory() / "scenes/gltf/blender_tv_room.glb"));

  const float tilt = 1.45f;
  const float turn = -0.35f;
  const glm::vec3 blenderForward{-std::sin(tilt) * std::sin(turn), std::sin(tilt) * std::cos(turn),
                                 -std::cos(tilt)};
  const glm::vec3 forward{blenderForward.x, blenderForward.z, -blenderForward.y};
  // The exporter writes floats (a quaternion and a translation) rounded from Blender's values.
  constexpr float kExportRounding = 1e-5f;
  const Camera& camera = scene.camera;
  EXPECT_NEAR(camera.position.x, -1.2f, kExportRounding);
  EXPECT_NEAR(camera.position.y, 1.6f, kExportRounding);
  EXPECT_NEAR(camera.position.z, 2.3f, kExportRounding);
  const glm::vec3 viewDirection = glm::normalize(camera.target - camera.position);
  for (int axis = 0; axis < 3; ++axis)
    EXPECT_NEAR(viewDirection[axis], forward[axis], kExportRounding) << "axis " << axis;
  const float fovy = 2.0f * std::atan(std::tan(0.6f) * 360.0f / 640.0f);
  EXPECT_NEAR(camera.fovyDegrees, glm::degrees(fovy), 1e-4f);  // degrees from radians in float
  EXPECT_EQ(camera.size, glm::ivec2(1820, 1024));              // 16:9 at the default height

  // No area_light: the one light is the mesh of the material Screen, white at Emission
  // Strength 5 (KHR_materials_emissive_strength) and two-sided (Blender's Backface Culling off).
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_TRUE(scene.lights[0].isMesh());
  EXPECT_EQ(scene.lights[0].emission, glm::vec3(5.0f));
  EXPECT_TRUE(scene.lights[0].twoSided);

  Renderer renderer(scene, {64, 36});
  RenderSettings settings;
  settings.mode = RenderMode::Naive;
  settings.vplsPerLight = 16;
  renderer.render(0, settings);
  const Image image = renderer.readRadiance();
  int lit = 0;
  for (const glm::vec4& pixel : image.pixels)
    lit += pixel.r > 0.0f ? 1 : 0;
  // Lit by the screen, the floor, the right wall and the box cover more than a third of the
  // picture (the screen itself under a tenth); the back wall, in the screen's plane, gets none.
  EXPECT_GT(lit, static_cast<int>(image.pixels.size()) / 3);
}

}  // namespace
}  // namespace penumbra
