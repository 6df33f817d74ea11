// The multiresolution gather: where it samples (plane, silhouette), that it never carries light
// across a depth step, that it matches the naive gather, and its pyramid and classification
// kernels against a C++ reference that follows the shaders' definitions.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "image/metrics.h"
#include "render/frame.h"
#include "render/pass_references.h"
#include "render/render_test_scenes.h"
#include "shared.h"
#include "test_files.h"

namespace penumbra {
namespace {

using test::indexOf;

RenderSettings hierarchicalSettings(int coarsestSize, int vplsPerLight = 64) {
  RenderSettings settings;
  settings.mode = RenderMode::Hierarchical;
  settings.vplsPerLight = vplsPerLight;
  // Every test here is about unshadowed light: where the gather samples and how it upsamples.
  settings.shadows.enabled = false;
  settings.multiresolution.coarsestSize = coarsestSize;
  return settings;
}

Image renderIn(Renderer& renderer, RenderSettings settings, RenderMode mode) {
  settings.mode = mode;
  renderer.render(0, settings);
  return renderer.readRadiance();
}

// A unit square light at height 2 over the origin, emitting down, and a white diffuse material.
const std::string kLightAbove =
    "material white\n  dif 1 1 1\nend\n"
    "material glow\n  emit 1 1 1\nend\n"
    "area_light overhead\n"
    "  pos1 -0.5 2 -0.5\n  pos2 0.5 2 -0.5\n  pos3 0.5 2 0.5\n  pos4 -0.5 2 0.5\n"
    "  at 0 0 0\n  mat glow\nend\n";

TEST(HierarchicalGather, PlaneFacingTheLightIsGatheredAtTheCoarsestLevel) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  // Looking down at the floor 31 degrees off vertical: depth changes across the picture, but
  // the plane fills it, so there is no edge anywhere.
  Scene scene = test::loadSceneText(
      directory, kLightAbove +
                     "camera c\n  pos 0 1 0.6\n  at 0 0 0\n  screen_size 64 64\nend\n"
                     "object floor.obj\n  mat white\nend\n");
  Renderer renderer(scene, scene.camera.size);
  renderer.render(0, hierarchicalSettings(8));
  const FrameStatistics statistics = renderer.statistics();
  ASSERT_EQ(statistics.levels.size(), 4u);  // 64, 32, 16 and 8 texels per side
  EXPECT_EQ(statistics.fullResolutionSamples, 64u * 64u);
  ASSERT_GT(statistics.samplesGathered(), 0u);
  // "Almost every sample": the default thresholds leave some margin for planes seen at steeper
  // angles; this one has no reason to refine at all, so at most 1% may come from finer levels.
  EXPECT_GE(statistics.levels.back().samples, 0.99 * statistics.samplesGathered());
}

// A 0.6 x 0.6 square floating at height 0.4, facing up.
const char* const kFloatingSquareObj =
    "v -0.3 0.4 -0.3\nv 0.3 0.4 -0.3\nv 0.3 0.4 0.3\nv -0.3 0.4 0.3\nvn 0 1 0\n"
    "f 4//1 3//1 2//1 1//1\n";

TEST(HierarchicalGather, SilhouetteIsGatheredAtFullResolutionAndTheRestCoarse) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  test::writeFile(directory, "square.obj", kFloatingSquareObj);
  Scene scene = test::loadSceneText(
      directory, kLightAbove +
                     "camera c\n  pos 0 1.5 0\n  at 0 0 0\n  up 0 0 -1\n  screen_size 64 64\nend\n"
                     "object floor.obj\n  mat white\nend\n"
                     "object square.obj\n  mat white\nend\n");
  Renderer renderer(scene, scene.camera.size);
  renderer.render(0, hierarchicalSettings(8));
  const HierarchyTargets& levels = *renderer.hierarchy();
  ASSERT_EQ(levels.layout.levelCount(), 4);
  const int coarsest = levels.layout.coarsest();
  const int footprint = 1 << coarsest;

