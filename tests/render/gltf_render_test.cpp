// A glTF scene renders as its equivalent scene file: the .gltf with external files and the .glb
// with embedded ones give the same image, and both that of the scene file written with OBJ
// models, material blocks and a camera block. The glTF's emissive screen is a mesh light: the
// scenes render lit by it alone, and with a quad light added over them.

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

}  // namespace
}  // namespace penumbra
