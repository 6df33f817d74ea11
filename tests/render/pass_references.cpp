#include "render/pass_references.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "render/readback.h"
#include "shared.h"

namespace penumbra::test {

std::size_t indexOf(glm::ivec2 texel, glm::ivec2 size) {
  return static_cast<std::size_t>(texel.y) * size.x + texel.x;
}

void expectNearVec4(glm::vec4 found, glm::vec4 expected, const std::string& where,
                    float tolerance) {
  for (int c = 0; c < 4; ++c) {
    EXPECT_NEAR(found[c], expected[c], tolerance * std::max(1.0f, std::abs(expected[c])))
        << where << " component " << c;
  }
}

glm::vec4 referenceDiscontinuity(const Scene& scene, const std::vector<glm::vec4>& positionDepth,
                                 const std::vector<glm::vec4>& normalKind,
                                 const std::vector<glm::vec4>& specular, glm::ivec2 size,
                                 glm::ivec2 pixel) {
  const std::size_t at = indexOf(pixel, size);
  if (static_cast<int>(normalKind[at].w) != gpu::kPixelSurface)
    return {0.0f, 0.0f, 1.0f, 0.0f};
  const float depth = positionDepth[at].w;
  glm::vec2 depthStep(0.0f);
  glm::vec2 extent(1e30f);
  float curvature = 0.0f;
  const glm::ivec2 offsets[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  for (int i = 0; i < 4; ++i) {
    const glm::ivec2 neighbour = pixel + offsets[i];
    if (neighbour.x < 0 || neighbour.y < 0 || neighbour.x >= size.x || neighbour.y >= size.y)
      continue;
    const std::size_t other = indexOf(neighbour, size);
    if (static_cast<int>(normalKind[other].w) != gpu::kPixelSurface)
      continue;
    const float difference = std::abs(positionDepth[other].w - depth);
    float& axis = i < 2 ? depthStep.x : depthStep.y;
    axis = std::max(axis, difference);
    float& axisExtent = i < 2 ? extent.x : extent.y;
    axisExtent = std::min(
        axisExtent, glm::distance(glm::vec3(positionDepth[other]), glm::vec3(positionDepth[at])));
    curvature = std::max(curvature, glm::length(glm::vec3(normalKind[at] - normalKind[other])));
    if (specular[other] != specular[at])
      curvature = 2.0f;
  }
  const float gradient = glm::length(depthStep) / std::max(depth, 1e-6f) *
                         static_cast<float>(std::max(size.x, size.y));
  if (extent.x == 1e30f)
    extent.x = extent.y == 1e30f ? 0.0f : extent.y;
  if (extent.y == 1e30f)
    extent.y = extent.x;
  const float lightDistance = nearestReachingLightDistance(
      scene, glm::vec3(positionDepth[at]), glm::normalize(glm::vec3(normalKind[at])));
  return {gradient, curvature, 0.0f, std::max(extent.x, extent.y) / std::max(lightDistance, 1e-6f)};
}

LevelTexels readReducedLevel(const ReducedGBuffer& reduced, int level) {
  const glm::ivec2 size = reduced.layout().size(level);
  const auto texels = [size](const gl::Texture& texture) {
    return readTexture(texture.id(), size, RowOrder::BottomFirst).pixels;
  };
  LevelTexels read;
  read.size = size;
  read.positionDepth = texels(reduced.positionDepth(level));
  read.normal = texels(reduced.normal(level));
  read.specular = texels(reduced.specular(level));
  read.shadowLift = texels(reduced.shadowLift(level));
  read.faceNormal = texels(reduced.faceNormal(level));
  read.discontinuity = texels(reduced.discontinuity(level));
  return read;
}

LevelTexels readLevel(const ReducedGBuffer& reduced, const RefinementState& refinement,
                      const VisibilityMasks& visibility, int level) {
  LevelTexels read = readReducedLevel(reduced, level);
  read.states = readUintTexture(refinement.state(level).id(), read.size, RowOrder::BottomFirst);
  read.visibilityFlags =
      readUintTexture(visibility.flags(level).id(), read.size, RowOrder::BottomFirst);
  return read;
}

void expectReduction(const LevelTexels& finer, const LevelTexels& coarser, bool finerIsGBuffer,
                     int level, bool shadowRayEnds) {
  for (int y = 0; y < coarser.size.y; ++y) {
    for (int x = 0; x < coarser.size.x; ++x) {
      glm::vec4 discontinuity(0.0f);
      glm::vec4 positionDepth(0.0f);
      glm::vec3 normal(0.0f);
      glm::vec4 specular(0.0f);
      glm::vec4 shadowLift(0.0f);
      glm::vec3 faceNormal(0.0f);
      float coverage = 0.0f;
      int children = 0;
      for (int dy = 0; dy < 2; ++dy) {
        for (int dx = 0; dx < 2; ++dx) {
          const glm::ivec2 child(2 * x + dx, 2 * y + dy);
          if (child.x >= finer.size.x || child.y >= finer.size.y)
            continue;
          ++children;
          const std::size_t at = indexOf(child, finer.size);
          discontinuity = glm::max(discontinuity, finer.discontinuity[at]);
          const float weight =
              finerIsGBuffer
                  ? static_cast<float>(static_cast<int>(finer.normal[at].w) == gpu::kPixelSurface)
                  : finer.normal[at].w;
          if (weight == 0.0f)
            continue;
          coverage += weight;
          positionDepth += weight * finer.positionDepth[at];
          normal += weight * glm::vec3(finer.normal[at]);
          specular += weight * finer.specular[at];
          shadowLift += weight * finer.shadowLift[at];
          faceNormal += weight * glm::vec3(finer.faceNormal[at]);
        }
      }
      if (coverage > 0.0f) {
        positionDepth /= coverage;
        specular /= coverage;
        shadowLift /= coverage;
        normal = glm::length(normal) > 0.0f ? glm::normalize(normal) : glm::vec3(0.0f);
        faceNormal = glm::length(faceNormal) > 0.0f ? glm::normalize(faceNormal) : glm::vec3(0.0f);
      }
      const std::size_t at = indexOf({x, y}, coarser.size);
      const std::string where = "level " + std::to_string(level) + " texel " + std::to_string(x) +
                                "," + std::to_string(y);
      // The maximum involves no arithmetic: it must be exact.
      EXPECT_EQ(coarser.discontinuity[at], discontinuity) << where;
      expectNearVec4(coarser.positionDepth[at], positionDepth, where + " position");
      expectNearVec4(coarser.normal[at],
                     glm::vec4(normal, coverage / static_cast<float>(std::max(children, 1))),
                     where + " normal");
      expectNearVec4(coarser.specular[at], specular, where + " specular");
      if (shadowRayEnds) {
        expectNearVec4(coarser.shadowLift[at], shadowLift, where + " shadow lift");
        expectNearVec4(coarser.faceNormal[at], glm::vec4(faceNormal, 0.0f), where + " face normal");
      }
    }
  }
}

namespace {

bool lightCanReach(const QuadLight& quad, glm::vec3 position, glm::vec3 normal) {
  if (glm::dot(position - quad.corners[0], quad.normal) <= 0.0f)
    return false;
  for (const glm::vec3 corner : quad.corners) {
    if (glm::dot(corner - position, normal) > 0.0f)
      return true;
  }
  return false;
}

float distanceToSegment(glm::vec3 position, glm::vec3 from, glm::vec3 to) {
  const glm::vec3 along = to - from;
  const float t = std::clamp(
      glm::dot(position - from, along) / std::max(glm::dot(along, along), 1e-20f), 0.0f, 1.0f);
  return glm::distance(position, from + t * along);
}

float distanceToQuad(const QuadLight& quad, glm::vec3 position) {
  bool inside = true;
  float edgeDistance = 1e30f;
  for (std::size_t c = 0; c < 4; ++c) {
    const glm::vec3 from = quad.corners[c];
    const glm::vec3 to = quad.corners[(c + 1) % 4];
    inside = inside && glm::dot(glm::cross(to - from, position - from), quad.normal) *
                               glm::dot(glm::cross(to - from, quad.corners[(c + 2) % 4] - from),
                                        quad.normal) >=
                           0.0f;
    edgeDistance = std::min(edgeDistance, distanceToSegment(position, from, to));
  }
  return inside ? std::abs(glm::dot(position - quad.corners[0], quad.normal)) : edgeDistance;
}

}  // namespace

bool facesAnyLight(const Scene& scene, glm::vec3 position, glm::vec3 normal) {
  return std::any_of(scene.lights.begin(), scene.lights.end(), [&](const Light& light) {
    return lightCanReach(light.quad, position, normal);
  });
}

float nearestReachingLightDistance(const Scene& scene, glm::vec3 position, glm::vec3 normal) {
  float nearest = 1e30f;
  for (const Light& light : scene.lights) {
    if (lightCanReach(light.quad, position, normal))
      nearest = std::min(nearest, distanceToQuad(light.quad, position));
  }
  return nearest;
}

std::uint32_t referenceState(const Scene& scene, const LevelTexels& texels,
                             const LevelTexels* parent, int level, glm::ivec2 texel,
                             const RefinementThresholds& thresholds) {
  if (parent != nullptr) {
    const std::uint32_t parentState = parent->states[indexOf(texel / 2, parent->size)];
    if (parentState == gpu::kTexelComputed || parentState == gpu::kTexelCovered)
      return gpu::kTexelCovered;
    if (parentState == gpu::kTexelUnlit)
      return gpu::kTexelUnlit;
  }
  const std::size_t at = indexOf(texel, texels.size);
  const glm::vec4 discontinuity = texels.discontinuity[at];
  const bool holdsOtherPixels = discontinuity.b > 0.0f;
  const bool changes =
      discontinuity.r > thresholds.depth || discontinuity.g > thresholds.normal ||
      discontinuity.a * static_cast<float>(1 << level) > thresholds.lightProximity ||
      (texels.visibilityFlags[at] & gpu::kVisibilityChanges) != 0u;
  if (level == 0) {
    if (holdsOtherPixels)
      return gpu::kTexelInvalid;
  } else if (holdsOtherPixels || changes) {
    return gpu::kTexelRefined;
  }
  return facesAnyLight(scene, glm::vec3(texels.positionDepth[at]), glm::vec3(texels.normal[at]))
             ? gpu::kTexelComputed
             : gpu::kTexelUnlit;
}

}  // namespace penumbra::test
