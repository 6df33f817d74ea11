// One-bounce indirect light (docs/indirect.md): colour bleeding, the energy bound, the secondary
// VPL sampling, the hierarchical gather against the naive one, and the Cornell box against the
// Embree reference with one bounce.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "emitter_shapes.h"
#include "image/metrics.h"
#include "reference/emitter_mask.h"
#include "reference/reference.h"
#include "render/frame.h"
#include "render/gbuffer.h"
#include "render/readback.h"
#include "render/render_test_scenes.h"
#include "render/secondary_vpls.h"
#include "test_files.h"

namespace penumbra {
namespace {

// A white floor (the 20 x 20 quad at y = 0) meeting a red wall at x = 1 that faces -x, lit by a
// square light of radiance 1 above the floor beside the wall. Everything the floor receives
// indirectly comes from the wall (the floor cannot see itself).
constexpr const char* kWallObj =
    "v 1 0 -3\nv 1 0 3\nv 1 2 3\nv 1 2 -3\nvn -1 0 0\nf 1//1 2//1 3//1 4//1\n";
constexpr float kWallAlbedo[3] = {0.8f, 0.05f, 0.05f};
constexpr float kFloorAlbedo = 0.8f;

Scene floorAndRedWall() {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  test::writeFile(directory, "wall.obj", kWallObj);
  char materials[256];
  std::snprintf(materials, sizeof(materials),
                "material floor\n  dif %g %g %g\nend\nmaterial wall\n  dif %g %g %g\nend\n",
                kFloorAlbedo, kFloorAlbedo, kFloorAlbedo, kWallAlbedo[0], kWallAlbedo[1],
                kWallAlbedo[2]);
  return test::loadSceneText(
      directory,
      std::string(materials) +
          "material glow\n  emit 1 1 1\nend\n"
          "area_light square\n"
          "  pos1 -0.5 1.5 -0.5\n  pos2 0.5 1.5 -0.5\n  pos3 0.5 1.5 0.5\n  pos4 -0.5 1.5 0.5\n"
          "  at 0 0 0\n  mat glow\nend\n"
          "camera side\n  pos -3 2.5 0\n  at 0.5 0 0\n  screen_size 64 64\nend\n"
          "object floor.obj\n  mat floor\nend\n"
          "object wall.obj\n  mat wall\nend\n");
}

RenderSettings withIndirect(RenderMode mode) {
  RenderSettings settings;
  settings.mode = mode;
  settings.indirect.enabled = true;
  return settings;
}

TEST(Indirect, WhiteFloorNextToARedWallReceivesRedLight) {
  Scene scene = floorAndRedWall();
  Renderer renderer(scene, {64, 64});
  for (RenderMode mode : {RenderMode::Hierarchical, RenderMode::Naive}) {
    SCOPED_TRACE(renderModeName(mode));
    renderer.render(0, withIndirect(mode));
    const Image indirect = readTexture(renderer.indirect().id(), {64, 64}, RowOrder::TopFirst);
    const Image normals =
        readTexture(renderer.gbuffer().normalKind.id(), {64, 64}, RowOrder::TopFirst);
    glm::dvec3 floorSum(0.0);
    int floorPixels = 0;
    for (std::size_t i = 0; i < normals.pixels.size(); ++i) {
      if (normals.pixels[i].y > 0.99f) {
        floorSum += glm::dvec3(indirect.pixels[i]);
        ++floorPixels;
      }
    }
    ASSERT_GT(floorPixels, 500);
    // The wall reflects 16 times more red than green or blue, and the floor sees nothing else:
    // the floor's indirect light must be strongly red (a factor 8 leaves room for nothing but
    // rounding; green and blue come only from the wall's 0.05).
    EXPECT_GT(floorSum.r, 0.0);
    EXPECT_GT(floorSum.r, 8.0 * floorSum.g);
    EXPECT_GT(floorSum.r, 8.0 * floorSum.b);
  }
  // Without --indirect the indirect term is zero.
  renderer.render(0, RenderSettings{});
  const Image none = readTexture(renderer.indirect().id(), {64, 64}, RowOrder::TopFirst);
  for (const glm::vec4& pixel : none.pixels)
    ASSERT_EQ(glm::vec3(pixel), glm::vec3(0.0f));
}

TEST(Indirect, ReflectedFluxStaysWithinTheEnergyBound) {
  Scene scene = floorAndRedWall();
  Renderer renderer(scene, {64, 64});
  RenderSettings settings = withIndirect(RenderMode::Hierarchical);
  settings.shadows.enabled = false;
  renderer.render(0, settings);
  // The light emits pi L A = pi (radiance 1, area 1); one bounce reflects at most the albedo
  // times what the surfaces receive, which is at most all of it.
  const double emitted = std::numbers::pi;
  glm::dvec3 reflected(0.0);
  const std::vector<gpu::GpuVpl> secondary = renderer.secondaryVpls();
  for (const gpu::GpuVpl& vpl : secondary)
    reflected += std::numbers::pi * double{vpl.positionArea.w} * glm::dvec3(vpl.radiance);
  ASSERT_EQ(secondary.size(), static_cast<std::size_t>(settings.indirect.vplCount));
  std::printf("reflected flux / emitted: %.5f %.5f %.5f\n", reflected.r / emitted,
              reflected.g / emitted, reflected.b / emitted);
  // The 20 x 20 floor and the wall catch nearly all of the light's power here, so the bound is
  // tight: what is left is the maps' quadrature (a texel's area from its centre's solid angle
  // on a 64^2 face, and the VPLs' bounded form factor), measured at +0.12% over the bound in
  // red. 1% allows for that and still fails a flux off by a missing cosine or a doubled face.
  constexpr double kQuadrature = 1.01;
  EXPECT_LE(reflected.r, kQuadrature * kWallAlbedo[0] * emitted);
  EXPECT_LE(reflected.g, kQuadrature * kFloorAlbedo * emitted);
  EXPECT_LE(reflected.b, kQuadrature * kFloorAlbedo * emitted);
  // Green is reflected by the floor (0.8) only, and the floor catches most of the light: at
  // least half of the bound, or the bounce lost energy.
  EXPECT_GE(reflected.g, 0.5 * kFloorAlbedo * emitted);

  const Image indirect = readTexture(renderer.indirect().id(), {64, 64}, RowOrder::TopFirst);
  settings.indirect.enabled = false;
  renderer.render(0, settings);
  const Image direct = renderer.readRadiance();
  glm::dvec3 indirectSum(0.0);
  glm::dvec3 directSum(0.0);
  for (std::size_t i = 0; i < direct.pixels.size(); ++i) {
    indirectSum += glm::dvec3(indirect.pixels[i]);
    directSum += glm::dvec3(direct.pixels[i]);
  }
  std::printf("indirect / direct over the picture: %.4f %.4f %.4f\n", indirectSum.r / directSum.r,
              indirectSum.g / directSum.g, indirectSum.b / directSum.b);
  // The same bound in image space, summed over the picture: the indirect light at most the
  // direct light times the albedo (0.8). Not a strict law pixel by pixel (the view weighs
  // surfaces by their projected area), but here it holds with a wide margin (measured 0.17 of
  // the direct light in red, 0.014 in green) and fails a bounce scaled by a stray factor of pi.
  EXPECT_LE(indirectSum.r, kWallAlbedo[0] * directSum.r);
  EXPECT_LE(indirectSum.g, kFloorAlbedo * directSum.g);
  EXPECT_LE(indirectSum.b, kFloorAlbedo * directSum.b);
}

// A 2 x 2 plate at y = 1 between the light (y = 1.5) and the floor. The maps see the floor only
// where the light's centre sees it, so the plate's umbra gets no VPLs at all; its penumbra does,
// and there only the shadow pass (secondary_visibility.comp) can dim them. The maps are lit without
// visibility, so both runs place the same VPLs: with shadows each may only lose light, and those
// in the penumbra must.
TEST(Indirect, ShadowsDimTheSecondaryVplsInThePenumbra) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  test::writeFile(directory, "plate.obj",
                  "v -1 1 -1\nv 1 1 -1\nv 1 1 1\nv -1 1 1\nvn 0 1 0\nf 1//1 4//1 3//1 2//1\n");
  Scene scene = test::loadSceneText(
      directory,
      "material grey\n  dif 0.5 0.5 0.5\nend\n"
      "material glow\n  emit 1 1 1\nend\n"
      "area_light square\n"
      "  pos1 -0.5 1.5 -0.5\n  pos2 0.5 1.5 -0.5\n  pos3 0.5 1.5 0.5\n  pos4 -0.5 1.5 0.5\n"
      "  at 0 0 0\n  mat glow\nend\n"
      "camera c\n  pos 0 4 6\n  at 0 0 0\n  screen_size 32 32\nend\n"
      "object floor.obj\n  mat grey\nend\n"
      "object plate.obj\n  mat grey\nend\n");
  Renderer renderer(scene, {32, 32});
  RenderSettings settings = withIndirect(RenderMode::Naive);
  settings.shadows.enabled = false;
  renderer.render(0, settings);
  const std::vector<gpu::GpuVpl> unshadowed = renderer.secondaryVpls();
  settings.shadows.enabled = true;
  renderer.render(0, settings);
  const std::vector<gpu::GpuVpl> shadowed = renderer.secondaryVpls();
  ASSERT_EQ(shadowed.size(), unshadowed.size());
  int dimmed = 0;
  for (std::size_t k = 0; k < shadowed.size(); ++k) {
    ASSERT_EQ(shadowed[k].positionArea, unshadowed[k].positionArea);
    // The visible fraction is a ratio of two sums of the same terms: at most 1 up to rounding.
    EXPECT_LE(shadowed[k].radiance.r, unshadowed[k].radiance.r * (1.0f + 1e-5f));
    if (shadowed[k].radiance.r < 0.99f * unshadowed[k].radiance.r)
      ++dimmed;
  }
  // Along x, a floor point at distance d sees the light's point x_l past the plate's edge when
  // d/3 + 2 x_l/3 > 1: the umbra ends at d = 2, the light's centre shows from d = 3, and the
  // penumbra ends at d = 4. The band from 3 to 4 holds VPLs that only the shadow pass dims.
  EXPECT_GT(dimmed, 5);
}

TEST(Indirect, SecondaryVplsCarryTheMapsFluxInEqualShares) {
  // Four texels: flux (sum of rgb times area) 1, 0, 3 and 4: 8 in all; one invalid texel.
  Image positionArea(5, 1);
  Image normal(5, 1);
  Image radiance(5, 1);
  const float flux[5] = {1.0f, 0.0f, 3.0f, 4.0f, 100.0f};
  for (int x = 0; x < 5; ++x) {
    positionArea.at(x, 0) = glm::vec4(static_cast<float>(x), 0.0f, 0.0f, 2.0f);
    normal.at(x, 0) = glm::vec4(0.0f, 1.0f, 0.0f, x < 4 ? 1.0f : 0.0f);
    radiance.at(x, 0) = glm::vec4(flux[x] / 2.0f / 3.0f * glm::vec3(1.0f), 0.0f);
  }
  const std::vector<gpu::GpuVpl> vpls = sampleSecondaryVpls(positionArea, normal, radiance, 8, 1);
  ASSERT_EQ(vpls.size(), 8u);
  // Stratified: 1, 3 and 4 samples of texels 0, 2 and 3, in order, each 1/8 of the flux.
  const int expected[8] = {0, 2, 2, 2, 3, 3, 3, 3};
  for (int k = 0; k < 8; ++k) {
    EXPECT_EQ(vpls[static_cast<std::size_t>(k)].positionArea.x, static_cast<float>(expected[k]));
    const gpu::GpuVpl& vpl = vpls[static_cast<std::size_t>(k)];
    const float share = 3.0f * vpl.radiance.r * vpl.positionArea.w;
    EXPECT_NEAR(share, 1.0f, 1e-6f);  // float rounding only
  }
  EXPECT_TRUE(sampleSecondaryVpls(positionArea, normal, Image(5, 1), 8, 1).empty());
}

// Two lights' atlases of 2x2 texels a face, every texel with the same flux, and as many VPLs as
// texels: each texel once, by light, by face, and within a face along the Morton curve (u, v):
// (0, 0), (1, 0), (0, 1), (1, 1). The voxel programs shadow runs of consecutive VPLs as one
// cluster (secondary_gather.glsl), which the atlas's own order would spread over a whole row.
// What a light's reflective shadow map sees of a mesh far finer than its texels: its simplified
// triangles (GBufferPass::Triangles::simplifiedForMaps) show the same surfaces as the full mesh,
// a sphere of 261,120 triangles (simplified to 71,476) on a floor seen from above at 64x64, as a
// map's face sees the dragon.
TEST(ReflectiveShadowMaps, ASimplifiedMeshShowsTheSameSurfacesAtAMapsResolution) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  test::writeFile(directory, "sphere.ply", test::sphereBinaryPly(1.0, 256, 512));
  Scene scene = test::loadSceneText(directory,
                                    "camera above\n  pos 0 6 0.01\n  at 0 0 0\n  fovy 45\n"
                                    "  screen_size 64 64\nend\n"
                                    "object floor.obj\nend\n"
                                    "object sphere.ply\n  translate 0 1 0\nend\n");
  ASSERT_FALSE(scene.objects[1].model.meshes.at(0).mapTriangles.empty());
  SceneGpu sceneGpu(scene);
  sceneGpu.update(0, 0.0, 4);
  GBuffer full(scene.camera.size);
  GBuffer simplified(scene.camera.size);
  GBufferPass(GBufferPass::ShadowRayStarts::skipped).run({sceneGpu, scene.camera}, {full});
  GBufferPass(GBufferPass::ShadowRayStarts::skipped, GBufferPass::Triangles::simplifiedForMaps)
      .run({sceneGpu, scene.camera}, {simplified});
  const auto read = [&](const gl::Texture& texture) {
    return readTexture(texture.id(), scene.camera.size, RowOrder::BottomFirst).pixels;
  };
  const std::vector<glm::vec4> fullPositions = read(full.positionDepth);
  const std::vector<glm::vec4> fullNormals = read(full.normalKind);
  const std::vector<glm::vec4> simplifiedPositions = read(simplified.positionDepth);
  const std::vector<glm::vec4> simplifiedNormals = read(simplified.normalKind);
  int sphereFull = 0;
  int sphereSimplified = 0;
  double distance = 0.0;
  double normalDot = 0.0;
  int both = 0;
  for (std::size_t i = 0; i < fullPositions.size(); ++i) {
    // The floor lies at y = 0, the sphere from 0 to 2.
    const bool onSphereFull = fullPositions[i].y > 1e-3f;
    const bool onSphereSimplified = simplifiedPositions[i].y > 1e-3f;
    sphereFull += onSphereFull;
    sphereSimplified += onSphereSimplified;
    if (onSphereFull && onSphereSimplified) {
      distance += glm::length(glm::vec3(simplifiedPositions[i] - fullPositions[i]));
      normalDot += glm::dot(glm::normalize(glm::vec3(simplifiedNormals[i])),
                            glm::normalize(glm::vec3(fullNormals[i])));
      ++both;
    }
  }
  std::printf("sphere pixels: full %d, simplified %d; mean distance %.4f, mean normal dot %.5f\n",
              sphereFull, sphereSimplified, distance / both, normalDot / both);
  ASSERT_GT(sphereFull, 300);
  // The sphere covers 788 texels; its simplified outline may move by a texel along part of its
  // rim (about 100 texels). Measured: the same count.
  EXPECT_NEAR(sphereSimplified, sphereFull, 20);
  // A texel here is about 0.08 wide and a cell of the simplifier's grid 0.02 (1% of the sphere's
  // extent), whose chords lie within 0.0001 of the sphere. Measured: 0.0001 and 1.00000; a
  // tenth of a cell fails a simplified surface that strays from the full one.
  EXPECT_LT(distance / both, 0.002);
  EXPECT_GT(normalDot / both, 0.999);
}