  // Edge pixels: a 4-neighbour lies more than 10% nearer or farther (square 1.1 away, floor
  // 1.5; across the floor itself neighbouring depths differ by far less than 1%).
  const glm::ivec2 size = renderer.gbuffer().size;
  const std::vector<glm::vec4> positionDepth =
      readTexture(renderer.gbuffer().positionDepth.id(), size, RowOrder::BottomFirst).pixels;
  std::vector<glm::ivec2> edges;
  for (int y = 0; y < size.y; ++y) {
    for (int x = 0; x < size.x; ++x) {
      const float depth = positionDepth[indexOf({x, y}, size)].w;
      for (const glm::ivec2 step :
           {glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1)}) {
        const glm::ivec2 neighbour = glm::ivec2(x, y) + step;
        if (neighbour.x < 0 || neighbour.y < 0 || neighbour.x >= size.x || neighbour.y >= size.y)
          continue;
        if (std::abs(positionDepth[indexOf(neighbour, size)].w - depth) > 0.1f * depth) {
          edges.push_back({x, y});
          break;
        }
      }
    }
  }
  ASSERT_GT(edges.size(), 40u) << "the square's outline is missing from the picture";
  const auto distanceToEdge = [&edges](glm::ivec2 pixel) {
    int nearest = 1 << 20;
    for (const glm::ivec2 edge : edges)
      nearest = std::min(nearest, std::max(std::abs(edge.x - pixel.x), std::abs(edge.y - pixel.y)));
    return nearest;
  };

  const std::vector<std::uint32_t> fullResolution =
      readUintTexture(levels.refinement.state(0).id(), size, RowOrder::BottomFirst);
  const std::vector<std::uint32_t> coarsestStates = readUintTexture(
      levels.refinement.state(coarsest).id(), levels.layout.size(coarsest), RowOrder::BottomFirst);
  int farPixels = 0;
  for (int y = 0; y < size.y; ++y) {
    for (int x = 0; x < size.x; ++x) {
      const int distance = distanceToEdge({x, y});
      const std::uint32_t state = fullResolution[indexOf({x, y}, size)];
      if (distance == 0) {
        EXPECT_EQ(state, gpu::kTexelComputed) << "edge pixel " << x << "," << y;
      } else if (state == gpu::kTexelComputed) {
        // A full-resolution sample belongs to a 2x2 block that holds an edge pixel.
        EXPECT_LE(distance, 1) << "pixel " << x << "," << y;
      }
      // No coarsest footprint that holds this pixel can reach an edge pixel.
      if (distance >= footprint) {
        ++farPixels;
        EXPECT_EQ(
            coarsestStates[indexOf(glm::ivec2(x, y) / footprint, levels.layout.size(coarsest))],
            gpu::kTexelComputed)
            << "pixel " << x << "," << y;
      }
    }
  }
  EXPECT_GT(farPixels, size.x * size.y / 4);
}

TEST(HierarchicalGather, NoLightCrossesADepthStep) {
  const auto directory = test::scratchDirectory();
  // Near: a square turned 45 degrees towards a light off to the right. Far: a wall behind the
  // light's plane, which no light reaches. The light itself is outside the picture.
  test::writeFile(directory, "near.obj",
                  "v -0.495 -0.7 0.495\nv 0.495 -0.7 -0.495\nv 0.495 0.7 -0.495\n"
                  "v -0.495 0.7 0.495\nvn 0.70710678 0 0.70710678\nf 1//1 2//1 3//1 4//1\n");
  test::writeFile(directory, "far.obj",
                  "v -5 -5 -3\nv 5 -5 -3\nv 5 5 -3\nv -5 5 -3\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n");
  Scene scene = test::loadSceneText(
      directory,
      "material white\n  dif 1 1 1\nend\n"
      "material glow\n  emit 4 4 4\nend\n"
      "area_light side\n  pos1 3 -0.5 -1\n  pos2 4 -0.5 -1\n  pos3 4 0.5 -1\n  pos4 3 0.5 -1\n"
      "  at 3.5 0 5\n  mat glow\nend\n"
      "camera c\n  pos 0 0 5\n  at 0 0 0\n  screen_size 64 64\nend\n"
      "object near.obj\n  mat white\nend\n"
      "object far.obj\n  mat white\nend\n");
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings = hierarchicalSettings(8);
  // The square and the wall also differ in normal; above the largest curvature (2), the normal
  // test never fires, which leaves the depth metric alone to find the step.
  settings.multiresolution.normalThreshold = 3.0f;
  const Image naive = renderIn(renderer, settings, RenderMode::Naive);
  const Image hierarchical = renderIn(renderer, settings, RenderMode::Hierarchical);
  const Image depth = readTexture(renderer.gbuffer().positionDepth.id(), renderer.gbuffer().size,
                                  RowOrder::TopFirst);

  int nearPixels = 0;
  int farPixels = 0;
  for (std::size_t i = 0; i < depth.pixels.size(); ++i) {
    // The near square lies 4.3 to 5.7 from the eye, the far wall 8 or more.
    const bool near = depth.pixels[i].w < 7.0f;
    const glm::vec3 expected(naive.pixels[i]);
    const glm::vec3 found(hierarchical.pixels[i]);
    if (near) {
      ++nearPixels;
      ASSERT_GT(expected.r, 0.0f) << "the near square must be lit";
      // The nearby light falls off by half across the square's 15 pixels, which interpolation
      // from 2- to 8-pixel texels follows to within 2.4% (measured). Upsampling that took taps
      // from the unlit wall would darken pixels along the outline by 19% or more (an edge tap's
      // tent weight, 3/16; 30% measured with validity ignored).
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(found[c], expected[c], 0.05f * expected[c]) << "pixel " << i;
    } else {
      ++farPixels;
      ASSERT_EQ(expected, glm::vec3(0.0f)) << "the far wall must be unlit";
      EXPECT_EQ(found, glm::vec3(0.0f)) << "light leaked onto the far wall at pixel " << i;
    }
  }
  EXPECT_GT(nearPixels, 200);
  EXPECT_GT(farPixels, 200);
}

