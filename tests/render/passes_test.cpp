// Each hierarchical pass alone, on inputs the test writes into the pass's declared input
// structures, against a C++ reference of its shader on a tiny input (a few texels per side, odd
// sizes included): the discontinuity pyramid, the refinement, the visibility trace, the gather
// of one coarse level and the upsampling.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gl/dispatch.h"
#include "gl/uniforms.h"
#include "render/device_profile.h"
#include "render/discontinuity.h"
#include "render/gather_hierarchical.h"
#include "render/pass_references.h"
#include "render/readback.h"
#include "render/refinement.h"
#include "render/render_settings.h"
#include "render/render_test_scenes.h"
#include "render/upsample.h"
#include "render/visibility.h"
#include "render/voxel_queries.h"
#include "render/voxelize.h"
#include "render/vpls.h"
#include "shared.h"
#include "test_files.h"

namespace penumbra {
namespace {

using test::indexOf;

constexpr float kPi = 3.14159265358979f;

// Tolerance (relative, absolute below 1) for the gather's and the upsampling's sums: on top of
// kFloatTolerance's square roots and divisions they use inversesqrt and pow, which GLSL allows a
// few units in the last place (pow's error grows with the exponent), summed over tens of VPLs
// or four taps. 1e-4 is about 800 units in the last place, while leaving out one VPL or tap, or
// a wrong weight, changes a value by a few percent.
constexpr float kSumTolerance = 1e-4f;

std::string texelName(int level, glm::ivec2 texel) {
  return "level " + std::to_string(level) + " texel " + std::to_string(texel.x) + "," +
         std::to_string(texel.y);
}

// Texels in GL order into level 0 of a texture: what a pass's input would hold.
void upload(const gl::Texture& texture, glm::ivec2 size, const std::vector<glm::vec4>& texels) {
  ASSERT_EQ(texels.size(), static_cast<std::size_t>(size.x) * size.y);
  glTextureSubImage2D(texture.id(), 0, 0, 0, size.x, size.y, GL_RGBA, GL_FLOAT, texels.data());
}
void upload(const gl::Texture& texture, glm::ivec2 size, const std::vector<std::uint32_t>& words) {
  ASSERT_EQ(words.size(), static_cast<std::size_t>(size.x) * size.y);
  glTextureSubImage2D(texture.id(), 0, 0, 0, size.x, size.y, GL_RED_INTEGER, GL_UNSIGNED_INT,
                      words.data());
}

std::vector<glm::vec4> texelsOf(const gl::Texture& texture, glm::ivec2 size) {
  return readTexture(texture.id(), size, RowOrder::BottomFirst).pixels;
}

// A level's texels from a function of the texel.
template <class Value, class Make>
std::vector<Value> levelOf(glm::ivec2 size, Make make) {
  std::vector<Value> values;
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x)
      values.push_back(make(glm::ivec2(x, y)));
  return values;
}

// A 2 x 2 light at height 2 over the origin, emitting down, a floor, and a strip at height 1
// under the light, facing down, that shadows part of the floor: across the texels below, each
// VPL is visible from some and hidden from others.
const std::string kScene =
    "material white\n  dif 0.8 0.8 0.8\nend\n"
    "material glow\n  emit 2 2 2\nend\n"
    "area_light overhead\n"
    "  pos1 -1 2 -1\n  pos2 1 2 -1\n  pos3 1 2 1\n  pos4 -1 2 1\n"
    "  at 0 0 0\n  mat glow\nend\n"
    "camera c\n  pos 0 3 3\n  at 0 0 0\n  screen_size 6 4\nend\n"
    "object floor.obj\n  mat white\nend\n"
    "object strip.obj\n  mat white\nend\n";
const char* const kStripObj =
    "v -0.4 1 -2\nv 0.4 1 -2\nv 0.4 1 2\nv -0.4 1 2\nvn 0 -1 0\nf 1//1 2//1 3//1 4//1\n";
// 6 x 6 VPLs: two mask words, the second partly used.
constexpr int kCellsPerSide = 6;

// Two levels, 6x4 and 3x2, for the passes that work level by level.
const glm::ivec2 kFullSize(6, 4);
constexpr int kCoarsestSize = 3;

// The work lists' indirect dispatches: one invocation per listed texel, in rows of work groups
// along y past the 65535 along x that GL guarantees (a 4096x4096 level may list 16 million
// texels), as few and as even as may be; countLimit caps the count.
TEST(WorkListArguments, GroupsGoOnInRowsPastTheWorkGroupLimit) {
  const gl::Program program = workListArgumentsProgram();
  constexpr unsigned kGroupSize = gpu::kGatherGroupSize;
  constexpr unsigned kLimit = gl::kMaxWorkGroupsPerDimension;
  const std::vector<unsigned> counts = {
      0, 1, 100, kLimit * kGroupSize, kLimit * kGroupSize + 1, 16u << 20, 3000};
  struct Groups {
    unsigned x;
    unsigned y;
  };
  // 16 Mi texels are 262144 groups: 5 rows of 52429 (4 rows hold 262140).
  const std::vector<Groups> expected = {{0, 0},     {1, 1},     {2, 1}, {kLimit, 1},
                                        {32768, 2}, {52429, 5}, {47, 1}};
  std::vector<gpu::DispatchIndirect> dispatches;
  for (unsigned count : counts)
    dispatches.push_back({0, 0, 0, count});
  gl::Buffer buffer;
  glNamedBufferStorage(buffer.id(),
                       static_cast<GLsizeiptr>(dispatches.size() * sizeof(gpu::DispatchIndirect)),
                       dispatches.data(), 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kDispatchBinding, buffer.id());
  gl::setUniform(program, "levelCount", static_cast<int>(counts.size()));
  const auto computeArguments = [&](unsigned countLimit) {
    gl::setUniform(program, "countLimit", countLimit);
    program.use();
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    return readBuffer<gpu::DispatchIndirect>(buffer.id(), 0, counts.size());
  };
  const std::vector<gpu::DispatchIndirect> arguments = computeArguments(~0u);
  for (std::size_t i = 0; i < counts.size(); ++i) {
    EXPECT_EQ(arguments[i].groupsX, expected[i].x) << "count " << counts[i];
    EXPECT_EQ(arguments[i].groupsY, expected[i].y) << "count " << counts[i];
    EXPECT_EQ(arguments[i].groupsZ, 1u) << "count " << counts[i];
  }
  // 3000 texels capped at 1000: 16 groups.
  EXPECT_EQ(computeArguments(1000u).back().groupsX, 16u);
}

class PassTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto directory = test::scratchDirectory();
    test::writeFile(directory, "floor.obj", test::kFloorObj);
    test::writeFile(directory, "strip.obj", kStripObj);
    scene_ = std::make_unique<Scene>(test::loadSceneText(directory, kScene));
    sceneGpu_ = std::make_unique<SceneGpu>(*scene_);
    sceneGpu_->update(0, 0.0, kCellsPerSide);
    VplPass().run({*sceneGpu_}, {vpls_});
  }

  std::unique_ptr<Scene> scene_;
  std::unique_ptr<SceneGpu> sceneGpu_;
  VplBuffer vpls_;
  LevelLayout layout_{kFullSize, kCoarsestSize};
  GBuffer gbuffer_{kFullSize};
};

// A G-buffer of surfaces on the floor with a depth step, a normal change, a specular change, a
// background and a light pixel; shadow lifts and face normals that vary from texel to texel.
void writeGBuffer(const GBuffer& gbuffer) {
  const glm::ivec2 size = gbuffer.size;
  upload(gbuffer.positionDepth, size, levelOf<glm::vec4>(size, [](glm::ivec2 texel) {
           const glm::vec3 position(0.3f * static_cast<float>(texel.x) - 0.8f, 0.0f,
                                    0.25f * static_cast<float>(texel.y) - 0.4f);
           const float depth = texel.x >= 4 ? 6.0f : 3.0f + 0.1f * static_cast<float>(texel.y);
           return glm::vec4(position, depth);
         }));
  upload(gbuffer.normalKind, size, levelOf<glm::vec4>(size, [](glm::ivec2 texel) {
           if (texel == glm::ivec2(4, 2))
             return glm::vec4(0.0f, 0.0f, 0.0f, gpu::kPixelBackground);
           if (texel == glm::ivec2(0, 2))
             return glm::vec4(0.0f, 0.0f, 0.0f, gpu::kPixelEmitter);
           const glm::vec3 normal = texel.y == 0 ? glm::normalize(glm::vec3(0.3f, 1.0f, 0.0f))
                                                 : glm::vec3(0.0f, 1.0f, 0.0f);
           return glm::vec4(normal, gpu::kPixelSurface);
         }));
  upload(gbuffer.specular, size, levelOf<glm::vec4>(size, [](glm::ivec2 texel) {
           return texel.x == 1 ? glm::vec4(0.2f, 0.2f, 0.2f, 8.0f) : glm::vec4(0.0f);
         }));
  upload(gbuffer.shadowLift, size, levelOf<glm::vec4>(size, [](glm::ivec2 texel) {
           return glm::vec4(0.01f * static_cast<float>(texel.x),
                            0.02f * static_cast<float>(texel.y), 0.0f, 0.0f);
         }));
  upload(gbuffer.faceNormal, size, levelOf<glm::vec4>(size, [](glm::ivec2 texel) {
           return glm::vec4(
               glm::normalize(glm::vec3(0.1f * static_cast<float>(texel.x), 1.0f, 0.0f)), 0.0f);
         }));
}

