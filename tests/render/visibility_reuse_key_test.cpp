// The key of visibility reuse (visibility_reuse.h): equal for the same geometry and settings
// whatever the frame of a static scene, and different for each input the masks depend on,
// including those a renderer cannot change between two of its frames (its output size, the
// quad lights' corners), which only a new key shows.

#include <optional>

#include <gtest/gtest.h>

#include "render/visibility_reuse.h"

namespace penumbra {
namespace {

class VisibilityReuseKeyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Light light;
    light.quad.corners = {glm::vec3(-1, 2, -1), glm::vec3(1, 2, -1), glm::vec3(1, 2, 1),
                          glm::vec3(-1, 2, 1)};
    scene_.lights.push_back(light);
    scene_.objects.emplace_back();  // static
    scene_.objects.emplace_back();
    scene_.objects.back().desc.animations.push_back(
        {Animation::Kind::Translate, glm::vec3(1, 0, 0), 0.2f});
    camera_.size = {64, 64};
  }

  VisibilityReuseKey key(int frame = 0) const {
    return visibilityReuseKey(scene_, camera_, frame, settings_);
  }
  VisibilityStructureKey structureKey(int frame = 0) const {
    return visibilityStructureKey(scene_, camera_, frame, settings_.shadows);
  }

  Scene scene_;
  Camera camera_;
  RenderSettings settings_;
};

TEST_F(VisibilityReuseKeyTest, SameInputsGiveEqualKeys) {
  EXPECT_EQ(key(), key());
}

TEST_F(VisibilityReuseKeyTest, StaticSceneKeepsItsKeyAcrossFrames) {
  scene_.objects.back().desc.animations.clear();
  EXPECT_EQ(key(0), key(1));
  EXPECT_EQ(key(0), key(300));
}

TEST_F(VisibilityReuseKeyTest, AnimationFrameChangesIt) {
  EXPECT_NE(key(0), key(1));
}

TEST_F(VisibilityReuseKeyTest, OutputSizeChangesIt) {
  const VisibilityReuseKey before = key();
  camera_.size = {64, 48};
  EXPECT_NE(before, key());
}

TEST_F(VisibilityReuseKeyTest, CameraChangesIt) {
  const VisibilityReuseKey before = key();
  camera_.fovyDegrees += 1.0f;
  EXPECT_NE(before, key());
}

TEST_F(VisibilityReuseKeyTest, LightCornerChangesIt) {
  const VisibilityReuseKey before = key();
  scene_.lights.front().quad.corners[2].y += 0.01f;
  EXPECT_NE(before, key());
}

TEST_F(VisibilityReuseKeyTest, EachShadowAndHierarchySettingChangesIt) {
  const VisibilityReuseKey before = key();
  const auto expectChange = [&](auto change, const char* what) {
    const RenderSettings kept = settings_;
    change(settings_);
    EXPECT_NE(before, key()) << what;
    settings_ = kept;
  };
  expectChange([](RenderSettings& s) { s.vplsPerLight = 64; }, "VPL count");
  expectChange([](RenderSettings& s) { s.multiresolution.coarsestSize = 32; }, "coarsest size");
  expectChange([](RenderSettings& s) { s.multiresolution.depthThreshold *= 2.0f; },
               "depth threshold");
  expectChange([](RenderSettings& s) { s.multiresolution.normalThreshold *= 2.0f; },
               "normal threshold");
  expectChange([](RenderSettings& s) { s.multiresolution.lightProximityThreshold *= 2.0f; },
               "light proximity threshold");
  expectChange([](RenderSettings& s) { s.shadows.voxels.originOffset = 2.0f; }, "shadow offset");
  expectChange([](RenderSettings& s) { s.shadows.voxels.resolution = 64; }, "voxel resolution");
  expectChange([](RenderSettings& s) { s.shadows.voxels.shape = VoxelSettings::Shape::Equal; },
               "voxel shape");
  expectChange([](RenderSettings& s) { s.shadows.voxels.grid = VoxelSettings::Grid::Screen; },
               "voxel grid");
  expectChange([](RenderSettings& s) { s.shadows.visibility = ShadowSettings::Visibility::Bvh; },
               "visibility method");
  expectChange([](RenderSettings& s) { s.shadows.refinement.threshold = 0.1f; },
               "visibility threshold");
}

TEST_F(VisibilityReuseKeyTest, RadianceOnlySettingsKeepIt) {
  // The bounce is recomputed in every frame (docs/performance.md), and the switch itself says
  // whether to look at the key, not what the masks hold.
  const VisibilityReuseKey before = key();
  settings_.indirect.enabled = true;
  settings_.indirect.vplCount = 64;
  settings_.reuseVisibility = false;
  EXPECT_EQ(before, key());
}