// The accuracy target of issue 4: relative MSE of hierarchical against naive at most 1e-3.
void expectCloseToNaive(const std::filesystem::path& sceneFile) {
  Scene scene = loadScene(parseSceneFile(sceneFile));
  Renderer renderer(scene, {128, 128});
  // Three levels (128, 64 and 32 texels per side). A coarsest texel covers twice the scene that
  // it covers at 512x512 with the default 64: a harder case than the target's.
  const RenderSettings settings = hierarchicalSettings(32);
  const Image naive = renderIn(renderer, settings, RenderMode::Naive);
  const Image hierarchical = renderIn(renderer, settings, RenderMode::Hierarchical);
  const FrameStatistics statistics = renderer.statistics();
  // The comparison means something only when most samples came from coarser levels.
  EXPECT_LT(statistics.samplesGathered(), statistics.fullResolutionSamples / 2);
  EXPECT_LE(compareImages(hierarchical, naive).relativeMse, 1e-3) << sceneFile;
}

TEST(HierarchicalGather, DemoMatchesTheNaiveGather) {
  expectCloseToNaive(test::sourceDirectory() / "scenes/demo.scene");
}

TEST(HierarchicalGather, CornellBunnyMatchesTheNaiveGather) {
  expectCloseToNaive(test::sourceDirectory() / "scenes/cornell_bunny.scene");
}

// A wall 10 cm behind a ceiling panel: just under the panel its irradiance rises from zero at the
// light's plane over a few centimetres, far from linearly, while the wall is flat, so no depth or
// normal test refines it. The light-proximity rule refines the texels whose extent is a sizeable
// part of their distance to the light. Without it this measures 3.4e-3 (the wall under the panel
// up to 30% too bright); with it 6.1e-5. The bound is issue 15's for the hierarchy against the
// exact modes (it adds nothing visible).
TEST(HierarchicalGather, WallNextToALightMatchesTheNaiveGather) {
  Scene scene =
      loadScene(parseSceneFile(test::sourceDirectory() / "scenes/shadow_light_near_wall.scene"));
  Renderer renderer(scene, {128, 128});
  // Three levels (128, 64 and 32 texels per side), as in expectCloseToNaive.
  const RenderSettings settings = hierarchicalSettings(32);
  const Image naive = renderIn(renderer, settings, RenderMode::Naive);
  const Image hierarchical = renderIn(renderer, settings, RenderMode::Hierarchical);
  EXPECT_LT(renderer.statistics().samplesGathered(),
            renderer.statistics().fullResolutionSamples / 2);
  EXPECT_LE(compareImages(hierarchical, naive).relativeMse, 2e-4);
}

// --- The pyramid and classification kernels against a C++ reference --------------------------

// A floor to the horizon (background above it), a wall whose top rises above the light's plane
// (unlit there), a shiny box (a material change and sharp normal changes), and the light in view.
const std::string kKernelScene =
    "material white\n  dif 0.8 0.8 0.8\nend\n"
    "material shiny\n  dif 0.5 0.2 0.2\n  spec 0.3 0.3 0.3\n  shin 20\nend\n"
    "material glow\n  emit 2 2 2\nend\n"
    "area_light overhead\n"
    "  pos1 -1.5 1.5 -1\n  pos2 -0.5 1.5 -1\n  pos3 -0.5 1.5 0\n  pos4 -1.5 1.5 0\n"
    "  at 0 0 0\n  mat glow\nend\n"
    "camera c\n  pos 0.3 1 3\n  at 0 0.4 0\n  screen_size 40 24\nend\n"
    "object floor.obj\n  mat white\nend\n"
    "object wall.obj\n  mat white\nend\n"
    "object box.obj\n  mat shiny\nend\n";

const char* const kWallObj =
    "v -1 0 -2\nv 1 0 -2\nv 1 3 -2\nv -1 3 -2\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n";