// The discontinuity pass on writeGBuffer's G-buffer of `size`, its levels down to `coarsest`
// texels, against the C++ reference: level 0 per pixel, every coarser level the reduction of the
// one below.
void expectDiscontinuityMatchesTheReference(const Scene& scene, const SceneGpu& sceneGpu,
                                            glm::ivec2 size, int coarsest, int levelCount) {
  GBuffer gbuffer(size);
  writeGBuffer(gbuffer);
  ReducedGBuffer reduced(gbuffer, LevelLayout(size, coarsest));
  ASSERT_EQ(reduced.layout().levelCount(), levelCount);
  DiscontinuityPass().run({gbuffer, sceneGpu}, {reduced});

  std::vector<test::LevelTexels> levels;
  for (int level = 0; level < reduced.layout().levelCount(); ++level)
    levels.push_back(test::readReducedLevel(reduced, level));
  const test::LevelTexels& full = levels[0];
  std::set<bool> exceeds;
  std::set<bool> nearLight;
  for (int y = 0; y < full.size.y; ++y) {
    for (int x = 0; x < full.size.x; ++x) {
      const glm::vec4 expected = test::referenceDiscontinuity(
          scene, full.positionDepth, full.normal, full.specular, full.size, {x, y});
      test::expectNearVec4(full.discontinuity[indexOf({x, y}, full.size)], expected,
                           texelName(0, {x, y}));
      exceeds.insert(expected.r > 1.0f);
      nearLight.insert(expected.a > 0.0f);
    }
  }
  // The input has both smooth texels and a depth step, and pixels that the light reaches (a light
  // proximity above 0) and pixels it cannot.
  EXPECT_EQ(exceeds, (std::set<bool>{false, true}));
  EXPECT_EQ(nearLight, (std::set<bool>{false, true}));
  for (int level = 1; level < reduced.layout().levelCount(); ++level)
    test::expectReduction(levels[static_cast<std::size_t>(level - 1)],
                          levels[static_cast<std::size_t>(level)], level == 1, level, true);
}

// The pass takes the pixels in 2x2 blocks and builds level 1 with level 0: odd sizes give blocks
// cut by the image's edge, 9x8 blocks whose neighbours all lie inside it, and a single level a
// pass that writes level 0 alone.
TEST_F(PassTest, DiscontinuityMatchesTheCppReference) {
  // 5x3 down to 1x1: levels of 5x3, 3x2, 2x1 and 1x1.
  expectDiscontinuityMatchesTheReference(*scene_, *sceneGpu_, {5, 3}, 1, 4);
}

TEST_F(PassTest, DiscontinuityMatchesTheCppReferenceWithInnerBlocks) {
  expectDiscontinuityMatchesTheReference(*scene_, *sceneGpu_, {9, 8}, 4, 3);
}

TEST_F(PassTest, DiscontinuityOfASingleLevelMatchesTheCppReference) {
  expectDiscontinuityMatchesTheReference(*scene_, *sceneGpu_, {5, 3}, 8, 1);
}

TEST_F(PassTest, WithoutShadowsTheDiscontinuityPassLeavesTheShadowRayEndsAlone) {
  GBuffer gbuffer({5, 3});
  writeGBuffer(gbuffer);
  const LevelLayout layout({5, 3}, 1);
  ReducedGBuffer withEnds(gbuffer, layout);
  ReducedGBuffer withoutEnds(gbuffer, layout);
  // A value no average of the G-buffer above takes, in the levels the pass would write.
  const glm::vec4 untouched(-7.0f);
  for (int level = 1; level < layout.levelCount(); ++level) {
    const glm::ivec2 size = layout.size(level);
    const std::vector<glm::vec4> marked(static_cast<std::size_t>(size.x) * size.y, untouched);
    upload(withoutEnds.shadowLift(level), size, marked);
    upload(withoutEnds.faceNormal(level), size, marked);
  }
  DiscontinuityPass().run({gbuffer, *sceneGpu_, true}, {withEnds});
  DiscontinuityPass().run({gbuffer, *sceneGpu_, false}, {withoutEnds});

  for (int level = 1; level < layout.levelCount(); ++level) {
    const test::LevelTexels expected = test::readReducedLevel(withEnds, level);
    const test::LevelTexels read = test::readReducedLevel(withoutEnds, level);
    // What the gather, the refinement and the upsampling read: bit for bit the same.
    EXPECT_EQ(read.positionDepth, expected.positionDepth) << "level " << level;
    EXPECT_EQ(read.normal, expected.normal) << "level " << level;
    EXPECT_EQ(read.specular, expected.specular) << "level " << level;
    EXPECT_EQ(read.discontinuity, expected.discontinuity) << "level " << level;
    for (std::size_t i = 0; i < read.shadowLift.size(); ++i) {
      EXPECT_EQ(read.shadowLift[i], untouched) << "level " << level << ", texel " << i;
      EXPECT_EQ(read.faceNormal[i], untouched) << "level " << level << ", texel " << i;
      EXPECT_NE(expected.shadowLift[i], untouched);
    }
  }
}

