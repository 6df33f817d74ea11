#version 450 core
#extension GL_GOOGLE_include_directive : require
// Level 0 of the discontinuity pyramid, per pixel:
//  r: relative depth gradient |grad z| / z, per pixel, times the image's larger side, so that a
//     plane gives the same value at every resolution;
//  g: normal curvature max |N - N_q| = 2 sin(angle/2) over the 4-neighbourhood, forced to 2
//     where the specular material changes (the gather shares k_s and n across a texel);
//  b: 1 when the pixel is not a lit surface (background or light), which forces refinement of
//     every coarser texel whose footprint holds it;
//  a: light proximity, the pixel's extent on its surface (the distance to its nearer neighbour
//     along each axis, the larger of the two axes) over its distance to the nearest light that
//     can reach it (0 when none can). A light's irradiance bends on the scale of the distance to
//     it, so a texel of 2^l pixels whose extent is a sizeable part of that distance cannot stand
//     for its pixels by interpolation.
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = kLightBinding) readonly buffer Lights { GpuLight lights[]; };

#include "light_facing.glsl"

layout(binding = 0) uniform sampler2D gPositionDepth;
layout(binding = 1) uniform sampler2D gNormalKind;
layout(binding = 2) uniform sampler2D gSpecular;
layout(rgba32f, binding = 0) uniform writeonly image2D discontinuityOut;

uniform int lightCount;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(discontinuityOut);
  if (any(greaterThanEqual(pixel, size))) return;
  vec4 normalKind = texelFetch(gNormalKind, pixel, 0);
  if (int(normalKind.w) != kPixelSurface) {
    imageStore(discontinuityOut, pixel, vec4(0.0, 0.0, 1.0, 0.0));
    return;
  }
  vec4 positionDepth = texelFetch(gPositionDepth, pixel, 0);
  float depth = positionDepth.w;
  vec4 specular = texelFetch(gSpecular, pixel, 0);
  const ivec2 offsets[4] = ivec2[](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
  vec2 depthStep = vec2(0.0);
  // Per axis, the distance to the nearer neighbour: across a depth step the other side's.
  vec2 extent = vec2(1e30);
  float curvature = 0.0;
  for (int i = 0; i < 4; ++i) {
    ivec2 neighbour = pixel + offsets[i];
    if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, size))) continue;
    vec4 neighbourNormal = texelFetch(gNormalKind, neighbour, 0);
    if (int(neighbourNormal.w) != kPixelSurface) continue;
    vec4 neighbourPositionDepth = texelFetch(gPositionDepth, neighbour, 0);
    float difference = abs(neighbourPositionDepth.w - depth);
    float spacing = distance(neighbourPositionDepth.xyz, positionDepth.xyz);
    // The larger of the forward and backward differences, so a step is seen from both sides.
    if (i < 2) {
      depthStep.x = max(depthStep.x, difference);
      extent.x = min(extent.x, spacing);
    } else {
      depthStep.y = max(depthStep.y, difference);
      extent.y = min(extent.y, spacing);
    }
    curvature = max(curvature, length(normalKind.xyz - neighbourNormal.xyz));
    if (texelFetch(gSpecular, neighbour, 0) != specular) curvature = 2.0;
  }
  float gradient = length(depthStep) / max(depth, 1e-6) * float(max(size.x, size.y));
  // An axis without a surface neighbour takes the other's extent (0 when neither has one).
  if (extent.x == 1e30) extent.x = extent.y == 1e30 ? 0.0 : extent.y;
  if (extent.y == 1e30) extent.y = extent.x;
  float lightDistance = nearestReachingLightDistance(positionDepth.xyz, normalize(normalKind.xyz),
                                                     lightCount);
  float proximity = max(extent.x, extent.y) / max(lightDistance, 1e-6);
  imageStore(discontinuityOut, pixel, vec4(gradient, curvature, 0.0, proximity));
}
