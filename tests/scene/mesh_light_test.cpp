// Mesh lights on the CPU (docs/mesh-lights.md): the scene-file keys and their errors, the lights a
// scene makes of its emissive meshes, their world-space triangles per frame and their VPLs.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "emitter_shapes.h"
#include "scene/mesh_light.h"
#include "scene/scene.h"
#include "scene/scene_builder.h"
#include "test_files.h"

namespace penumbra {
namespace {

constexpr double kPi = std::numbers::pi;

Scene loadText(const std::filesystem::path& directory, const std::string& text) {
  return loadScene(parseSceneFile(test::writeFile(directory, "test.scene", text)));
}

// The message and location of the SceneError `action` throws.
std::string errorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const SceneError& error) {
    return error.what();
  }
  return "(no error)";
}

std::string sceneWithObject(const std::string& material, const std::string& model) {
  return "material glow\n" + material + "end\ncamera c\n  pos 0 0 5\n  at 0 0 0\nend\nobject " +
         model + "\n  mat glow\nend\n";
}

TEST(MeshLightKeys, ParseIntoTheMaterial) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "glow.png", "");
  const SceneDesc desc = parseScene(
      "material glow\n  emit 1 2 3\n  emit_tex glow.png\n  two_sided on\nend\n", directory / "a");
  const MaterialDesc& material = desc.materials.front();
  EXPECT_EQ(*material.emission, glm::vec3(1, 2, 3));
  EXPECT_EQ(*material.emissionTexture, directory / "glow.png");
  EXPECT_TRUE(material.twoSided);
  const SceneDesc off =
      parseScene("material glow\n  emit 1 1 1\n  emit_tex -1\n  two_sided off\nend\n", "a");
  EXPECT_FALSE(off.materials.front().emissionTexture);
  EXPECT_FALSE(off.materials.front().twoSided);
}

// As on a quad, `tex` of an emitting material is its emission texture unless `emit_tex` is given.
TEST(MeshLightKeys, TexIsTheEmissionTextureOfAnEmittingMaterial) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "a.png", "");
  test::writeFile(directory, "b.png", "");
  const SceneDesc desc = parseScene(
      "material tv\n  emit 1 1 1\n  tex a.png\nend\n"
      "material both\n  emit 1 1 1\n  tex a.png\n  emit_tex b.png\nend\n"
      "material plain\n  tex a.png\nend\n",
      directory / "s.scene");
  EXPECT_EQ(*desc.materials[0].emissionTexture, directory / "a.png");
  EXPECT_EQ(*desc.materials[1].emissionTexture, directory / "b.png");
  EXPECT_FALSE(desc.materials[2].emissionTexture);
}

// Bad input, one test per kind: each names the file, line and column of the offending value.
TEST(MeshLightKeys, MissingEmissionTextureFile) {
  const auto directory = test::scratchDirectory();
  const auto file = directory / "a.scene";
  EXPECT_EQ(
      errorOf([&] { parseScene("material glow\n  emit 1 1 1\n  emit_tex gone.png\nend\n", file); }),
      file.string() + ":3:12: error: emission texture file 'gone.png' not found (looked for '" +
          (directory / "gone.png").string() + "')");
}

TEST(MeshLightKeys, EmissionTextureWithoutEmit) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "glow.png", "");
  EXPECT_EQ(errorOf([&] {
              parseScene("material glow\n  emit_tex glow.png\nend\n", directory / "a.scene");
            }),
            (directory / "a.scene").string() +
                ":2:12: error: material 'glow': 'emit_tex' needs 'emit' (the radiance the texture "
                "scales)");
}

TEST(MeshLightKeys, TwoSidedWithoutEmit) {
  EXPECT_EQ(errorOf([] { parseScene("material glow\n  two_sided on\nend\n", "a.scene"); }),
            "a.scene:2:13: error: material 'glow': 'two_sided' needs 'emit'");
}

