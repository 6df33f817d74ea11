// Visibility reuse across frames (visibility_reuse.h): a frame that keeps the last frame's
// visibility (and with it the reduced G-buffer and the refinement) renders exactly what a fresh
// renderer renders for the same state, it is taken when only the video moves on, and every input
// of the key makes the next frame trace again. The voxel grid or BVH is kept when only what the
// masks alone depend on changes (the camera with a world grid, the VPL count, the hierarchy's
// settings), and the frame is again a fresh renderer's. A frame that reuses the visibility keeps
// the sums of the lights without a video and gathers only the video's VPLs (or nothing).

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "image/metrics.h"
#include "image/video_writer.h"
#include "render/frame.h"
#include "render/render_test_scenes.h"
#include "test_files.h"

namespace penumbra {
namespace {

// A 0.8 x 0.8 square at height 1, facing up, that casts a shadow on the floor below it.
constexpr const char* kOccluderObj =
    "v -0.4 1 -0.4\nv 0.4 1 -0.4\nv 0.4 1 0.4\nv -0.4 1 0.4\nvn 0 1 0\nf 4//1 3//1 2//1 1//1\n";

// A video light above the occluder, which oscillates along x (step 0.2 radians a frame), over
// the floor, and a steady panel beside it; the camera looks down on the shadow's penumbra.
constexpr const char* kSceneText =
    "material white\n  dif 0.8 0.8 0.8\nend\n"
    "material screen\n  emit 3 3 3\n  tex colours.mp4\nend\n"
    "material panel\n  emit 1 0.8 0.6\nend\n"
    "area_light tv\n  pos1 -0.6 2.5 -0.6\n  pos2 0.6 2.5 -0.6\n  pos3 0.6 2.5 0.6\n"
    "  pos4 -0.6 2.5 0.6\n  at 0 0 0\n  mat screen\nend\n"
    "area_light panel\n  pos1 1.2 2 -0.3\n  pos2 1.8 2 -0.3\n  pos3 1.8 2 0.3\n"
    "  pos4 1.2 2 0.3\n  at 0.5 0 0\n  mat panel\nend\n"
    "camera c\n  pos 0 3 3\n  at 0 0 0\n  screen_size 64 64\nend\n"
    "object floor.obj\n  mat white\nend\n"
    "object occluder.obj\n  mat white\n  anim translate 0.5 0 0 0.2\nend\n";

// Three video frames of one colour each, far apart, so that each frame of the video lights the
// scene differently.
void writeColourVideo(const std::filesystem::path& file) {
  VideoOptions options;
  options.nearLossless = true;
  VideoWriter writer(file, {16, 16}, options);
  for (const glm::vec4 colour :
       {glm::vec4(1.0f, 0.2f, 0.2f, 1.0f), glm::vec4(0.2f, 1.0f, 0.2f, 1.0f),
        glm::vec4(0.2f, 0.2f, 1.0f, 1.0f)}) {
    Image picture(16, 16);
    for (glm::vec4& pixel : picture.pixels)
      pixel = colour;
    writer.write(picture);
  }
  writer.finish();
}

constexpr int kVplsPerLight = 16;

// Everything one frame is rendered from.
struct FrameState {
  int frame = 0;
  double videoSeconds = 0.5 / 30.0;  // the middle of the video's first frame
  Camera camera;
  RenderSettings settings;
};

class VisibilityReuse : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = test::scratchDirectory();
    test::writeFile(directory_, "floor.obj", test::kFloorObj);
    test::writeFile(directory_, "occluder.obj", kOccluderObj);
    writeColourVideo(directory_ / "colours.mp4");
    scene_ = test::loadSceneText(directory_, kSceneText);
    initial_.camera = scene_.camera;
    initial_.settings.vplsPerLight = kVplsPerLight;
    initial_.settings.multiresolution.coarsestSize = 16;
  }

  static void render(Renderer& renderer, const FrameState& state) {
    renderer.setCamera(state.camera);
    renderer.render(state.frame, state.settings, state.videoSeconds);
  }

