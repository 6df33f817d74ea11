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

// Everything the bounce's sources depend on (Renderer's indirect light: the reflective shadow
// maps, the secondary VPLs sampled from them and the first leg's visibility, which dims them):
// the geometry and the first leg's rays (the structure's key, with whether the frame has
// shadows), the primary VPLs' count and the maps' settings; not the camera, so that a camera
// moving through a still scene keeps them. The lights' radiance is in no key, as in the gather's
// kept sums: only a video changes it between frames, and then there is no key.
struct BounceSourceKey {
  VisibilityStructureKey structure;
  bool shadows = false;
  int vplsPerLight = 0;
  int rsmSize = 0;
  int secondaryVplCount = 0;
  bool operator==(const BounceSourceKey&) const = default;
};

// Whether a light's radiance (its VPLs', its maps' flux) can change between two frames of the same
// key: the keys hold every transform and light corner, so only a video texture's can.
bool radianceVaries(const Scene& scene, const Light& light);

// The keys of frame `frame` of `scene` seen by `camera` (whose size is the output's).
VisibilityStructureKey visibilityStructureKey(const Scene& scene, const Camera& camera, int frame,
                                              const ShadowSettings& shadows);
VisibilityReuseKey visibilityReuseKey(const Scene& scene, const Camera& camera, int frame,
                                      const RenderSettings& settings);
// None when a light's radiance varies (radianceVaries).
std::optional<BounceSourceKey> bounceSourceKey(const Scene& scene, const Camera& camera, int frame,
                                               const RenderSettings& settings);

}  // namespace penumbra
