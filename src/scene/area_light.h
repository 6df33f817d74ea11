#pragma once
// Quad area lights: geometry, texture coordinates and virtual point lights, on the CPU.
// The GPU VPL pass (shaders/vpls.comp) computes the same VPLs; tests hold them equal.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "image/image.h"

namespace penumbra {

struct QuadLight {
  std::array<glm::vec3, 4> corners{};  // pos1..pos4
  glm::vec3 normal{0.0f};              // unit, on the emitting side
  float area = 0.0f;

  // Bilinear map from texture coordinates: u from edge pos1-pos4 to edge pos2-pos3,
  // v from edge pos1-pos2 to edge pos4-pos3.
  glm::vec3 pointAt(glm::vec2 uv) const;
  // Inverse of pointAt for a point on the quad's plane; nullopt outside the quad.
  std::optional<glm::vec2> uvAt(glm::vec3 point) const;
};

// Builds the light, with the normal flipped towards `emittingSidePoint` when given.
// Returns the problem (zero area, corners not coplanar, non-convex order) as text in `problem`
// and nullopt when the corners do not make a valid light.
std::optional<QuadLight> makeQuadLight(const std::array<glm::vec3, 4>& corners,
                                       const std::optional<glm::vec3>& emittingSidePoint,
                                       std::string& problem);

struct Vpl {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f};
  glm::vec3 radiance{0.0f};
  float area = 0.0f;
};

// Mean of a piecewise-constant texture over the (u,v) rectangle [u0,u1]x[v0,v1], each texel
// weighted by its overlap; v = 0 is the bottom row of the image.
glm::vec3 textureCellMean(const Image& texture, glm::vec2 uvMin, glm::vec2 uvMax);

// cellsPerSide^2 VPLs, VPL (i,j) at the centre of cell (i,j) of the (u,v) grid, carrying
// emission * the cell's mean texture value (1 without a texture) and area A/N.
std::vector<Vpl> makeVpls(const QuadLight& light, glm::vec3 emission, const Image* texture,
                          int cellsPerSide);

}  // namespace penumbra
