// Exact visibility (--visibility bvh): the naive and hierarchical modes with shadow rays through
// the BVH against reference-vpl (the same VPLs, Embree's exact visibility) on every shadow scene
// of the repository, the top level of an animated scene following its transforms, and the
// G-buffer's shadow-ray start (the shadow-terminator lift) against the reference's. And the naive
// mode with the default voxel visibility against the same bounds (issue 15's goal).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "image/metrics.h"
#include "reference/emitter_mask.h"
#include "reference/reference.h"
#include "render/frame.h"
#include "render/readback.h"
#include "render/render_test_scenes.h"
#include "scene/shadow_terminator.h"
#include "test_files.h"

namespace penumbra {
namespace {

// Small images and 64 VPLs per light keep each scene to a few seconds on llvmpipe; the
// visibility of every pixel and VPL is still compared, which is what these tests are about.
constexpr glm::ivec2 kSize{96, 96};
constexpr int kVplsPerLight = 64;

// The issue's goal (issue 15): with exact visibility both sides trace the same rays to the same
// VPLs from the same points (on smooth-normal meshes the points lifted onto the surface the
// normals describe, as the G-buffer stores them), so what remains is float rounding (the naive
// mode measures 1e-14 to 2e-7 here, the pixels seen edge-on left out). relMSE 2e-4 is a 1.4% RMS
// relative error.
constexpr double kRelativeMseBound = 2e-4;
constexpr double kSsimBound = 0.995;
// The hierarchy adds its own interpolation between texels and takes masks from coarser texels
// where their surface stands for the texel's (parent_surface.glsl). With the light-proximity
// refinement (docs/multiresolution.md) it meets the goal above on most scenes: relMSE 2e-6 to
// 1e-4 and SSIM 0.998 to 0.9999 at this size (HierarchyBound::Goal). Where it does not
// (HierarchyBound::Open), its bound is the hierarchy's own against the naive mode
// (Shadows.HierarchyMatchesTheNaiveMode*): the post grids (5.6e-4 and 6.4e-4 at this size, where
// a post is narrower than a pixel; they meet the goal at 256x256, the test below), the demo
// (2.7e-4, SSIM 0.991) and the thin posts (1.4e-4, but SSIM 0.9953 leaves too little above 0.995
// for llvmpipe's rounding differences between machines). The demo's SSIM bound leaves 0.004 for
// those; the goal stays open there (issue 15, docs/shadows.md).
constexpr double kHierarchyRelativeMseBound = 2e-3;
constexpr double kHierarchySsimBound = 0.985;
enum class HierarchyBound { Goal, Open };

RenderSettings exactSettings(
    RenderMode mode, ShadowSettings::Visibility visibility = ShadowSettings::Visibility::Bvh) {
  RenderSettings settings;
  settings.mode = mode;
  settings.vplsPerLight = kVplsPerLight;
  settings.shadows.visibility = visibility;
  return settings;
}

Image renderReferenceVpl(const Scene& scene, int frame, bool shadows = true,
                         glm::ivec2 size = kSize) {
  ReferenceSettings settings;
  settings.sampling = ReferenceSettings::Sampling::Vpl;
  settings.vplsPerLight = kVplsPerLight;
  settings.size = size;
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

std::vector<bool> comparedPixels(const Scene& scene, Renderer& renderer, int frame,
                                 glm::ivec2 size = kSize) {
  std::vector<bool> compared = emitterMask(scene, size, frame);
  compared.flip();
  RenderSettings unshadowed = exactSettings(RenderMode::Naive);
  unshadowed.shadows.enabled = false;
  renderer.render(frame, unshadowed);
  const int edgeOnPixels = test::leaveOutEdgeOnPixels(
      renderer.readRadiance(), renderReferenceVpl(scene, frame, false, size), compared);
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
                                              HierarchyBound hierarchyBound,
                                              glm::ivec2 size = kSize) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes" / sceneName));
  const Image reference = renderReferenceVpl(scene, 0, true, size);
  Renderer renderer(scene, size);
  const std::vector<bool> compared = comparedPixels(scene, renderer, 0, size);
  for (const RenderMode mode : {RenderMode::Naive, RenderMode::Hierarchical}) {
    renderer.render(0, exactSettings(mode));
    const Agreement result = agreement(renderer.readRadiance(), reference, compared);
    std::printf("%s, %s with --visibility bvh against reference-vpl: relMSE %.3g, SSIM %.5f\n",
                sceneName.c_str(), renderModeName(mode), result.relativeMse, result.ssim);
    const bool goal = mode == RenderMode::Naive || hierarchyBound == HierarchyBound::Goal;
    EXPECT_LE(result.relativeMse, goal ? kRelativeMseBound : kHierarchyRelativeMseBound)
        << sceneName << " " << renderModeName(mode);
    EXPECT_GE(result.ssim, goal ? kSsimBound : kHierarchySsimBound)
        << sceneName << " " << renderModeName(mode);
  }
}

TEST(ExactVisibility, MatchesReferenceVplOnTheBox) {
  expectExactVisibilityMatchesReferenceVpl("shadow_box.scene", HierarchyBound::Goal);
}

TEST(ExactVisibility, MatchesReferenceVplOnTheThinPosts) {
  expectExactVisibilityMatchesReferenceVpl("shadow_posts.scene", HierarchyBound::Open);
}

TEST(ExactVisibility, MatchesReferenceVplOnTheTwoColourLight) {
  expectExactVisibilityMatchesReferenceVpl("shadow_two_colour.scene", HierarchyBound::Goal);
}

TEST(ExactVisibility, MatchesReferenceVplOnTheOffscreenOccluder) {
  expectExactVisibilityMatchesReferenceVpl("shadow_offscreen.scene", HierarchyBound::Goal);
}

TEST(ExactVisibility, MatchesReferenceVplOnTheCornellBoxWithTheBunny) {
  expectExactVisibilityMatchesReferenceVpl("cornell_bunny.scene", HierarchyBound::Goal);
}

TEST(ExactVisibility, MatchesReferenceVplOnTheDemo) {
  expectExactVisibilityMatchesReferenceVpl("demo.scene", HierarchyBound::Open);
}

TEST(ExactVisibility, MatchesReferenceVplOnTheHungCube) {
  expectExactVisibilityMatchesReferenceVpl("shadow_hung_cube.scene", HierarchyBound::Goal);
}

TEST(ExactVisibility, MatchesReferenceVplOnTheThinPostGrid) {
  expectExactVisibilityMatchesReferenceVpl("shadow_post_grid.scene", HierarchyBound::Open);
}

TEST(ExactVisibility, MatchesReferenceVplOnTheThinPostGridWithSmoothNormals) {
  expectExactVisibilityMatchesReferenceVpl("shadow_post_grid_smooth.scene", HierarchyBound::Open);
}

// At 256x256, issue 15's size, the hierarchy meets the goal on the post grids too: where a
// parent texel straddles a post and the floor, the floor texels in the post's narrow shadow
// trace their own visibility instead of taking the parent's (parent_surface.glsl). Measured with
// 64 VPLs per light: relMSE 1.1e-4 and 1.0e-4; taking the parent's everywhere, as before, 6.0e-4
// and 5.5e-4.
constexpr glm::ivec2 kIssueSize{256, 256};

TEST(ExactVisibility, TheHierarchyMeetsTheGoalOnThePostGridsAt256) {
  for (const char* sceneName : {"shadow_post_grid.scene", "shadow_post_grid_smooth.scene"})
    expectExactVisibilityMatchesReferenceVpl(sceneName, HierarchyBound::Goal, kIssueSize);
}

TEST(ExactVisibility, MatchesReferenceVplOnTheLowPolySphere) {
  expectExactVisibilityMatchesReferenceVpl("shadow_low_poly_sphere.scene", HierarchyBound::Goal);
}

TEST(ExactVisibility, MatchesReferenceVplOnObjectsRestingOnAFloor) {
  expectExactVisibilityMatchesReferenceVpl("shadow_resting.scene", HierarchyBound::Goal);
}

TEST(ExactVisibility, MatchesReferenceVplOnALargeLightCloseToAWall) {
  expectExactVisibilityMatchesReferenceVpl("shadow_light_near_wall.scene", HierarchyBound::Goal);
}

// Issue 15's goal for the voxels at the default settings: the naive mode with voxel visibility
// (the default grid: as many voxels as a cube of 304 a side, shared out in proportion to the
// scene's box, with the boxes and slabs of the surfaces inside them) against reference-vpl, the
// same bounds as the BVH's above. Measured at this size on 2026-12-07: relMSE 4.4e-6 to 3.3e-5
// and SSIM 0.9990 to 0.9999 on eleven scenes, the resting objects 1.0e-4 and 0.9997 (with the
// equal grid of 192 voxels per axis, the default until then, 4.2e-4: the test of that grid
// below).
void expectVoxelVisibilityMatchesReferenceVpl(const std::string& sceneName,
                                              double relativeMseBound = kRelativeMseBound,
                                              double ssimBound = kSsimBound,
                                              RenderMode mode = RenderMode::Naive,
                                              glm::ivec2 size = kSize,
                                              const VoxelSettings& voxels = {}) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes" / sceneName));
  const Image reference = renderReferenceVpl(scene, 0, true, size);
  Renderer renderer(scene, size);
  const std::vector<bool> compared = comparedPixels(scene, renderer, 0, size);
  RenderSettings settings = exactSettings(mode, ShadowSettings::Visibility::Voxels);
  settings.shadows.voxels = voxels;
  renderer.render(0, settings);
  const Agreement result = agreement(renderer.readRadiance(), reference, compared);
  std::printf("%s, %s with voxels (%d, %s) against reference-vpl: relMSE %.3g, SSIM %.5f\n",
              sceneName.c_str(), renderModeName(mode), voxels.resolution,
              voxels.shape == VoxelSettings::Shape::Cubic ? "cubic" : "equal", result.relativeMse,
              result.ssim);
  EXPECT_LE(result.relativeMse, relativeMseBound) << sceneName;
  EXPECT_GE(result.ssim, ssimBound) << sceneName;
}

TEST(VoxelVisibility, MatchesReferenceVplOnTheShadowScenes) {
  for (const char* sceneName :
       {"shadow_box.scene", "shadow_hung_cube.scene", "shadow_light_near_wall.scene",
        "shadow_low_poly_sphere.scene", "shadow_offscreen.scene", "shadow_two_colour.scene",
        "shadow_resting.scene"})
    expectVoxelVisibilityMatchesReferenceVpl(sceneName);
}

TEST(VoxelVisibility, MatchesReferenceVplOnThinPosts) {
  for (const char* sceneName :
       {"shadow_posts.scene", "shadow_post_grid.scene", "shadow_post_grid_smooth.scene"})
    expectVoxelVisibilityMatchesReferenceVpl(sceneName);
}

TEST(VoxelVisibility, MatchesReferenceVplOnTheCornellBoxAndTheDemo) {
  for (const char* sceneName : {"cornell_bunny.scene", "demo.scene"})
    expectVoxelVisibilityMatchesReferenceVpl(sceneName);
}

// The equal grid (`--voxel-shape equal`) of 192 voxels per axis, the default until 2026-12-07, on
// the scene it does not bring within the goal: the bunny's curved surface fills its flat voxels'
// slabs more than a plane does (docs/shadows.md, "Cubic voxels"). Measured 4.2e-4, SSIM 0.9991;
// the bound, 6e-4, leaves llvmpipe's rounding on other machines a margin and still fails a step
// back (3.4e-3 before the slabs inside the voxels).
TEST(VoxelVisibility, AnEqualGridOf192StaysWithinItsMeasuredErrorOnTheRestingObjects) {
  VoxelSettings equal;
  equal.shape = VoxelSettings::Shape::Equal;
  equal.resolution = 192;
  expectVoxelVisibilityMatchesReferenceVpl("shadow_resting.scene", 6e-4, kSsimBound,
                                           RenderMode::Naive, kSize, equal);
}

// The default mode at issue 15's size on every shadow scene: the hierarchy adds nothing visible
// to the voxels' error. Measured with 64 VPLs per light: relMSE 5.8e-6 to 1.7e-4 and SSIM 0.9959
// to 0.9999, the thin posts the highest (1.7e-4, 0.9959: posts a few pixels wide, whose shadows
// the texels' interpolation softens; 1.5e-4 and 0.9963 before the full resolution shared its VPLs
// out over 2x2 pixels, docs/shadows.md "VPLs shared out over 2x2 pixels"); docs/shadows.md
// ("Cubic voxels") gives them with 256.
TEST(VoxelVisibility, TheHierarchyMeetsTheGoalOnEveryShadowSceneAt256) {
  for (const char* sceneName :
       {"shadow_box.scene", "shadow_hung_cube.scene", "shadow_light_near_wall.scene",
        "shadow_low_poly_sphere.scene", "shadow_offscreen.scene", "shadow_two_colour.scene",
        "shadow_posts.scene", "shadow_post_grid.scene", "shadow_post_grid_smooth.scene",
        "demo.scene"})
    expectVoxelVisibilityMatchesReferenceVpl(sceneName, kRelativeMseBound, kSsimBound,
                                             RenderMode::Hierarchical, kIssueSize);
}

// The same on the Cornell box with the bunny's box, whose side away from the light leaves the
// floor at its foot next to texels without a mask: the floor there traces its own rays instead of
// taking its parent's light (visibility_trace.comp), which kept the contact shadow; taking the
// parent's where only the neighbours with masks agreed measured 5.1e-4 (a row of pixels lit at the
// box's foot). The same at the bunny's feet on its box, whose undersides face no light: a texel
// next to such a surface counts as changing visibility (visibility_compare.comp), so that its
// children trace instead of taking a parent's mask whole. Measured with 64 VPLs per light: relMSE
// 3.9e-5, SSIM 0.9984 (3.7e-5 before the VPLs were shared out over 2x2 pixels; 4.9e-5 with the
// equal grid of 192); 1.4e-4 before (two pixels at a foot lit as the open box top). The bound,
// 8e-5, leaves llvmpipe's rounding on other machines a margin and fails the step back.
TEST(VoxelVisibility, TheHierarchyKeepsTheContactShadowsAtTheFeetOfTheBoxAndTheBunny) {
  expectVoxelVisibilityMatchesReferenceVpl("cornell_bunny.scene", 8e-5, kSsimBound,
                                           RenderMode::Hierarchical, kIssueSize);
}

// And on the resting objects. Under the bunny's toes the floor is dark in pixels between lit
// ones, a shadow narrower than a parent texel that neither the parent nor its neighbours saw: a
// pixel next to another mesh's surface (visibility_select.comp) traces its own VPLs instead of
// taking its parent's. Measured with 64 VPLs per light: relMSE 1.5e-4, SSIM 0.9992, with the VPLs
// shared out over 2x2 pixels or not (the equal grid of 192: 4.1e-4, and 5.8e-4 before that rule,
// with two such floor pixels lit).
TEST(VoxelVisibility, TheHierarchyKeepsTheContactShadowsUnderTheBunnysToes) {
  expectVoxelVisibilityMatchesReferenceVpl("shadow_resting.scene", kRelativeMseBound, kSsimBound,
                                           RenderMode::Hierarchical, kIssueSize);
}

// The G-buffer of a naive frame at the scene's camera size, read back. With shadows, since
// without them the renderer leaves out where shadow rays start.
struct GBufferPixels {
  std::vector<glm::vec4> positions;
  std::vector<glm::vec4> normalKinds;
  std::vector<glm::vec4> lifts;
  std::vector<glm::vec4> faceNormals;
};

GBufferPixels renderGBuffer(Scene& scene, bool shadows = true) {
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings;
  settings.mode = RenderMode::Naive;
  settings.shadows.enabled = shadows;
  renderer.render(0, settings);
  const GBuffer& gbuffer = renderer.gbuffer();
  const auto read = [&](const gl::Texture& texture) {
    return readTexture(texture.id(), gbuffer.size, RowOrder::BottomFirst).pixels;
  };
  return {read(gbuffer.positionDepth), read(gbuffer.normalKind), read(gbuffer.shadowLift),
          read(gbuffer.faceNormal)};
}

// The G-buffer's face normal carries the mesh of each surface pixel, which the rule above reads:
// the floor is the first object's mesh (1), the cube resting on it the second's (2), and a light
// quad in view has none (0).
TEST(VoxelVisibility, TheGBufferTellsWhichMeshEachPixelShows) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  Scene scene = test::loadSceneText(
      directory,
      "material glow\n  emit 3 3 3\nend\n"
      "area_light panel\n"
      "  pos1 -1 2 -2\n  pos2 1 2 -2\n  pos3 1 2.5 -3\n  pos4 -1 2.5 -3\n  at 0 0 0\n"
      "  mat glow\nend\n"
      "camera c\n  pos 0 1.5 4\n  at 0 0.8 0\n  fovy 60\n  screen_size 48 48\nend\n"
      "object floor.obj\nend\n"
      "object " +
          test::sourceDirectory().string() + "/scenes/assets/cube.obj\n  translate 0 0.5 0\nend\n");
  const GBufferPixels gbuffer = renderGBuffer(scene);
  std::array<int, 3> pixelsOfMesh{};
  for (std::size_t pixel = 0; pixel < gbuffer.positions.size(); ++pixel) {
    const int kind = static_cast<int>(gbuffer.normalKinds[pixel].w);
    if (kind == gpu::kPixelBackground)
      continue;
    // The floor lies at y = 0 (within the G-buffer's rounding), the cube above it.
    const int expected = kind == gpu::kPixelEmitter           ? 0
                         : gbuffer.positions[pixel].y < 1e-4f ? 1
                                                              : 2;
    EXPECT_EQ(gbuffer.faceNormals[pixel].w, static_cast<float>(expected)) << "pixel " << pixel;
    ++pixelsOfMesh[static_cast<std::size_t>(expected)];
  }
  EXPECT_GT(pixelsOfMesh[0], 0) << "the light is out of view";
  EXPECT_GT(pixelsOfMesh[1], 0) << "the floor is out of view";
  EXPECT_GT(pixelsOfMesh[2], 0) << "the cube is out of view";
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

// A pyramid of four triangles with smooth normals (the apex's straight up, the base corners'
// leaning out): every point of its faces lies below its corners' tangent planes, so the lift
// moves every point but the corners.
const std::array<glm::vec3, 5> kPyramidCorners{
    glm::vec3(0.0f, 0.6f, 0.0f), glm::vec3(-1.0f, 0.0f, -1.0f), glm::vec3(1.0f, 0.0f, -1.0f),
    glm::vec3(1.0f, 0.0f, 1.0f), glm::vec3(-1.0f, 0.0f, 1.0f)};
const std::array<glm::vec3, 5> kPyramidNormals{
    glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(-0.5f, 0.7f, -0.5f), glm::vec3(0.5f, 0.7f, -0.5f),
    glm::vec3(0.5f, 0.7f, 0.5f), glm::vec3(-0.5f, 0.7f, 0.5f)};
const std::array<std::array<std::size_t, 3>, 4> kPyramidFaces{
    {{0, 2, 1}, {0, 3, 2}, {0, 4, 3}, {0, 1, 4}}};
const char* const kPyramidObj =
    "v 0 0.6 0\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\n"
    "vn 0 1 0\nvn -0.5 0.7 -0.5\nvn 0.5 0.7 -0.5\nvn 0.5 0.7 0.5\nvn -0.5 0.7 0.5\n"
    "f 1//1 3//3 2//2\nf 1//1 4//4 3//3\nf 1//1 5//5 4//4\nf 1//1 2//2 5//5\n";

// Barycentric weights of `point` in the triangle of `corners`.
glm::vec3 barycentric(glm::vec3 point, const std::array<glm::vec3, 3>& corners) {
  const glm::vec3 u = corners[1] - corners[0];
  const glm::vec3 v = corners[2] - corners[0];
  const glm::vec3 w = point - corners[0];
  const float uu = glm::dot(u, u);
  const float uv = glm::dot(u, v);
  const float vv = glm::dot(v, v);
  const float denominator = uu * vv - uv * uv;
  const float weight1 = (vv * glm::dot(w, u) - uv * glm::dot(w, v)) / denominator;
  const float weight2 = (uu * glm::dot(w, v) - uv * glm::dot(w, u)) / denominator;
  return {1.0f - weight1 - weight2, weight1, weight2};
}

// The smooth-normal pyramid seen from above, lit from the side.
Scene pyramidLitFromTheSide() {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "pyramid.obj", kPyramidObj);
  return test::loadSceneText(
      directory,
      "material glow\n  emit 3 3 3\nend\n"
      "area_light side\n"
      "  pos1 3 1 -1\n  pos2 3 1 1\n  pos3 3 2 1\n  pos4 3 2 -1\n  at 0 0 0\n  mat glow\nend\n"
      "camera c\n  pos 0.4 3 1.2\n  at 0 0 0\n  screen_size 48 48\nend\n"
      "object pyramid.obj\nend\n");
}

