#include "reference/emitter_mask.h"

#include <cstdint>

#include <tbb/parallel_for.h>

#include "reference/ray_scene.h"

namespace penumbra {

std::vector<bool> emitterMask(const Scene& scene, glm::ivec2 size, int frame) {
  const FrameGeometry geometry = buildFrameGeometry(scene, frame);
  const RayScene rays(geometry, scene.lights);
  Camera camera = scene.camera;
  camera.size = size;
  // Bytes, not bools, while threads write: neighbouring std::vector<bool> entries share a word.
  std::vector<std::uint8_t> showsLight(static_cast<std::size_t>(size.x) * size.y, 0);
  tbb::parallel_for(0, size.y, [&](int y) {
    for (int x = 0; x < size.x; ++x) {
      const RayHit hit = traceCameraRay(rays, camera, camera.rayDirection(x, y));
      const bool onMeshLight =
          hit.kind == RayHit::Kind::Surface &&
          scene
              .materials[static_cast<std::size_t>(
                  geometry.triangleMaterial[static_cast<std::size_t>(hit.index)])]
              .emits;
      showsLight[static_cast<std::size_t>(y) * size.x + x] =
          hit.kind == RayHit::Kind::Light || onMeshLight;
    }
  });
  return {showsLight.begin(), showsLight.end()};
}

}  // namespace penumbra