// The starts read the full triangles by their index (gl_PrimitiveID), so they cannot come with the
// simplified ones.
TEST(ReflectiveShadowMaps, ShadowRayStartsNeedTheFullTriangles) {
  EXPECT_THROW(
      GBufferPass(GBufferPass::ShadowRayStarts::written, GBufferPass::Triangles::simplifiedForMaps),
      std::invalid_argument);
}

TEST(Indirect, SecondaryVplsComeInClusterOrder) {
  constexpr int kFaceSize = 2;
  constexpr int kWidth = gpu::kRsmFaces * kFaceSize;
  constexpr int kHeight = 2 * kFaceSize;
  Image positionArea(kWidth, kHeight);
  Image normal(kWidth, kHeight);
  Image radiance(kWidth, kHeight);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      positionArea.at(x, y) = glm::vec4(static_cast<float>(x), static_cast<float>(y), 0.0f, 1.0f);
      normal.at(x, y) = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
      radiance.at(x, y) = glm::vec4(1.0f);
    }
  }
  const std::vector<gpu::GpuVpl> vpls =
      sampleSecondaryVpls(positionArea, normal, radiance, kWidth * kHeight, kFaceSize);
  ASSERT_EQ(vpls.size(), static_cast<std::size_t>(kWidth * kHeight));
  const glm::ivec2 morton[4] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  std::size_t k = 0;
  for (int light = 0; light < 2; ++light) {
    for (int face = 0; face < gpu::kRsmFaces; ++face) {
      for (const glm::ivec2 texel : morton) {
        const gpu::GpuVpl& vpl = vpls[k++];
        EXPECT_EQ(vpl.positionArea.x, static_cast<float>(face * kFaceSize + texel.x)) << k;
        EXPECT_EQ(vpl.positionArea.y, static_cast<float>(light * kFaceSize + texel.y)) << k;
        EXPECT_EQ(vpl.normal.w, static_cast<float>(light)) << k;
      }
    }
  }
}

