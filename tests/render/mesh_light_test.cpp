// Mesh lights in every mode (docs/mesh-lights.md): a mesh light shaped as a quad against the
// area_light it replaces, the GPU modes against the reference with the same VPLs (textured,
// video, animated), shadows (a mesh light does not shadow its own VPLs and occludes other
// lights), and the reference's irradiance from a sphere light and a curved screen against a
// direct numerical integration over their triangles.

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "emitter_shapes.h"
#include "image/metrics.h"
#include "reference/emitter_mask.h"
#include "reference/reference.h"
#include "render/frame.h"
#include "render/render_test_scenes.h"
#include "scene/mesh_light.h"
#include "test_files.h"

namespace penumbra {
namespace {

constexpr glm::ivec2 kSize{48, 48};

// Same VPLs and the same formula: float rounding only (the reference agreement tests' bound).
constexpr double kSameVplsBound = 1e-5;

std::string scientific(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3e", value);
  return text;
}

Image renderGpu(Scene& scene, RenderMode mode, bool shadows = false, int frame = 0,
                bool indirect = false) {
  Renderer renderer(scene, kSize);
  RenderSettings settings;
  settings.mode = mode;
  settings.shadows.enabled = shadows;
  settings.indirect.enabled = indirect;
  renderer.render(frame, settings);
  return renderer.readRadiance();
}

Image renderOnCpu(const Scene& scene, ReferenceSettings::Sampling sampling, bool shadows = false,
                  int frame = 0, glm::ivec2 size = kSize, int samplesPerPixel = 256) {
  ReferenceSettings settings;
  settings.sampling = sampling;
  settings.samplesPerPixel = samplesPerPixel;
  settings.shadows = shadows;
  settings.frame = frame;
  settings.size = size;
  return renderReference(scene, settings);
}

// The pixels that show no light, in either scene.
std::vector<bool> litPixels(const Scene& a, const Scene& b, int frame = 0) {
  std::vector<bool> compared = emitterMask(a, kSize, frame);
  const std::vector<bool> other = emitterMask(b, kSize, frame);
  for (std::size_t i = 0; i < compared.size(); ++i)
    compared[i] = !(compared[i] || other[i]);
  return compared;
}

double relativeMse(const Image& image, const Image& reference, const std::vector<bool>& compared) {
  return compareImages(image, reference, &compared).relativeMse;
}

const char* const kFloorAndCamera =
    "material floor\n  dif 0.7 0.7 0.7\n  spec 0.3 0.3 0.3\n  shin 20\nend\n"
    "camera c\n  pos 0 1.2 3.5\n  at 0 0.3 0\nend\n"
    "object floor.obj\n  mat floor\nend\n";

struct QuadScenes {
  Scene quad;
  Scene mesh;
};

QuadScenes quadAndMeshLight(const std::string& material) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  test::writeFile(directory, "quad.obj", test::kCeilingQuadObj);
  const std::string glow = "material glow\n" + material + "end\n";
  return {
      test::loadSceneText(directory,
                          glow + "area_light square\n" + test::kCeilingQuadCorners +
                              "  mat glow\nend\n" + kFloorAndCamera,
                          "quad.scene"),
      test::loadSceneText(directory, glow + "object quad.obj\n  mat glow\nend\n" + kFloorAndCamera,
                          "mesh.scene")};
}

// The two triangles of a quad light as a mesh light give the quad's image. The 256 VPLs sit
// differently (a 16x16 grid against 256 right-triangle cells of the same area), so the GPU images
// differ by the two placements' discretisation errors, each far below 1e-4 in relative MSE
// against the exact integral on this floor (ReferenceAgreement's bound); against each other they
// measured 1.9e-8 in both GPU modes, and 1e-6 leaves room for rounding on other drivers. The
// reference samples the quad by (u,v) and the mesh by area over its triangles: both unbiased
// with 256 stratified samples, so the images differ by their noise, measured 1.5e-5: 1e-4.
TEST(MeshLightImages, QuadMeshLightGivesTheAreaLightsImage) {
  QuadScenes scenes = quadAndMeshLight("  emit 2 2 2\n");
  ASSERT_EQ(scenes.mesh.lights.size(), 1u);
  ASSERT_TRUE(scenes.mesh.lights[0].isMesh());
  const std::vector<bool> compared = litPixels(scenes.quad, scenes.mesh);
  const double naive = relativeMse(renderGpu(scenes.mesh, RenderMode::Naive),
                                   renderGpu(scenes.quad, RenderMode::Naive), compared);
  const double hierarchical =
      relativeMse(renderGpu(scenes.mesh, RenderMode::Hierarchical, true),
                  renderGpu(scenes.quad, RenderMode::Hierarchical, true), compared);
  const double reference =
      relativeMse(renderOnCpu(scenes.mesh, ReferenceSettings::Sampling::Stratified),
                  renderOnCpu(scenes.quad, ReferenceSettings::Sampling::Stratified), compared);
  ::testing::Test::RecordProperty("relmse_naive_mesh_vs_quad", scientific(naive));
  ::testing::Test::RecordProperty("relmse_reference_mesh_vs_quad", scientific(reference));
  ::testing::Test::RecordProperty("relmse_hierarchical_mesh_vs_quad", scientific(hierarchical));
  EXPECT_LE(hierarchical, 1e-6);
  EXPECT_LE(naive, 1e-6);
  EXPECT_LE(reference, 1e-4);
}

// Indirect light: a flat mesh light's reflective shadow map looks from its centre along its
// normal, as a quad's does, so the red wall's bounce onto the floor is the quad's. The bounce
// changes the image by 2.4e-2 in relative MSE. The maps hold the direct light, which differs
// by 2e-8 (above), and the secondary VPLs are drawn in proportion to the maps' flux, so a few of
// them move: measured 1.5e-6 between the two. 1e-4 (ReferenceAgreement's bound, 1/200 of the
// bounce) would still catch a map that looks the wrong way or misses the light's VPLs.
TEST(MeshLightImages, QuadMeshLightGivesTheAreaLightsIndirectLight) {
  QuadScenes scenes = quadAndMeshLight("  emit 2 2 2\n");
  for (Scene* scene : {&scenes.quad, &scenes.mesh}) {
    // A red wall behind the light, facing the camera.
    SceneObject wall = scene->objects.back();  // the floor, the last object of both scenes
    wall.desc.transform.clear();
    wall.desc.staticTransform =
        glm::translate(glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0)),
                       glm::vec3(0, -1.2f, 0));
    scene->materials.push_back({glm::vec3(0.0f), glm::vec3(0.9f, 0.1f, 0.1f)});
    wall.meshMaterial.assign(wall.meshMaterial.size(),
                             static_cast<int>(scene->materials.size()) - 1);
    scene->objects.push_back(wall);
  }
  const std::vector<bool> compared = litPixels(scenes.quad, scenes.mesh);
  const Image direct = renderGpu(scenes.mesh, RenderMode::Naive);
  const Image withBounce = renderGpu(scenes.mesh, RenderMode::Naive, false, 0, true);
  const double error =
      relativeMse(withBounce, renderGpu(scenes.quad, RenderMode::Naive, false, 0, true), compared);
  ::testing::Test::RecordProperty("relmse_indirect_mesh_vs_quad", scientific(error));
  ::testing::Test::RecordProperty("relmse_bounce",
                                  scientific(relativeMse(withBounce, direct, compared)));
  EXPECT_GT(relativeMse(withBounce, direct, compared), 1e-3);
  EXPECT_LE(error, 1e-4);
}