TEST(MeshLightKeys, TwoSidedTakesOnOrOff) {
  EXPECT_EQ(
      errorOf([] { parseScene("material glow\n  emit 1 1 1\n  two_sided yes\nend\n", "a.scene"); }),
      "a.scene:3:13: error: unknown 'two_sided' value 'yes', expected one of: on, off");
}

TEST(MeshLightKeys, EmptyEmissionImageInMemory) {
  SceneBuilder builder;
  MaterialDesc material;
  material.name = "glow";
  material.emission = glm::vec3(1.0f);
  material.emissionTextureImage = std::make_shared<Image>();
  EXPECT_EQ(errorOf([&] { builder.addMaterial(material); }),
            "in-memory scene: error: material 'glow': the emission texture image has no pixels "
            "or the wrong number");
}

TEST(MeshLightKeys, EmissiveMeshWithoutArea) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  EXPECT_EQ(errorOf([&] { loadText(directory, sceneWithObject("  emit 1 1 1\n", "flat.obj")); }),
            (directory / "test.scene").string() + ":8:1: error: emissive mesh of " +
                (directory / "flat.obj").string() + " has zero area: it cannot emit light");
}

TEST(MeshLights, EveryEmissiveMaterialOfAnObjectIsOneLight) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "quad.obj", test::kCeilingQuadObj);
  const Scene scene = loadText(directory, sceneWithObject("  emit 2 3 4\n", "quad.obj"));
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_TRUE(scene.lights[0].isMesh());
  EXPECT_EQ(scene.lights[0].emission, glm::vec3(2, 3, 4));
  EXPECT_TRUE(scene.materials[static_cast<std::size_t>(scene.objects[0].meshMaterial[0])].emits);
  // `emit 0 0 0` emits nothing: an ordinary surface, no light.
  EXPECT_TRUE(loadText(directory, sceneWithObject("  emit 0 0 0\n", "quad.obj")).lights.empty());
}

// A light's VPLs carry its power: sum of pi A_i L_i = pi A E, the area being the mesh's, and the
// cells split it evenly. The cuts are exact in double precision and the VPL areas are floats:
// 1e-4 relative is far above that rounding.
void expectPowerAndEqualCells(const Scene& scene, double exactArea) {
  const Light& light = scene.lights.at(0);
  const MeshLightGeometry geometry = meshLightGeometry(scene, light, 0);
  EXPECT_NEAR(geometry.area, exactArea, 1e-4 * exactArea);
  const std::vector<Vpl> vpls = makeMeshVpls(geometry, light.emission, nullptr, false, 256);
  ASSERT_EQ(vpls.size(), 256u);
  const glm::vec3 power = emittedPower(vpls);
  const double exactPower = kPi * exactArea * light.emission.x;
  char error[32];
  std::snprintf(error, sizeof(error), "%.3e", std::abs(power.x - exactPower) / exactPower);
  ::testing::Test::RecordProperty("power_relative_error", error);
  EXPECT_NEAR(power.x, exactPower, 1e-4 * exactPower);
  for (const Vpl& vpl : vpls) {
    EXPECT_NEAR(vpl.area, exactArea / 256.0, 1e-4 * exactArea / 256.0);
    EXPECT_NEAR(glm::length(vpl.normal), 1.0f, 1e-5f);
  }
}

TEST(MeshLights, SphereLightEmitsAreaTimesRadiance) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "sphere.obj", test::sphereObj(0.5, 16, 32));
  const Scene scene = loadText(directory, sceneWithObject("  emit 3 3 3\n", "sphere.obj"));
  expectPowerAndEqualCells(scene, test::sphereObjArea(0.5, 16, 32));
  // A closed surface: its VPLs face every way and sit on it.
  const std::vector<Vpl> vpls = makeMeshVpls(meshLightGeometry(scene, scene.lights[0], 0),
                                             glm::vec3(1.0f), nullptr, false, 256);
  glm::vec3 normalSum(0.0f);
  for (const Vpl& vpl : vpls) {
    normalSum += vpl.normal;
    // On a face of the polyhedron: between its inscribed radius and 0.5.
    EXPECT_LE(glm::length(vpl.position), 0.5f + 1e-5f);
    EXPECT_GE(glm::length(vpl.position), 0.5f * std::cos(kPi / 16) * std::cos(kPi / 32) - 1e-5f);
    EXPECT_GT(glm::dot(vpl.normal, glm::normalize(vpl.position)), 0.9f);
  }
  EXPECT_LT(glm::length(normalSum), 1e-3f * 256.0f);
}