std::string scientific(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3e", value);
  return text;
}

constexpr glm::ivec2 kCornellSize{64, 64};

// At 64x64 the default sizes would gather everything at full resolution; these give the same
// factor of 8 between the gather and full resolution as the defaults do at 1024x1024.
RenderSettings hierarchicalAtSmallSize() {
  RenderSettings settings = withIndirect(RenderMode::Hierarchical);
  settings.multiresolution.coarsestSize = 8;
  settings.indirect.gatherSize = 8;
  return settings;
}

TEST(Indirect, CornellBoxHierarchicalAgreesWithNaive) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes/cornell_bunny.scene"));
  Renderer renderer(scene, kCornellSize);
  renderer.render(0, withIndirect(RenderMode::Naive));
  const Image naive = readTexture(renderer.indirect().id(), kCornellSize, RowOrder::TopFirst);
  renderer.render(0, hierarchicalAtSmallSize());
  const Image hierarchical =
      readTexture(renderer.indirect().id(), kCornellSize, RowOrder::TopFirst);
  std::vector<bool> compared = emitterMask(scene, kCornellSize, 0);
  compared.flip();
  int exact = 0;
  for (const glm::vec4& pixel : hierarchical.pixels)
    exact += pixel.w > 0.0f ? 1 : 0;
  const double error = compareImages(hierarchical, naive, &compared).relativeMse;
  ::testing::Test::RecordProperty("relmse_indirect_hierarchical_vs_naive", scientific(error));
  std::printf("indirect relmse hierarchical vs naive %s, %d pixels gathered exactly\n",
              scientific(error).c_str(), exact);
  // The indirect term alone, so this is the upsampling's error from an 8x8 level (a quarter of
  // the pixels, the bunny and the edges, are gathered exactly), with the hierarchy's texels taking
  // a quarter of the naive mode's VPLs each (interleaved) and filtered over 3x3 texels, and the
  // exact pixels' second leg unshadowed where the naive mode's is shadowed. Measured 4.1e-3
  // (3.6e-3 before the upsampling weighed the normals more steeply, which helps where the gather
  // level is a factor of 2 coarser and costs a little at this factor of 8; 3.5e-3 with both
  // unshadowed, 2.5e-3 with one set of 256 VPLs for both); the bound of 5.4e-3
  // allows for drivers that round differently, and fails an upsampling that smears the red and
  // green walls' light across the box's corners (about 3e-2 with no agreement test).
  EXPECT_LE(error, 5.4e-3);
}