TEST_F(PassTest, RefinementMatchesTheCppReference) {
  writeGBuffer(gbuffer_);
  ReducedGBuffer reduced(gbuffer_, layout_);
  VisibilityMasks visibility(layout_);
  RefinementState refinement(layout_);
  // Each cause of refinement at one coarse texel: a depth discontinuity at (1, 0), a normal
  // discontinuity at (1, 1), a footprint that holds other pixels (b > 0) at (2, 0), a change of
  // visibility at (2, 1); at level 0, where only other pixels make a pixel invalid, they repeat.
  // The light proximity at (0, 1), 0.4 once scaled by the level-1 texel's size of 2 pixels, stays
  // below this threshold; a second run below lowers it.
  RefinementThresholds thresholds{1.0f, 0.1f, 0.5f};
  for (int level = 0; level < layout_.levelCount(); ++level) {
    const glm::ivec2 size = layout_.size(level);
    upload(reduced.discontinuity(level), size, levelOf<glm::vec4>(size, [](glm::ivec2 texel) {
             return glm::vec4(
                 texel == glm::ivec2(1, 0) ? 2.0f : 0.5f, texel == glm::ivec2(1, 1) ? 0.2f : 0.05f,
                 texel == glm::ivec2(2, 0) ? 1.0f : 0.0f, texel == glm::ivec2(0, 1) ? 0.2f : 0.1f);
           }));
    upload(visibility.flags(level), size, levelOf<std::uint32_t>(size, [](glm::ivec2 texel) {
             return texel == glm::ivec2(2, 1) ? gpu::kVisibilityHasMask | gpu::kVisibilityChanges
                                              : gpu::kVisibilityHasMask;
           }));
  }
  const glm::ivec2 coarse = layout_.size(1);
  const ReducedGBuffer::Averages averages = reduced.averages(1);
  upload(averages.positionDepth, coarse, levelOf<glm::vec4>(coarse, [](glm::ivec2 texel) {
           return glm::vec4(0.6f * static_cast<float>(texel.x) - 0.6f, 0.0f, 0.0f, 4.0f);
         }));
  // One coarse texel faces away from the light: it and the texels under it are unlit.
  upload(averages.normal, coarse, levelOf<glm::vec4>(coarse, [](glm::ivec2 texel) {
           return texel == glm::ivec2(0, 0) ? glm::vec4(0.0f, -1.0f, 0.0f, 1.0f)
                                            : glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
         }));
  upload(averages.specular, coarse, std::vector<glm::vec4>(6, glm::vec4(0.0f)));

  const RefinementPass pass;
  for (int level = layout_.coarsest(); level >= 0; --level)
    pass.runLevel(level, {*sceneGpu_, reduced, &visibility, thresholds}, {refinement});

  std::vector<test::LevelTexels> levels;
  for (int level = 0; level < layout_.levelCount(); ++level)
    levels.push_back(test::readLevel(reduced, refinement, visibility, level));
  const std::vector<unsigned> counts = refinement.texelsPerLevel();
  const auto dispatches = readBuffer<gpu::DispatchIndirect>(
      refinement.dispatches().id(), 0, static_cast<std::size_t>(layout_.levelCount()));
  std::set<std::uint32_t> statesSeen;
  for (int level = layout_.coarsest(); level >= 0; --level) {
    const auto index = static_cast<std::size_t>(level);
    const test::LevelTexels& texels = levels[index];
    const test::LevelTexels* parent = level < layout_.coarsest() ? &levels[index + 1] : nullptr;
    std::set<std::uint32_t> computed;
    for (int y = 0; y < texels.size.y; ++y) {
      for (int x = 0; x < texels.size.x; ++x) {
        const std::uint32_t expected =
            test::referenceState(*scene_, texels, parent, level, {x, y}, thresholds);
        EXPECT_EQ(texels.states[indexOf({x, y}, texels.size)], expected)
            << texelName(level, {x, y});
        statesSeen.insert(expected);
        if (expected == gpu::kTexelComputed)
          computed.insert(static_cast<std::uint32_t>(x) | static_cast<std::uint32_t>(y) << 16);
      }
    }
    ASSERT_EQ(counts[index], computed.size()) << "level " << level;
    const auto listed = readBuffer<std::uint32_t>(refinement.workList().id(),
                                                  layout_.texelOffset(level), counts[index]);
    EXPECT_EQ(std::set<std::uint32_t>(listed.begin(), listed.end()), computed) << "level " << level;
    // Level 0's run turned every level's count into its indirect dispatch.
    EXPECT_EQ(dispatches[index].groupsX,
              (counts[index] + gpu::kGatherGroupSize - 1) / gpu::kGatherGroupSize);
    EXPECT_EQ(dispatches[index].groupsY, 1u);
    EXPECT_EQ(dispatches[index].groupsZ, 1u);
  }
  EXPECT_EQ(statesSeen,
            (std::set<std::uint32_t>{gpu::kTexelInvalid, gpu::kTexelComputed, gpu::kTexelCovered,
                                     gpu::kTexelRefined, gpu::kTexelUnlit}));

  // A threshold of 0.3, above the unscaled 0.2, refines (0, 1) of the coarsest level, and only it.
  thresholds.lightProximity = 0.3f;
  pass.runLevel(layout_.coarsest(), {*sceneGpu_, reduced, &visibility, thresholds}, {refinement});
  const test::LevelTexels coarsest = test::readLevel(reduced, refinement, visibility, 1);
  for (int y = 0; y < coarsest.size.y; ++y) {
    for (int x = 0; x < coarsest.size.x; ++x) {
      const std::uint32_t expected = glm::ivec2(x, y) == glm::ivec2(0, 1)
                                         ? gpu::kTexelRefined
                                         : levels[1].states[indexOf({x, y}, coarsest.size)];
      EXPECT_EQ(coarsest.states[indexOf({x, y}, coarsest.size)], expected) << texelName(1, {x, y});
      EXPECT_EQ(test::referenceState(*scene_, coarsest, nullptr, 1, {x, y}, thresholds), expected)
          << texelName(1, {x, y});
    }
  }

  // Without shadows the pass reads no visibility flags: (2, 1), refined above only for its flag,
  // is classified as the reference does with every flag clear.
  ASSERT_EQ(coarsest.states[indexOf({2, 1}, coarsest.size)], gpu::kTexelRefined);
  pass.runLevel(layout_.coarsest(), {*sceneGpu_, reduced, nullptr, thresholds}, {refinement});
  test::LevelTexels withoutShadows = test::readLevel(reduced, refinement, visibility, 1);
  std::fill(withoutShadows.visibilityFlags.begin(), withoutShadows.visibilityFlags.end(), 0u);
  EXPECT_NE(withoutShadows.states[indexOf({2, 1}, withoutShadows.size)], gpu::kTexelRefined);
  for (int y = 0; y < withoutShadows.size.y; ++y) {
    for (int x = 0; x < withoutShadows.size.x; ++x) {
      EXPECT_EQ(withoutShadows.states[indexOf({x, y}, withoutShadows.size)],
                test::referenceState(*scene_, withoutShadows, nullptr, 1, {x, y}, thresholds))
          << texelName(1, {x, y});
    }
  }
}

// visibility_select, visibility_trace, visibility_share (at level 0, with `shareVplsInBlocks`)
// and visibility_compare over the levels, with the voxel grid's answer for each texel and VPL
// (vplVisible, tested on its own in traversal_test.cpp).
struct VisibilityReference {
  std::vector<std::vector<std::uint32_t>> flags;  // per level
  std::vector<std::vector<std::uint32_t>> masks;  // per level, wordsPerMask words per texel
  std::vector<VisibilityWork> work;               // per level
  // Texels under a parent with a mask whose averaged surface does not stand for theirs.
  int parentsNotStandingFor = 0;
  // Pixels under such a parent whose surface it stands for, next to another mesh's surface.
  int pixelsTouchingAnotherMesh = 0;
  // Bits of level 0 that a texel took from its neighbours (sibling_vpls.glsl), and bits it traced
  // because they disagreed.
  int sharedBitsTaken = 0;
  int sharedBitsTraced = 0;
};

// sibling_vpls.glsl's places and candidates.
std::uint32_t placeInBlock(glm::ivec2 texel) {
  return static_cast<std::uint32_t>((texel.x & 1) | (texel.y & 1) << 1);
}

std::uint32_t vplsOfPlace(std::uint32_t place) {
  return 0x11111111u << place;
}

std::vector<glm::ivec2> candidateTexels(glm::ivec2 texel, std::uint32_t place) {
  switch (placeInBlock(texel) ^ place) {
    case 1u:
      return {texel + glm::ivec2(-1, 0), texel + glm::ivec2(1, 0)};
    case 2u:
      return {texel + glm::ivec2(0, -1), texel + glm::ivec2(0, 1)};
    default:
      return {texel + glm::ivec2(-1, -1), texel + glm::ivec2(1, 1), texel + glm::ivec2(-1, 1),
              texel + glm::ivec2(1, -1)};
  }
}