TEST(MeshLights, CurvedScreenEmitsAreaTimesRadiance) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "screen.obj", test::curvedScreenObj(2.0, 0.6, 1.0, 24));
  const Scene scene = loadText(directory, sceneWithObject("  emit 5 5 5\n", "screen.obj"));
  expectPowerAndEqualCells(scene, test::curvedScreenObjArea(2.0, 0.6, 1.0, 24));
}

// Stratified: the 256 cells of the two triangles of a unit square cover it evenly. Halving
// right isosceles triangles across their hypotenuse cuts the square into 256 right isosceles
// cells of legs l = sqrt(2/256) = 0.088, and every point of a cell lies within l sqrt(5)/3 =
// 0.0659 of its centroid, the VPL (measured 0.0659; 0.07 allows the float rounding). A 16x16
// grid's bound is 0.044; random placement leaves gaps of 0.15 and more.
TEST(MeshLights, VplsCoverTheSurfaceEvenly) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "quad.obj",
                  "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n");
  const Scene scene = loadText(directory, sceneWithObject("  emit 1 1 1\n", "quad.obj"));
  const std::vector<Vpl> vpls = makeMeshVpls(meshLightGeometry(scene, scene.lights[0], 0),
                                             glm::vec3(1.0f), nullptr, false, 256);
  float farthest = 0.0f;
  for (int y = 0; y <= 100; ++y) {
    for (int x = 0; x <= 100; ++x) {
      const glm::vec3 point(static_cast<float>(x) / 100.0f, static_cast<float>(y) / 100.0f, 0.0f);
      float nearest = 1e9f;
      for (const Vpl& vpl : vpls)
        nearest = std::min(nearest, glm::length(vpl.position - point));
      farthest = std::max(farthest, nearest);
    }
  }
  ::testing::Test::RecordProperty("farthest", std::to_string(farthest));
  EXPECT_LT(farthest, 0.07f);
  for (const Vpl& vpl : vpls)
    EXPECT_EQ(vpl.normal, glm::vec3(0, 0, 1));
}

TEST(MeshLights, TwoSidedLightsHaveAVplOnEachSide) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "quad.obj", test::kCeilingQuadObj);
  const Scene scene =
      loadText(directory, sceneWithObject("  emit 1 1 1\n  two_sided on\n", "quad.obj"));
  ASSERT_TRUE(scene.lights[0].twoSided);
  const std::vector<Vpl> vpls = makeMeshVpls(meshLightGeometry(scene, scene.lights[0], 0),
                                             glm::vec3(1.0f), nullptr, true, 256);
  ASSERT_EQ(vpls.size(), 256u);
  for (std::size_t i = 0; i < vpls.size(); i += 2) {
    EXPECT_EQ(vpls[i].position, vpls[i + 1].position);
    EXPECT_EQ(vpls[i].normal, -vpls[i + 1].normal);
  }
  // Both sides emit: twice the power of one side (rounding of float areas, as above).
  EXPECT_NEAR(emittedPower(vpls).x, 2.0 * kPi * 4.0, 1e-4 * 2.0 * kPi * 4.0);
}