// The G-buffer shows a mesh light's emission from its emitting side, as a quad's: the camera
// looks up at the light from below.
TEST(MeshLightImages, MeshLightShowsItsEmission) {
  QuadScenes scenes = quadAndMeshLight("  emit 2 3 4\n");
  for (Scene* scene : {&scenes.quad, &scenes.mesh}) {
    scene->camera.position = {0.0f, 0.0f, 0.0f};
    scene->camera.target = {0.0f, 1.5f, 0.0f};
    scene->camera.up = {0.0f, 0.0f, 1.0f};
    const Image image = renderGpu(*scene, RenderMode::Naive);
    EXPECT_EQ(glm::vec3(image.at(kSize.x / 2, kSize.y / 2)), glm::vec3(2, 3, 4));
  }
}

// The GPU modes use the CPU's mesh VPLs: the naive gather equals the reference with the same
// VPLs, for a textured two-sided curved screen.
TEST(MeshLightImages, TexturedTwoSidedCurvedScreenMatchesTheReferenceWithTheSameVpls) {
  const auto directory = test::scratchDirectory();
  saveImage(test::cellCuttingPicture(), directory / "picture.exr");
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  test::writeFile(directory, "screen.obj", test::curvedScreenObj(1.5, 0.7, 1.0, 16));
  Scene scene = test::loadSceneText(
      directory, std::string("material screen\n  emit 3 3 3\n  emit_tex picture.exr\n"
                             "  two_sided on\nend\n"
                             "object screen.obj\n  translate 0 0.3 0.5\n  mat screen\nend\n") +
                     kFloorAndCamera);
  const std::vector<bool> compared = litPixels(scene, scene);
  const Image sameVpls = renderOnCpu(scene, ReferenceSettings::Sampling::Vpl);
  const double naive = relativeMse(renderGpu(scene, RenderMode::Naive), sameVpls, compared);
  ::testing::Test::RecordProperty("relmse_naive_vs_reference_vpl", scientific(naive));
  EXPECT_LE(naive, kSameVplsBound);
}