TEST(Indirect, CornellBoxAgreesWithTheReferenceWithOneBounce) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes/cornell_bunny.scene"));
  Renderer renderer(scene, kCornellSize);
  renderer.render(0, hierarchicalAtSmallSize());
  const Image gpu = renderer.readRadiance();
  renderer.render(0, RenderSettings{});
  const Image direct = renderer.readRadiance();
  ReferenceSettings settings;
  settings.samplesPerPixel = 256;
  settings.bounces = 1;
  settings.size = kCornellSize;
  const Image reference = renderReference(scene, settings);
  std::vector<bool> compared = emitterMask(scene, kCornellSize, 0);
  compared.flip();
  const double error = compareImages(gpu, reference, &compared).relativeMse;
  const double directOnly = compareImages(direct, reference, &compared).relativeMse;
  ::testing::Test::RecordProperty("relmse_vs_reference_bounces_1", scientific(error));
  ::testing::Test::RecordProperty("relmse_direct_only_vs_reference_bounces_1",
                                  scientific(directOnly));
  std::printf("relmse %s, direct only %s\n", scientific(error).c_str(),
              scientific(directOnly).c_str());
  // What remains: the direct light's multiresolution and voxel-shadow error, the second leg's
  // clusters and the pixels gathered exactly that it leaves unshadowed (a quarter at this size),
  // the maps' quadrature, the 8x upsampling, and the reference's noise with 256 bounce rays per
  // pixel. Measured 3.7e-3 (3.3e-3 before the upsampling weighed the normals more steeply; 4.4e-3
  // with the second leg unshadowed; 6.0e-3 with one set of 256
  // unshadowed VPLs; 2.0e-3 unshadowed and gathered at full resolution); the bound of 1.2e-2 is
  // twice the figure of one set.
  // Without the indirect light the error is 4.6e-2.
  EXPECT_LE(error, 1.2e-2);
  // The indirect light must close most of the gap that leaving it out leaves.
  EXPECT_LT(error, 0.25 * directOnly);
}

