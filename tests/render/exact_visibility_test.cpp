// Exact visibility (--visibility bvh): the naive and hierarchical modes with shadow rays through
// the BVH against reference-vpl (the same VPLs, Embree's exact visibility) on every shadow scene
// of the repository, and the top level of an animated scene following its transforms.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "image/metrics.h"
#include "reference/emitter_mask.h"
#include "reference/reference.h"
#include "render/frame.h"
#include "render/render_test_scenes.h"
#include "test_files.h"

namespace penumbra {
namespace {

// Small images and 64 VPLs per light keep each scene to a few seconds on llvmpipe; the
// visibility of every pixel and VPL is still compared, which is what these tests are about.
constexpr glm::ivec2 kSize{96, 96};
constexpr int kVplsPerLight = 64;

// The goal (issue 15): with exact visibility both sides trace the same rays to the same
// VPLs, so what remains is float rounding (the naive mode measures 1e-14 to 2e-7 here, the
// pixels seen edge-on left out). relMSE 2e-4 is a 1.4% RMS relative error.
constexpr double kRelativeMseBound = 2e-4;
constexpr double kSsimBound = 0.995;
// Smooth normals on coarse geometry: the reference starts its shadow rays from the point lifted
// onto the surface the normals describe (Hanika's shadow-terminator fix, docs/shadows.md); the GPU
// modes do not yet (they would need the triangle's vertices per pixel), so their lit sides of the
// posts differ: 2.6e-4 measured on the post grid with smooth normals. Not the goal: issue 15 stays
// open for it.
constexpr double kSmoothNormalsRelativeMseBound = 4e-4;
// The hierarchy adds its own interpolation between texels, which the visibility does not change:
// against the naive mode with the same rays it measures 3.4e-4 (Cornell box) and 4.2e-4 (demo) at
// this size, 1.1e-4 and 2.2e-4 at 256x256, so it misses the goal above on those two scenes. Its
// bound is the hierarchy's own against the naive mode (Shadows.HierarchyMatchesTheNaiveMode*).
// Its SSIM (image/metrics: the PNG tone map, RGB) is 0.989 on the demo at this size, 0.995 to
// 0.9999 elsewhere: the demo's bound leaves 0.004 for llvmpipe's rounding differences between
// machines; the goal stays open for the hierarchy (issue 15, docs/shadows.md).
constexpr double kHierarchyRelativeMseBound = 2e-3;
constexpr double kHierarchySsimBound = 0.985;

RenderSettings exactSettings(RenderMode mode) {
  RenderSettings settings;
  settings.mode = mode;
  settings.vplsPerLight = kVplsPerLight;
  settings.shadows.visibility = ShadowSettings::Visibility::Bvh;
  return settings;
}

Image renderReferenceVpl(const Scene& scene, int frame, bool shadows = true) {
  ReferenceSettings settings;
  settings.sampling = ReferenceSettings::Sampling::Vpl;
  settings.vplsPerLight = kVplsPerLight;
  settings.size = kSize;
  settings.frame = frame;
  settings.shadows = shadows;
  return renderReference(scene, settings);
}

// Pixels where the rasteriser and Embree see different surfaces (faces seen edge-on, a slab's
// thin side) differ with or without shadows; they say nothing about visibility. They are found
// without shadows (test::leaveOutEdgeOnPixels), counted and left out, with
// the light quads and emitting surfaces (which are not lit).
// Measured: 0 or 1 on the repository's scenes, 12 and 11 on the animated slab's thin sides.
constexpr int kMaxEdgeOnPixels = 16;

std::vector<bool> comparedPixels(const Scene& scene, Renderer& renderer, int frame) {
  std::vector<bool> compared = emitterMask(scene, kSize, frame);
  compared.flip();
  RenderSettings unshadowed = exactSettings(RenderMode::Naive);
  unshadowed.shadows.enabled = false;
  renderer.render(frame, unshadowed);
  const int edgeOnPixels = test::leaveOutEdgeOnPixels(
      renderer.readRadiance(), renderReferenceVpl(scene, frame, false), compared);
  std::printf("frame %d: %d pixels edge-on\n", frame, edgeOnPixels);
  EXPECT_LE(edgeOnPixels, kMaxEdgeOnPixels) << "frame " << frame;
  return compared;
}

struct Agreement {
  double relativeMse = 0.0;
  double ssim = 0.0;
};

Agreement agreement(const Image& image, const Image& reference, const std::vector<bool>& compared) {
  return {compareImages(image, reference, &compared).relativeMse,
          structuralSimilarity(image, reference, &compared).mean};
}

void expectExactVisibilityMatchesReferenceVpl(const std::string& sceneName,
                                              double naiveRelativeMseBound = kRelativeMseBound) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes" / sceneName));
  const Image reference = renderReferenceVpl(scene, 0);
  Renderer renderer(scene, kSize);
  const std::vector<bool> compared = comparedPixels(scene, renderer, 0);
  for (const RenderMode mode : {RenderMode::Naive, RenderMode::Hierarchical}) {
    renderer.render(0, exactSettings(mode));
    const Agreement result = agreement(renderer.readRadiance(), reference, compared);
    std::printf("%s, %s with --visibility bvh against reference-vpl: relMSE %.3g, SSIM %.5f\n",
                sceneName.c_str(), renderModeName(mode), result.relativeMse, result.ssim);
    EXPECT_LE(result.relativeMse,
              mode == RenderMode::Naive ? naiveRelativeMseBound : kHierarchyRelativeMseBound)
        << sceneName << " " << renderModeName(mode);
    EXPECT_GE(result.ssim, mode == RenderMode::Naive ? kSsimBound : kHierarchySsimBound)
        << sceneName << " " << renderModeName(mode);
  }
}

TEST(ExactVisibility, MatchesReferenceVplOnTheBox) {
  expectExactVisibilityMatchesReferenceVpl("shadow_box.scene");
}

TEST(ExactVisibility, MatchesReferenceVplOnTheThinPosts) {
  expectExactVisibilityMatchesReferenceVpl("shadow_posts.scene");
}

TEST(ExactVisibility, MatchesReferenceVplOnTheTwoColourLight) {
  expectExactVisibilityMatchesReferenceVpl("shadow_two_colour.scene");
}

TEST(ExactVisibility, MatchesReferenceVplOnTheOffscreenOccluder) {
  expectExactVisibilityMatchesReferenceVpl("shadow_offscreen.scene");
}

TEST(ExactVisibility, MatchesReferenceVplOnTheCornellBoxWithTheBunny) {
  expectExactVisibilityMatchesReferenceVpl("cornell_bunny.scene");
}

TEST(ExactVisibility, MatchesReferenceVplOnTheDemo) {
  expectExactVisibilityMatchesReferenceVpl("demo.scene");
}

TEST(ExactVisibility, MatchesReferenceVplOnTheHungCube) {
  expectExactVisibilityMatchesReferenceVpl("shadow_hung_cube.scene");
}

TEST(ExactVisibility, MatchesReferenceVplOnTheThinPostGrid) {
  expectExactVisibilityMatchesReferenceVpl("shadow_post_grid.scene");
}

TEST(ExactVisibility, MatchesReferenceVplOnTheThinPostGridWithSmoothNormals) {
  expectExactVisibilityMatchesReferenceVpl("shadow_post_grid_smooth.scene",
                                           kSmoothNormalsRelativeMseBound);
}

TEST(ExactVisibility, MatchesReferenceVplOnTheLowPolySphere) {
  expectExactVisibilityMatchesReferenceVpl("shadow_low_poly_sphere.scene");
}

TEST(ExactVisibility, MatchesReferenceVplOnObjectsRestingOnAFloor) {
  expectExactVisibilityMatchesReferenceVpl("shadow_resting.scene");
}

TEST(ExactVisibility, MatchesReferenceVplOnALargeLightCloseToAWall) {
  expectExactVisibilityMatchesReferenceVpl("shadow_light_near_wall.scene");
}

// A slab swinging over a floor under a light: the top level follows its transform every frame
// (and is rebuilt only then), and its shadow lands where reference-vpl puts it at each frame.
TEST(ExactVisibility, TheTopLevelFollowsAnAnimatedObject) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  Scene scene = test::loadSceneText(
      directory,
      "material glow\n  emit 3 3 3\nend\n"
      "area_light square\n"
      "  pos1 -1 3 -1\n  pos2 1 3 -1\n  pos3 1 3 1\n  pos4 -1 3 1\n  at 0 0 0\n  mat glow\nend\n"
      "camera c\n  pos 0 5 5\n  at 0 0 0\nend\n"
      "object floor.obj\nend\n"
      "object " +
          test::sourceDirectory().string() +
          "/scenes/assets/cube.obj\n"
          "  translate 0 1.5 0\n  scale 0.6 0.1 0.6\n  anim translate 2 0 0 0.5\nend\n");
  Renderer renderer(scene, kSize);
  const int moved = 3;  // sin(1.5): the slab at nearly its farthest to the side
  const std::vector<bool> comparedAt[] = {comparedPixels(scene, renderer, 0),
                                          comparedPixels(scene, renderer, moved)};
  const RenderSettings settings = exactSettings(RenderMode::Naive);
  renderer.render(0, settings);
  const Image first = renderer.readRadiance();
  EXPECT_EQ(renderer.bvh().topLevelBuilds(), 1);
  renderer.render(0, settings);
  EXPECT_EQ(renderer.bvh().topLevelBuilds(), 1) << "nothing moved, yet the top level was rebuilt";
  EXPECT_EQ(renderer.bvh().instances().size(), 3u);  // the floor, the slab and the light quad

  renderer.render(moved, settings);
  EXPECT_EQ(renderer.bvh().topLevelBuilds(), 2);
  const Image second = renderer.readRadiance();
  for (const int frame : {0, moved}) {
    const Agreement result = agreement(frame == 0 ? first : second,
                                       renderReferenceVpl(scene, frame), comparedAt[frame != 0]);
    std::printf("frame %d against reference-vpl: relMSE %.3g, SSIM %.5f\n", frame,
                result.relativeMse, result.ssim);
    EXPECT_LE(result.relativeMse, kRelativeMseBound) << "frame " << frame;
    EXPECT_GE(result.ssim, kSsimBound) << "frame " << frame;
  }
  // The shadow moved: the two frames differ well beyond the bound above.
  std::vector<bool> all(first.pixels.size(), true);
  EXPECT_GT(compareImages(first, second, &all).relativeMse, 100 * kRelativeMseBound);
}

}  // namespace
}  // namespace penumbra