  // Renders `initial_`, then the same state with the video at `videoSeconds`: that frame must
  // reuse the hierarchy, keep `vplsKept` VPLs' sums and give a fresh renderer's picture. Returns
  // its state.
  FrameState expectPlayingOnReuses(Renderer& renderer, double videoSeconds, int vplsKept) {
    render(renderer, initial_);
    FrameState later = initial_;
    later.videoSeconds = videoSeconds;
    render(renderer, later);
    EXPECT_TRUE(renderer.statistics().visibilityReused);
    EXPECT_EQ(renderer.statistics().vplsKept, vplsKept);
    expectIdentical(renderer.readRadiance(), freshImage(later));
    return later;
  }

  // The picture of `state` from a renderer that never rendered anything else.
  Image freshImage(const FrameState& state) {
    Renderer fresh(scene_, state.camera.size);
    render(fresh, state);
    EXPECT_FALSE(fresh.statistics().visibilityReused);
    return fresh.readRadiance();
  }

  // Renders `initial_` twice in one renderer (the second frame reuses), then `changed`: the
  // change must make that renderer trace again, through the grid or BVH it kept or built anew as
  // `structure` says, and give a fresh renderer's picture.
  enum class Structure { Kept, Rebuilt };
  void expectChangeTracesAgain(const FrameState& changed, Structure structure) {
    Renderer renderer(scene_, initial_.camera.size);
    render(renderer, initial_);
    EXPECT_FALSE(renderer.statistics().visibilityStructureKept);
    render(renderer, initial_);
    ASSERT_TRUE(renderer.statistics().visibilityReused) << "the unchanged frame must reuse";
    EXPECT_TRUE(renderer.statistics().visibilityStructureKept);
    render(renderer, changed);
    const FrameStatistics statistics = renderer.statistics();
    EXPECT_FALSE(statistics.visibilityReused);
    EXPECT_EQ(statistics.vplsKept, 0) << "a frame that traces gathers every light";
    EXPECT_EQ(statistics.visibilityStructureKept, structure == Structure::Kept);
    EXPECT_GT(statistics.shadowRays(), 0u);
    expectIdentical(renderer.readRadiance(), freshImage(changed));
  }

  // Reuse is exact: the same bits, not merely close (issue 16 allows a relative MSE of 1e-6;
  // the passes are deterministic, so nothing but identity is expected).
  static void expectIdentical(const Image& actual, const Image& expected) {
    const ImageMetrics metrics = compareImages(actual, expected);
    EXPECT_EQ(metrics.maxError, 0.0) << "RMSE " << metrics.rmse;
  }

  std::filesystem::path directory_;
  Scene scene_;
  FrameState initial_;
};

TEST_F(VisibilityReuse, VideoFrameAloneReusesAndMatchesAFreshRenderer) {
  Renderer renderer(scene_, initial_.camera.size);
  render(renderer, initial_);
  const FrameStatistics traced = renderer.statistics();
  EXPECT_FALSE(traced.visibilityReused);
  EXPECT_GT(traced.shadowRays(), 0u);
  const Image firstVideoFrame = renderer.readRadiance();

  FrameState laterVideo = initial_;
  laterVideo.videoSeconds = 1.5 / 30.0;
  render(renderer, laterVideo);
  EXPECT_EQ(renderer.statistics().vplsKept, kVplsPerLight);
  laterVideo.videoSeconds = 2.5 / 30.0;  // the video's third frame
  render(renderer, laterVideo);
  const FrameStatistics reused = renderer.statistics();
  EXPECT_TRUE(reused.visibilityReused);
  EXPECT_EQ(traced.vplsKept, 0);
  EXPECT_EQ(reused.vplsKept, kVplsPerLight) << "the panel's sums are kept, the video's gathered";
  EXPECT_EQ(reused.shadowRays(), 0u);
  EXPECT_EQ(reused.visibilityTraced(), 0u);
  // The same texels hold masks as when they were traced: the refinement kept is the traced one.
  EXPECT_EQ(reused.visibilityMasked(), traced.visibilityMasked());
  // Neither the discontinuity pyramid nor the refinement ran again (their inputs are in the key).
  for (const StageTime& stage : renderer.stageTimes()) {
    EXPECT_NE(stage.key.stage, Stage::Discontinuity);
    EXPECT_NE(stage.key.stage, Stage::Refinement);
    EXPECT_NE(stage.key.stage, Stage::Visibility);
  }
  const Image reusedImage = renderer.readRadiance();
  EXPECT_GT(compareImages(reusedImage, firstVideoFrame).maxError, 0.1)
      << "the video's frames must light the scene differently";
  expectIdentical(reusedImage, freshImage(laterVideo));
}