// Two rooms side by side, split by a wall at x = 0 that reaches the ceiling: light 0 lights only
// the room at x < 0, light 1 only the room at x > 0. The maps are rendered on the GPU and read
// back; every secondary VPL must lie in the room of the light it names, and both lights must
// own some (the layout computed on the CPU from the atlas agrees with where the GPU drew).
TEST(Indirect, SecondaryVplsLieInTheRoomOfTheirLight) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  test::writeFile(directory, "wall.obj",
                  "v 0 0 -10\nv 0 0 10\nv 0 3 10\nv 0 3 -10\nvn 1 0 0\nf 1//1 2//1 3//1 4//1\n");
  Scene scene = test::loadSceneText(
      directory,
      "material grey\n  dif 0.5 0.5 0.5\nend\n"
      "material glow\n  emit 1 1 1\nend\n"
      "area_light west\n"
      "  pos1 -3 2.5 -0.5\n  pos2 -2 2.5 -0.5\n  pos3 -2 2.5 0.5\n  pos4 -3 2.5 0.5\n"
      "  at -2.5 0 0\n  mat glow\nend\n"
      "area_light east\n"
      "  pos1 2 2.5 -0.5\n  pos2 3 2.5 -0.5\n  pos3 3 2.5 0.5\n  pos4 2 2.5 0.5\n"
      "  at 2.5 0 0\n  mat glow\nend\n"
      "camera c\n  pos 0 6 8\n  at 0 0 0\n  screen_size 32 32\nend\n"
      "object floor.obj\n  mat grey\nend\n"
      "object wall.obj\n  mat grey\nend\n");
  Renderer renderer(scene, {32, 32});
  RenderSettings settings = withIndirect(RenderMode::Naive);
  settings.shadows.enabled = false;
  renderer.render(0, settings);
  const std::vector<gpu::GpuVpl> vpls = renderer.secondaryVpls();
  ASSERT_EQ(vpls.size(), static_cast<std::size_t>(settings.indirect.vplCount));
  int perLight[2] = {0, 0};
  for (const gpu::GpuVpl& vpl : vpls) {
    const int light = static_cast<int>(vpl.normal.w);
    ASSERT_TRUE(light == 0 || light == 1) << light;
    ++perLight[light];
    // The wall itself (x = 0) is lit from both sides; a hair of float rounding either way.
    if (light == 0)
      EXPECT_LE(vpl.positionArea.x, 1e-4f);
    else
      EXPECT_GE(vpl.positionArea.x, -1e-4f);
  }
  // The rooms are mirror images: each light reflects half the flux (sampling rounds).
  const int half = settings.indirect.vplCount / 2;
  EXPECT_NEAR(perLight[0], half, 4);
  EXPECT_NEAR(perLight[1], half, 4);
}

// The scene of `file` with the lights whose indices `lit` lists emitting and the others dark.
// A dark light stays in the scene: its quad still blocks light and bounce rays, as the scene
// format has it (an opaque surface), so that the scenes differ only in what is emitted.
Scene sceneWithLit(const std::filesystem::path& file, const std::vector<int>& lit) {
  Scene scene = loadScene(parseSceneFile(file));
  for (std::size_t light = 0; light < scene.lights.size(); ++light) {
    if (std::find(lit.begin(), lit.end(), static_cast<int>(light)) == lit.end())
      scene.lights[light].emission = glm::vec3(0.0f);
  }
  return scene;
}

// The mean of each channel of `image` over the pixels `normals` marks as surfaces (no light
// quad, no background).
glm::dvec3 meanOverSurfaces(const Image& image, const Image& normals) {
  glm::dvec3 sum(0.0);
  int count = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (static_cast<int>(normals.pixels[i].w) == gpu::kPixelSurface) {
      sum += glm::dvec3(image.pixels[i]);
      ++count;
    }
  }
  return count > 0 ? sum / static_cast<double>(count) : sum;
}

struct ReferenceWithBounce {
  Image withBounce;  // the reference's image with one bounce
  Image bounce;      // the bounce alone
};

// The bounce alone is the image with one bounce minus the direct image. Both use the same seed
// and the same sample streams for the direct light, which cancels exactly.
ReferenceWithBounce referenceWithBounce(const Scene& scene, int frame, glm::ivec2 size,
                                        int samplesPerPixel) {
  ReferenceSettings settings;
  settings.samplesPerPixel = samplesPerPixel;
  settings.size = size;
  settings.frame = frame;
  const Image direct = renderReference(scene, settings);
  settings.bounces = 1;
  ReferenceWithBounce images{renderReference(scene, settings), {}};
  images.bounce = images.withBounce;
  for (std::size_t i = 0; i < direct.pixels.size(); ++i)
    images.bounce.pixels[i] -= direct.pixels[i];
  return images;
}

Image referenceBounce(const Scene& scene, int frame) {
  return referenceWithBounce(scene, frame, kCornellSize, 256).bounce;
}

// The mean bounce of one set of lit lights in the three modes.
struct BounceMeans {
  glm::dvec3 naive{0.0};
  glm::dvec3 hierarchical{0.0};
  glm::dvec3 reference{0.0};
};

BounceMeans bounceMeans(
    const std::filesystem::path& file, int frame, const std::vector<int>& lit, int secondaryVpls,
    ShadowSettings::Visibility visibility = ShadowSettings::Visibility::Voxels) {
  Scene scene = sceneWithLit(file, lit);
  Renderer renderer(scene, kCornellSize);
  BounceMeans means;
  RenderSettings settings = withIndirect(RenderMode::Naive);
  settings.shadows.visibility = visibility;
  settings.indirect.vplCount = secondaryVpls;
  renderer.render(frame, settings);
  const Image normals =
      readTexture(renderer.gbuffer().normalKind.id(), kCornellSize, RowOrder::TopFirst);
  means.naive = meanOverSurfaces(
      readTexture(renderer.indirect().id(), kCornellSize, RowOrder::TopFirst), normals);
  settings = hierarchicalAtSmallSize();
  settings.shadows.visibility = visibility;
  settings.indirect.vplCount = secondaryVpls;
  renderer.render(frame, settings);
  means.hierarchical = meanOverSurfaces(
      readTexture(renderer.indirect().id(), kCornellSize, RowOrder::TopFirst), normals);
  means.reference = meanOverSurfaces(referenceBounce(scene, frame), normals);
  return means;
}

void printRatio(glm::dvec3 value, glm::dvec3 expected, const char* what) {
  std::printf("  %s: %.4f %.4f %.4f\n", what, value.r / expected.r, value.g / expected.g,
              value.b / expected.b);
}

void expectRatioNear(glm::dvec3 value, glm::dvec3 expected, double tolerance, const char* what) {
  printRatio(value, expected, what);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(value[c] / expected[c], 1.0, tolerance) << what << ", channel " << c;
}

