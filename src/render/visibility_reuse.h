#pragma once
// Visibility reuse across frames (docs/performance.md, "Visibility reuse"): the visibility masks
// of a hierarchical frame, and the voxel grid or BVH they were traced through, depend only on
// the geometry the frame sees and on the settings that shape the hierarchy, never on the
// lights' radiance. A frame whose key equals the last frame's keeps them instead of tracing
// again, and so renders exactly the picture a fresh renderer would: a video (or any change of
// VPL radiance) alone keeps the key. No GL here.

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "render/render_settings.h"
#include "scene/scene.h"

namespace penumbra {

// Everything the masks depend on, compared member by member: the camera (with the output size),
// every object's world transform at the frame (an animation moves objects and mesh lights), the
// quad lights' corners, the VPL count, and the settings of the shadows and the hierarchy.
struct VisibilityReuseKey {
  Camera camera;
  std::vector<glm::mat4> objectTransforms;
  std::vector<std::array<glm::vec3, 4>> lightCorners;
  int vplsPerLight = 0;
  MultiresolutionSettings multiresolution;
  ShadowSettings shadows;
  bool operator==(const VisibilityReuseKey&) const = default;
};

// The key of frame `frame` of `scene` seen by `camera` (whose size is the output's).
VisibilityReuseKey visibilityReuseKey(const Scene& scene, const Camera& camera, int frame,
                                      const RenderSettings& settings);

}  // namespace penumbra
