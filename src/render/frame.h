#pragma once
// The frame function: the passes of one frame in order, for every GPU renderer mode.
//
//   hierarchical: scene upload, VPLs, G-buffer, voxelization, discontinuity pyramid, then level
//                 by level from the coarsest: bitmask visibility and refinement; the
//                 multiresolution gather, upsample and combine;
//   naive:        scene upload, VPLs, G-buffer, voxelization, per-pixel gather with a shadow
//                 ray per pixel and VPL;
//   indirect:     (either mode, when on) reflective shadow maps, secondary VPLs, and their
//                 gather, added to the direct light (docs/indirect.md).

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gl/handles.h"
#include "image/image.h"
#include "render/bvh_gpu.h"
#include "render/device_profile.h"
#include "render/discontinuity.h"
#include "render/gather_hierarchical.h"
#include "render/gather_indirect.h"
#include "render/gather_naive.h"
#include "render/gbuffer.h"
#include "render/levels.h"
#include "render/readback.h"
#include "render/refinement.h"
#include "render/render_error.h"
#include "render/render_settings.h"
#include "render/rsm.h"
#include "render/scene_gpu.h"
#include "render/secondary_visibility.h"
#include "render/shadow_rays.h"
#include "render/timing.h"
#include "render/upsample.h"
#include "render/visibility.h"
#include "render/visibility_reuse.h"
#include "render/voxelize.h"
#include "render/vpls.h"
#include "scene/scene.h"

namespace penumbra {

const char* renderModeName(RenderMode mode);

// Throws RenderError when the VPL count is not a square in [1, kMaxVplsPerLight].
int cellsPerSideFor(int vplsPerLight);
// Throws RenderError for parameters out of range.
void validate(const RenderSettings& settings);

struct LevelStatistics {
  glm::ivec2 size{0};
  unsigned samples = 0;           // texels gathered at this level
  unsigned visibilityMasked = 0;  // texels that hold a visibility mask of their own here
  unsigned visibilityTraced = 0;  // those that traced (some of) it in this frame
  std::uint64_t shadowRays = 0;   // shadow rays they traced
  // Texels that traced no ray because every light passed the clear-light test (not counted in
  // visibilityTraced).
  unsigned visibilityClear = 0;
};

struct FrameStatistics {
  std::vector<LevelStatistics> levels;  // empty in naive mode
  unsigned fullResolutionSamples = 0;   // lit-surface pixels: what the naive gather computes
  int vplCount = 0;                     // VPLs of all lights; 0 without shadows
  // Bytes of scene data (geometry, textures, light list) the frame uploaded (SceneGpu): 0 for a
  // static scene after its first frame.
  std::uint64_t sceneUploadBytes = 0;
  std::size_t visibilityBytes = 0;  // GPU memory of the voxel grid or the BVH; 0 without shadows
  // The frame kept the last frame's hierarchy: the discontinuity pyramid, the refinement and,
  // with shadows, the masks and the voxel grid or BVH (visibility_reuse.h).
  bool visibilityReused = false;
  // The frame kept the last frame's voxel grid or BVH (with its masks, or with a moved camera).
  bool visibilityStructureKept = false;
  // VPLs whose sums the gather kept from the last frame instead of gathering them: the lights
  // without a video, in a frame that reused the hierarchy (Renderer::render).
  int vplsKept = 0;
  // With indirect light: the frame kept the last frame's reflective shadow maps, secondary VPLs
  // and their first leg's visibility (BounceSourceKey, visibility_reuse.h).
  bool bounceSourcesKept = false;
  std::uint64_t shadowRays() const;
  unsigned samplesGathered() const;
  unsigned visibilityMasked() const;
  unsigned visibilityTraced() const;
  unsigned visibilityClear() const;
};

// What the hierarchical passes write, each part owned by its one writer (the upsampling
// completes the gathered levels), all laid out by one LevelLayout.
struct HierarchyTargets {
  HierarchyTargets(const GBuffer& gbuffer, int coarsestSize);
  LevelLayout layout;
  ReducedGBuffer reduced;      // DiscontinuityPass
  RefinementState refinement;  // RefinementPass
  VisibilityMasks visibility;  // VisibilityPass; flags cleared in frames without shadows
  GatheredLevels gathered;     // HierarchicalGatherPass, then UpsamplePass
  // HierarchicalGatherPass: in a scene with both video lights and others, the other lights' sums
  // alone, which frames that reuse the hierarchy keep (made by the first frame that needs them).
  std::unique_ptr<GatheredLevels> steadySums;
};

class Renderer {
 public:
  // Throws RenderError when `size` exceeds the GL implementation's limits. `profile`: the
  // context's (deviceProfileFor), or the portable one that works everywhere.
  Renderer(Scene& scene, glm::ivec2 size, const DeviceProfile& profile = DeviceProfile::portable());

