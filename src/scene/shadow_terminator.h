#pragma once
// Where a shadow ray of a smooth-normal triangle starts (Hanika 2021, "Hacking the shadow
// terminator"): on the curved surface the corners' normals describe, not on the flat triangle.
// Plain maths, no Embree or GL: the reference uses it, and the tests check the G-buffer's port
// (shaders/gbuffer_surface.frag) against it.

#include <algorithm>
#include <array>
#include <cstddef>

#include <glm/glm.hpp>

namespace penumbra {

// Hanika's shading point: the barycentric blend of the point's projections onto the tangent
// planes of the triangle's corners, each projection only where the point lies below that plane
// (convex there), so that flat and concave parts stay where they are. `side` is -1 where the
// surface is seen from behind its normals.
inline glm::vec3 liftedOntoNormals(glm::vec3 position, const std::array<glm::vec3, 3>& corners,
                                   const std::array<glm::vec3, 3>& cornerNormals, glm::vec3 weights,
                                   float side) {
  glm::vec3 lifted = position;
  for (std::size_t corner = 0; corner < 3; ++corner) {
    const glm::vec3 normal = cornerNormals[corner];
    const float length = glm::length(normal);
    if (!(length > 0.0f)) {
      continue;
    }
    const glm::vec3 unit = side * normal / length;
    const float height = glm::dot(position - corners[corner], unit);
    lifted -= weights[static_cast<glm::length_t>(corner)] * std::min(0.0f, height) * unit;
  }
  return lifted;
}

}  // namespace penumbra