TEST_F(VisibilityReuse, StaticSceneReusesAcrossSceneFrames) {
  scene_.objects.back().desc.animations.clear();
  Renderer renderer(scene_, initial_.camera.size);
  render(renderer, initial_);
  FrameState later = initial_;
  later.frame = 7;
  render(renderer, later);
  EXPECT_TRUE(renderer.statistics().visibilityReused);
  expectIdentical(renderer.readRadiance(), freshImage(later));
}

// Without a video no light's radiance changes, so a frame that reuses the visibility keeps every
// sum and gathers nothing.
TEST_F(VisibilityReuse, WithoutAVideoTheReusedFrameGathersNothing) {
  scene_.lights.front().texture = -1;
  Renderer renderer(scene_, initial_.camera.size);
  render(renderer, initial_);
  FrameState later = initial_;
  // Every frame after the first keeps the sums, the third as the second.
  for (const double seconds : {1.5 / 30.0, 2.5 / 30.0}) {
    later.videoSeconds = seconds;
    render(renderer, later);
    EXPECT_TRUE(renderer.statistics().visibilityReused);
    EXPECT_EQ(renderer.statistics().vplsKept, 2 * kVplsPerLight);
    for (const StageTime& stage : renderer.stageTimes())
      EXPECT_NE(stage.key.stage, Stage::Gather);
  }
  expectIdentical(renderer.readRadiance(), freshImage(later));
}

// The thesis's visible fraction scales each texel's sum by its share of visible VPLs over all
// lights, so its frames gather every light, reused or not.
TEST_F(VisibilityReuse, VisibleFractionGathersEveryLight) {
  initial_.settings.shadows.visibleFraction = true;
  Renderer renderer(scene_, initial_.camera.size);
  expectPlayingOnReuses(renderer, 2.5 / 30.0, 0);
}

// Without shadows there are no masks, but the discontinuity pyramid, the refinement and the
// panel's sums depend on the same key: a still frame keeps them, a moved camera makes them anew.
TEST_F(VisibilityReuse, WithoutShadowsAStillFrameKeepsTheHierarchy) {
  initial_.settings.shadows.enabled = false;
  Renderer renderer(scene_, initial_.camera.size);
  const FrameState laterVideo = expectPlayingOnReuses(renderer, 2.5 / 30.0, kVplsPerLight);
  for (const StageTime& stage : renderer.stageTimes()) {
    EXPECT_NE(stage.key.stage, Stage::Discontinuity);
    EXPECT_NE(stage.key.stage, Stage::Refinement);
  }
  FrameState moved = laterVideo;
  moved.camera.position.x += 0.3f;
  render(renderer, moved);
  EXPECT_FALSE(renderer.statistics().visibilityReused);
  EXPECT_EQ(renderer.statistics().vplsKept, 0);
  expectIdentical(renderer.readRadiance(), freshImage(moved));
}

TEST_F(VisibilityReuse, WithIndirectLightReusesAndMatchesAFreshRenderer) {
  initial_.settings.indirect.enabled = true;
  initial_.settings.indirect.vplCount = 32;
  initial_.settings.indirect.rsmSize = 16;
  Renderer renderer(scene_, initial_.camera.size);
  expectPlayingOnReuses(renderer, 1.5 / 30.0, kVplsPerLight);
  EXPECT_FALSE(renderer.statistics().bounceSourcesKept) << "the video changes the maps' flux";
}

TEST_F(VisibilityReuse, SettingOffTracesEveryFrame) {
  initial_.settings.reuseVisibility = false;
  Renderer renderer(scene_, initial_.camera.size);
  render(renderer, initial_);
  render(renderer, initial_);
  EXPECT_FALSE(renderer.statistics().visibilityReused);
  EXPECT_FALSE(renderer.statistics().visibilityStructureKept);
  EXPECT_GT(renderer.statistics().shadowRays(), 0u);
}