  // Renders frame `frame` into radiance(): the animation at time frame/30 s, and the video
  // textures at `videoSeconds`, by default the same time, so that a frame's picture is
  // deterministic. The viewer passes its wall clock instead, so that videos play in real time.
  // A hierarchical frame whose VisibilityReuseKey equals the last frame's keeps that frame's
  // hierarchy (unless settings.reuseVisibility is off): its discontinuity pyramid, refinement and,
  // with shadows, visibility, and the gather's sums of the lights without a video, so it gathers
  // only the video lights' VPLs; the same picture as a fresh renderer's, without voxelizing or
  // tracing. A frame with shadows whose VisibilityStructureKey equals the last one's keeps the
  // voxel grid or BVH (a camera move through a still scene) and traces through it.
  void render(int frame, const RenderSettings& settings,
              std::optional<double> videoSeconds = std::nullopt);
  // Linear radiance of the last frame, read back (row 0 at the top).
  Image readRadiance() const;

  // Counts of the last hierarchical frame (reads GPU counters and the G-buffer back).
  FrameStatistics statistics() const;
  // Stage times of the last frame, in order.
  const std::vector<StageTime>& stageTimes() const { return stageTimes_; }
  TimingMethod timingMethod() const { return timer_.method(); }
  const DeviceProfile& deviceProfile() const { return profile_; }

  const Camera& camera() const { return camera_; }
  // Moves the camera for the next frame; its size stays the renderer's.
  void setCamera(const Camera& camera);
  const GBuffer& gbuffer() const { return gbuffer_; }
  // The level resources of the last hierarchical frame; nullptr before one.
  const HierarchyTargets* hierarchy() const { return hierarchy_.get(); }
  // The gathered levels of the last hierarchical frame, level 0 complete (only where
  // canCompleteGatheredLevels). A frame writes level 0's radiance but leaves its interpolated and
  // unlit texels out of its results, which nothing in the frame reads; the first call after a
  // hierarchical frame stores them, for the debug views that show them.
  const GatheredLevels& completedGatheredLevels() const;
  // Whether completedGatheredLevels can: the last frame was hierarchical, or its level 0 was
  // completed before a naive frame replaced the G-buffer it is interpolated on.
  bool canCompleteGatheredLevels() const {
    return hierarchy_ && (lastMode_ == RenderMode::Hierarchical || fullResolutionCompleted_);
  }
  // The voxel grid of the last frame with voxel shadows.
  const VoxelGrid& voxelGrid() const { return voxelGrid_; }
  // The hierarchy of the last frame with exact (BVH) shadows; empty before one.
  const BvhGpu& bvh() const { return bvh_; }
  // The visibility masks of the last frame when it was hierarchical with shadows, else nullptr.
  const VisibilityMasks* visibilityMasks() const {
    return lastMode_ == RenderMode::Hierarchical && lastShadows_ && hierarchy_
               ? &hierarchy_->visibility
               : nullptr;
  }
  const gl::Texture& radiance() const { return radiance_; }
  // The indirect light alone (albedo/pi times the secondary VPLs' irradiance; w 1 where gathered
  // exactly) of the last frame, zero when it had none.
  const gl::Texture& indirect() const { return indirect_; }
  // The secondary VPLs of the last frame with indirect light, read back (empty before one).
  std::vector<gpu::GpuVpl> secondaryVpls() const { return readVpls(secondaryVpls_); }
  // The reflective shadow maps of the last frame with indirect light; nullptr before one.
  const ReflectiveShadowMap* reflectiveShadowMap() const { return rsm_.get(); }