// The voxel grid and the BVH: a world grid and a BVH do not depend on the camera; a screen grid
// does; the geometry and the structure's own settings change them; settings of the masks alone
// do not.
TEST_F(VisibilityReuseKeyTest, WorldGridAndBvhKeepTheirKeyWhenTheCameraMoves) {
  for (const auto visibility :
       {ShadowSettings::Visibility::Voxels, ShadowSettings::Visibility::Bvh}) {
    settings_.shadows.visibility = visibility;
    const VisibilityStructureKey before = structureKey();
    camera_.position.x += 1.0f;
    camera_.size = {64, 48};
    EXPECT_EQ(before, structureKey());
  }
}

TEST_F(VisibilityReuseKeyTest, ScreenGridChangesItsKeyWhenTheCameraMoves) {
  settings_.shadows.voxels.grid = VoxelSettings::Grid::Screen;
  const VisibilityStructureKey before = structureKey();
  camera_.position.x += 1.0f;
  EXPECT_NE(before, structureKey());
}

TEST_F(VisibilityReuseKeyTest, GeometryAndStructureSettingsChangeTheStructureKey) {
  EXPECT_NE(structureKey(0), structureKey(1));
  const VisibilityStructureKey before = structureKey();
  scene_.lights[0].quad.corners[2].y += 0.1f;
  EXPECT_NE(before, structureKey());
  scene_.lights[0].quad.corners[2].y -= 0.1f;
  settings_.shadows.voxels.resolution = 64;
  EXPECT_NE(before, structureKey());
  settings_.shadows.voxels.resolution = VoxelSettings{}.resolution;
  settings_.shadows.visibility = ShadowSettings::Visibility::Bvh;
  EXPECT_NE(before, structureKey());
}

TEST_F(VisibilityReuseKeyTest, SettingsOfTheMasksAloneKeepTheStructureKey) {
  const VisibilityStructureKey before = structureKey();
  const VisibilityReuseKey masksBefore = key();
  settings_.vplsPerLight = 64;
  settings_.multiresolution.coarsestSize = 8;
  settings_.shadows.refinement.threshold = 0.5f;
  EXPECT_EQ(before, structureKey());
  EXPECT_NE(masksBefore, key());
}

// The bounce's sources (the maps, the secondary VPLs and their first leg) do not depend on the
// camera or on the settings of the hierarchy and the gather; the geometry, the shadows and the
// maps' settings change them. (A video light gives no key: VisibilityReuse's GPU tests.)
TEST_F(VisibilityReuseKeyTest, BounceSourcesKeepTheirKeyWhenTheCameraMoves) {
  const std::optional<BounceSourceKey> before = bounceSourceKey(scene_, camera_, 0, settings_);
  ASSERT_TRUE(before.has_value());
  camera_.position.x += 1.0f;
  camera_.size = {64, 48};
  settings_.multiresolution.coarsestSize = 8;
  settings_.indirect.gatherSize = 32;
  settings_.indirect.planeTolerance = 0.2f;
  EXPECT_EQ(before, bounceSourceKey(scene_, camera_, 0, settings_));
}

TEST_F(VisibilityReuseKeyTest, GeometryShadowsAndMapSettingsChangeTheBounceSourceKey) {
  const auto sourceKey = [&](int frame = 0) {
    return bounceSourceKey(scene_, camera_, frame, settings_);
  };
  const std::optional<BounceSourceKey> before = sourceKey();
  EXPECT_NE(before, sourceKey(1));
  scene_.lights[0].quad.corners[2].y += 0.1f;
  EXPECT_NE(before, sourceKey());
  scene_.lights[0].quad.corners[2].y -= 0.1f;
  const RenderSettings initial = settings_;
  const auto expectChanges = [&](auto change, const char* what) {
    settings_ = initial;
    change(settings_);
    EXPECT_NE(before, sourceKey()) << what;
  };
  expectChanges([](RenderSettings& s) { s.shadows.enabled = false; }, "shadows");
  expectChanges([](RenderSettings& s) { s.shadows.visibility = ShadowSettings::Visibility::Bvh; },
                "visibility");
  expectChanges([](RenderSettings& s) { s.shadows.voxels.resolution = 64; }, "voxels");
  expectChanges([](RenderSettings& s) { s.vplsPerLight = 64; }, "VPLs per light");
  expectChanges([](RenderSettings& s) { s.indirect.rsmSize = 32; }, "map size");
  expectChanges([](RenderSettings& s) { s.indirect.vplCount = 256; }, "secondary VPLs");
}

}  // namespace
}  // namespace penumbra