TEST_F(VisibilityReuse, NaiveModeKeepsOnlyTheGrid) {
  initial_.settings.mode = RenderMode::Naive;
  Renderer renderer(scene_, initial_.camera.size);
  render(renderer, initial_);
  FrameState moved = initial_;
  moved.camera.position.x += 0.3f;
  render(renderer, moved);
  EXPECT_FALSE(renderer.statistics().visibilityReused);
  EXPECT_TRUE(renderer.statistics().visibilityStructureKept);
  expectIdentical(renderer.readRadiance(), freshImage(moved));
}

// The screen grid follows the camera's frustum, so a camera move builds it again; both ways the
// frame is a fresh renderer's.
TEST_F(VisibilityReuse, ScreenGridIsBuiltAgainWhenTheCameraMoves) {
  initial_.settings.shadows.voxels.grid = VoxelSettings::Grid::Screen;
  initial_.settings.shadows.voxels.traversal = VoxelSettings::Traversal::Uniform;
  FrameState changed = initial_;
  changed.camera.position.x += 0.3f;
  expectChangeTracesAgain(changed, Structure::Rebuilt);
}

TEST_F(VisibilityReuse, FrameWithoutShadowsOrNaiveInBetweenTracesAgain) {
  // Such a frame clears (no shadows) or leaves out (naive) the masks, so the next shadowed
  // hierarchical frame of the same state has nothing to keep.
  for (const bool naive : {false, true}) {
    Renderer renderer(scene_, initial_.camera.size);
    render(renderer, initial_);
    FrameState between = initial_;
    if (naive)
      between.settings.mode = RenderMode::Naive;
    else
      between.settings.shadows.enabled = false;
    render(renderer, between);
    render(renderer, initial_);
    EXPECT_FALSE(renderer.statistics().visibilityReused) << (naive ? "naive" : "no shadows");
    expectIdentical(renderer.readRadiance(), freshImage(initial_));
  }
}

TEST_F(VisibilityReuse, CameraMoveTracesAgain) {
  FrameState changed = initial_;
  changed.camera.position.x += 0.3f;
  expectChangeTracesAgain(changed, Structure::Kept);
}

TEST_F(VisibilityReuse, AnimationFrameTracesAgain) {
  FrameState changed = initial_;
  changed.frame = 5;  // the occluder 0.5 sin(1) to the side
  expectChangeTracesAgain(changed, Structure::Rebuilt);
}

TEST_F(VisibilityReuse, ShadowOffsetTracesAgain) {
  FrameState changed = initial_;
  changed.settings.shadows.voxels.originOffset = 3.0f;
  expectChangeTracesAgain(changed, Structure::Rebuilt);
}

TEST_F(VisibilityReuse, VisibilityMethodTracesAgain) {
  FrameState changed = initial_;
  changed.settings.shadows.visibility = ShadowSettings::Visibility::Bvh;
  expectChangeTracesAgain(changed, Structure::Rebuilt);
}

TEST_F(VisibilityReuse, VplCountTracesAgain) {
  FrameState changed = initial_;
  changed.settings.vplsPerLight = 9;
  expectChangeTracesAgain(changed, Structure::Kept);
}

TEST_F(VisibilityReuse, CoarsestLevelTracesAgain) {
  FrameState changed = initial_;
  changed.settings.multiresolution.coarsestSize = 8;
  expectChangeTracesAgain(changed, Structure::Kept);
}

// The bounce's sources (the maps, the secondary VPLs and their first leg's visibility): the
// scene above with the TV's video replaced by its material's plain emission, so that no light's
// radiance varies, and a wall beside the floor whose light the floor receives; small maps and few
// secondary VPLs.
class BounceSourceReuse : public VisibilityReuse {
 protected:
  void SetUp() override {
    VisibilityReuse::SetUp();
    std::string text = kSceneText;
    const std::string video = "  tex colours.mp4\n";
    text.erase(text.find(video), video.size());
    test::writeFile(directory_, "wall.obj",
                    "v 1 0 -3\nv 1 0 3\nv 1 2 3\nv 1 2 -3\nvn -1 0 0\nf 1//1 2//1 3//1 4//1\n");
    text += "object wall.obj\n  mat white\nend\n";
    scene_ = test::loadSceneText(directory_, text);
    initial_.settings.indirect.enabled = true;
    initial_.settings.indirect.vplCount = 32;
    initial_.settings.indirect.rsmSize = 16;
  }