// Two rooms split by a grey wall at x = 0, 3 high: the light hangs at 2.5 in the west room and
// lights a red wall at x = -3 that faces east; the east room gets no direct light, and every
// path of one bounce into it crosses the dividing wall, so the truth's bounce there is zero. The
// red wall's secondary VPLs face the east floor, so an unshadowed second leg lights it through
// the wall.
Scene litRoomBesideADarkOne() {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "floor.obj", test::kFloorObj);
  test::writeFile(directory, "red_wall.obj",
                  "v -3 0 -3\nv -3 0 3\nv -3 3 3\nv -3 3 -3\nvn 1 0 0\nf 1//1 2//1 3//1 4//1\n");
  test::writeFile(directory, "divider.obj",
                  "v 0 0 -10\nv 0 0 10\nv 0 3 10\nv 0 3 -10\nvn 1 0 0\nf 1//1 2//1 3//1 4//1\n");
  return test::loadSceneText(
      directory,
      "material grey\n  dif 0.5 0.5 0.5\nend\n"
      "material red\n  dif 0.8 0.05 0.05\nend\n"
      "material glow\n  emit 4 4 4\nend\n"
      "area_light west\n"
      "  pos1 -2.5 2.5 -0.5\n  pos2 -1.5 2.5 -0.5\n  pos3 -1.5 2.5 0.5\n  pos4 -2.5 2.5 0.5\n"
      "  at -3 1 0\n  mat glow\nend\n"
      "camera c\n  pos 1.5 10 6\n  at -0.5 0 0\n  screen_size 64 64\nend\n"
      "object floor.obj\n  mat grey\nend\n"
      "object red_wall.obj\n  mat red\nend\n"
      "object divider.obj\n  mat grey\nend\n");
}

// The mean of `image` over one room's floor: up-facing surface pixels at x > 0.25 (east) or
// x < -0.25 (west).
glm::dvec3 meanOverTheFloor(const Image& image, const Renderer& renderer, glm::ivec2 size,
                            bool east) {
  const Image normals = readTexture(renderer.gbuffer().normalKind.id(), size, RowOrder::TopFirst);
  const Image positions =
      readTexture(renderer.gbuffer().positionDepth.id(), size, RowOrder::TopFirst);
  glm::dvec3 sum(0.0);
  int count = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const float x = positions.pixels[i].x;
    if (static_cast<int>(normals.pixels[i].w) == gpu::kPixelSurface &&
        normals.pixels[i].y > 0.99f && (east ? x > 0.25f : x < -0.25f)) {
      sum += glm::dvec3(image.pixels[i]);
      ++count;
    }
  }
  EXPECT_GT(count, 300);
  return count > 0 ? sum / static_cast<double>(count) : sum;
}

struct FloorBounces {
  glm::dvec3 east{0.0};
  glm::dvec3 west{0.0};
};

FloorBounces floorBounces(const Image& image, const Renderer& renderer, glm::ivec2 size) {
  return {meanOverTheFloor(image, renderer, size, true),
          meanOverTheFloor(image, renderer, size, false)};
}

// With shadows the second leg is shadowed: the dark room's floor gets (nearly) no bounce, as in
// the reference, where without shadows the bounce leaks through the wall.
TEST(Indirect, ShadowRaysShadowTheBounceBehindAWall) {
  Scene scene = litRoomBesideADarkOne();
  constexpr glm::ivec2 kSize{64, 64};
  Renderer renderer(scene, kSize);
  ReferenceSettings referenceSettings;
  referenceSettings.samplesPerPixel = 64;
  referenceSettings.size = kSize;
  Image referenceImage = renderReference(scene, referenceSettings);
  referenceSettings.bounces = 1;
  const Image withBounce = renderReference(scene, referenceSettings);
  for (std::size_t i = 0; i < referenceImage.pixels.size(); ++i)
    referenceImage.pixels[i] = withBounce.pixels[i] - referenceImage.pixels[i];
  // Any render gives the same G-buffer, which is all the floor masks read.
  renderer.render(0, withIndirect(RenderMode::Naive));
  const FloorBounces reference = floorBounces(referenceImage, renderer, kSize);
  const auto total = [](glm::dvec3 rgb) { return rgb.r + rgb.g + rgb.b; };
  // The premise: the truth has no bounce in the dark room.
  EXPECT_LE(total(reference.east), 0.0);
  for (RenderMode mode : {RenderMode::Naive, RenderMode::Hierarchical}) {
    SCOPED_TRACE(renderModeName(mode));
    RenderSettings settings =
        mode == RenderMode::Naive ? withIndirect(mode) : hierarchicalAtSmallSize();
    const auto bounces = [&] {
      renderer.render(0, settings);
      return floorBounces(readTexture(renderer.indirect().id(), kSize, RowOrder::TopFirst),
                          renderer, kSize);
    };
    settings.shadows.enabled = false;
    const FloorBounces unshadowed = bounces();
    // The premise: without shadows the bounce leaks.
    EXPECT_GT(total(unshadowed.east), 0.0);
    settings.shadows.enabled = true;
    for (const auto visibility :
         {ShadowSettings::Visibility::Bvh, ShadowSettings::Visibility::Voxels}) {
      const bool voxels = visibility == ShadowSettings::Visibility::Voxels;
      SCOPED_TRACE(voxels ? "voxels" : "bvh");
      settings.shadows.visibility = visibility;
      const FloorBounces shadowed = bounces();
      std::printf("%s, %s: east floor's bounce %.2f%% of the leak without shadows (R %.3e)\n",
                  renderModeName(mode), voxels ? "voxels" : "bvh",
                  100.0 * total(shadowed.east) / total(unshadowed.east), shadowed.east.r);
      // Measured as a share of the leak without shadows. Naive: bvh 0 (exact rays; a hundredth
      // allows for rays that graze the wall's foot), voxels 7.3% (clusters of secondary VPLs
      // that hold both the red wall and the west floor at the wall's foot, whose ray grazes the
      // foot). Hierarchical: bvh 4.0%, from the 8x8 level's texels that straddle the wall's foot
      // (their floor averages both rooms'); voxels 23%, the same, the texels that take their
      // rays' answers from a texel of their surface, and the pixels gathered exactly along the
      // wall's foot, whose leg stays unshadowed with the voxels (a quarter of the pixels at this
      // size). The naive voxels' bound is about twice its figure. The hierarchical voxels' bound
      // guards the rays' sharing too: the ways of sharing that keep a texel to its side of the
      // wall measured 21 to 24% (none: 22%), those that do not 32% (a texel lending all it
      // traced, not only the receiver's deal) and 36% (the floors on either side sharing, with
      // no test of the texels between); a filter over the gather level that weighs surfaces only
      // spread 26% of the leak through the wall. The BVH's bounds are those it had against the
      // leak of the voxels' unshadowed leg.
      const double allowed =
          mode == RenderMode::Naive ? (voxels ? 0.15 : 0.01) : (voxels ? 0.30 : 0.06);
      EXPECT_LE(total(shadowed.east), allowed * total(unshadowed.east));
      // The lit room keeps its bounce: measured within 4% (naive) and 17% (hierarchical) of the
      // reference's, from the VPLs' blotches, the 8x8 level and the reference's 64 rays; 20%
      // allows for those and still fails shadow rays that block the lit room's own bounce.
      expectRatioNear(shadowed.west, reference.west, 0.2, "west floor / reference");
    }
  }
}

