#include "render/visibility_reuse.h"

#include "scene/transform.h"

namespace penumbra {

bool radianceVaries(const Scene& scene, const Light& light) {
  return light.texture >= 0 && scene.textures[static_cast<std::size_t>(light.texture)]->animated();
}

VisibilityStructureKey visibilityStructureKey(const Scene& scene, const Camera& camera, int frame,
                                              const ShadowSettings& shadows) {
  VisibilityStructureKey key;
  if (shadows.visibility == ShadowSettings::Visibility::Voxels &&
      shadows.voxels.grid == VoxelSettings::Grid::Screen)
    key.screenGridCamera = camera;
  for (const SceneObject& object : scene.objects)
    key.objectTransforms.push_back(worldFromObject(object.desc, frame));
  for (const Light& light : scene.lights)
    key.lightCorners.push_back(light.quad.corners);
  key.visibility = shadows.visibility;
  key.voxels = shadows.voxels;
  return key;
}

VisibilityReuseKey visibilityReuseKey(const Scene& scene, const Camera& camera, int frame,
                                      const RenderSettings& settings) {
  VisibilityReuseKey key;
  key.structure = visibilityStructureKey(scene, camera, frame, settings.shadows);
  key.camera = camera;
  key.vplsPerLight = settings.vplsPerLight;
  key.multiresolution = settings.multiresolution;
  key.shadows = settings.shadows;
  return key;
}

std::optional<BounceSourceKey> bounceSourceKey(const Scene& scene, const Camera& camera, int frame,
                                               const RenderSettings& settings) {
  for (const Light& light : scene.lights) {
    if (radianceVaries(scene, light))
      return std::nullopt;
  }
  BounceSourceKey key;
  key.structure = visibilityStructureKey(scene, camera, frame, settings.shadows);
  key.shadows = settings.shadows.enabled;
  key.vplsPerLight = settings.vplsPerLight;
  key.rsmSize = settings.indirect.rsmSize;
  key.secondaryVplCount = settings.indirect.vplCount;
  return key;
}

}  // namespace penumbra
