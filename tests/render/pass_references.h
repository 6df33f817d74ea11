#pragma once
// C++ references of the hierarchical passes' shaders, following their definitions, and the
// read-back of a level's inputs and outputs in GL's texel order (row 0 at the bottom), as the
// shaders index them. Used by the pass tests (passes_test.cpp) and the whole-frame kernel test
// (hierarchy_test.cpp).

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "render/discontinuity.h"
#include "render/refinement.h"
#include "render/visibility.h"
#include "scene/scene.h"

namespace penumbra::test {

// Tolerance (relative, absolute below 1) for values the GPU computes with square roots and
// divisions in float, as the C++ code does: llvmpipe matches it bit for bit, but GLSL allows
// divisions and square roots a few units in the last place of error and lets drivers fuse or
// reorder operations. 1e-5 is about 80 units in the last place: far below any difference a wrong
// formula would make.
constexpr float kFloatTolerance = 1e-5f;

std::size_t indexOf(glm::ivec2 texel, glm::ivec2 size);
// Each component within `tolerance`, relative (absolute below 1).
void expectNearVec4(glm::vec4 found, glm::vec4 expected, const std::string& where,
                    float tolerance = kFloatTolerance);

// A level's inputs and outputs, in GL order.
struct LevelTexels {
  glm::ivec2 size{0};
  std::vector<glm::vec4> positionDepth;
  std::vector<glm::vec4> normal;
  std::vector<glm::vec4> specular;
  std::vector<glm::vec4> shadowLift;
  std::vector<glm::vec4> faceNormal;
  std::vector<glm::vec4> discontinuity;
  std::vector<std::uint32_t> states;
  std::vector<std::uint32_t> visibilityFlags;
};

// The reduced G-buffer's textures of a level (states and flags left empty).
LevelTexels readReducedLevel(const ReducedGBuffer& reduced, int level);
LevelTexels readLevel(const ReducedGBuffer& reduced, const RefinementState& refinement,
                      const VisibilityMasks& visibility, int level);

// discontinuity.comp, per pixel (the scene's quad lights for the light proximity).
glm::vec4 referenceDiscontinuity(const Scene& scene, const std::vector<glm::vec4>& positionDepth,
                                 const std::vector<glm::vec4>& normalKind,
                                 const std::vector<glm::vec4>& specular, glm::ivec2 size,
                                 glm::ivec2 pixel);
// pyramid_reduce.comp: expects level `coarser` computed from the GPU's finer level; the shadow
// rays' ends (lift, face normal) only when the frame averaged them (one with shadows).
void expectReduction(const LevelTexels& finer, const LevelTexels& coarser, bool finerIsGBuffer,
                     int level, bool shadowRayEnds);
// light_facing.glsl, for quad lights.
bool facesAnyLight(const Scene& scene, glm::vec3 position, glm::vec3 normal);
// 1e30 when no light can reach the point.
float nearestReachingLightDistance(const Scene& scene, glm::vec3 position, glm::vec3 normal);
// refine_classify.comp, with the GPU's own inputs of the level and its parent's states.
std::uint32_t referenceState(const Scene& scene, const LevelTexels& texels,
                             const LevelTexels* parent, int level, glm::ivec2 texel,
                             const RefinementThresholds& thresholds);

}  // namespace penumbra::test
