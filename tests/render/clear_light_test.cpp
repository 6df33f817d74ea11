// The clear-light test (light_pyramid.glsl; visibility_clear.comp) through the voxel grid's
// occupancy pyramid (voxel_grid.glsl, lightClearFrom) and through the BVH (bvh.glsl,
// bvhLightClearFrom): a texel that it finds clear of a quad light takes all of that light's VPLs
// as visible without tracing a ray, so it must never pass where a ray would be blocked, and the
// masks (hence the images) must be those of tracing every ray. And the other use of the occupancy
// pyramid, the traversal's empty-space skipping (cellsBlocked): it must answer every shadow ray as
// the walk over every column does.

#include <array>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "reference/ray_scene.h"
#include "render/frame.h"
#include "render/readback.h"
#include "render/voxel_queries.h"
#include "scene/area_light.h"
#include "shared.h"
#include "test_files.h"

namespace penumbra {
namespace {

Scene loadRepositoryScene(const std::string& name) {
  return loadScene(parseSceneFile(test::sourceDirectory() / "scenes" / (name + ".scene")));
}

struct ClearLightCounts {
  std::size_t pairs = 0;            // (point, light) pairs where the light can light the point
  std::size_t seenWhole = 0;        // of those, pairs whose every VPL the traversal finds visible
  std::size_t clear = 0;            // pairs the test passes
  std::size_t clearButBlocked = 0;  // passed, yet the traversal blocks a VPL
  std::size_t clearButExactlyBlocked = 0;  // passed, yet Embree blocks a VPL
};

// The G-buffer's surface points at 64x64 against each quad light's 16 x 16 VPLs (the default
// count): the test's answer against the traversal's for every VPL (the GPU's vplVisible through
// the renderer's grid) and against Embree's exact visibility, with the reference's offsets.
ClearLightCounts countClearLights(const std::string& sceneName) {
  Scene scene = loadRepositoryScene(sceneName);
  Renderer renderer(scene, {64, 64});
  // Hierarchical: the grid's occupancy pyramid is built for the hierarchy only.
  RenderSettings settings;
  settings.vplsPerLight = 1;
  renderer.render(0, settings);

  const std::vector<test::VoxelQueries::Point> points = test::surfacePoints(renderer.gbuffer());

  test::VoxelQueries queries;
  queries.useGrid(renderer.voxelGrid().header.id(), renderer.voxelGrid().words.id());
  const FrameGeometry geometry = buildFrameGeometry(scene, 0);
  const RayScene rays(geometry, scene.lights);
  const float offset = 1e-4f * glm::length(geometry.boundsMax - geometry.boundsMin);

  ClearLightCounts counts;
  for (const Light& light : scene.lights) {
    if (light.isMesh())
      continue;
    std::vector<test::VoxelQueries::Vpl> vpls;
    for (const Vpl& vpl : makeVpls(light.quad, light.emission, nullptr, 16))
      vpls.push_back({vpl.position, vpl.normal});
    const std::vector<bool> visible = queries.vplsVisible(points, vpls);
    const std::vector<bool> clear =
        queries.lightClear(points, light.quad.corners, light.quad.normal);
    for (std::size_t p = 0; p < points.size(); ++p) {
      bool canLight = false;
      bool seenWhole = true;
      bool exactlySeenWhole = true;
      for (std::size_t v = 0; v < vpls.size(); ++v) {
        const glm::vec3 towardsVpl = vpls[v].position - points[p].position;
        if (glm::dot(towardsVpl, points[p].normal) <= 0.0f ||
            glm::dot(towardsVpl, vpls[v].normal) >= 0.0f)
          continue;
        canLight = true;
        seenWhole = seenWhole && visible[p * vpls.size() + v];
        const glm::vec3 origin = points[p].position + offset * points[p].normal;
        const glm::vec3 toVpl = vpls[v].position - origin;
        const float distance = glm::length(toVpl);
        exactlySeenWhole =
            exactlySeenWhole && !rays.occluded(origin, toVpl / distance, (1.0f - 1e-4f) * distance);
      }
      if (!canLight)
        continue;
      ++counts.pairs;
      counts.seenWhole += seenWhole ? 1 : 0;
      counts.clear += clear[p] ? 1 : 0;
      counts.clearButBlocked += clear[p] && !seenWhole ? 1 : 0;
      counts.clearButExactlyBlocked += clear[p] && !exactlySeenWhole ? 1 : 0;
    }
  }
  std::printf(
      "%s: %zu point-light pairs, %zu seen whole through the voxels, %zu clear "
      "(%zu blocked through the voxels, %zu blocked exactly)\n",
      sceneName.c_str(), counts.pairs, counts.seenWhole, counts.clear, counts.clearButBlocked,
      counts.clearButExactlyBlocked);
  return counts;
}

class ClearLightOnScene : public ::testing::TestWithParam<const char*> {};

// Never clear where the traversal blocks a ray; and the test must decide many of the pairs the
// voxels see whole, or it saves nothing. Measured: 43 to 100% of them on these scenes (the rest
// pass too close to a surface's box for the boxes of the occupancy pyramid: 73% on the thin post
// grid; 43% on the light near the wall, likely because the points at the wall's foot start
// inside the box of the floor and the wall together, which their rays leave and the test's
// pyramid does not, and the pyramids of the wall's points graze it); 40% is the bound. The pairs
// it passes that Embree blocks (printed: 0 on most scenes, 1 to 9 on the bunny's box, the resting
// objects and the demo, 49 on the low-poly sphere) are ones the voxel traversal sees whole too:
// contact shadows closer than the voxel offset, and the smooth sphere's terminator (these points
// are not lifted, docs/shadows.md), the voxels' own error, which issue 15 is about.
TEST_P(ClearLightOnScene, NeverPassesWhereTheTraversalIsBlocked) {
  const ClearLightCounts counts = countClearLights(GetParam());
  EXPECT_GT(counts.pairs, 1000u);
  EXPECT_GT(counts.seenWhole, 50u);
  EXPECT_EQ(counts.clearButBlocked, 0u);
  EXPECT_GE(static_cast<double>(counts.clear), 0.40 * static_cast<double>(counts.seenWhole));
}

// Skipping the pyramid's cells must not change a single answer: the shadow rays of the G-buffer's
// points at 64x64 to each quad light's 16 x 16 VPLs (both ends 1.25 voxel layers off their
// surfaces, the offset without boxes, so that they start outside their own surface's voxels)
// through the renderer's grid and its boxes, by the skipping traversal and by the column walk
// alone. Both answers must occur often, or the comparison shows nothing.
TEST_P(ClearLightOnScene, SkippingEmptyCellsAnswersEveryRayAsTheColumnWalk) {
  Scene scene = loadRepositoryScene(GetParam());
  Renderer renderer(scene, {64, 64});
  RenderSettings settings;
  settings.vplsPerLight = 1;
  renderer.render(0, settings);
  const gpu::GpuVoxelGrid& grid = renderer.voxelGrid().description;
  ASSERT_GE(grid.occupancy.x, 5) << "the default grid skips cells of occupancy level 5";
  const glm::vec3 voxelSize(grid.voxelSize);
  const auto offSurface = [&](glm::vec3 position, glm::vec3 normal) {
    return position + normal * (1.25f * glm::dot(glm::abs(normal), voxelSize));
  };

  std::vector<glm::vec3> ends;
  for (const Light& light : scene.lights) {
    if (light.isMesh())
      continue;
    for (const test::VoxelQueries::Point& point : test::surfacePoints(renderer.gbuffer())) {
      for (const Vpl& vpl : makeVpls(light.quad, light.emission, nullptr, 16)) {
        ends.push_back(offSurface(point.position, point.normal));
        ends.push_back(offSurface(vpl.position, vpl.normal));
      }
    }
  }
  test::VoxelQueries queries;
  queries.useGrid(renderer.voxelGrid().header.id(), renderer.voxelGrid().words.id());
  const std::vector<bool> skipping = queries.segmentsBlocked(ends);
  const std::vector<bool> columns =
      queries.segmentsBlocked(ends, test::VoxelQueries::Walk::ColumnsOnly);
  std::size_t blocked = 0;
  std::size_t differing = 0;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    blocked += columns[i] ? 1 : 0;
    differing += skipping[i] != columns[i] ? 1 : 0;
  }
  std::printf("%s: %zu rays, %zu blocked, %zu answered differently\n", GetParam(), columns.size(),
              blocked, differing);
  EXPECT_EQ(differing, 0u);
  EXPECT_GT(blocked, columns.size() / 100);
  EXPECT_LT(blocked, columns.size() - columns.size() / 100);
}

INSTANTIATE_TEST_SUITE_P(ShadowScenes, ClearLightOnScene,
                         ::testing::Values("shadow_box", "shadow_hung_cube", "shadow_posts",
                                           "shadow_post_grid", "shadow_offscreen", "shadow_resting",
                                           "shadow_light_near_wall", "shadow_low_poly_sphere",
                                           "shadow_two_colour", "cornell_bunny", "demo"),
                         [](const ::testing::TestParamInfo<const char*>& scene) {
                           return std::string(scene.param);
                         });

// The hierarchical mode's image with the test is the image without it, bit for bit: the test
// only spares rays whose answer it knows. And it spares most of the coarsest level's rays. Through
// the voxel grid and through the BVH, whose exact rays would show any VPL the test passed wrongly:
// through the BVH on every shadow scene of the repository, among them the thin posts (rays that
// pass between them), objects resting on a floor (pyramids that graze the floor next to them), a
// light close to a wall (texels near the light's plane, whose pyramids end close to its quad),
// and the low-poly sphere, whose rays start from points lifted off its triangles.
struct ClearLightImageCase {
  ShadowSettings::Visibility visibility;
  std::vector<const char*> scenes;
};

class ClearLightImage : public ::testing::TestWithParam<ClearLightImageCase> {};

TEST_P(ClearLightImage, LeavesTheImageAsTracingEveryRayDoesAndSparesRays) {
  for (const char* name : GetParam().scenes) {
    Scene scene = loadRepositoryScene(name);
    RenderSettings settings;
    settings.vplsPerLight = 64;
    settings.shadows.visibility = GetParam().visibility;
    std::vector<Image> images;
    std::vector<FrameStatistics> statistics;
    for (const bool test : {true, false}) {
      Renderer renderer(scene, {96, 96});
      settings.shadows.clearLightTest = test;
      renderer.render(0, settings);
      images.push_back(renderer.readRadiance());
      statistics.push_back(renderer.statistics());
    }
    ASSERT_EQ(images[0].pixels.size(), images[1].pixels.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < images[0].pixels.size(); ++i)
      differing += images[0].pixels[i] != images[1].pixels[i] ? 1 : 0;
    EXPECT_EQ(differing, 0u) << name;
    EXPECT_LT(statistics[0].shadowRays(), statistics[1].shadowRays()) << name;
    const LevelStatistics& coarsestWith = statistics[0].levels.back();
    const LevelStatistics& coarsestWithout = statistics[1].levels.back();
    EXPECT_EQ(coarsestWithout.visibilityTraced, coarsestWithout.visibilityMasked) << name;
    std::printf(
        "%s: %llu shadow rays with the test, %llu without; coarsest level %u of %u "
        "texels traced with it\n",
        name, static_cast<unsigned long long>(statistics[0].shadowRays()),
        static_cast<unsigned long long>(statistics[1].shadowRays()), coarsestWith.visibilityTraced,
        coarsestWith.visibilityMasked);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Visibility, ClearLightImage,
    ::testing::Values(
        ClearLightImageCase{ShadowSettings::Visibility::Voxels,
                            {"shadow_box", "shadow_post_grid", "shadow_resting", "demo"}},
        ClearLightImageCase{ShadowSettings::Visibility::Bvh,
                            {"shadow_box", "shadow_hung_cube", "shadow_posts", "shadow_post_grid",
                             "shadow_post_grid_smooth", "shadow_offscreen", "shadow_resting",
                             "shadow_light_near_wall", "shadow_low_poly_sphere",
                             "shadow_two_colour", "cornell_bunny", "demo"}}),
    [](const ::testing::TestParamInfo<ClearLightImageCase>& test) {
      return std::string(test.param.visibility == ShadowSettings::Visibility::Bvh ? "Bvh"
                                                                                  : "Voxels");
    });

}  // namespace
}  // namespace penumbra
