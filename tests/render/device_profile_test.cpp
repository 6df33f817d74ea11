// The device profile (render/device_profile.h): chosen from the context's strings, and the
// dispatch batching it sets changes no image.

#include "render/device_profile.h"

#include <gtest/gtest.h>

#include "render/frame.h"
#include "scene/scene.h"
#include "scene/scene_desc.h"
#include "shared.h"
#include "test_files.h"

namespace penumbra {
namespace {

gl::ContextInfo contextWith(const std::string& renderer, bool timerQueries) {
  gl::ContextInfo info;
  info.vendor = "a vendor";
  info.renderer = renderer;
  info.timerQueries = timerQueries;
  return info;
}

TEST(DeviceProfile, LlvmpipeTimesWithTheCpuClockAndBatchesItsRays) {
  // Even where its timer queries passed the context's check (they do under GLX).
  const DeviceProfile profile =
      deviceProfileFor(contextWith("llvmpipe (LLVM 15.0.6, 256 bits)", true));
  EXPECT_TRUE(profile.software);
  EXPECT_EQ(profile.timing, TimingMethod::CpuAfterFinish);
  EXPECT_EQ(profile.shadowRaysPerDispatch, gpu::kShadowRaysPerDispatch);
  EXPECT_EQ(profile.secondaryVplSampling, SecondaryVplSampling::Cpu);
}

TEST(DeviceProfile, GpuUsesTimerQueriesWhereTheyWorkAndOneDispatch) {
  const DeviceProfile gpu = deviceProfileFor(contextWith("NVIDIA H200/PCIe/SSE2", true));
  EXPECT_FALSE(gpu.software);
  EXPECT_EQ(gpu.timing, TimingMethod::GpuTimerQueries);
  EXPECT_EQ(gpu.shadowRaysPerDispatch, gpu::kMaxShadowedVpls);
  const DeviceProfile noTimers = deviceProfileFor(contextWith("NVIDIA H200/PCIe/SSE2", false));
  EXPECT_EQ(noTimers.timing, TimingMethod::CpuAfterFinish);
  EXPECT_NE(describe(gpu).find("gl-timer-queries"), std::string::npos) << describe(gpu);
}

// Renders a 48x48 frame of `scene` with the portable profile and with `other`, and expects the
// same pixels.
void expectTheSameImage(Scene& scene, const RenderSettings& settings, const DeviceProfile& other,
                        const std::string& what) {
  Renderer portable(scene, {48, 48});
  portable.render(0, settings);
  Renderer changed(scene, {48, 48}, other);
  changed.render(0, settings);
  EXPECT_EQ(changed.readRadiance().pixels, portable.readRadiance().pixels) << what;
}

// Every pass that batches its shadow rays (naive gather, visibility trace, secondary
// visibility) gives the same image with two words per dispatch as with one: each invocation
// still sums its VPLs in order. Small enough for llvmpipe's loop limit at 64 rays: a 16^3 grid.
TEST(DeviceProfile, BatchingChangesNoImage) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes/cornell_bunny.scene"));
  RenderSettings settings;
  settings.vplsPerLight = 64;
  settings.multiresolution.coarsestSize = 8;
  settings.shadows.voxels.resolution = 16;
  settings.indirect.enabled = true;
  settings.indirect.vplCount = 16;
  settings.indirect.rsmSize = 16;
  DeviceProfile twoWords = DeviceProfile::portable();
  twoWords.shadowRaysPerDispatch = 2 * 32;
  for (const RenderMode mode : {RenderMode::Naive, RenderMode::Hierarchical}) {
    settings.mode = mode;
    expectTheSameImage(scene, settings, twoWords, renderModeName(mode));
  }
}

// The gathers read the VPLs from a uniform block where they fit in one and from the storage buffer
// otherwise (gather_vpls.glsl); the images are the same, bit for bit, with shadows and without,
// since each invocation sums the same VPLs in the same order either way.
TEST(DeviceProfile, VplsFromTheStorageBufferChangeNoImage) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes/shadow_box.scene"));
  RenderSettings settings;
  settings.vplsPerLight = 64;
  settings.multiresolution.coarsestSize = 8;
  DeviceProfile storageBuffer = DeviceProfile::portable();
  storageBuffer.gatherVpls = GatherVplSource::StorageBuffer;
  for (const bool shadows : {false, true}) {
    settings.shadows.enabled = shadows;
    for (const RenderMode mode : {RenderMode::Naive, RenderMode::Hierarchical}) {
      settings.mode = mode;
      expectTheSameImage(
          scene, settings, storageBuffer,
          std::string(renderModeName(mode)) + (shadows ? " with" : " without") + " shadows");
    }
  }
}

// More VPLs than the block holds go through the storage buffer; llvmpipe takes uniform blocks of
// 64 KiB, more than the block's 48.
TEST(DeviceProfile, VplsBeyondTheUniformBlockComeFromTheStorageBuffer) {
  EXPECT_EQ(gatherVplSource(gpu::kVplsInUniformBlock, GatherVplSource::UniformBlock),
            GatherVplSource::UniformBlock);
  EXPECT_EQ(gatherVplSource(gpu::kVplsInUniformBlock + 1, GatherVplSource::UniformBlock),
            GatherVplSource::StorageBuffer);
  EXPECT_EQ(gatherVplSource(1, GatherVplSource::StorageBuffer), GatherVplSource::StorageBuffer);
  EXPECT_EQ(gatherVplSourceOnThisContext(GatherVplSource::UniformBlock),
            GatherVplSource::UniformBlock);
  EXPECT_EQ(gatherVplSourceOnThisContext(GatherVplSource::StorageBuffer),
            GatherVplSource::StorageBuffer);
}

}  // namespace
}  // namespace penumbra