// A video on a mesh, at frame 45 (1.5 s): the GPU's VPLs and the reference's come from the same
// video frame.
TEST(MeshLightImages, VideoMeshLightFollowsTheSceneTime) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  test::writeFile(directory, "quad.obj", test::kCeilingQuadObj);
  const auto clip = test::sourceDirectory() / "scenes/assets/tv_screen_128x72_30fps.mp4";
  Scene scene = test::loadSceneText(
      directory, "material tv\n  emit 2 2 2\n  emit_tex \"" + clip.string() +
                     "\"\nend\nobject quad.obj\n  mat tv\nend\n" + kFloorAndCamera);
  const std::vector<bool> compared = litPixels(scene, scene);
  const Image early = renderGpu(scene, RenderMode::Naive, false, 0);
  const Image late = renderGpu(scene, RenderMode::Naive, false, 45);
  EXPECT_LE(
      relativeMse(late, renderOnCpu(scene, ReferenceSettings::Sampling::Vpl, false, 45), compared),
      kSameVplsBound);
  // The video's frames differ, and so does the light.
  EXPECT_GT(relativeMse(early, late, compared), 1e-4);
}

// Animated transforms move a mesh light: at frame 12 the GPU's image equals the reference's with
// the same (moved) VPLs, and differs from frame 0.
TEST(MeshLightImages, AnimatedMeshLightMoves) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  test::writeFile(directory, "quad.obj", test::kCeilingQuadObj);
  Scene scene = test::loadSceneText(
      directory, std::string("material glow\n  emit 2 2 2\nend\n"
                             "object quad.obj\n  anim translate 1.5 0 0 0.1\n  mat glow\nend\n") +
                     kFloorAndCamera);
  const std::vector<bool> compared = litPixels(scene, scene, 12);
  const Image moved = renderGpu(scene, RenderMode::Naive, false, 12);
  EXPECT_LE(
      relativeMse(moved, renderOnCpu(scene, ReferenceSettings::Sampling::Vpl, false, 12), compared),
      kSameVplsBound);
  EXPECT_GT(relativeMse(moved, renderGpu(scene, RenderMode::Naive, false, 0), compared), 1e-3);
}

