#version 450 core
#extension GL_GOOGLE_include_directive : require
// Builds pyramid level l from level l-1 over each texel's 2x2 children (fewer at the border of
// sizes that are not powers of two), for l >= 2 (discontinuity.comp builds level 1 from the
// G-buffer): the maximum of the discontinuity values, and the G-buffer averaged over the
// children's surface pixels (the shadow rays' lift like the position, the face normal like the
// normal), which a texel that traces its shadow rays starts them from. A frame without shadows
// leaves those two out: they are a third of the pass's reads and writes.
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

// Level l-1, whose normal w is the fraction of the footprint covered by lit surface.
layout(binding = 0) uniform sampler2D finerPositionDepth;
layout(binding = 1) uniform sampler2D finerNormal;
layout(binding = 2) uniform sampler2D finerSpecular;
layout(binding = 3) uniform sampler2D finerDiscontinuity;
layout(binding = 4) uniform sampler2D finerShadowLift;
layout(binding = 5) uniform sampler2D finerFaceNormal;
uniform bool shadowRayEnds;

layout(rgba32f, binding = 0) uniform writeonly image2D positionDepthOut;
layout(rgba32f, binding = 1) uniform writeonly image2D normalOut;
layout(rgba32f, binding = 2) uniform writeonly image2D specularOut;
layout(rgba32f, binding = 3) uniform writeonly image2D discontinuityOut;
layout(rgba32f, binding = 4) uniform writeonly image2D shadowLiftOut;
layout(rgba32f, binding = 5) uniform writeonly image2D faceNormalOut;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(discontinuityOut)))) return;
  ivec2 finerSize = textureSize(finerDiscontinuity, 0);
  vec4 discontinuity = vec4(0.0);
  vec4 positionDepth = vec4(0.0);
  vec3 normal = vec3(0.0);
  vec4 specular = vec4(0.0);
  vec4 shadowLift = vec4(0.0);
  vec3 faceNormal = vec3(0.0);
  float coverage = 0.0;
  int children = 0;
  for (int dy = 0; dy < 2; ++dy) {
    for (int dx = 0; dx < 2; ++dx) {
      ivec2 child = 2 * texel + ivec2(dx, dy);
      if (any(greaterThanEqual(child, finerSize))) continue;
      ++children;
      discontinuity = max(discontinuity, texelFetch(finerDiscontinuity, child, 0));
      vec4 childNormal = texelFetch(finerNormal, child, 0);
      float weight = childNormal.w;
      if (weight == 0.0) continue;
      coverage += weight;
      positionDepth += weight * texelFetch(finerPositionDepth, child, 0);
      normal += weight * childNormal.xyz;
      specular += weight * texelFetch(finerSpecular, child, 0);
      if (shadowRayEnds) {
        shadowLift += weight * texelFetch(finerShadowLift, child, 0);
        faceNormal += weight * texelFetch(finerFaceNormal, child, 0).xyz;
      }
    }
  }
  if (coverage > 0.0) {
    positionDepth /= coverage;
    specular /= coverage;
    shadowLift /= coverage;
    normal = length(normal) > 0.0 ? normalize(normal) : vec3(0.0);
    faceNormal = length(faceNormal) > 0.0 ? normalize(faceNormal) : vec3(0.0);
  }
  imageStore(positionDepthOut, texel, positionDepth);
  imageStore(normalOut, texel, vec4(normal, coverage / float(max(children, 1))));
  imageStore(specularOut, texel, specular);
  imageStore(discontinuityOut, texel, discontinuity);
  if (shadowRayEnds) {
    imageStore(shadowLiftOut, texel, shadowLift);
    imageStore(faceNormalOut, texel, vec4(faceNormal, 0.0));
  }
}
