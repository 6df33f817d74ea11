#pragma once
// The renderer's settings. A default-constructed Settings holds the measured defaults of
// `penumbra render` (docs/multiresolution.md, docs/shadows.md, docs/indirect.md).

namespace penumbra::api {

enum class Mode {
  Hierarchical,  // the multiresolution renderer
  Naive,         // every pixel gathers every VPL: the accuracy target of the hierarchy
};

struct Settings {
  Settings();

  Mode mode;
  int vplsPerLight;  // a square number from 1 to 1024
  // The multiresolution gather (docs/multiresolution.md).
  int coarsestSize;
  float depthThreshold;
  float normalThreshold;
  float planeTolerance;
  float lightProximityThreshold;  // refine where a texel's extent over its light distance exceeds
  // Visibility of the area lights (docs/shadows.md): through the voxel grid, or exact.
  bool shadows;
  bool exactVisibility;       // shadow rays through a BVH of the triangles instead of voxels
  int voxelResolution;        // voxels per axis of the world grid (cubicVoxels: of a cube as full)
  bool cubicVoxels;           // share the voxels out in proportion to the scene's box
  float visibilityThreshold;  // refine where the visible VPLs differ by more than this fraction
  // One bounce of indirect light (docs/indirect.md).
  bool indirect;
  int indirectVpls;
  // Keep the last frame's visibility, refinement and the gather's sums of the lights without a
  // video while camera, geometry, lights' shape and these settings stay the same (a video changes
  // none of them): the same picture, without tracing or gathering again.
  bool reuseVisibility;
};

}  // namespace penumbra::api