// A mesh light's own voxels do not shadow its VPLs: with nothing between light and floor, the
// image with shadows equals the one without, in both GPU modes (the hierarchical one's masks
// and the naive one's per-pixel rays).
TEST(MeshLightShadows, MeshLightDoesNotShadowItself) {
  QuadScenes scenes = quadAndMeshLight("  emit 2 2 2\n");
  const std::vector<bool> compared = litPixels(scenes.mesh, scenes.mesh);
  for (const RenderMode mode : {RenderMode::Naive, RenderMode::Hierarchical}) {
    const double error = relativeMse(renderGpu(scenes.mesh, mode, true),
                                     renderGpu(scenes.mesh, mode, false), compared);
    ::testing::Test::RecordProperty(std::string("relmse_shadows_") + renderModeName(mode),
                                    scientific(error));
    EXPECT_LE(error, kSameVplsBound) << renderModeName(mode);
  }
}

// A mesh light occludes other lights like any object: an upward-facing emissive plate between a
// quad light and the floor casts a shadow, as Embree's exact visibility has it for the same VPLs
// (3e-3: the voxel grid's approximation, ReferenceAgreement's bound for shadows).
TEST(MeshLightShadows, MeshLightOccludesOtherLights) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  test::writeFile(directory, "plate.obj",
                  "v -0.4 0.7 -0.4\nv 0.4 0.7 -0.4\nv 0.4 0.7 0.4\nv -0.4 0.7 0.4\nvn 0 1 0\n"
                  "f 1//1 4//1 3//1 2//1\n");
  Scene scene = test::loadSceneText(
      directory, std::string("material glow\n  emit 2 2 2\nend\n"
                             "material plate\n  emit 1 1 1\nend\n"
                             "area_light square\n") +
                     test::kCeilingQuadCorners +
                     "  mat glow\nend\nobject plate.obj\n  mat plate\nend\n" + kFloorAndCamera);
  ASSERT_EQ(scene.lights.size(), 2u);
  const std::vector<bool> compared = litPixels(scene, scene);
  const Image shadowed = renderGpu(scene, RenderMode::Naive, true);
  const double error =
      relativeMse(shadowed, renderOnCpu(scene, ReferenceSettings::Sampling::Vpl, true), compared);
  ::testing::Test::RecordProperty("relmse_vs_reference_vpl", scientific(error));
  EXPECT_LE(error, 3e-3);
  // The floor straight below the plate, seen past its edge from the camera, is darker with
  // shadows than without.
  const Image unshadowed = renderGpu(scene, RenderMode::Naive, false);
  double darker = 0.0;
  double total = 0.0;
  for (std::size_t i = 0; i < compared.size(); ++i) {
    if (!compared[i])
      continue;
    darker += unshadowed.pixels[i].g - shadowed.pixels[i].g;
    total += unshadowed.pixels[i].g;
  }
  EXPECT_GT(darker, 0.05 * total);
}

