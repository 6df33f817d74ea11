#version 450 core
#extension GL_GOOGLE_include_directive : require
// Level 0 of the discontinuity pyramid, per pixel:
//  r: relative depth gradient |grad z| / z, per pixel, times the image's larger side, so that a
//     plane gives the same value at every resolution;
//  g: normal curvature max |N - N_q| = 2 sin(angle/2) over the 4-neighbourhood, forced to 2
//     where the specular material changes (the gather shares k_s and n across a texel);
//  b: 1 when the pixel is not a lit surface (background or light), which forces refinement of
//     every coarser texel whose footprint holds it.
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D gPositionDepth;
layout(binding = 1) uniform sampler2D gNormalKind;
layout(binding = 2) uniform sampler2D gSpecular;
layout(rgba32f, binding = 0) uniform writeonly image2D discontinuityOut;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(discontinuityOut);
  if (any(greaterThanEqual(pixel, size))) return;
  vec4 normalKind = texelFetch(gNormalKind, pixel, 0);
  if (int(normalKind.w) != kPixelSurface) {
    imageStore(discontinuityOut, pixel, vec4(0.0, 0.0, 1.0, 0.0));
    return;
  }
  float depth = texelFetch(gPositionDepth, pixel, 0).w;
  vec4 specular = texelFetch(gSpecular, pixel, 0);
  const ivec2 offsets[4] = ivec2[](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
  vec2 depthStep = vec2(0.0);
  float curvature = 0.0;
  for (int i = 0; i < 4; ++i) {
    ivec2 neighbour = pixel + offsets[i];
    if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, size))) continue;
    vec4 neighbourNormal = texelFetch(gNormalKind, neighbour, 0);
    if (int(neighbourNormal.w) != kPixelSurface) continue;
    float difference = abs(texelFetch(gPositionDepth, neighbour, 0).w - depth);
    // The larger of the forward and backward differences, so a step is seen from both sides.
    if (i < 2) depthStep.x = max(depthStep.x, difference);
    else depthStep.y = max(depthStep.y, difference);
    curvature = max(curvature, length(normalKind.xyz - neighbourNormal.xyz));
    if (texelFetch(gSpecular, neighbour, 0) != specular) curvature = 2.0;
  }
  float gradient = length(depthStep) / max(depth, 1e-6) * float(max(size.x, size.y));
  imageStore(discontinuityOut, pixel, vec4(gradient, curvature, 0.0, 0.0));
}