// The texture follows the mesh's uv: a picture red on its left half and blue on its right gives
// the VPLs over u < 0.5 red and the others blue, and the power is E times the texture's mean
// over the surface (the cells straddling u = 0.5 mix both, each exactly by its footprint).
TEST(MeshLights, TexturedLightVplsCarryTheirFootprintsMean) {
  const auto directory = test::scratchDirectory();
  Image picture(8, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x)
      picture.at(x, y) = x < 4 ? glm::vec4(1, 0, 0, 1) : glm::vec4(0, 0, 1, 1);
  saveImage(picture, directory / "halves.exr");
  test::writeFile(directory, "quad.obj", test::kCeilingQuadObj);
  const Scene scene =
      loadText(directory, sceneWithObject("  emit 2 2 2\n  emit_tex halves.exr\n", "quad.obj"));
  const Light& light = scene.lights[0];
  ASSERT_GE(light.texture, 0);
  const Image& frame = scene.textures[static_cast<std::size_t>(light.texture)]->frameAt(0.0);
  const std::vector<Vpl> vpls =
      makeMeshVpls(meshLightGeometry(scene, light, 0), light.emission, &frame, false, 256);
  for (const Vpl& vpl : vpls) {
    // u = (x + 1) / 2 on this quad; VPLs well inside a half carry that half's colour alone.
    if (vpl.position.x < -0.2f) {
      EXPECT_EQ(vpl.radiance, glm::vec3(2, 0, 0));
    } else if (vpl.position.x > 0.2f) {
      EXPECT_EQ(vpl.radiance, glm::vec3(0, 0, 2));
    }
  }
  const glm::vec3 power = emittedPower(vpls);
  // Each half: pi * 2 (area) * 2 (E). The 16 samples per footprint piece resolve a cut through
  // a piece to 1/16 of it; a handful of the 256 cells straddle the cut: 2% of a half's power.
  EXPECT_NEAR(power.x, kPi * 4.0, 0.02 * kPi * 4.0);
  EXPECT_NEAR(power.z, kPi * 4.0, 0.02 * kPi * 4.0);
}

// A video on a mesh: the VPLs follow the frame at scene time frame/30.
TEST(MeshLights, VideoLightVplsFollowTheFrame) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "quad.obj", test::kCeilingQuadObj);
  const auto clip = test::sourceDirectory() / "scenes/assets/tv_screen_128x72_30fps.mp4";
  Scene scene =
      loadText(directory,
               sceneWithObject("  emit 1 1 1\n  emit_tex \"" + clip.string() + "\"\n", "quad.obj"));
  const Light& light = scene.lights[0];
  TextureSource& video = *scene.textures[static_cast<std::size_t>(light.texture)];
  ASSERT_TRUE(video.animated());
  const MeshLightGeometry geometry = meshLightGeometry(scene, light, 0);
  const std::vector<Vpl> first =
      makeMeshVpls(geometry, light.emission, &video.frameAt(0.0), false, 64);
  const std::vector<Vpl> later =
      makeMeshVpls(geometry, light.emission, &video.frameAt(45.0 / 30.0), false, 64);
  double change = 0.0;
  for (std::size_t i = 0; i < first.size(); ++i)
    change += glm::length(first[i].radiance - later[i].radiance);
  EXPECT_GT(change, 0.0);
}

// Animated transforms move the light: a translation oscillating along x moves every VPL by the
// same offset as the object.
TEST(MeshLights, AnimatedLightsMove) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "quad.obj", test::kCeilingQuadObj);
  const Scene scene =
      loadText(directory,
               "material glow\n  emit 1 1 1\nend\ncamera c\n  pos 0 0 5\n  at 0 0 0\n"
               "end\nobject quad.obj\n  anim translate 1 0 0 0.1\n  mat glow\nend\n");
  const Light& light = scene.lights[0];
  const std::vector<Vpl> still =
      makeMeshVpls(meshLightGeometry(scene, light, 0), light.emission, nullptr, false, 64);
  const std::vector<Vpl> moved =
      makeMeshVpls(meshLightGeometry(scene, light, 10), light.emission, nullptr, false, 64);
  const glm::vec3 offset(std::sin(0.1f * 10.0f), 0.0f, 0.0f);
  // The cells' order may change with the rounding of the moved corners, not their places.
  for (const Vpl& vpl : moved) {
    float nearest = 1e9f;
    for (const Vpl& before : still)
      nearest = std::min(nearest, glm::length(vpl.position - (before.position + offset)));
    EXPECT_LT(nearest, 1e-5f);
  }
}

}  // namespace
}  // namespace penumbra