// An axis-aligned box from (-0.2, 0, -0.2) to (0.3, 0.5, 0.3) with flat faces.
const char* const kBoxObj =
    "v -0.2 0 -0.2\nv 0.3 0 -0.2\nv 0.3 0.5 -0.2\nv -0.2 0.5 -0.2\n"
    "v -0.2 0 0.3\nv 0.3 0 0.3\nv 0.3 0.5 0.3\nv -0.2 0.5 0.3\n"
    "vn 0 0 -1\nvn 0 0 1\nvn -1 0 0\nvn 1 0 0\nvn 0 1 0\n"
    "f 1//1 4//1 3//1 2//1\nf 5//2 6//2 7//2 8//2\nf 1//3 5//3 8//3 4//3\n"
    "f 2//4 3//4 7//4 6//4\nf 4//5 8//5 7//5 3//5\n";

TEST(HierarchicalKernels, PyramidAndClassificationMatchTheCppReference) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  test::writeFile(directory, "wall.obj", kWallObj);
  test::writeFile(directory, "box.obj", kBoxObj);
  Scene scene = test::loadSceneText(directory, kKernelScene);
  Renderer renderer(scene, scene.camera.size);
  // Coarsest 4: levels of 40x24, 20x12, 10x6, 5x3 and 3x2, odd sizes included.
  const RenderSettings settings = hierarchicalSettings(4, 16);
  renderer.render(0, settings);
  const HierarchyTargets& targets = *renderer.hierarchy();
  const LevelLayout& layout = targets.layout;
  ASSERT_EQ(layout.levelCount(), 5);
  EXPECT_EQ(layout.size(3), glm::ivec2(5, 3));
  EXPECT_EQ(layout.size(4), glm::ivec2(3, 2));

  std::vector<test::LevelTexels> levels;
  for (int level = 0; level < layout.levelCount(); ++level)
    levels.push_back(
        test::readLevel(targets.reduced, targets.refinement, targets.visibility, level));

  // Level 0: the discontinuity metrics from the G-buffer.
  const test::LevelTexels& full = levels[0];
  for (int y = 0; y < full.size.y; ++y) {
    for (int x = 0; x < full.size.x; ++x) {
      test::expectNearVec4(full.discontinuity[indexOf({x, y}, full.size)],
                           test::referenceDiscontinuity(scene, full.positionDepth, full.normal,
                                                        full.specular, full.size, {x, y}),
                           "pixel " + std::to_string(x) + "," + std::to_string(y));
    }
  }
  // Coarser levels: maximum and footprint averages of the level below.
  for (int level = 1; level < layout.levelCount(); ++level)
    test::expectReduction(levels[static_cast<std::size_t>(level - 1)],
                          levels[static_cast<std::size_t>(level)], level == 1, level,
                          settings.shadows.enabled);

  // Classification, exactly, and the work lists it fills.
  std::set<std::uint32_t> statesSeen;
  const RefinementThresholds thresholds{settings.multiresolution.depthThreshold,
                                        settings.multiresolution.normalThreshold,
                                        settings.multiresolution.lightProximityThreshold};
  for (int level = layout.coarsest(); level >= 0; --level) {
    const test::LevelTexels& texels = levels[static_cast<std::size_t>(level)];
    const test::LevelTexels* parent =
        level < layout.coarsest() ? &levels[static_cast<std::size_t>(level + 1)] : nullptr;
    std::set<std::uint32_t> computed;
    for (int y = 0; y < texels.size.y; ++y) {
      for (int x = 0; x < texels.size.x; ++x) {
        const std::uint32_t expected =
            test::referenceState(scene, texels, parent, level, {x, y}, thresholds);
        EXPECT_EQ(texels.states[indexOf({x, y}, texels.size)], expected)
            << "level " << level << " texel " << x << "," << y;
        statesSeen.insert(expected);
        if (expected == gpu::kTexelComputed)
          computed.insert(static_cast<std::uint32_t>(x) | static_cast<std::uint32_t>(y) << 16);
      }
    }
    const unsigned count = targets.refinement.texelsPerLevel()[static_cast<std::size_t>(level)];
    ASSERT_EQ(count, computed.size()) << "level " << level;
    const auto listed = readBuffer<std::uint32_t>(targets.refinement.workList().id(),
                                                  layout.texelOffset(level), count);
    EXPECT_EQ(std::set<std::uint32_t>(listed.begin(), listed.end()), computed) << "level " << level;
  }
  // The scene exercises every branch of the classification.
  EXPECT_EQ(statesSeen,
            (std::set<std::uint32_t>{gpu::kTexelInvalid, gpu::kTexelComputed, gpu::kTexelCovered,
                                     gpu::kTexelRefined, gpu::kTexelUnlit}));
}

}  // namespace
}  // namespace penumbra