VisibilityReference referenceVisibility(const Scene& scene, const LevelLayout& layout,
                                        const std::vector<test::LevelTexels>& levels,
                                        const std::vector<gpu::GpuVpl>& vpls,
                                        const std::vector<std::vector<bool>>& visibleFrom,
                                        float planeTolerance, float thresholdInVpls,
                                        bool shareVplsInBlocks) {
  const int vplCount = static_cast<int>(vpls.size());
  const int words = (vplCount + 31) / 32;
  VisibilityReference reference;
  const auto levelCount = static_cast<std::size_t>(layout.levelCount());
  reference.flags.resize(levelCount);
  reference.masks.resize(levelCount);
  reference.work.resize(levelCount);
  for (int level = layout.coarsest(); level >= 0; --level) {
    const auto index = static_cast<std::size_t>(level);
    const glm::ivec2 size = layout.size(level);
    const test::LevelTexels& texels = levels[index];
    const bool hasParent = level < layout.coarsest();
    std::vector<std::uint32_t>& flags = reference.flags[index];
    std::vector<std::uint32_t>& masks = reference.masks[index];
    flags.assign(texels.positionDepth.size(), 0u);
    masks.assign(texels.positionDepth.size() * static_cast<std::size_t>(words), 0u);
    const glm::ivec2 parentSize = hasParent ? layout.size(level + 1) : glm::ivec2(0);
    const auto parentHasMask = [&](glm::ivec2 parent) {
      return parent.x >= 0 && parent.y >= 0 && parent.x < parentSize.x && parent.y < parentSize.y &&
             (reference.flags[index + 1][indexOf(parent, parentSize)] & gpu::kVisibilityHasMask) !=
                 0u;
    };
    const auto parentWord = [&](glm::ivec2 parent, int word) {
      return reference
          .masks[index + 1][indexOf(parent, parentSize) * static_cast<std::size_t>(words) +
                            static_cast<std::size_t>(word)];
    };
    const auto maskWord = [&](glm::ivec2 texel, int word) -> std::uint32_t& {
      return masks[indexOf(texel, size) * static_cast<std::size_t>(words) +
                   static_cast<std::size_t>(word)];
    };
    const auto disagreement = [&](glm::ivec2 parent, int word) {
      std::uint32_t disagreeing = 0u;
      for (int n = 0; n < 9; ++n) {
        const glm::ivec2 neighbour = parent + glm::ivec2(n % 3 - 1, n / 3 - 1);
        if (n != 4)
          disagreeing |= parentHasMask(neighbour)
                             ? parentWord(parent, word) ^ parentWord(neighbour, word)
                             : ~0u;
      }
      return disagreeing;
    };
    // vplBitSet: a VPL that cannot light the texel counts as visible.
    const auto traceBits = [&](glm::ivec2 texel, int word, std::uint32_t toTrace) {
      const std::size_t at = indexOf(texel, size);
      const glm::vec3 position(texels.positionDepth[at]);
      std::uint32_t bits = 0u;
      reference.work[index].shadowRays += static_cast<unsigned>(std::popcount(toTrace));
      for (int bit = 0; bit < 32; ++bit) {
        if ((toTrace >> bit & 1u) == 0u)
          continue;
        const gpu::GpuVpl& vpl = vpls[static_cast<std::size_t>(32 * word + bit)];
        const glm::vec3 towardsVpl = glm::vec3(vpl.positionArea) - position;
        const bool canLight =
            glm::dot(towardsVpl, glm::normalize(glm::vec3(texels.normal[at]))) > 0.0f &&
            glm::dot(towardsVpl, glm::vec3(vpl.normal)) < 0.0f;
        if (!canLight ||
            visibleFrom[index][at * vpls.size() + static_cast<std::size_t>(32 * word + bit)])
          bits |= 1u << bit;
      }
      return bits;
    };

    // parent_surface.glsl, surfaceStandsFor: another surface (a parent's averaged one, or a
    // neighbour's) stands for the texel's.
    const auto surfaceStandsFor = [&](glm::ivec2 texel, glm::vec4 otherPositionDepth,
                                      glm::vec4 otherNormal) {
      const std::size_t at = indexOf(texel, size);
      const glm::vec3 ownNormal = glm::normalize(glm::vec3(texels.normal[at]));
      return glm::dot(ownNormal, glm::normalize(glm::vec3(otherNormal))) >=
                 gpu::kParentNormalAgreement &&
             std::abs(glm::dot(glm::vec3(otherPositionDepth) - glm::vec3(texels.positionDepth[at]),
                               ownNormal)) <= planeTolerance * texels.positionDepth[at].w;
    };

    // Select: which texels hold masks, which copy their parent's, and which take the VPLs on which
    // the parent's neighbourhood agrees from it.
    std::vector<bool> copiesParent(flags.size(), false);
    std::vector<bool> parentMaskStands(flags.size(), false);
    for (int y = 0; y < size.y; ++y) {
      for (int x = 0; x < size.x; ++x) {
        const glm::ivec2 texel(x, y);
        const std::size_t at = indexOf(texel, size);
        const glm::vec4 normal = texels.normal[at];
        const glm::vec3 position(texels.positionDepth[at]);
        const bool surface =
            level == 0 ? static_cast<int>(normal.w) == gpu::kPixelSurface : normal.w > 0.0f;
        const bool uncovered =
            !hasParent ||
            levels[index + 1].states[indexOf(texel / 2, parentSize)] == gpu::kTexelRefined;
        if (!surface || !uncovered ||
            !test::facesAnyLight(scene, position, glm::normalize(glm::vec3(normal))))
          continue;
        flags[at] = gpu::kVisibilityHasMask;
        const glm::ivec2 parent = texel / 2;
        // parent_surface.glsl: the parent's averaged surface stands for the texel's.
        bool parentStandsFor = false;
        if (hasParent) {
          const std::size_t parentAt = indexOf(parent, parentSize);
          parentStandsFor = surfaceStandsFor(texel, levels[index + 1].positionDepth[parentAt],
                                             levels[index + 1].normal[parentAt]);
        }
        if (hasParent && !parentStandsFor && parentHasMask(parent))
          ++reference.parentsNotStandingFor;
        // touchesAnotherMesh: a pixel next to another mesh's surface takes nothing from its parent.
        if (level == 0 && parentStandsFor && parentHasMask(parent)) {
          for (const glm::ivec2 step :
               {glm::ivec2(-1, 0), glm::ivec2(1, 0), glm::ivec2(0, -1), glm::ivec2(0, 1)}) {
            const glm::ivec2 neighbour = texel + step;
            if (neighbour.x < 0 || neighbour.y < 0 || neighbour.x >= size.x ||
                neighbour.y >= size.y)
              continue;
            const std::size_t neighbourAt = indexOf(neighbour, size);
            if (static_cast<int>(texels.normal[neighbourAt].w) == gpu::kPixelSurface &&
                texels.faceNormal[neighbourAt].w != texels.faceNormal[at].w &&
                glm::distance(glm::vec3(texels.positionDepth[neighbourAt]), position) <=
                    planeTolerance * texels.positionDepth[at].w)
              parentStandsFor = false;
          }
          if (!parentStandsFor)
            ++reference.pixelsTouchingAnotherMesh;
        }
        const std::uint32_t parentFlags =
            hasParent && parentStandsFor ? reference.flags[index + 1][indexOf(parent, parentSize)]
                                         : 0u;
        copiesParent[at] = parentFlags == gpu::kVisibilityHasMask;
        parentMaskStands[at] = hasParent && parentStandsFor && parentHasMask(parent);
      }
    }

    // sibling_vpls.glsl: the neighbours that give a listed texel of level 0 their quarters.
    const bool sharing = level == 0 && shareVplsInBlocks;
    const auto neighbourStandsFor = [&](glm::ivec2 texel, glm::ivec2 neighbour) {
      if (neighbour.x < 0 || neighbour.y < 0 || neighbour.x >= size.x || neighbour.y >= size.y ||
          (flags[indexOf(neighbour, size)] & gpu::kVisibilityHasMask) == 0u)
        return false;
      const std::size_t neighbourAt = indexOf(neighbour, size);
      return surfaceStandsFor(texel, texels.positionDepth[neighbourAt], texels.normal[neighbourAt]);
    };
    const auto givingNeighbours = [&](glm::ivec2 texel, std::uint32_t place) {
      std::vector<glm::ivec2> giving;
      if (sharing && place != placeInBlock(texel)) {
        for (const glm::ivec2 candidate : candidateTexels(texel, place))
          if (neighbourStandsFor(texel, candidate))
            giving.push_back(candidate);
      }
      return giving;
    };
    const auto pendingBits = [&](glm::ivec2 texel, int word) {
      const int inWord = std::clamp(vplCount - 32 * word, 0, 32);
      const std::uint32_t valid = inWord == 32 ? ~0u : (1u << inWord) - 1u;
      return parentMaskStands[indexOf(texel, size)] ? valid & disagreement(texel / 2, word) : valid;
    };

    // Trace: every pending VPL but those of the quarters that neighbours give.
    for (int y = 0; y < size.y; ++y) {
      for (int x = 0; x < size.x; ++x) {
        const glm::ivec2 texel(x, y);
        const std::size_t at = indexOf(texel, size);
        if ((flags[at] & gpu::kVisibilityHasMask) == 0u)
          continue;
        std::uint32_t givenVpls = 0u;
        for (std::uint32_t place = 0u; place < 4u; ++place)
          if (!givingNeighbours(texel, place).empty())
            givenVpls |= vplsOfPlace(place);
        for (int word = 0; word < words; ++word) {
          std::uint32_t& bits = maskWord(texel, word);
          if (copiesParent[at]) {
            bits = parentWord(texel / 2, word);
            continue;
          }
          const std::uint32_t pending = pendingBits(texel, word);
          if (parentMaskStands[at])
            bits = parentWord(texel / 2, word) & ~pending;
          bits |= traceBits(texel, word, pending & ~givenVpls);
        }
        if (!copiesParent[at])
          ++reference.work[index].tracedTexels;
      }
    }

    // Share: a given VPL on which the giving neighbours and the texel's own VPLs on either side
    // agree is taken; the others are traced.
    const std::vector<std::uint32_t> traced = masks;
    const auto tracedWord = [&](glm::ivec2 texel, int word) {
      return traced[indexOf(texel, size) * static_cast<std::size_t>(words) +
                    static_cast<std::size_t>(word)];
    };
    for (int y = 0; y < size.y && sharing; ++y) {
      for (int x = 0; x < size.x; ++x) {
        const glm::ivec2 texel(x, y);
        const std::size_t at = indexOf(texel, size);
        if ((flags[at] & gpu::kVisibilityHasMask) == 0u || copiesParent[at])
          continue;
        const std::uint32_t ownPlace = placeInBlock(texel);
        for (int word = 0; word < words; ++word) {
          const std::uint32_t pending = pendingBits(texel, word);
          for (std::uint32_t place = 0u; place < 4u; ++place) {
            const std::vector<glm::ivec2> giving = givingNeighbours(texel, place);
            for (int bit = static_cast<int>(place); bit < 32 && !giving.empty(); bit += 4) {
              if ((pending >> bit & 1u) == 0u)
                continue;
              // The texel's own VPLs on either side: 4k + its place, and the same of the next
              // four (of the last, where its place comes after this one); none past the word.
              const int ownBit = bit - static_cast<int>(place) + static_cast<int>(ownPlace);
              const int otherOwnBit = place > ownPlace ? ownBit + 4 : ownBit - 4;
              const std::uint32_t own = tracedWord(texel, word) >> ownBit & 1u;
              const std::uint32_t otherOwn = otherOwnBit >= 0 && otherOwnBit < 32
                                                 ? tracedWord(texel, word) >> otherOwnBit & 1u
                                                 : 0u;
              bool agree = otherOwn == own;
              for (const glm::ivec2 neighbour : giving)
                agree = agree && (tracedWord(neighbour, word) >> bit & 1u) == own;
              if (agree) {
                maskWord(texel, word) |= own << bit;
                ++reference.sharedBitsTaken;
              } else {
                maskWord(texel, word) |= traceBits(texel, word, 1u << bit);
                ++reference.sharedBitsTraced;
              }
            }
          }
        }
      }
    }

    // Compare with the 4-neighbours (popcount of the XOR).
    const std::vector<std::uint32_t> selected = flags;
    for (int y = 0; y < size.y; ++y) {
      for (int x = 0; x < size.x; ++x) {
        const std::size_t at = indexOf({x, y}, size);
        if ((selected[at] & gpu::kVisibilityHasMask) == 0u)
          continue;
        for (const glm::ivec2 step :
             {glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1)}) {
          const glm::ivec2 neighbour = glm::ivec2(x, y) + step;
          if (neighbour.x < 0 || neighbour.y < 0 || neighbour.x >= size.x ||
              neighbour.y >= size.y ||
              (selected[indexOf(neighbour, size)] & gpu::kVisibilityHasMask) == 0u)
            continue;
          int differing = 0;
          for (int word = 0; word < words; ++word) {
            const auto w = static_cast<std::size_t>(word);
            differing += std::popcount(
                masks[at * static_cast<std::size_t>(words) + w] ^
                masks[indexOf(neighbour, size) * static_cast<std::size_t>(words) + w]);
          }
          if (static_cast<float>(differing) > thresholdInVpls)
            flags[at] |= gpu::kVisibilityChanges;
        }
      }
    }
  }
  return reference;
}

