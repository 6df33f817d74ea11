#pragma once
// Which pixels show a light (a quad, or a mesh light's surface): `penumbra compare --mask-emitters`
// leaves them out, since an emitter's own radiance dwarfs the reflected light the renderer modes
// differ in.

#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace penumbra {

// One entry per pixel, row-major with row 0 at the top (as Image): true where the camera ray
// through the pixel's centre (the scene's camera at `size`) first hits a light quad, from either
// side. Geometry is that of `frame`.
std::vector<bool> emitterMask(const Scene& scene, glm::ivec2 size, int frame);

}  // namespace penumbra
