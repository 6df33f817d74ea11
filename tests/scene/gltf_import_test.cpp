// glTF scenes imported whole: the .gltf with external files and the .glb with embedded ones give
// the same scene, that of the equivalent scene file; the camera matches; what is not imported is
// listed; a scene file's material block and camera override the glTF's; bad files are one
// SceneError each.

#include <gtest/gtest.h>

#include <algorithm>

#include "scene/gltf_test_scene.h"
#include "scene/scene.h"
#include "test_files.h"

namespace penumbra {
namespace {

Scene loadFile(const std::filesystem::path& file) {
  return loadScene(parseSceneFile(file));
}

// Float rounding of the node transforms (baked into the vertices) against the scene file's
// transforms applied per vertex; far below any visible difference.
constexpr float kPositionTolerance = 1e-5f;

void expectNear(glm::vec3 a, glm::vec3 b, float tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

void expectSameCamera(const Camera& a, const Camera& b) {
  expectNear(a.position, b.position, kPositionTolerance);
  expectNear(glm::normalize(a.target - a.position), glm::normalize(b.target - b.position),
             kPositionTolerance);
  expectNear(a.up, b.up, kPositionTolerance);
  EXPECT_NEAR(a.fovyDegrees, b.fovyDegrees, 1e-4f);  // degrees from radians in float
  EXPECT_FLOAT_EQ(a.nearPlane, b.nearPlane);
  EXPECT_FLOAT_EQ(a.farPlane, b.farPlane);
  EXPECT_EQ(a.size, b.size);
}

// The sorted world-space corners of every triangle, per material's diffuse colour: equal for two
// scenes that draw the same triangles with the same materials, whatever their vertex order.
std::vector<std::array<float, 12>> triangleSoup(const Scene& scene) {
  const FrameGeometry geometry = buildFrameGeometry(scene, 0);
  std::vector<std::array<float, 12>> soup;
  for (std::size_t t = 0; t < geometry.triangles.size(); ++t) {
    std::array<glm::vec3, 3> corners;
    for (int c = 0; c < 3; ++c)
      corners[static_cast<std::size_t>(c)] = geometry.positions[geometry.triangles[t][c]];
    std::sort(corners.begin(), corners.end(), [](glm::vec3 a, glm::vec3 b) {
      return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
    });
    const glm::vec3 diffuse = scene.materials[geometry.triangleMaterial[t]].diffuse;
    std::array<float, 12> entry{};
    for (std::size_t c = 0; c < 3; ++c)
      for (int axis = 0; axis < 3; ++axis)
        entry[c * 3 + static_cast<std::size_t>(axis)] = corners[c][axis];
    entry[9] = diffuse.r;
    entry[10] = diffuse.g;
    entry[11] = diffuse.b;
    soup.push_back(entry);
  }
  std::sort(soup.begin(), soup.end());
  return soup;
}

void expectSameTriangles(const Scene& a, const Scene& b, float tolerance) {
  const auto soupA = triangleSoup(a);
  const auto soupB = triangleSoup(b);
  ASSERT_EQ(soupA.size(), soupB.size());
  for (std::size_t t = 0; t < soupA.size(); ++t)
    for (std::size_t i = 0; i < 12; ++i)
      ASSERT_NEAR(soupA[t][i], soupB[t][i], tolerance) << "triangle " << t << " value " << i;
}

TEST(GltfImport, GltfAndGlbGiveTheSceneOfTheEquivalentSceneFile) {
  const auto directory = test::scratchDirectory();
  Scene gltf = loadFile(test::writeGltfTestScene(directory));
  Scene glb = loadFile(test::writeGltfTestScene(directory, {.binary = true}));
  const Scene equivalent = loadFile(
      test::writeFile(directory, "equivalent.scene", test::equivalentSceneBlocks(directory)));
  ASSERT_EQ(gltf.objects.size(), 3u);
  // The same bytes of geometry in both files: exactly the same triangles.
  expectSameTriangles(gltf, glb, 0.0f);
  expectSameTriangles(gltf, equivalent, kPositionTolerance);
  expectSameCamera(gltf.camera, glb.camera);
  expectSameCamera(gltf.camera, equivalent.camera);
  // The glTF's aspect ratio 1.5 at the scene format's default height.
  EXPECT_EQ(gltf.camera.size, glm::ivec2(1536, 1024));

  // The floor's texture: a file beside the .gltf, an image inside the .glb; the same pixels.
  const SurfaceMaterial& floorGltf = gltf.materials[gltf.objects[0].meshMaterial[0]];
  const SurfaceMaterial& floorGlb = glb.materials[glb.objects[0].meshMaterial[0]];
  ASSERT_GE(floorGltf.texture, 0);
  ASSERT_GE(floorGlb.texture, 0);
  const Image& external = gltf.textures[static_cast<std::size_t>(floorGltf.texture)]->frameAt(0.0);
  const Image& embedded = glb.textures[static_cast<std::size_t>(floorGlb.texture)]->frameAt(0.0);
  ASSERT_EQ(external.width, embedded.width);
  EXPECT_EQ(external.pixels, embedded.pixels);
}

TEST(GltfImport, MaterialsTakeBaseColourEmissionAndItsStrength) {
  const auto directory = test::scratchDirectory();
  const SceneDesc desc = parseSceneFile(test::writeGltfTestScene(directory, {.binary = true}));
  const MaterialDesc* screen = desc.findMaterial("Screen");
  ASSERT_NE(screen, nullptr);
  EXPECT_EQ(screen->diffuse, glm::vec3(0.1f));
  // emissiveFactor 1 times KHR_materials_emissive_strength 4.
  ASSERT_TRUE(screen->emission.has_value());
  EXPECT_EQ(*screen->emission, glm::vec3(4.0f));
  EXPECT_FALSE(screen->twoSided);
  const MaterialDesc* floor = desc.findMaterial("Floor");
  ASSERT_NE(floor, nullptr);
  EXPECT_EQ(floor->diffuse, glm::vec3(0.8f));
  EXPECT_NE(floor->textureImage, nullptr);
  EXPECT_FALSE(floor->emission.has_value());
}

// Blender 3.4 writes doubleSided on every material (examples/blender/make_tv_room.py's export):
// the emitting Screen becomes a two-sided light, the diffuse materials import as they are.
TEST(GltfImport, DoubleSidedMakesEmittingMaterialsTwoSidedAndLeavesDiffuseOnes) {
  const SceneDesc desc =
      parseSceneFile(test::sourceDirectory() / "scenes/gltf/blender_tv_room.glb");
  for (const char* name : {"Floor", "Wall", "TVFrame", "Box"}) {
    const MaterialDesc* diffuse = desc.findMaterial(name);
    ASSERT_NE(diffuse, nullptr) << name;
    EXPECT_FALSE(diffuse->emission.has_value()) << name;
    EXPECT_FALSE(diffuse->twoSided) << name;
  }
  const MaterialDesc* screen = desc.findMaterial("Screen");
  ASSERT_NE(screen, nullptr);
  ASSERT_TRUE(screen->emission.has_value());
  EXPECT_EQ(*screen->emission, glm::vec3(5.0f));  // emissiveFactor 1 times emissiveStrength 5
  EXPECT_TRUE(screen->twoSided);
}

TEST(GltfImport, WarningsNameEachFeatureNotImportedWithItsCount) {
  const auto directory = test::scratchDirectory();
  const Scene scene = loadFile(test::writeGltfTestScene(directory));
  const std::vector<std::string> expected = {
      "1 animation not imported",
      "1 skin not imported",
      "1 punctual light (KHR_lights_punctual) not imported",
      "1 camera not used",
      "1 primitive with morph targets drawn in its base shape",
      "1 material with metallic-roughness values shaded without them"};
  ASSERT_EQ(scene.warnings.size(), expected.size());
  for (const std::string& feature : expected) {
    const auto found =
        std::find_if(scene.warnings.begin(), scene.warnings.end(),
                     [&](const std::string& w) { return w.find(feature) != std::string::npos; });
    EXPECT_NE(found, scene.warnings.end()) << "no warning says '" << feature << "'";
  }
}

TEST(GltfImport, SceneFileMaterialAndCameraOverrideTheGltfs) {
  const auto directory = test::scratchDirectory();
  test::writeGltfTestScene(directory);
  const std::string texture =
      (test::sourceDirectory() / "scenes" / "assets" / "tv_frame150.png").string();
  const Scene scene = loadFile(test::writeFile(directory, "override.scene",
                                               "camera mine\n  pos 0 5 5\n  at 0 0 0\nend\n"
                                               "scene scene.gltf\nend\n"
                                               "material Screen\n  dif 0.5 0.5 0.5\n  tex \"" +
                                                   texture + "\"\nend\n"));
  EXPECT_EQ(scene.camera.position, glm::vec3(0, 5, 5));
  const SurfaceMaterial& screen = scene.materials[scene.objects[2].meshMaterial[0]];
  EXPECT_EQ(screen.diffuse, glm::vec3(0.5f));
  EXPECT_GE(screen.texture, 0);
}

void expectGltfError(const std::filesystem::path& file, const std::string& message) {
  try {
    parseSceneFile(file);
    FAIL() << "no error for " << file;
  } catch (const SceneError& error) {
    EXPECT_EQ(error.where().file, file.string());
    EXPECT_NE(error.message().find(message), std::string::npos) << error.what();
  }
}

TEST(GltfImport, BrokenJsonIsOneError) {
  const auto directory = test::scratchDirectory();
  expectGltfError(test::writeFile(directory, "broken.gltf", "{ \"asset\": { \"version\": "),
                  "broken JSON");
}

TEST(GltfImport, TruncatedGlbIsOneError) {
  const auto directory = test::scratchDirectory();
  const auto file = test::writeGltfTestScene(directory, {.binary = true});
  const auto bytes = std::filesystem::file_size(file);
  std::filesystem::resize_file(file, bytes - 100);
  expectGltfError(file, "the GLB header gives its length as " + std::to_string(bytes) +
                            " bytes, but the file has " + std::to_string(bytes - 100) +
                            " (is the file truncated?)");
}

TEST(GltfImport, MissingBufferIsOneError) {
  const auto directory = test::scratchDirectory();
  const auto file = test::writeGltfTestScene(directory);
  std::filesystem::remove(directory / "scene.bin");
  expectGltfError(file, "glTF '" + file.string() + "'");
}

TEST(GltfImport, AccessorBeyondItsBufferIsOneError) {
  const auto directory = test::scratchDirectory();
  expectGltfError(test::writeGltfTestScene(directory, {.cubeCount = 100000}),
                  "glTF '" + (directory / "scene.gltf").string() + "'");
}

TEST(GltfImport, NanPositionIsOneError) {
  const auto directory = test::scratchDirectory();
  expectGltfError(test::writeGltfTestScene(directory, {.nanPosition = true}),
                  "vertex 0 has the non-finite position (nan, nan, nan)");
}

TEST(GltfImport, ZeroAspectCameraIsOneError) {
  const auto directory = test::scratchDirectory();
  expectGltfError(test::writeGltfTestScene(directory, {.aspect = "0"}),
                  "camera 'View': 'aspectRatio' must be a positive number, found 0");
}

TEST(GltfImport, SceneBlockErrorsPointAtTheSceneFile) {
  const auto directory = test::scratchDirectory();
  test::writeGltfTestScene(directory);
  const auto twice =
      test::writeFile(directory, "twice.scene", "scene scene.gltf\nend\nscene scene.gltf\nend\n");
  try {
    parseSceneFile(twice);
    FAIL() << "a second scene block was accepted";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.where().line, 3);
    EXPECT_NE(error.message().find("only one glTF scene may be imported"), std::string::npos);
  }
  const auto missing = test::writeFile(directory, "missing.scene", "scene none.glb\nend\n");
  try {
    parseSceneFile(missing);
    FAIL() << "a missing glTF was accepted";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.where().line, 1);
    EXPECT_EQ(error.where().column, 7);
    EXPECT_NE(error.message().find("not found"), std::string::npos);
  }
}

}  // namespace
}  // namespace penumbra