// The two-light Cornell box's mean bounce, shadowed through the BVH, with 256, 1024 and 4096
// secondary VPLs. Two faults made it depend on the count:
// - 4096 VPLs with exact shadow rays take 128 dispatches of 32 on llvmpipe: in one, the driver's
//   loop limit (65535 iterations per invocation, device_profile.h) cut the gather short in the
//   BVH, and the bounce lost light;
// - the bounded form factor of a point lost the light of VPLs that stand for large patches, on
//   a floor along a lit wall, so the bounce grew darker as the VPLs grew fewer; next to its own
//   surface a VPL now counts as its square patch's exact integral (patchIncident,
//   secondary_gather.glsl).
TEST(Indirect, ShadowedBounceKeepsItsMeanWithFewOrManyVpls) {
  Scene scene =
      loadScene(parseSceneFile(test::sourceDirectory() / "scenes/cornell_two_lights.scene"));
  Renderer renderer(scene, kCornellSize);
  RenderSettings settings = withIndirect(RenderMode::Naive);
  settings.shadows.visibility = ShadowSettings::Visibility::Bvh;
  const auto meanBounce = [&](int vplCount) {
    settings.indirect.vplCount = vplCount;
    renderer.render(150, settings);
    const Image normals =
        readTexture(renderer.gbuffer().normalKind.id(), kCornellSize, RowOrder::TopFirst);
    return meanOverSurfaces(readTexture(renderer.indirect().id(), kCornellSize, RowOrder::TopFirst),
                            normals);
  };
  const glm::dvec3 many = meanBounce(4096);
  // The samplings of 1024 and 4096 differ by their noise (measured 2.2%); without the batches
  // 4096 VPLs gave 75%, 78% and 42% of the bounce of 1024.
  expectRatioNear(many, meanBounce(1024), 0.03, "4096 VPLs over 1024");

  const glm::dvec3 few = meanBounce(256);
  printRatio(few, many, "256 VPLs over 4096");
  const double meanRatio = (few.r / many.r + few.g / many.g + few.b / many.b) / 3.0;
  // Measured over the three channels: 256 VPLs 3.2% below 4096 (0.984 0.999 0.920; 4.4% before
  // a patch above the receiver's plane kept the flux of the part of its square below it,
  // docs/indirect.md; the TV's few VPLs stand for the largest patches), against 8.1% with the
  // bounded form factor (0.929 0.946 0.881). The VPLs are placed deterministically, so 6% passes
  // the first and fails the second every run.
  EXPECT_NEAR(meanRatio, 1.0, 0.06) << "mean over the channels of 256 VPLs' bounce over 4096's";
}

// Issue 20's goal: the hierarchical --indirect image against the reference with one bounce, on
// the two- and three-light boxes and the bunny's, with the second leg shadowed through the voxel
// grid (the default: a ray per cluster of secondary VPLs) and through the BVH. Interleaved
// sampling (secondary_gather.glsl) lets each texel of the gather level take a quarter of the
// default 1024 secondary VPLs: the same cost per texel as 256 VPLs, the blotches of 256 gone.
// At 256x256 with the default settings (gathered at 128x128), as docs/indirect.md measures, and
// the two-light box also at 128x128 gathered at 64x64 (the same factor of two).
struct GoalScene {
  const char* name;
  const char* scene;
  int frame;
  int size = 256;
  int gatherSize = IndirectSettings{}.gatherSize;
};

class IndirectGoal : public ::testing::TestWithParam<GoalScene> {};