// Every surface pixel of the G-buffer: its position plus its shadowLift is where the reference
// starts the same point's shadow rays (liftedOntoNormals), and its face normal is the
// reference's, on the triangle the pixel lies in (the one its weights are most inside of; on an
// edge both give the same lift, the normals being shared).
TEST(ShadowTerminator, TheGBufferLiftsPointsAsTheReferenceDoes) {
  Scene scene = pyramidLitFromTheSide();
  const GBufferPixels gbuffer = renderGBuffer(scene);
  const std::vector<glm::vec4>& positions = gbuffer.positions;
  const std::vector<glm::vec4>& normalKinds = gbuffer.normalKinds;
  const std::vector<glm::vec4>& lifts = gbuffer.lifts;
  const std::vector<glm::vec4>& faceNormals = gbuffer.faceNormals;

  int surfacePixels = 0;
  int liftedPixels = 0;
  float largestDifference = 0.0f;
  float largestFaceNormalDifference = 0.0f;
  for (std::size_t pixel = 0; pixel < positions.size(); ++pixel) {
    if (static_cast<int>(normalKinds[pixel].w) != gpu::kPixelSurface)
      continue;
    ++surfacePixels;
    const glm::vec3 position(positions[pixel]);
    std::array<glm::vec3, 3> corners{};
    std::array<glm::vec3, 3> cornerNormals{};
    glm::vec3 weights(-1.0f);
    for (const auto& face : kPyramidFaces) {
      const std::array<glm::vec3, 3> faceCorners{kPyramidCorners[face[0]], kPyramidCorners[face[1]],
                                                 kPyramidCorners[face[2]]};
      const glm::vec3 faceWeights = barycentric(position, faceCorners);
      if (std::min({faceWeights.x, faceWeights.y, faceWeights.z}) >
          std::min({weights.x, weights.y, weights.z})) {
        weights = faceWeights;
        corners = faceCorners;
        cornerNormals = {kPyramidNormals[face[0]], kPyramidNormals[face[1]],
                         kPyramidNormals[face[2]]};
      }
    }
    const glm::vec3 towardsEye = scene.camera.position - position;
    glm::vec3 faceNormal = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
    faceNormal = glm::normalize(glm::dot(faceNormal, towardsEye) < 0.0f ? -faceNormal : faceNormal);
    const glm::vec3 smoothNormal =
        weights.x * cornerNormals[0] + weights.y * cornerNormals[1] + weights.z * cornerNormals[2];
    const float side = glm::dot(smoothNormal, faceNormal) < 0.0f ? -1.0f : 1.0f;
    const glm::vec3 expected = liftedOntoNormals(position, corners, cornerNormals, weights, side);
    const glm::vec3 lift(lifts[pixel]);
    largestDifference = std::max(largestDifference, glm::length(position + lift - expected));
    largestFaceNormalDifference = std::max(largestFaceNormalDifference,
                                           glm::length(glm::vec3(faceNormals[pixel]) - faceNormal));
    if (glm::length(expected - position) > 0.01f)
      ++liftedPixels;
  }
  std::printf(
      "%d surface pixels, %d lifted by over 1 cm; largest difference %.3g (origin), %.3g "
      "(face normal)\n",
      surfacePixels, liftedPixels, largestDifference, largestFaceNormalDifference);
  EXPECT_GT(surfacePixels, 500);
  // Nearly every point moves by over a centimetre (all but those next to the apex, where the
  // lift vanishes; 1204 of 1204 measured): the test sees the lift, not zeros on both sides.
  EXPECT_GT(liftedPixels, surfacePixels / 2);
  // The G-buffer's weights come from the rasteriser's interpolation, the test's from the
  // interpolated position: they differ by float rounding, a few 1e-7 on this 2 m mesh. Leaving
  // out a corner's term or the side would move points by centimetres.
  EXPECT_LT(largestDifference, 1e-5f);
  EXPECT_LT(largestFaceNormalDifference, 1e-5f);
}

