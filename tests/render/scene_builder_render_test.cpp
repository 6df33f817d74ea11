// A scene built in memory renders exactly as the same scene parsed from its file: the meshes
// handed over as arrays (read from the file's models) and the light's texture as an image in
// memory (read from the file's texture) give bit-identical images in both GPU modes.

#include <gtest/gtest.h>

#include "render/frame.h"
#include "scene/scene.h"
#include "scene/scene_builder.h"
#include "test_files.h"

namespace penumbra {
namespace {

const std::filesystem::path kAssets = test::sourceDirectory() / "scenes" / "assets";

// A textured light over a floor and a cube, with a textured cube material.
std::string sceneText() {
  const std::string texture = (kAssets / "red_blue.png").string();
  return "material floor\n  dif 0.8 0.8 0.8\nend\n"
         "material box\n  dif 0.6 0.5 0.4\n  tex \"" +
         texture +
         "\"\nend\n"
         "material glow\n  emit 6 6 6\n  tex \"" +
         texture +
         "\"\nend\n"
         "area_light panel\n  pos1 -0.5 2 -0.5\n  pos2 0.5 2 -0.5\n  pos3 0.5 2 0.5\n"
         "  pos4 -0.5 2 0.5\n  at 0 0 0\n  mat glow\nend\n"
         "camera view\n  pos 0 2 3.5\n  at 0 0.3 0\n  fovy 45\n  screen_size 64 64\nend\n"
         "object \"" +
         (kAssets / "floor.obj").string() +
         "\"\n  scale 4\n  mat floor\nend\n"
         "object \"" +
         (kAssets / "cube.obj").string() +
         "\"\n  translate 0 0.5 0\n  rotate 30 0 1 0\n  scale 0.6\n  mat box\nend\n";
}

ObjectDesc meshObject(const SceneBuilder& builder, const std::string& file) {
  const Model model = loadModel(kAssets / file, NormalsMode::File);
  EXPECT_EQ(model.meshes.size(), 1u);
  MeshArrays arrays;
  arrays.name = file;
  arrays.positions = model.meshes[0].positions;
  arrays.normals = model.meshes[0].normals;
  arrays.uvs = model.meshes[0].uvs;
  arrays.triangles = model.meshes[0].triangles;
  ObjectDesc object;
  object.mesh = makeMeshModel(arrays, NormalsMode::File, builder.origin());
  return object;
}

Scene builtScene() {
  SceneBuilder builder;
  const auto image = std::make_shared<const Image>(loadImage(kAssets / "red_blue.png"));
  MaterialDesc floor;
  floor.name = "floor";
  floor.diffuse = glm::vec3(0.8f);
  builder.addMaterial(floor);
  MaterialDesc box;
  box.name = "box";
  box.diffuse = {0.6f, 0.5f, 0.4f};
  box.textureImage = image;
  builder.addMaterial(box);
  MaterialDesc glow;
  glow.name = "glow";
  glow.emission = glm::vec3(6.0f);
  glow.textureImage = image;
  builder.addMaterial(glow);

  AreaLightDesc panel;
  panel.name = "panel";
  panel.corners = {glm::vec3(-0.5f, 2, -0.5f), glm::vec3(0.5f, 2, -0.5f), glm::vec3(0.5f, 2, 0.5f),
                   glm::vec3(-0.5f, 2, 0.5f)};
  panel.emittingSidePoint = glm::vec3(0.0f);
  panel.material = "glow";
  builder.addLight(panel);

  CameraDesc camera;
  camera.name = "view";
  camera.position = {0, 2, 3.5f};
  camera.target = {0, 0.3f, 0};
  camera.screenSize = {64, 64};
  builder.setCamera(camera);

  ObjectDesc floorObject = meshObject(builder, "floor.obj");
  floorObject.transform = {{TransformStep::Kind::Scale, glm::vec3(4.0f)}};
  floorObject.material = "floor";
  builder.addObject(floorObject);
  ObjectDesc cube = meshObject(builder, "cube.obj");
  cube.transform = {{TransformStep::Kind::Translate, {0, 0.5f, 0}},
                    {TransformStep::Kind::Rotate, {0, 1, 0}, 30},
                    {TransformStep::Kind::Scale, glm::vec3(0.6f)}};
  cube.material = "box";
  builder.addObject(cube);
  return loadScene(builder.finish());
}

Image render(Scene& scene, RenderMode mode) {
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings;
  settings.mode = mode;
  settings.vplsPerLight = 16;
  renderer.render(0, settings);
  return renderer.readRadiance();
}

class SceneBuilderRender : public ::testing::TestWithParam<RenderMode> {};

TEST_P(SceneBuilderRender, InMemorySceneRendersLikeItsFile) {
  Scene parsed = loadScene(parseScene(sceneText(), "test.scene"));
  Scene built = builtScene();
  const Image fromFile = render(parsed, GetParam());
  const Image fromMemory = render(built, GetParam());
  ASSERT_EQ(fromMemory.width, fromFile.width);
  ASSERT_EQ(fromMemory.height, fromFile.height);
  int lit = 0;
  for (std::size_t i = 0; i < fromFile.pixels.size(); ++i) {
    // Exact: the same floats go through the same passes.
    ASSERT_EQ(fromMemory.pixels[i], fromFile.pixels[i]) << "pixel " << i;
    lit += fromFile.pixels[i].r > 0.0f ? 1 : 0;
  }
  // The comparison means something only if the picture is not black.
  EXPECT_GT(lit, static_cast<int>(fromFile.pixels.size()) / 2);
}

INSTANTIATE_TEST_SUITE_P(BothGpuModes, SceneBuilderRender,
                         ::testing::Values(RenderMode::Hierarchical, RenderMode::Naive),
                         [](const auto& param) {
                           return std::string(renderModeName(param.param));
                         });

}  // namespace
}  // namespace penumbra
