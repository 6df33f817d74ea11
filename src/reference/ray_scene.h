#pragma once
// The Embree scene of one frame, for the reference renderer and the emitter mask: the scene's
// triangles and the light quads (two triangles each, pos1 pos2 pos3 and pos1 pos3 pos4), with
// first-hit and occlusion queries. Internal to penumbra_reference (it includes Embree).

#include <cstdint>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace penumbra {

struct RayHit {
  enum class Kind { Nothing, Surface, Light };
  Kind kind = Kind::Nothing;
  float distance = 0.0f;
  int index = -1;               // Surface: triangle of the FrameGeometry; Light: index into lights
  int lightTriangle = 0;        // Light: 0 for pos1 pos2 pos3, 1 for pos1 pos3 pos4
  glm::vec2 barycentric{0.0f};  // weights of the triangle's second and third vertex
};

class RayScene {
 public:
  RayScene(const FrameGeometry& geometry, const std::vector<Light>& lights);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // First hit along origin + t * direction for t in [tNear, tFar].
  RayHit intersect(glm::vec3 origin, glm::vec3 direction, float tNear, float tFar) const;
  // Whether anything (a surface or a light quad) lies along origin + t * direction, t in [0, tFar].
  bool occluded(glm::vec3 origin, glm::vec3 direction, float tFar) const;

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  unsigned surfaceGeometry_ = RTC_INVALID_GEOMETRY_ID;
  unsigned lightGeometry_ = RTC_INVALID_GEOMETRY_ID;
};

// The camera ray along `direction` (a Camera::rayDirection), clipped to the near and far planes
// as the rasterising modes clip it: planes perpendicular to the viewing direction.
RayHit traceCameraRay(const RayScene& rays, const Camera& camera, glm::vec3 direction);

}  // namespace penumbra
