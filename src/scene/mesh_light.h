#pragma once
// Mesh lights (docs/mesh-lights.md): any object's meshes drawn with an emitting material light
// the scene. Their world-space triangles for a frame, their VPLs (equal-area cells of the surface,
// each with the mean emission of its footprint) and uniform area samples for the reference.

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "scene/area_light.h"
#include "scene/scene.h"

namespace penumbra {

struct EmitterTriangle {
  std::array<glm::vec3, 3> positions{};
  std::array<glm::vec2, 3> uvs{};
  glm::vec3 normal{0.0f};  // unit, on the emitting side: the side the vertex normals face
  float area = 0.0f;
};

struct MeshLightGeometry {
  std::vector<EmitterTriangle> triangles;  // those of zero area left out
  double area = 0.0;
  glm::vec3 boundsMin{0.0f};
  glm::vec3 boundsMax{0.0f};
  glm::vec3 meanNormal{0.0f};  // the area-weighted mean of the normals, unit; 0 for a closed mesh
};

// The light's triangles at `frame`, moved by its object's transform (and animation).
MeshLightGeometry meshLightGeometry(const Scene& scene, const Light& light, int frame);

// `count` VPLs over the surface. The surface is cut into `count` cells of equal area (equal power,
// the radiance scale E being one per light) by recursive halving: the cell's triangles are split
// along the longest axis of their centroids' bounds, the triangle straddling the cut cut in two
// across its longest edge. Each VPL lies on its cell, at the centroid of the cell's piece nearest
// the cell's centroid, with the cell's mean normal, its area, and E times the mean of the texture
// over the cell (16 samples per piece). A two-sided light has count/2 cells, each with a VPL on
// either side (an odd count leaves one VPL of zero area; a single VPL is one-sided).
std::vector<Vpl> makeMeshVpls(const MeshLightGeometry& geometry, glm::vec3 emission,
                              const Image* texture, bool twoSided, int count);

// The power a set of VPLs emits: sum of pi * A_i * L_i (each Lambertian side emits pi A L).
glm::vec3 emittedPower(const std::vector<Vpl>& vpls);

struct SurfaceSample {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f};
  glm::vec2 uv{0.0f};
};

// Uniform samples by area: u in [0,1)^2 picks a triangle by u.x over the cumulative area (so
// stratified u stay stratified over the triangles) and a point in it; the density is 1 / area.
class MeshLightSampler {
 public:
  explicit MeshLightSampler(const MeshLightGeometry& geometry);
  SurfaceSample sample(glm::vec2 u) const;
  float area() const { return static_cast<float>(total_); }

 private:
  const MeshLightGeometry* geometry_ = nullptr;
  std::vector<double> cumulative_;  // area of triangles 0..i inclusive
  double total_ = 0.0;
};

}  // namespace penumbra