// With the default list of shadow rays, and with a list of 5 rays, so that nearly every ray is
// traced by the trace and share steps themselves once the list is full (the fallback must give
// the same masks); with the VPLs shared out at level 0 (the default) and without.
TEST_F(PassTest, VisibilityTraceMatchesTheCppReference) {
  for (const auto& [rayListCapacity, shareVpls] :
       {std::pair{kShadowRayListCapacity, true}, std::pair{5u, true},
        std::pair{kShadowRayListCapacity, false}, std::pair{5u, false}}) {
    SCOPED_TRACE("shadow ray list of " + std::to_string(rayListCapacity) +
                 (shareVpls ? ", VPLs shared" : ", VPLs not shared"));
    VoxelGrid grid;
    VoxelizePass().run({*sceneGpu_, scene_->camera, VoxelSettings{}}, {grid});
    ReducedGBuffer reduced(gbuffer_, layout_);
    RefinementState refinement(layout_);
    VisibilityMasks visibility(layout_);
    visibility.prepare(vpls_.count);
    ASSERT_EQ(visibility.wordsPerMask(), 2);

    // Floor points, normals straight up (normalize is exact there, so the voxel queries below see
    // the points exactly as the pass does). The strip's shadow depends on x alone: the coarse
    // level's first column lies in its penumbra, the others in full light (x > 1.8); level 0's
    // points lie 0.3 to either side of their parent's. Level 0 has a background pixel, and the
    // coarse level a texel without surface. Level 0's (4, 1) lies 0.4 above its parent's plane,
    // beyond the plane tolerance (0.02 of the distance of 3): it traces its own VPLs where its
    // parent's mask would stand for it. Level 0's (5, 2) is another mesh's surface right beside
    // (5, 1) (0.05 away, within the plane tolerance): (5, 1), whose parent's mask would stand for
    // it whole, traces its own VPLs instead.
    const auto coarseX = [](int column) { return std::array<float, 3>{-0.6f, 2.4f, 3.6f}[column]; };
    const glm::ivec2 otherMesh(5, 2);
    upload(gbuffer_.positionDepth, kFullSize, levelOf<glm::vec4>(kFullSize, [&](glm::ivec2 texel) {
             const float x = coarseX(texel.x / 2) + (texel.x % 2 == 1 ? 0.3f : -0.3f);
             const float height = texel == glm::ivec2(4, 1) ? 0.4f : 0.0f;
             const float z =
                 texel == otherMesh ? -0.25f : 0.5f * static_cast<float>(texel.y) - 0.8f;
             return glm::vec4(x, height, z, 3.0f);
           }));
    upload(gbuffer_.normalKind, kFullSize, levelOf<glm::vec4>(kFullSize, [](glm::ivec2 texel) {
             return glm::vec4(
                 0.0f, 1.0f, 0.0f,
                 texel == glm::ivec2(5, 0) ? gpu::kPixelBackground : gpu::kPixelSurface);
           }));
    // The rays start from the points lifted (by a lift the voxels must not ignore: it moves the
    // points across the penumbra), off along the normal.
    const glm::vec4 lift(0.3f, 0.05f, 0.0f, 0.0f);
    const glm::vec4 up(0.0f, 1.0f, 0.0f, 0.0f);
    upload(gbuffer_.shadowLift, kFullSize,
           levelOf<glm::vec4>(kFullSize, [&](glm::ivec2) { return lift; }));
    upload(gbuffer_.faceNormal, kFullSize, levelOf<glm::vec4>(kFullSize, [&](glm::ivec2 texel) {
             return glm::vec4(glm::vec3(up), texel == otherMesh ? 2.0f : 1.0f);
           }));
    const glm::ivec2 coarse = layout_.size(1);
    const ReducedGBuffer::Averages averages = reduced.averages(1);
    upload(averages.positionDepth, coarse, levelOf<glm::vec4>(coarse, [&](glm::ivec2 texel) {
             return glm::vec4(coarseX(texel.x), 0.0f, static_cast<float>(texel.y) - 0.55f, 3.0f);
           }));
    upload(averages.normal, coarse, levelOf<glm::vec4>(coarse, [](glm::ivec2 texel) {
             return glm::vec4(0.0f, 1.0f, 0.0f, texel == glm::ivec2(2, 1) ? 0.0f : 1.0f);
           }));
    upload(averages.shadowLift, coarse,
           levelOf<glm::vec4>(coarse, [&](glm::ivec2) { return lift; }));
    upload(averages.faceNormal, coarse, levelOf<glm::vec4>(coarse, [&](glm::ivec2) { return up; }));
    // The coarse level's states, as its refinement would leave them: the texels under a computed
    // one are covered and need no mask. Under (2, 0), whose mask agrees with its neighbours',
    // level 0 inherits; under (2, 1), without a mask, it traces every VPL; under the penumbra's
    // column it traces the VPLs on which the parent's neighbourhood disagrees (every VPL next to a
    // parent without a mask or outside the level).
    upload(refinement.state(1), coarse, levelOf<std::uint32_t>(coarse, [](glm::ivec2 texel) {
             return texel == glm::ivec2(1, 1) ? gpu::kTexelComputed : gpu::kTexelRefined;
           }));

    const VisibilityRefinement settings{VisibilityRefinement::Measure::XorPopcount, 0.02f,
                                        shareVpls};
    const float planeTolerance = MultiresolutionSettings{}.planeTolerance;
    const VisibilityPass pass(DeviceProfile::portable().shadowRaysPerDispatch, rayListCapacity);
    const ShadowRays rays{.grid = &grid};
    // Without the clear-light test, which spares rays but changes no bit (clear_light_test.cpp):
    // the reference counts every ray the trace would take.
    for (int level = layout_.coarsest(); level >= 0; --level)
      pass.runLevel(level,
                    {*sceneGpu_, reduced, refinement, vpls_, rays, planeTolerance, settings, false},
                    {visibility});

    std::vector<test::LevelTexels> levels;
    for (int level = 0; level < layout_.levelCount(); ++level)
      levels.push_back(test::readLevel(reduced, refinement, visibility, level));
    const std::vector<gpu::GpuVpl> vpls = readVpls(vpls_);
    std::vector<test::VoxelQueries::Vpl> queryVpls;
    for (const gpu::GpuVpl& vpl : vpls)
      queryVpls.push_back({glm::vec3(vpl.positionArea), glm::vec3(vpl.normal)});
    test::VoxelQueries queries;
    queries.useGrid(grid.header.id(), grid.words.id());
    std::vector<std::vector<bool>> visibleFrom;
    bool liftChangesVisibility = false;
    for (const test::LevelTexels& texels : levels) {
      std::vector<test::VoxelQueries::Point> points;
      std::vector<test::VoxelQueries::Point> unlifted;
      for (std::size_t i = 0; i < texels.positionDepth.size(); ++i) {
        const glm::vec3 position(texels.positionDepth[i]);
        points.push_back({position + glm::vec3(texels.shadowLift[i]), glm::vec3(texels.normal[i])});
        unlifted.push_back({position, glm::vec3(texels.normal[i])});
      }
      visibleFrom.push_back(queries.vplsVisible(points, queryVpls));
      liftChangesVisibility |= visibleFrom.back() != queries.vplsVisible(unlifted, queryVpls);
    }
    EXPECT_TRUE(liftChangesVisibility) << "the lift moves no point across the penumbra";
    const VisibilityReference reference =
        referenceVisibility(*scene_, layout_, levels, vpls, visibleFrom, planeTolerance,
                            settings.threshold * static_cast<float>(vpls.size()), shareVpls);
    EXPECT_EQ(reference.parentsNotStandingFor, 1);
    EXPECT_EQ(reference.pixelsTouchingAnotherMesh, 1);
    // Shared out, texels take bits from their neighbours and trace some on which they disagree.
    EXPECT_EQ(reference.sharedBitsTaken > 0, shareVpls);
    EXPECT_EQ(reference.sharedBitsTraced > 0, shareVpls);

    const std::vector<VisibilityWork> work = visibility.workPerLevel();
    std::set<std::uint32_t> flagsSeen;
    bool inherited = false;
    for (int level = layout_.coarsest(); level >= 0; --level) {
      const auto index = static_cast<std::size_t>(level);
      const glm::ivec2 size = layout_.size(level);
      const auto masks =
          readBuffer<std::uint32_t>(visibility.masks().id(), visibility.maskOffset(level),
                                    static_cast<std::size_t>(size.x) * size.y * 2);
      for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
          const std::size_t at = indexOf({x, y}, size);
          const std::uint32_t expected = reference.flags[index][at];
          EXPECT_EQ(levels[index].visibilityFlags[at], expected) << texelName(level, {x, y});
          flagsSeen.insert(expected);
          if ((expected & gpu::kVisibilityHasMask) == 0u)
            continue;
          for (std::size_t word = 0; word < 2; ++word)
            EXPECT_EQ(masks[2 * at + word], reference.masks[index][2 * at + word])
                << texelName(level, {x, y}) << " word " << word;
        }
      }
      EXPECT_EQ(work[index].tracedTexels, reference.work[index].tracedTexels) << "level " << level;
      EXPECT_EQ(work[index].shadowRays, reference.work[index].shadowRays) << "level " << level;
      if (level == 0)
        inherited = reference.work[index].tracedTexels <
                    static_cast<unsigned>(
                        std::count(reference.flags[index].begin(), reference.flags[index].end(),
                                   gpu::kVisibilityHasMask) +
                        std::count(reference.flags[index].begin(), reference.flags[index].end(),
                                   gpu::kVisibilityHasMask | gpu::kVisibilityChanges));
    }
    // The input exercises no mask, masks that agree and masks that differ, and at level 0 both
    // inherited and traced masks.
    EXPECT_EQ(flagsSeen,
              (std::set<std::uint32_t>{0u, gpu::kVisibilityHasMask,
                                       gpu::kVisibilityHasMask | gpu::kVisibilityChanges}));
    EXPECT_TRUE(inherited);
    EXPECT_GT(work[0].tracedTexels, 0u);
  }
}