 private:
  DeviceProfile profile_;
  Camera camera_;
  SceneGpu sceneGpu_;
  GBuffer gbuffer_;
  VplBuffer vpls_;
  gl::Texture radiance_{GL_TEXTURE_2D};
  std::unique_ptr<HierarchyTargets> hierarchy_;
  VoxelGrid voxelGrid_;
  BvhGpu bvh_;
  GBufferPass gbufferPass_;
  // Without shadows nothing reads where shadow rays start, and writing it took two fifths of the
  // G-buffer's time on the dragon (docs/performance.md).
  GBufferPass unshadowedGBufferPass_{GBufferPass::ShadowRayStarts::skipped};
  VoxelizePass voxelizePass_;
  VisibilityPass visibilityPass_;
  VplPass vplPass_;
  NaiveGatherPass naiveGather_;
  DiscontinuityPass discontinuityPass_;
  RefinementPass refinementPass_;
  HierarchicalGatherPass hierarchicalGather_;
  UpsamplePass upsamplePass_;
  std::unique_ptr<ReflectiveShadowMap> rsm_;
  RsmPass rsmPass_;
  VplBuffer secondaryVpls_;
  SecondaryVisibilityPass secondaryVisibility_;
  IndirectGatherPass indirectGather_;
  gl::Texture indirect_{GL_TEXTURE_2D};
  StageTimer timer_;
  std::vector<StageTime> stageTimes_;
  RenderMode lastMode_ = RenderMode::Hierarchical;
  bool lastShadows_ = false;
  bool lastBvh_ = false;
  bool visibilityReused_ = false;  // by the last frame
  // The upsampling inputs of the last hierarchical frame, and whether completedGatheredLevels has
  // completed its level 0 since.
  float lastPlaneTolerance_ = 0.0f;
  mutable bool fullResolutionCompleted_ = false;
  // The key of the hierarchy's state (reduced G-buffer, refinement, masks with shadows) held in
  // hierarchy_, while it is valid; none after a naive frame or one that failed on the way.
  std::optional<VisibilityReuseKey> maskKey_;
  bool structureKept_ = false;  // the last frame kept the voxel grid or BVH of the one before
  // The last frame left the sums of its lights without a video in hierarchy_ (in steadySums, or
  // in gathered when no light has a video), at the texels of the work lists of maskKey_.
  bool steadySumsKept_ = false;
  int vplsKept_ = 0;  // by the last frame's gather
  // The key of the voxel grid or BVH the last frame with shadows left, while it is valid (as
  // maskKey_).
  std::optional<VisibilityStructureKey> structureKey_;
  // The key of the bounce's sources (rsm_, secondaryVpls_) while they are valid, and whether the
  // last frame kept them.
  std::optional<BounceSourceKey> bounceSourceKey_;
  bool bounceSourcesKept_ = false;

  HierarchyTargets& hierarchyFor(int coarsestSize);
  // The hierarchical gather of every level into levels.gathered; `steadySumsValid`: the sums
  // steadySumsKept_ describes are this frame's.
  void gatherHierarchy(const RenderSettings& settings, HierarchyTargets& levels,
                       bool steadySumsValid);
  void checkShadowedVplCount(bool shadows) const;
  // The indirect light of frame `frame`, with the bounce's sources kept from the last frame when
  // their BounceSourceKey is the same (settings.reuseVisibility); `rays` answer the direct
  // light's shadow rays (null without shadows).
  void renderIndirect(int frame, const RenderSettings& settings, const ShadowRays* rays);
  // The reflective shadow maps, the secondary VPLs, and their first leg's visibility through
  // `rays` (null: unshadowed).
  void renderBounceSources(const IndirectSettings& indirect, const ShadowRays* rays);
};

}  // namespace penumbra
