#pragma once
// Visibility reuse across frames (docs/performance.md, "Visibility reuse"): the visibility masks
// of a hierarchical frame, and the voxel grid or BVH they were traced through, depend only on
// the geometry the frame sees and on the settings that shape the hierarchy, never on the
// lights' radiance. A frame whose key equals the last frame's keeps them instead of tracing
// again, and so renders exactly the picture a fresh renderer would: a video (or any change of
// VPL radiance) alone keeps the key. The voxel grid or BVH alone depends on less: a world grid
// and a BVH do not depend on the camera, so a frame whose camera moved through a still scene
// keeps them and traces its masks through them. The discontinuity pyramid and the refinement of
// a hierarchical frame depend on the same key, with shadows or without, so a frame without
// shadows whose key equals the last one's keeps those. No GL here.

#include <array>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "render/render_settings.h"
#include "scene/scene.h"

namespace penumbra {

// Everything the voxel grid or the BVH depends on: every object's world transform at the frame
// (an animation moves objects and mesh lights), the quad lights' corners (the grid holds the
// lights' quads), the visibility method and the voxel settings, and the camera for a screen grid,
// which follows the frustum.
struct VisibilityStructureKey {
  std::optional<Camera> screenGridCamera;
  std::vector<glm::mat4> objectTransforms;
  std::vector<std::array<glm::vec3, 4>> lightCorners;
  ShadowSettings::Visibility visibility = ShadowSettings::Visibility::Voxels;
  VoxelSettings voxels;
  bool operator==(const VisibilityStructureKey&) const = default;
};

// Everything the masks depend on, compared member by member: the structure they were traced
// through, the camera (with the output size), the VPL count, and the settings of the shadows and
// the hierarchy.
struct VisibilityReuseKey {
  VisibilityStructureKey structure;
  Camera camera;
  int vplsPerLight = 0;
  MultiresolutionSettings multiresolution;
  ShadowSettings shadows;
  bool operator==(const VisibilityReuseKey&) const = default;
};

// The keys of frame `frame` of `scene` seen by `camera` (whose size is the output's).
VisibilityStructureKey visibilityStructureKey(const Scene& scene, const Camera& camera, int frame,
                                              const ShadowSettings& shadows);
VisibilityReuseKey visibilityReuseKey(const Scene& scene, const Camera& camera, int frame,
                                      const RenderSettings& settings);

}  // namespace penumbra