// vplIncident and phongBrdf of shading.glsl.
glm::vec3 referenceIncident(glm::vec3 position, glm::vec3 normal, const gpu::GpuVpl& vpl,
                            glm::vec3& towardsLight) {
  const glm::vec3 d = glm::vec3(vpl.positionArea) - position;
  const float distanceSquared = std::max(glm::dot(d, d), 1e-12f);
  towardsLight = d / std::sqrt(distanceSquared);
  const float cosSurface = std::max(glm::dot(normal, towardsLight), 0.0f);
  const float cosLight = std::max(-glm::dot(glm::vec3(vpl.normal), towardsLight), 0.0f);
  const float area = vpl.positionArea.w;
  return glm::vec3(vpl.radiance) *
         (kPi * area * cosSurface * cosLight / (kPi * distanceSquared + area));
}

glm::vec3 referencePhong(glm::vec3 specular, float shininess, glm::vec3 normal,
                         glm::vec3 towardsLight, glm::vec3 towardsEye) {
  if (specular == glm::vec3(0.0f))
    return glm::vec3(0.0f);
  const float cosAlpha = std::max(glm::dot(glm::reflect(-towardsLight, normal), towardsEye), 0.0f);
  const float lobe = shininess > 0.0f ? std::pow(cosAlpha, shininess) : 1.0f;
  return specular * ((shininess + 2.0f) / (2.0f * kPi)) * lobe;
}

