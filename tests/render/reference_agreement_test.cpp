// The GPU naive renderer against the Embree reference, with shadows off, on four scenes: the
// demo, the Cornell box with the bunny, a tilted textured light and a floor with leaning smooth
// normals seen at a grazing angle; and with shadows on the demo, against Embree's exact
// visibility for the same VPLs.

#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "image/metrics.h"
#include "reference/emitter_mask.h"
#include "reference/reference.h"
#include "render/frame.h"
#include "render/render_test_scenes.h"
#include "test_files.h"

namespace penumbra {
namespace {

constexpr glm::ivec2 kSize{48, 48};

Image renderNaive(Scene& scene, bool shadows = false) {
  Renderer renderer(scene, kSize);
  RenderSettings settings;
  settings.mode = RenderMode::Naive;
  settings.shadows.enabled = shadows;
  renderer.render(0, settings);
  return renderer.readRadiance();
}

Image renderOnCpu(const Scene& scene, ReferenceSettings::Sampling sampling, bool shadows = false) {
  ReferenceSettings settings;
  settings.sampling = sampling;
  settings.samplesPerPixel = 256;
  settings.shadows = shadows;
  settings.size = kSize;
  return renderReference(scene, settings);
}

// Pixels whose surface the rasteriser and Embree disagree on: faces seen exactly edge-on, where
// the two pick different triangles. They are counted, and left out of the error metrics.
constexpr int kMaxEdgeOnPixels = 4;
// Same VPLs and the same formula: what remains is float rounding. Measured about 7e-7.
constexpr double kSameVplsBound = 1e-5;
// Against the exact integral: the VPLs' discretisation (largest on receivers close to a light,
// where 16x16 VPLs and the bounded form factor both deviate) plus the reference's noise with
// 256 stratified samples. 1e-4 is a 1% RMS relative error; measured about 5e-6 on the demo.
constexpr double kExactLightBound = 1e-4;

std::string scientific(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3e", value);
  return text;
}

void expectAgreement(Scene& scene) {
  const Image naive = renderNaive(scene);
  const Image sameVpls = renderOnCpu(scene, ReferenceSettings::Sampling::Vpl);
  const Image exactLight = renderOnCpu(scene, ReferenceSettings::Sampling::Stratified);
  std::vector<bool> compared = emitterMask(scene, kSize, 0);
  compared.flip();
  const int edgeOnPixels = test::leaveOutEdgeOnPixels(naive, sameVpls, compared);
  const double withSameVpls = compareImages(naive, sameVpls, &compared).relativeMse;
  const double withExactLight = compareImages(naive, exactLight, &compared).relativeMse;
  ::testing::Test::RecordProperty("edge_on_pixels", edgeOnPixels);
  ::testing::Test::RecordProperty("relmse_vs_reference_vpl", scientific(withSameVpls));
  ::testing::Test::RecordProperty("relmse_vs_reference", scientific(withExactLight));
  EXPECT_LE(edgeOnPixels, kMaxEdgeOnPixels);
  EXPECT_LE(withSameVpls, kSameVplsBound);
  EXPECT_LE(withExactLight, kExactLightBound);
}

TEST(ReferenceAgreement, Demo) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes/demo.scene"));
  expectAgreement(scene);
}

TEST(ReferenceAgreement, CornellBoxWithBunny) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes/cornell_bunny.scene"));
  expectAgreement(scene);
}

TEST(ReferenceAgreement, TiltedTexturedLight) {
  const auto directory = test::scratchDirectory();
  saveImage(test::cellCuttingPicture(), directory / "picture.exr");
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  Scene scene = test::loadSceneText(
      directory,
      "material screen\n  emit 3 3 3\n  tex picture.exr\nend\n"
      "material floor\n  dif 0.7 0.7 0.7\n  spec 0.3 0.3 0.3\n  shin 20\nend\n"
      "area_light tilted\n  pos1 -1 0.4 -1\n  pos2 1 0.6 -1.2\n  pos3 1 1.6 -0.8\n"
      "  pos4 -1 1.4 -0.6\n  at 0 0 1\n  mat screen\nend\n"
      "camera c\n  pos 0 1.5 3\n  at 0 0.3 0\nend\n"
      "object floor.obj\n  mat floor\nend\n");
  expectAgreement(scene);
}

// Two-sided surfaces flip by their face, in every mode (docs/scene-format.md): a floor whose
// smooth normals all lean 53 degrees towards +x, seen at a grazing angle from -x, is seen from
// its front although its normal leans away from the eye. Flipping by the angle to the eye (the
// G-buffer's rule before issue 20) left the far part of the floor black on the GPU.
TEST(ReferenceAgreement, SmoothNormalsLeaningAwayFromAGrazingEye) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj",
                  "v -10 0 -10\nv 10 0 -10\nv 10 0 10\nv -10 0 10\nvn 0.8 0.6 0\n"
                  "f 4//1 3//1 2//1 1//1\n");
  Scene scene =
      test::loadSceneText(directory,
                          "material glow\n  emit 2 2 2\nend\n"
                          "area_light square\n"
                          "  pos1 -1 1.5 -1\n  pos2 1 1.5 -1\n  pos3 1 1.5 1\n  pos4 -1 1.5 1\n"
                          "  at 0 0 0\n  mat glow\nend\n"
                          "camera grazing\n  pos -6 0.8 0.3\n  at 0 0 0\nend\n"
                          "object floor.obj\nend\n");
  expectAgreement(scene);
}

// Voxel shadow rays against Embree's exact ones for the same 2 x 256 VPLs. The naive gather
// traces its shadow rays in batches (gather_naive.comp); when one invocation traced all 512,
// llvmpipe's loop limit dropped the later VPLs of many pixels and this error was 5e-2. What
// remains is the grid's approximation: about 1% of the visibility bits differ from Embree's on
// the demo (VoxelVisibility.AgreesWithEmbreeOnTheDemo), which gives 1.6e-4 here (1.9e-4 before
// the traversal left the occupied voxels a ray starts in). 5e-4 leaves room for the spread
// between drivers and for small changes of the grid: its placement alone moves the demo's
// figure by up to twice (docs/shadows.md).
TEST(ReferenceAgreement, DemoWithShadowsAgainstExactVisibilityForTheSameVpls) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes/demo.scene"));
  const Image naive = renderNaive(scene, true);
  const Image sameVpls = renderOnCpu(scene, ReferenceSettings::Sampling::Vpl, true);
  std::vector<bool> compared = emitterMask(scene, kSize, 0);
  compared.flip();
  const double error = compareImages(naive, sameVpls, &compared).relativeMse;
  ::testing::Test::RecordProperty("relmse_vs_reference_vpl", scientific(error));
  EXPECT_LE(error, 5e-4);
}

}  // namespace
}  // namespace penumbra
