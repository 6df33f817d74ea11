#version 450 core
#extension GL_GOOGLE_include_directive : require
// Builds pyramid level l from level l-1 for l >= 2 (discontinuity.comp builds level 1 from the
// G-buffer): pyramid_footprint.glsl's reduction over each texel's children. A frame without
// shadows leaves the shadow rays' ends out: they are a third of the pass's reads and writes.
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

#include "pyramid_footprint.glsl"

// Level l-1, whose normal w is the fraction of the footprint covered by lit surface.
layout(binding = 0) uniform sampler2D finerPositionDepth;
layout(binding = 1) uniform sampler2D finerNormal;
layout(binding = 2) uniform sampler2D finerSpecular;
layout(binding = 3) uniform sampler2D finerDiscontinuity;
layout(binding = 4) uniform sampler2D finerShadowLift;
layout(binding = 5) uniform sampler2D finerFaceNormal;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(discontinuityOut)))) return;
  ivec2 finerSize = textureSize(finerDiscontinuity, 0);
  Footprint footprint = emptyFootprint();
  for (int dy = 0; dy < 2; ++dy) {
    for (int dx = 0; dx < 2; ++dx) {
      ivec2 child = 2 * texel + ivec2(dx, dy);
      if (any(greaterThanEqual(child, finerSize))) continue;
      addChild(footprint, texelFetch(finerDiscontinuity, child, 0));
      vec4 childNormal = texelFetch(finerNormal, child, 0);
      if (childNormal.w == 0.0) continue;
      addSurface(footprint, childNormal.w, texelFetch(finerPositionDepth, child, 0),
                 childNormal.xyz, texelFetch(finerSpecular, child, 0));
      if (shadowRayEnds)
        addShadowRayEnds(footprint, childNormal.w, texelFetch(finerShadowLift, child, 0),
                         texelFetch(finerFaceNormal, child, 0).xyz);
    }
  }
  storeFootprint(footprint, texel);
}