TEST_F(PassTest, GatherOfACoarseLevelMatchesTheCppReference) {
  constexpr int kLevel = 1;
  const glm::ivec2 size = layout_.size(kLevel);
  ReducedGBuffer reduced(gbuffer_, layout_);
  RefinementState refinement(layout_);
  VisibilityMasks visibility(layout_);
  GatheredLevels gathered(layout_);
  visibility.prepare(vpls_.count);

  const std::vector<glm::vec4> positions = levelOf<glm::vec4>(size, [](glm::ivec2 texel) {
    return glm::vec4(0.7f * static_cast<float>(texel.x) - 0.7f, 0.1f * static_cast<float>(texel.y),
                     0.4f, 3.0f);
  });
  const std::vector<glm::vec4> normals = levelOf<glm::vec4>(size, [](glm::ivec2 texel) {
    return glm::vec4(0.2f * static_cast<float>(texel.x) - 0.2f, 1.0f, 0.1f, 1.0f);
  });
  const std::vector<glm::vec4> speculars = levelOf<glm::vec4>(size, [](glm::ivec2 texel) {
    return texel.x == 2 ? glm::vec4(0.3f, 0.2f, 0.1f, 12.0f) : glm::vec4(0.0f);
  });
  const ReducedGBuffer::Averages averages = reduced.averages(kLevel);
  upload(averages.positionDepth, size, positions);
  upload(averages.normal, size, normals);
  upload(averages.specular, size, speculars);
  // Masks: a different pattern per texel, so that each texel sums its own subset of the VPLs.
  const auto texelCount = static_cast<std::size_t>(size.x) * size.y;
  std::vector<std::uint32_t> masks;
  for (std::size_t texel = 0; texel < texelCount; ++texel) {
    masks.push_back(0x9e3779b9u * static_cast<std::uint32_t>(texel + 1));
    masks.push_back(0x7f4a7c15u * static_cast<std::uint32_t>(texel + 3));
  }
  glNamedBufferSubData(visibility.masks().id(),
                       static_cast<GLintptr>(visibility.maskOffset(kLevel) * sizeof(std::uint32_t)),
                       static_cast<GLsizeiptr>(masks.size() * sizeof(std::uint32_t)), masks.data());
  // The work list: four of the six texels, as the refinement would list them.
  const std::vector<glm::ivec2> listed = {{0, 0}, {2, 0}, {1, 1}, {2, 1}};
  std::vector<std::uint32_t> workList;
  for (const glm::ivec2 texel : listed)
    workList.push_back(static_cast<std::uint32_t>(texel.x) | static_cast<std::uint32_t>(texel.y)
                                                                 << 16);
  glNamedBufferSubData(refinement.workList().id(),
                       static_cast<GLintptr>(layout_.texelOffset(kLevel) * sizeof(std::uint32_t)),
                       static_cast<GLsizeiptr>(workList.size() * sizeof(std::uint32_t)),
                       workList.data());
  const gpu::DispatchIndirect dispatch{1u, 1u, 1u, static_cast<std::uint32_t>(listed.size())};
  glNamedBufferSubData(refinement.dispatches().id(),
                       static_cast<GLintptr>(kLevel * sizeof(gpu::DispatchIndirect)),
                       sizeof dispatch, &dispatch);
  // The same sums whether the gather reads the VPLs from the uniform block or the storage buffer
  // (gather_vpls.glsl).
  for (const GatherVplSource source :
       {GatherVplSource::UniformBlock, GatherVplSource::StorageBuffer}) {
    SCOPED_TRACE(source == GatherVplSource::UniformBlock ? "uniform block" : "storage buffer");
    // Texels not listed keep what they held.
    const glm::vec4 untouched(-7.0f);
    glClearTexImage(gathered.diffuse(kLevel).id(), 0, GL_RGBA, GL_FLOAT, &untouched[0]);
    glClearTexImage(gathered.specular(kLevel).id(), 0, GL_RGBA, GL_FLOAT, &untouched[0]);

    const glm::vec3 eye(0.5f, 3.0f, 2.5f);
    HierarchicalGatherPass pass(source);
    pass.runLevel(kLevel, {reduced, refinement, vpls_, eye, &visibility, false, 0, {}, nullptr},
                  {gathered});
    // Part of the VPLs (two ranges, the second across the mask words' boundary) added to sums kept
    // in other levels, as a frame that keeps the lights without a video gathers the others.
    const std::vector<gpu::GpuVplRange> ranges = {{glm::ivec4(0, 5, -1, 0)},
                                                  {glm::ivec4(20, 36, -1, 0)}};
    GatheredLevels kept(layout_);
    const glm::vec4 keptDiffuse(0.25f, 0.5f, 0.75f, 9.0f);
    const glm::vec4 keptSpecular(0.125f, 0.0625f, 1.5f, 9.0f);
    glClearTexImage(kept.diffuse(kLevel).id(), 0, GL_RGBA, GL_FLOAT, &keptDiffuse[0]);
    glClearTexImage(kept.specular(kLevel).id(), 0, GL_RGBA, GL_FLOAT, &keptSpecular[0]);
    GatheredLevels partial(layout_);
    glClearTexImage(partial.diffuse(kLevel).id(), 0, GL_RGBA, GL_FLOAT, &untouched[0]);
    glClearTexImage(partial.specular(kLevel).id(), 0, GL_RGBA, GL_FLOAT, &untouched[0]);
    pass.runLevel(kLevel, {reduced, refinement, vpls_, eye, &visibility, false, 0, ranges, &kept},
                  {partial});

    const std::vector<gpu::GpuVpl> vpls = readVpls(vpls_);
    ASSERT_EQ(vpls.size(), 36u);
    // What the pass must have written into `levels`: the sums of the VPLs `summed` says, plus
    // `base`.
    const auto expectSums = [&](const GatheredLevels& levels,
                                const std::function<bool(int)>& summed, glm::vec3 diffuseBase,
                                glm::vec3 specularBase) {
      const std::vector<glm::vec4> diffuse = texelsOf(levels.diffuse(kLevel), size);
      const std::vector<glm::vec4> specular = texelsOf(levels.specular(kLevel), size);
      for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
          const std::size_t at = indexOf({x, y}, size);
          const std::string where = texelName(kLevel, {x, y});
          if (std::find(listed.begin(), listed.end(), glm::ivec2(x, y)) == listed.end()) {
            EXPECT_EQ(diffuse[at], untouched) << where;
            EXPECT_EQ(specular[at], untouched) << where;
            continue;
          }
          const glm::vec3 position(positions[at]);
          const glm::vec3 normal = glm::normalize(glm::vec3(normals[at]));
          const glm::vec3 towardsEye = glm::normalize(eye - position);
          glm::vec3 diffuseSum = diffuseBase;
          glm::vec3 specularSum = specularBase;
          for (std::size_t i = 0; i < vpls.size(); ++i) {
            if (!summed(static_cast<int>(i)) || (masks[2 * at + i / 32] >> (i % 32) & 1u) == 0u)
              continue;
            glm::vec3 towardsLight(0.0f);
            const glm::vec3 incident = referenceIncident(position, normal, vpls[i], towardsLight);
            diffuseSum += incident;
            specularSum += incident * referencePhong(glm::vec3(speculars[at]), speculars[at].w,
                                                     normal, towardsLight, towardsEye);
          }
          ASSERT_GT(diffuseSum.r, diffuseBase.r) << where;
          test::expectNearVec4(diffuse[at], glm::vec4(diffuseSum, kLevel + 1), where,
                               kSumTolerance);
          test::expectNearVec4(specular[at], glm::vec4(specularSum, 0.0f), where, kSumTolerance);
        }
      }
    };
    expectSums(
        gathered, [](int) { return true; }, glm::vec3(0.0f), glm::vec3(0.0f));
    // The light named as a range's light (which the pass leaves out where it cannot light a texel)
    // lights every listed texel here, so the sums are those of every VPL, bit for bit.
    const std::vector<gpu::GpuVplRange> wholeLight = {{glm::ivec4(0, 36, 0, 0)}};
    GatheredLevels byLight(layout_);
    glClearTexImage(byLight.diffuse(kLevel).id(), 0, GL_RGBA, GL_FLOAT, &untouched[0]);
    glClearTexImage(byLight.specular(kLevel).id(), 0, GL_RGBA, GL_FLOAT, &untouched[0]);
    pass.runLevel(kLevel,
                  {reduced, refinement, vpls_, eye, &visibility, false, sceneGpu_->lightBuffer(),
                   wholeLight, nullptr},
                  {byLight});
    EXPECT_EQ(texelsOf(byLight.diffuse(kLevel), size), texelsOf(gathered.diffuse(kLevel), size));
    EXPECT_EQ(texelsOf(byLight.specular(kLevel), size), texelsOf(gathered.specular(kLevel), size));
    expectSums(
        partial, [](int vpl) { return vpl < 5 || vpl >= 20; }, glm::vec3(keptDiffuse),
        glm::vec3(keptSpecular));
  }
}

// upsample.comp at one texel.
struct Light {
  glm::vec4 diffuse{0.0f};
  glm::vec4 specular{0.0f};
};

Light referenceUpsampled(const test::LevelTexels& texels, const test::LevelTexels& coarser,
                         const std::vector<Light>& coarserLight, glm::ivec2 texel,
                         float planeTolerance) {
  const glm::ivec2 parent = texel / 2;
  const glm::ivec2 step(texel.x % 2 == 1 ? 1 : -1, texel.y % 2 == 1 ? 1 : -1);
  const glm::vec4 positionDepth = texels.positionDepth[indexOf(texel, texels.size)];
  const glm::vec3 normal = glm::normalize(glm::vec3(texels.normal[indexOf(texel, texels.size)]));
  const glm::ivec2 taps[4] = {parent, parent + glm::ivec2(step.x, 0),
                              parent + glm::ivec2(0, step.y), parent + step};
  const float tent[4] = {0.5625f, 0.1875f, 0.1875f, 0.0625f};
  Light tapLight[4];
  bool valid[4];
  for (int i = 0; i < 4; ++i) {
    const bool inside = taps[i].x >= 0 && taps[i].y >= 0 && taps[i].x < coarser.size.x &&
                        taps[i].y < coarser.size.y;
    if (inside)
      tapLight[i] = coarserLight[indexOf(taps[i], coarser.size)];
    valid[i] = inside && tapLight[i].diffuse.w != 0.0f;
  }
  valid[3] = valid[3] && (valid[1] || valid[2]);
  glm::vec3 diffuseSum(0.0f);
  glm::vec3 specularSum(0.0f);
  float weightSum = 0.0f;
  for (int i = 0; i < 4; ++i) {
    if (!valid[i])
      continue;
    const std::size_t at = indexOf(taps[i], coarser.size);
    const glm::vec3 otherNormal = glm::normalize(glm::vec3(coarser.normal[at]));
    const float offPlane =
        std::abs(
            glm::dot(glm::vec3(coarser.positionDepth[at]) - glm::vec3(positionDepth), normal)) /
        (planeTolerance * positionDepth.w);
    const float facing = std::max(glm::dot(normal, otherNormal), 0.0f);
    const float weight = tent[i] * facing * facing / (1.0f + offPlane * offPlane);
    diffuseSum += weight * glm::vec3(tapLight[i].diffuse);
    specularSum += weight * glm::vec3(tapLight[i].specular);
    weightSum += weight;
  }
  if (weightSum > 0.0f)
    return {glm::vec4(diffuseSum / weightSum, tapLight[0].diffuse.w),
            glm::vec4(specularSum / weightSum, 0.0f)};
  return coarserLight[indexOf(parent, coarser.size)];
}