// Irradiance at the floor points the pixels see, from the reference: a white floor (albedo 1)
// reflects E/pi. It is compared with a direct numerical integration of L cos cos / r^2 over the
// light's triangles (each cut into 32^2 equal sub-triangles, midpoint rule: relative error below
// 1e-4 at these distances), point by point, at the points `unoccluded` accepts: those from which
// no part of the light hides another (the integration has no visibility; the reference has).
void expectReferenceIrradiance(const std::string& objText, const std::string& placement,
                               double radiance, const std::function<bool(glm::dvec3)>& unoccluded) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  test::writeFile(directory, "light.obj", objText);
  constexpr glm::ivec2 size{12, 12};
  constexpr int kSamples = 4096;
  Scene scene =
      test::loadSceneText(directory, "material glow\n  emit " + std::to_string(radiance) + " " +
                                         std::to_string(radiance) + " " + std::to_string(radiance) +
                                         "\nend\nmaterial white\n  dif 1 1 1\nend\n"
                                         "camera c\n  pos 0 4 3\n  at 0 0 0\nend\n"
                                         "object floor.obj\n  mat white\nend\nobject light.obj\n" +
                                         placement + "  mat glow\nend\n");
  const Image image =
      renderOnCpu(scene, ReferenceSettings::Sampling::Stratified, true, 0, size, kSamples);
  const MeshLightGeometry light = meshLightGeometry(scene, scene.lights.at(0), 0);
  const std::vector<bool> shown = emitterMask(scene, size, 0);
  Camera camera = scene.camera;
  camera.size = size;
  int points = 0;
  double worst = 0.0;
  double signedSum = 0.0;
  for (int y = 0; y < size.y; ++y) {
    for (int x = 0; x < size.x; ++x) {
      const glm::vec3 direction = camera.rayDirection(x, y);
      if (shown[static_cast<std::size_t>(y * size.x + x)] || direction.y >= 0.0f)
        continue;
      const glm::dvec3 point =
          glm::dvec3(camera.position) -
          glm::dvec3(direction) * (static_cast<double>(camera.position.y) / direction.y);
      if (!unoccluded(point))
        continue;
      constexpr int k = 32;
      double irradiance = 0.0;
      for (const EmitterTriangle& t : light.triangles) {
        const glm::dvec3 a(t.positions[0]);
        const glm::dvec3 e1 = (glm::dvec3(t.positions[1]) - a) / double(k);
        const glm::dvec3 e2 = (glm::dvec3(t.positions[2]) - a) / double(k);
        const double subArea = t.area / double(k * k);
        for (int i = 0; i < k; ++i) {
          for (int j = 0; i + j < k; ++j) {
            for (const double corner : {1.0 / 3.0, 2.0 / 3.0}) {
              if (corner > 0.5 && i + j + 1 >= k)
                continue;  // the inverted sub-triangle exists only inside
              const glm::dvec3 y0 = a + (i + corner) * e1 + (j + corner) * e2;
              const glm::dvec3 toLight = y0 - point;
              const double r2 = glm::dot(toLight, toLight);
              const glm::dvec3 w = toLight / std::sqrt(r2);
              const double cosFloor = std::max(0.0, w.y);
              const double cosLight = std::max(0.0, -glm::dot(glm::dvec3(t.normal), w));
              irradiance += radiance * cosFloor * cosLight / r2 * subArea;
            }
          }
        }
      }
      const double measured = std::numbers::pi * image.at(x, y).g;
      worst = std::max(worst, std::abs(measured - irradiance) / irradiance);
      signedSum += (measured - irradiance) / irradiance;
      ++points;
    }
  }
  ::testing::Test::RecordProperty("points", points);
  ::testing::Test::RecordProperty("worst_relative_error", scientific(worst));
  ::testing::Test::RecordProperty("mean_relative_error", scientific(signedSum / points));
  EXPECT_GT(points, 40);
  // 4096 stratified area samples per point: their noise, measured at most 2.5e-2 (sphere: half
  // its samples face away) and 5.8e-3 (screen). The mean over the points averages the noise out
  // and would show a bias (a wrong area or density): measured 1.6e-3 and -3.6e-4.
  EXPECT_LT(worst, 0.05);
  EXPECT_LT(std::abs(signedSum / points), 5e-3);
}

TEST(MeshLightReference, SphereLightIrradianceMatchesNumericalIntegration) {
  // A convex light hides none of itself.
  expectReferenceIrradiance(test::sphereObj(0.5, 12, 24), "  translate 0 1.2 0\n", 3.0,
                            [](glm::dvec3) { return true; });
}

TEST(MeshLightReference, CurvedScreenIrradianceMatchesNumericalIntegration) {
  // From inside its cylinder (axis x = 0, z = 0.5, radius 1.5) the whole inner side of the
  // screen is in view; from behind, its near part hides the far wings' inner side.
  expectReferenceIrradiance(test::curvedScreenObj(1.5, 0.7, 1.0, 16), "  translate 0 0.2 0.5\n",
                            3.0, [](glm::dvec3 point) {
                              return point.x * point.x + (point.z - 0.5) * (point.z - 0.5) < 2.25;
                            });
}

}  // namespace
}  // namespace penumbra
