#version 450 core
#extension GL_GOOGLE_include_directive : require
// The indirect light's gather level, filtered before the upsampling when its texels took
// interleaved subsets of the secondary VPLs (secondary_gather.glsl): each texel takes the 3x3
// tent (1 2 1 by 1 2 1) over its neighbours, weighted by how well they agree with its surface.
// On a plane the tent gives each of the four subsets a quarter of the weight, wherever the
// texel lies in its 2x2 block, so the block's pattern cancels; the upsampling's bilinear blend
// alone left it showing (docs/indirect.md). Texels across an edge barely count, as in the
// upsampling.
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D levelPositionDepth;
layout(binding = 1) uniform sampler2D levelNormal;
layout(binding = 2) uniform sampler2D gathered;  // rgb irradiance, w 1 where a surface
layout(rgba32f, binding = 0) uniform writeonly image2D filtered;

// Width of the agreement test, as a fraction of the texel's distance to the eye.
uniform float planeTolerance;

#include "level_agreement.glsl"

// How alike two texels' irradiance is: near 1 for the differences between subsets on one
// surface, near 0 across a shadow boundary of the bounce (one side lit, the other dark), which the
// surfaces' agreement alone does not see where a wall stands on a floor.
const float kSimilarityWidth = 0.5;
float similarity(vec3 a, vec3 b) {
  float sumA = a.r + a.g + a.b;
  float sumB = b.r + b.g + b.b;
  float relative = abs(sumA - sumB) / max(kSimilarityWidth * (sumA + sumB), 1e-30);
  return exp(-relative * relative);
}

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(filtered);
  if (any(greaterThanEqual(texel, size))) return;
  vec4 own = texelFetch(gathered, texel, 0);
  if (own.w == 0.0) {
    imageStore(filtered, texel, own);
    return;
  }
  vec4 positionDepth = texelFetch(levelPositionDepth, texel, 0);
  vec3 normal = normalize(texelFetch(levelNormal, texel, 0).xyz);
  vec3 sum = vec3(0.0);
  float weightSum = 0.0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 neighbour = texel + ivec2(dx, dy);
      if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, size))) continue;
      vec4 irradiance = texelFetch(gathered, neighbour, 0);
      if (irradiance.w == 0.0) continue;
      float weight = float((2 - abs(dx)) * (2 - abs(dy))) *
                     agreement(positionDepth.xyz, normal, positionDepth.w, levelPositionDepth,
                               levelNormal, neighbour) *
                     similarity(own.rgb, irradiance.rgb);
      sum += weight * irradiance.rgb;
      weightSum += weight;
    }
  }
  // The texel itself agrees fully, so weightSum is at least its tent weight of 4.
  imageStore(filtered, texel, vec4(sum / weightSum, 1.0));
}