// The reflective shadow map's faces, and the camera's G-buffer without shadows, leave out where
// shadow rays start (GBufferPass::ShadowRayStarts::skipped): zeros there, and in every other
// target what the G-buffer with them holds, bit for bit (the secondary VPLs and the shading come
// from those).
TEST(ShadowTerminator, AGBufferWithoutShadowRayStartsHoldsTheSameSurfaces) {
  Scene scene = pyramidLitFromTheSide();
  SceneGpu sceneGpu(scene);
  sceneGpu.update(0, 0.0, 4);
  GBuffer written(scene.camera.size);
  GBuffer skipped(scene.camera.size);
  GBufferPass().run({sceneGpu, scene.camera}, {written});
  GBufferPass(GBufferPass::ShadowRayStarts::skipped).run({sceneGpu, scene.camera}, {skipped});
  const auto read = [&](const gl::Texture& texture) {
    return readTexture(texture.id(), scene.camera.size, RowOrder::BottomFirst).pixels;
  };
  EXPECT_EQ(read(skipped.positionDepth), read(written.positionDepth));
  EXPECT_EQ(read(skipped.normalKind), read(written.normalKind));
  EXPECT_EQ(read(skipped.albedo), read(written.albedo));
  EXPECT_EQ(read(skipped.specular), read(written.specular));
  EXPECT_EQ(read(skipped.emission), read(written.emission));
  const std::vector<glm::vec4> zeros(read(written.shadowLift).size(), glm::vec4(0.0f));
  // The camera's G-buffer does write them here (the pyramid's smooth normals lift its points),
  // so the zeros are the variant's.
  EXPECT_NE(read(written.shadowLift), zeros);
  EXPECT_NE(read(written.faceNormal), zeros);
  EXPECT_EQ(read(skipped.shadowLift), zeros);
  EXPECT_EQ(read(skipped.faceNormal), zeros);

  const GBufferPixels unshadowed = renderGBuffer(scene, false);
  EXPECT_EQ(unshadowed.positions, read(written.positionDepth));
  EXPECT_EQ(unshadowed.lifts, zeros);
  EXPECT_EQ(unshadowed.faceNormals, zeros);
}

}  // namespace
}  // namespace penumbra
