// The registry of debug views (render/debug_view_registry.h): every registered view renders
// through debugView, the path of `render --debug-view`, after a hierarchical frame with shadows
// and indirect light, and the one colouring gives what its kinds promise.

#include "render/debug_views.h"

#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "render/frame.h"
#include "render/readback.h"
#include "scene/scene.h"
#include "scene/scene_desc.h"
#include "test_files.h"

namespace penumbra {
namespace {

RenderSettings everyPassSettings() {
  RenderSettings settings;
  settings.mode = RenderMode::Hierarchical;
  settings.vplsPerLight = 16;
  settings.multiresolution.coarsestSize = 8;
  settings.shadows.enabled = true;
  settings.shadows.voxels.resolution = 32;
  settings.indirect.enabled = true;
  settings.indirect.vplCount = 16;
  settings.indirect.rsmSize = 16;
  return settings;
}

class DebugViews : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(
        loadScene(parseSceneFile(test::sourceDirectory() / "scenes/cornell_bunny.scene")));
    renderer_ = new Renderer(*scene_, {64, 64});
    renderer_->render(0, everyPassSettings());
  }
  static void TearDownTestSuite() {
    delete renderer_;
    delete scene_;
  }
  static Scene* scene_;
  static Renderer* renderer_;
};
Scene* DebugViews::scene_ = nullptr;
Renderer* DebugViews::renderer_ = nullptr;

TEST_F(DebugViews, EveryRegisteredViewRenders) {
  const RenderSettings settings = everyPassSettings();
  for (const DebugViewInfo& info : debugViewInfos()) {
    std::string why;
    ASSERT_TRUE(debugViewAvailable(info, *renderer_, &why)) << why;
    const Image view = debugView(*renderer_, info.name, settings);
    EXPECT_GT(view.width, 0) << info.name;
    EXPECT_GT(view.height, 0) << info.name;
    if (info.indexed) {
      const glm::ivec2 indices = debugViewIndices(info, *renderer_);
      const std::string last = std::string(info.name) + "-" + std::to_string(indices.y);
      EXPECT_NO_THROW(debugView(*renderer_, last, settings)) << last;
      EXPECT_THROW(
          debugView(*renderer_, std::string(info.name) + "-" + std::to_string(indices.y + 1),
                    settings),
          RenderError)
          << info.name;
    }
  }
}

TEST_F(DebugViews, NamesListEveryRegisteredView) {
  const std::vector<std::string> names = debugViewNames(*renderer_);
  for (const DebugViewInfo& info : debugViewInfos()) {
    const std::string expected = std::string(info.name) + (info.indexed ? "-" : "");
    EXPECT_TRUE(std::any_of(names.begin(), names.end(), [&](const std::string& name) {
      return info.indexed ? name.starts_with(expected) : name == expected;
    })) << info.name;
  }
}

TEST_F(DebugViews, UnknownNameListsTheRegistry) {
  try {
    debugView(*renderer_, "colour", everyPassSettings());
    ADD_FAILURE() << "expected a RenderError";
  } catch (const RenderError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("unknown debug view 'colour'"), std::string::npos) << message;
    EXPECT_NE(message.find(debugViewNameList()), std::string::npos) << message;
  }
  EXPECT_THROW(debugView(*renderer_, "albedo-1", everyPassSettings()), RenderError);
}

// Level 0's results are stored on request from the hierarchical frame's G-buffer, which a naive
// frame replaces: after a naive frame the views of them are unavailable unless they were stored
// before it, while the other views of the hierarchy stay.
TEST(DebugViewsAfterANaiveFrame, ShowLevelZerosResultsOnlyWhenStoredBeforeIt) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes/cornell_bunny.scene"));
  Renderer renderer(scene, {32, 32});
  RenderSettings hierarchical;
  hierarchical.vplsPerLight = 16;
  hierarchical.multiresolution.coarsestSize = 8;
  hierarchical.shadows.enabled = false;
  RenderSettings naive = hierarchical;
  naive.mode = RenderMode::Naive;
  const DebugViewInfo& levels = *findDebugView("levels");
  const DebugViewInfo& worklist = *findDebugView("worklist");

  renderer.render(0, hierarchical);
  renderer.render(0, naive);
  std::string why;
  EXPECT_FALSE(debugViewAvailable(levels, renderer, &why));
  EXPECT_EQ(why, "debug view 'levels' needs a hierarchical last frame");
  EXPECT_TRUE(debugViewAvailable(worklist, renderer, nullptr));

  renderer.render(0, hierarchical);
  const Image before = debugView(renderer, "levels", hierarchical);
  renderer.render(0, naive);
  ASSERT_TRUE(debugViewAvailable(levels, renderer, &why)) << why;
  EXPECT_EQ(debugView(renderer, "levels", hierarchical).pixels, before.pixels);
}

// The colouring against a C++ reference of its two simplest kinds, on the G-buffer read back:
// colour views copy rgb (exactly), normal views show 0.5 N + 0.5 and black where w = 0.
TEST_F(DebugViews, ColouringMatchesTheGBuffer) {
  const RenderSettings settings = everyPassSettings();
  const GBuffer& gbuffer = renderer_->gbuffer();
  const Image albedo = readTexture(gbuffer.albedo.id(), gbuffer.size, RowOrder::TopFirst);
  const Image albedoView = debugView(*renderer_, "albedo", settings);
  const Image normals = readTexture(gbuffer.normalKind.id(), gbuffer.size, RowOrder::TopFirst);
  const Image normalView = debugView(*renderer_, "normal", settings);
  ASSERT_EQ(albedoView.pixels.size(), albedo.pixels.size());
  ASSERT_EQ(normalView.pixels.size(), normals.pixels.size());
  for (std::size_t i = 0; i < albedo.pixels.size(); ++i) {
    ASSERT_EQ(albedoView.pixels[i], glm::vec4(glm::vec3(albedo.pixels[i]), 1.0f)) << i;
    const glm::vec4 normal = normals.pixels[i];
    const glm::vec4 expected = normal.w == 0.0f ? glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)
                                                : glm::vec4(0.5f * glm::vec3(normal) + 0.5f, 1.0f);
    // 1e-6: the shader's multiply-add may be fused (one rounding instead of two), and the
    // values lie in [0, 1], where a float's spacing is at most 6e-8.
    for (int channel = 0; channel < 4; ++channel)
      ASSERT_NEAR(normalView.pixels[i][channel], expected[channel], 1e-6f) << i;
  }
}

}  // namespace
}  // namespace penumbra
