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
    Renderer oneWord(scene, {48, 48});
    oneWord.render(0, settings);
    Renderer batched(scene, {48, 48}, twoWords);
    batched.render(0, settings);
    EXPECT_EQ(batched.readRadiance().pixels, oneWord.readRadiance().pixels) << renderModeName(mode);
  }
}

}  // namespace
}  // namespace penumbra