TEST_P(IndirectGoal, BounceMatchesTheReferenceWithEitherVisibility) {
  const GoalScene& goal = GetParam();
  const glm::ivec2 size{goal.size, goal.size};
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / goal.scene));
  const ReferenceWithBounce reference = referenceWithBounce(scene, goal.frame, size, 1024);
  std::vector<bool> compared = emitterMask(scene, size, goal.frame);
  compared.flip();
  Renderer renderer(scene, size);
  for (const auto visibility :
       {ShadowSettings::Visibility::Voxels, ShadowSettings::Visibility::Bvh}) {
    const bool voxels = visibility == ShadowSettings::Visibility::Voxels;
    SCOPED_TRACE(voxels ? "voxels" : "bvh");
    RenderSettings settings = withIndirect(RenderMode::Hierarchical);
    settings.shadows.visibility = visibility;
    settings.indirect.gatherSize = goal.gatherSize;
    renderer.render(goal.frame, settings);
    const Image gpu = renderer.readRadiance();
    const Image bounce = readTexture(renderer.indirect().id(), size, RowOrder::TopFirst);
    const Image normals = readTexture(renderer.gbuffer().normalKind.id(), size, RowOrder::TopFirst);
    const double error = compareImages(gpu, reference.withBounce, &compared).relativeMse;
    ::testing::Test::RecordProperty(
        voxels ? "relmse_voxels_vs_reference" : "relmse_bvh_vs_reference", scientific(error));
    std::printf("%s: relmse against the reference with one bounce %s\n", voxels ? "voxels" : "bvh",
                scientific(error).c_str());
    // Measured, voxels and bvh: the two-light box 5.6e-4 and 4.2e-4, the three-light box 8.3e-4
    // and 6.9e-4, the bunny's box 5.6e-4 and 6.3e-4, of which about 1e-4 is the reference's own
    // noise at 1024 samples; the voxels' second leg unshadowed (before the clusters) measured
    // 2.0e-3, 2.5e-3 and 1.2e-3. The two-light box at 128x128: 7.9e-4 and 5.9e-4 (7.7e-4 with
    // the equal voxel grid of 192); before the upsampling weighed the normals more steeply
    // (indirect_combine.comp), 1.05e-3 and 8.9e-4 (8.4e-4 with the equal grid of 192, whose error
    // offset part of the upsampling's down the tall block's side face). The bounds are the issue's
    // goal. At 128x128 the bunny's box measured 1.0e-3 and 1.5e-3: the goal is set at the size the
    // issue measured.
    EXPECT_LE(error, 1e-3);
    // The bounce alone, in the mean: issue 20 asks for 5% per channel. Measured 2.5 to 4.5% low
    // with the voxels, 0.8 to 4.5% with the BVH (the bunny's box in green).
    expectRatioNear(meanOverSurfaces(bounce, normals), meanOverSurfaces(reference.bounce, normals),
                    0.05, "bounce over the reference's");
  }
}

INSTANTIATE_TEST_SUITE_P(
    CornellBoxes, IndirectGoal,
    ::testing::Values(GoalScene{"TwoLights", "scenes/cornell_two_lights.scene", 150},
                      GoalScene{"ThreeLights", "scenes/cornell_three_lights.scene", 150},
                      GoalScene{"Bunny", "scenes/cornell_bunny.scene", 0},
                      GoalScene{"TwoLightsAt128", "scenes/cornell_two_lights.scene", 150, 128, 64}),
    [](const ::testing::TestParamInfo<GoalScene>& goal) { return std::string(goal.param.name); });

struct LightSet {
  const char* name;
  const char* scene;
  int frame;
  int lightCount;
};

class IndirectWithSeveralLights : public ::testing::TestWithParam<LightSet> {};

// Each light alone and all together, in the naive, hierarchical and reference modes: the
// bounce is additive, since each light's map carries only its own flux and each secondary VPL is
// shadowed against its own light's VPLs.
TEST_P(IndirectWithSeveralLights, BounceOfAllLightsIsTheSumOfEachAlone) {
  const LightSet& set = GetParam();
  const auto file = test::sourceDirectory() / set.scene;
  // The VPLs are shared out over the lights in proportion to flux, so a dim light gets few of
  // them together and all of them alone; with 256 a light of a fifth of the flux has about 50,
  // and the sampling alone moved its bounce by up to 11%. 4096 VPLs bring that down fourfold.
  constexpr int kSecondaryVpls = 4096;
  std::vector<int> all;
  BounceMeans sum;
  for (int light = 0; light < set.lightCount; ++light) {
    all.push_back(light);
    const BounceMeans alone = bounceMeans(file, set.frame, {light}, kSecondaryVpls);
    sum.naive += alone.naive;
    sum.hierarchical += alone.hierarchical;
    sum.reference += alone.reference;
  }
  const BounceMeans together = bounceMeans(file, set.frame, all, kSecondaryVpls);
  // The reference uses the same bounce rays and the same light samples of each light whichever
  // lights are lit: additive up to float rounding. The GPU modes place other VPLs together and
  // alone: measured within 0.7%; 3% still fails issue 20's bounce, which lost 30 to 50% of the
  // light with two lights.
  expectRatioNear(together.reference, sum.reference, 1e-4, "reference");
  expectRatioNear(together.naive, sum.naive, 0.03, "naive");
  expectRatioNear(together.hierarchical, sum.hierarchical, 0.03, "hierarchical");
}

// All lights on, against the reference in the mean, with the default count of secondary VPLs
// and the second leg shadowed through the BVH and through the voxels. Both guard the light index
// of the secondary VPLs (issue 20: the bounce was 53 to 69% of the reference's with two lights);
// issue 20's 5% is checked at a finer level by IndirectGoal. Here, at 64x64 gathered at 8x8, the
// naive mode measures within 2.6% with either visibility, the hierarchical within 8.3% (bvh) and
// 8.9% (voxels; the 8x8 level's texels each stand for 64 pixels); 10% allows for those.
TEST_P(IndirectWithSeveralLights, BounceMatchesTheReferenceInTheMean) {
  const LightSet& set = GetParam();
  std::vector<int> all(static_cast<std::size_t>(set.lightCount));
  std::iota(all.begin(), all.end(), 0);
  const auto file = test::sourceDirectory() / set.scene;
  for (const auto visibility :
       {ShadowSettings::Visibility::Bvh, ShadowSettings::Visibility::Voxels}) {
    const bool voxels = visibility == ShadowSettings::Visibility::Voxels;
    const BounceMeans means =
        bounceMeans(file, set.frame, all, IndirectSettings{}.vplCount, visibility);
    expectRatioNear(means.naive, means.reference, 0.1, voxels ? "naive, voxels" : "naive, bvh");
    expectRatioNear(means.hierarchical, means.reference, 0.1,
                    voxels ? "hierarchical, voxels" : "hierarchical, bvh");
  }
}

INSTANTIATE_TEST_SUITE_P(
    CornellBoxes, IndirectWithSeveralLights,
    ::testing::Values(LightSet{"TwoLights", "scenes/cornell_two_lights.scene", 150, 2},
                      LightSet{"ThreeLights", "scenes/cornell_three_lights.scene", 150, 3}),
    [](const ::testing::TestParamInfo<LightSet>& set) { return std::string(set.param.name); });

}  // namespace
}  // namespace penumbra
