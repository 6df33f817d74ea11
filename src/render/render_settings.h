#pragma once
// The settings of the GPU renderer's frame (frame.h), apart from the passes, so that what
// depends on them (visibility_reuse.h) need not include the frame.

#include "render/visibility.h"
#include "render/voxelize.h"

namespace penumbra {

enum class RenderMode { Hierarchical, Naive };

// The parameters of the multiresolution gather, in one struct that the CLI and the viewer drive.
// Defaults chosen by measurement: docs/multiresolution.md.
struct MultiresolutionSettings {
  int coarsestSize = 64;          // largest side of the coarsest level, in texels
  float depthThreshold = 4.0f;    // on |grad z| / z times the image's larger side
  float normalThreshold = 0.05f;  // on |N1 - N2| between 4-neighbours
  float planeTolerance = 0.02f;   // upsampling: off-plane distance / distance to the eye
  // On a texel's extent over its distance to the nearest light (docs/multiresolution.md).
  float lightProximityThreshold = 0.125f;
  bool operator==(const MultiresolutionSettings&) const = default;
};

// Area-light shadows: voxel visibility, or exact visibility through a BVH. Defaults chosen by
// measurement: docs/shadows.md.
struct ShadowSettings {
  enum class Visibility { Voxels, Bvh };
  bool enabled = true;
  Visibility visibility = Visibility::Voxels;
  VoxelSettings voxels;
  // Hierarchical mode: before tracing, prove whole quad lights visible from a texel (the
  // clear-light test, light_pyramid.glsl) through the BVH, or through the occupancy pyramid of a
  // world voxel grid without `widen` (every such grid has it: the traversal skips its empty
  // cells). The masks are the same with it or without.
  bool clearLightTest = true;
  VisibilityRefinement refinement{VisibilityRefinement::Measure::XorPopcount, 0.02f};
  bool visibleFraction = false;  // the thesis's shortcut, for comparison
  bool operator==(const ShadowSettings&) const = default;
};

// One-bounce indirect light (docs/indirect.md). Off by default: it is an addition to the
// technique's direct light.
struct IndirectSettings {
  bool enabled = false;
  // Secondary VPLs in all lights' reflective shadow maps together; the hierarchical gather's
  // texels take a quarter each (interleaved, docs/indirect.md).
  int vplCount = 1024;
  int rsmSize = 64;  // texels per side of each of the five faces of a light's map
  // Hierarchical mode: the level the secondary VPLs are gathered at is the finest whose larger
  // side is at most this (the coarsest level when none is).
  int gatherSize = 128;
  // Upsampling trusts a coarse texel this close to a pixel's tangent plane (a fraction of the
  // distance to the eye); looser than the direct light's, as indirect light is smooth.
  float planeTolerance = 0.05f;
};

struct RenderSettings {
  RenderMode mode = RenderMode::Hierarchical;
  int vplsPerLight = 256;  // a square number from 1 to kMaxVplsPerLight
  MultiresolutionSettings multiresolution;
  ShadowSettings shadows;
  IndirectSettings indirect;
  // Keep the last frame's hierarchy (discontinuity pyramid, refinement, the gather's sums of the
  // lights without a video; with shadows the masks and the voxel grid or BVH) while nothing it
  // depends on changed (visibility_reuse.h); off: every frame starts from scratch.
  bool reuseVisibility = true;
};

}  // namespace penumbra