TEST_F(PassTest, UpsampleMatchesTheCppReference) {
  ReducedGBuffer reduced(gbuffer_, layout_);
  RefinementState refinement(layout_);
  GatheredLevels gathered(layout_);
  gl::Texture radiance(GL_TEXTURE_2D);
  glTextureStorage2D(radiance.id(), 1, GL_RGBA32F, kFullSize.x, kFullSize.y);

  // A floor with a step up in its right columns (off the plane of the texels beside it) and a
  // tilted row, so that the taps' weights differ.
  const auto position = [](glm::ivec2 texel, float scale) {
    const float x = scale * (static_cast<float>(texel.x) + 0.5f);
    return glm::vec4(x, x > 2.8f ? 0.5f : 0.0f, scale * (static_cast<float>(texel.y) + 0.5f),
                     3.0f + 0.2f * x);
  };
  // Pixel (0, 3) faces away from every tap: it keeps its parent's light.
  const auto normal = [](glm::ivec2 texel, float kind) {
    if (kind == gpu::kPixelSurface && texel == glm::ivec2(0, 3))
      return glm::vec4(0.0f, -1.0f, 0.0f, kind);
    return glm::vec4(
        texel.y == 0 ? glm::normalize(glm::vec3(0.4f, 1.0f, 0.0f)) : glm::vec3(0.0f, 1.0f, 0.0f),
        kind);
  };
  upload(gbuffer_.positionDepth, kFullSize,
         levelOf<glm::vec4>(kFullSize, [&](glm::ivec2 texel) { return position(texel, 0.6f); }));
  upload(gbuffer_.normalKind, kFullSize, levelOf<glm::vec4>(kFullSize, [&](glm::ivec2 texel) {
           return normal(texel, gpu::kPixelSurface);
         }));
  upload(gbuffer_.albedo, kFullSize, std::vector<glm::vec4>(24, glm::vec4(0.5f, 0.6f, 0.7f, 1)));
  upload(gbuffer_.emission, kFullSize, levelOf<glm::vec4>(kFullSize, [](glm::ivec2 texel) {
           return glm::vec4(0.01f * static_cast<float>(texel.x), 0.02f, 0.0f, 0.0f);
         }));
  const glm::ivec2 coarse = layout_.size(1);
  const ReducedGBuffer::Averages averages = reduced.averages(1);
  upload(averages.positionDepth, coarse,
         levelOf<glm::vec4>(coarse, [&](glm::ivec2 texel) { return position(texel, 1.2f); }));
  upload(averages.normal, coarse,
         levelOf<glm::vec4>(coarse, [&](glm::ivec2 texel) { return normal(texel, 1.0f); }));

  // The refinement's states: the coarse level computes four texels, one is unlit and one
  // refined; under the refined one level 0 computes two pixels and has an invalid and an unlit
  // one.
  const std::vector<std::uint32_t> coarseStates = {gpu::kTexelComputed, gpu::kTexelComputed,
                                                   gpu::kTexelRefined,  gpu::kTexelComputed,
                                                   gpu::kTexelUnlit,    gpu::kTexelComputed};
  upload(refinement.state(1), coarse, coarseStates);
  const std::vector<std::uint32_t> fineStates =
      levelOf<std::uint32_t>(kFullSize, [&](glm::ivec2 texel) {
        const std::uint32_t parent = coarseStates[indexOf(texel / 2, coarse)];
        if (parent == gpu::kTexelUnlit)
          return gpu::kTexelUnlit;
        if (parent != gpu::kTexelRefined)
          return gpu::kTexelCovered;
        const std::uint32_t under[4] = {gpu::kTexelComputed, gpu::kTexelInvalid, gpu::kTexelUnlit,
                                        gpu::kTexelComputed};
        return under[texel.x % 2 + 2 * (texel.y % 2)];
      });
  upload(refinement.state(0), kFullSize, fineStates);
  // The gather's results at the computed texels (w: 1 + the level).
  const auto gatheredAt = [](glm::ivec2 texel, int level) {
    const float x = static_cast<float>(texel.x);
    const float y = static_cast<float>(texel.y);
    return Light{glm::vec4(1.0f + x, 2.0f - 0.5f * y, 0.5f + x * y, level + 1),
                 glm::vec4(0.1f * x, 0.2f, 0.05f * y, 0.0f)};
  };
  for (int level = 0; level < layout_.levelCount(); ++level) {
    const glm::ivec2 size = layout_.size(level);
    const std::vector<std::uint32_t>& states = level == 0 ? fineStates : coarseStates;
    std::vector<glm::vec4> diffuse(states.size(), glm::vec4(-7.0f));
    std::vector<glm::vec4> specular(states.size(), glm::vec4(-7.0f));
    for (int y = 0; y < size.y; ++y) {
      for (int x = 0; x < size.x; ++x) {
        const std::size_t at = indexOf({x, y}, size);
        if (states[at] != gpu::kTexelComputed)
          continue;
        diffuse[at] = gatheredAt({x, y}, level).diffuse;
        specular[at] = gatheredAt({x, y}, level).specular;
      }
    }
    upload(gathered.diffuse(level), size, diffuse);
    upload(gathered.specular(level), size, specular);
  }

  constexpr float planeTolerance = 0.05f;
  const UpsamplePass pass;
  const UpsamplePass::Inputs inputs{gbuffer_, reduced, refinement, planeTolerance};
  pass.run(inputs, {gathered, radiance});
  // A frame leaves level 0's covered and unlit texels out of its results; the debug views have
  // them completed, without touching the radiance.
  const std::vector<glm::vec4> fineDiffuseOfTheFrame = texelsOf(gathered.diffuse(0), kFullSize);
  const std::vector<glm::vec4> found = texelsOf(radiance, kFullSize);
  pass.completeFullResolution(inputs, gathered);
  EXPECT_EQ(texelsOf(radiance, kFullSize), found);
  for (std::size_t at = 0; at < fineStates.size(); ++at) {
    if (fineStates[at] != gpu::kTexelComputed) {
      EXPECT_EQ(fineDiffuseOfTheFrame[at], glm::vec4(-7.0f)) << "pixel " << at;
    }
  }

  // The reference, level by level from the coarsest.
  std::vector<Light> coarser;
  std::set<bool> blended;
  for (int level = layout_.coarsest(); level >= 0; --level) {
    const glm::ivec2 size = layout_.size(level);
    const test::LevelTexels texels = test::readReducedLevel(reduced, level);
    const test::LevelTexels coarserTexels =
        test::readReducedLevel(reduced, std::min(level + 1, layout_.coarsest()));
    const std::vector<std::uint32_t>& states = level == 0 ? fineStates : coarseStates;
    const std::vector<glm::vec4> diffuse = texelsOf(gathered.diffuse(level), size);
    const std::vector<glm::vec4> specular = texelsOf(gathered.specular(level), size);
    std::vector<Light> expectedLevel;
    for (int y = 0; y < size.y; ++y) {
      for (int x = 0; x < size.x; ++x) {
        const std::size_t at = indexOf({x, y}, size);
        Light expected;
        if (states[at] == gpu::kTexelComputed) {
          expected = gatheredAt({x, y}, level);
        } else if (states[at] == gpu::kTexelCovered && level < layout_.coarsest()) {
          expected = referenceUpsampled(texels, coarserTexels, coarser, {x, y}, planeTolerance);
          blended.insert(expected.diffuse !=
                         coarser[indexOf({x / 2, y / 2}, coarserTexels.size)].diffuse);
        } else {
          expected.diffuse.w =
              states[at] == gpu::kTexelUnlit ? -static_cast<float>(level + 1) : 0.0f;
        }
        test::expectNearVec4(diffuse[at], expected.diffuse, texelName(level, {x, y}),
                             kSumTolerance);
        test::expectNearVec4(specular[at], expected.specular, texelName(level, {x, y}),
                             kSumTolerance);
        expectedLevel.push_back(expected);
      }
    }
    coarser = expectedLevel;
  }
  // Covered texels blend their taps, and the one facing away from them keeps its parent's light.
  EXPECT_EQ(blended, (std::set<bool>{false, true}));

  // Level 0 also wrote the radiance: emission plus albedo/pi times the diffuse light plus the
  // specular, where the texel holds a value.
  const std::vector<glm::vec4> albedo = texelsOf(gbuffer_.albedo, kFullSize);
  const std::vector<glm::vec4> emission = texelsOf(gbuffer_.emission, kFullSize);
  for (std::size_t at = 0; at < found.size(); ++at) {
    glm::vec3 expected(emission[at]);
    if (coarser[at].diffuse.w != 0.0f)
      expected += glm::vec3(albedo[at]) / kPi * glm::vec3(coarser[at].diffuse) +
                  glm::vec3(coarser[at].specular);
    test::expectNearVec4(found[at], glm::vec4(expected, 1.0f), "radiance " + std::to_string(at),
                         kSumTolerance);
  }
}

}  // namespace
}  // namespace penumbra