  static bool renderedBounceSources(const Renderer& renderer) {
    for (const StageTime& stage : renderer.stageTimes()) {
      if (stage.key.stage == Stage::BounceRsm || stage.key.stage == Stage::BounceVpls ||
          stage.key.stage == Stage::BounceShadows)
        return true;
    }
    return false;
  }
};

// A moving camera keeps them (they do not depend on it), and the frame is a fresh renderer's.
TEST_F(BounceSourceReuse, KeptWhileTheSceneStandsStillAndMatchFreshRenderers) {
  Renderer renderer(scene_, initial_.camera.size);
  render(renderer, initial_);
  EXPECT_FALSE(renderer.statistics().bounceSourcesKept);
  EXPECT_TRUE(renderedBounceSources(renderer));
  FrameState moved = initial_;
  moved.camera.position.x += 0.3f;
  render(renderer, moved);
  EXPECT_TRUE(renderer.statistics().bounceSourcesKept);
  EXPECT_FALSE(renderedBounceSources(renderer));
  // The premise: the picture holds a bounce for the kept sources to give.
  const Image bounce =
      readTexture(renderer.indirect().id(), initial_.camera.size, RowOrder::TopFirst);
  EXPECT_GT(compareImages(bounce, Image(bounce.width, bounce.height)).maxError, 1e-3);
  expectIdentical(renderer.readRadiance(), freshImage(moved));
  render(renderer, initial_);
  EXPECT_TRUE(renderer.statistics().bounceSourcesKept);
  expectIdentical(renderer.readRadiance(), freshImage(initial_));
}

TEST_F(BounceSourceReuse, EachChangeTheyDependOnRendersThemAgain) {
  const auto expectRenderedAgain = [&](auto change, const char* what) {
    SCOPED_TRACE(what);
    FrameState changed = initial_;
    change(changed);
    Renderer renderer(scene_, initial_.camera.size);
    render(renderer, initial_);
    render(renderer, initial_);
    ASSERT_TRUE(renderer.statistics().bounceSourcesKept) << "the unchanged frame must keep them";
    render(renderer, changed);
    EXPECT_FALSE(renderer.statistics().bounceSourcesKept);
    EXPECT_TRUE(renderedBounceSources(renderer));
    expectIdentical(renderer.readRadiance(), freshImage(changed));
  };
  expectRenderedAgain([](FrameState& state) { state.frame = 5; }, "animation frame");
  expectRenderedAgain([](FrameState& state) { state.settings.shadows.enabled = false; }, "shadows");
  expectRenderedAgain(
      [](FrameState& state) {
        state.settings.shadows.visibility = ShadowSettings::Visibility::Bvh;
      },
      "visibility method");
  expectRenderedAgain([](FrameState& state) { state.settings.vplsPerLight = 9; }, "VPLs per light");
  expectRenderedAgain([](FrameState& state) { state.settings.indirect.rsmSize = 8; }, "map size");
  expectRenderedAgain([](FrameState& state) { state.settings.indirect.vplCount = 16; },
                      "secondary VPLs");
  expectRenderedAgain([](FrameState& state) { state.settings.reuseVisibility = false; },
                      "reuse off");
}

// A frame without indirect light in between leaves nothing to keep.
TEST_F(BounceSourceReuse, FrameWithoutIndirectLightInBetweenRendersThemAgain) {
  Renderer renderer(scene_, initial_.camera.size);
  render(renderer, initial_);
  FrameState between = initial_;
  between.settings.indirect.enabled = false;
  render(renderer, between);
  render(renderer, initial_);
  EXPECT_FALSE(renderer.statistics().bounceSourcesKept);
  expectIdentical(renderer.readRadiance(), freshImage(initial_));
}

}  // namespace
}  // namespace penumbra
