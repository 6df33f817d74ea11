#include "render/visibility_reuse.h"

#include "scene/transform.h"

namespace penumbra {

VisibilityReuseKey visibilityReuseKey(const Scene& scene, const Camera& camera, int frame,
                                      const RenderSettings& settings) {
  VisibilityReuseKey key;
  key.camera = camera;
  for (const SceneObject& object : scene.objects)
    key.objectTransforms.push_back(worldFromObject(object.desc, frame));
  for (const Light& light : scene.lights)
    key.lightCorners.push_back(light.quad.corners);
  key.vplsPerLight = settings.vplsPerLight;
  key.multiresolution = settings.multiresolution;
  key.shadows = settings.shadows;
  return key;
}

}  // namespace penumbra
